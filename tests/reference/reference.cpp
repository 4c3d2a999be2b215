// The instantiations that reference.hpp declares extern.
#include "tests/reference/reference.hpp"

namespace ellipsect::reference {

ELLIPSECT_REFERENCE_FUNCTIONS(, 2)
ELLIPSECT_REFERENCE_FUNCTIONS(, 3)

}  // namespace ellipsect::reference
