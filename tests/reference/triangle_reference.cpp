// The instantiations that triangle_reference.hpp declares extern.
#include "tests/reference/triangle_reference.hpp"

namespace ellipsect::reference {

ELLIPSECT_TRIANGLE_REFERENCE_FUNCTIONS(, 2)
ELLIPSECT_TRIANGLE_REFERENCE_FUNCTIONS(, 3)

}  // namespace ellipsect::reference
