// The instantiations that half_space_reference.hpp declares extern.
#include "tests/reference/half_space_reference.hpp"

namespace ellipsect::reference {

ELLIPSECT_HALF_SPACE_REFERENCE_FUNCTIONS(, 2)
ELLIPSECT_HALF_SPACE_REFERENCE_FUNCTIONS(, 3)

}  // namespace ellipsect::reference
