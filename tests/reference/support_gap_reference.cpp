// The instantiations that support_gap_reference.hpp declares extern.
#include "tests/reference/support_gap_reference.hpp"

namespace ellipsect::reference {

ELLIPSECT_SUPPORT_GAP_REFERENCE_FUNCTIONS(, 2)
ELLIPSECT_SUPPORT_GAP_REFERENCE_FUNCTIONS(, 3)

}  // namespace ellipsect::reference
