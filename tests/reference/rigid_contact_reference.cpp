// The instantiations that rigid_contact_reference.hpp declares extern.
#include "tests/reference/rigid_contact_reference.hpp"

namespace ellipsect::reference {

ELLIPSECT_RIGID_CONTACT_REFERENCE_FUNCTIONS(, 2)
ELLIPSECT_RIGID_CONTACT_REFERENCE_FUNCTIONS(, 3)

}  // namespace ellipsect::reference
