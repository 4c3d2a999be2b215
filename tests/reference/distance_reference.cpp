// The instantiations that distance_reference.hpp declares extern.
#include "tests/reference/distance_reference.hpp"

namespace ellipsect::reference {

ELLIPSECT_DISTANCE_REFERENCE_FUNCTIONS(, 2)
ELLIPSECT_DISTANCE_REFERENCE_FUNCTIONS(, 3)

}  // namespace ellipsect::reference
