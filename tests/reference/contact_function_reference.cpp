// The instantiations that contact_function_reference.hpp declares extern.
#include "tests/reference/contact_function_reference.hpp"

namespace ellipsect::reference {

ELLIPSECT_CONTACT_FUNCTION_REFERENCE_FUNCTIONS(, 2)
ELLIPSECT_CONTACT_FUNCTION_REFERENCE_FUNCTIONS(, 3)

}  // namespace ellipsect::reference
