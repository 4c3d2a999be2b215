// The vectorized certificate filter behind include/ellipsect/batch.hpp (batch_kernels.cpp),
// dispatched at run time to the widest instruction set the CPU has.
#pragma once

#include <cstddef>

namespace ellipsect::detail {

enum class BatchQuery { overlap, classify, contact };

// codes[i - begin] = the certificate code (detail/certificates-inl.hpp) of pairs
// [begin, end), read from columns laid out as in Pairs<T, dim>.
void certify_pairs(int dim, BatchQuery query, const double* const* columns, std::size_t begin, std::size_t end,
                   double tol, signed char* codes);

}  // namespace ellipsect::detail
