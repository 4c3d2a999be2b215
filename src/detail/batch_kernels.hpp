// The vectorized certificate filter behind include/ellipsect/batch.hpp (batch_kernels.cpp),
// dispatched at run time to the widest instruction set the CPU has.
#pragma once

#include <cstddef>

namespace ellipsect::detail {

enum class BatchQuery { overlap, classify, contact };

// Column layout of one body in Pairs<T, n> (certificates-inl.hpp's BodyLanes): center,
// S and M as packed upper triangles (row by row), largest and smallest radius.
struct BodyLayout {
  int n;
  constexpr int packed(int i, int j) const { return i * n - i * (i - 1) / 2 + (j - i); }  // i <= j
  constexpr int triangle() const { return n * (n + 1) / 2; }
  constexpr int center(int i) const { return i; }
  constexpr int s(int i, int j) const { return n + packed(i, j); }
  constexpr int m(int i, int j) const { return n + triangle() + packed(i, j); }
  constexpr int rmax() const { return n + 2 * triangle(); }
  constexpr int rmin() const { return rmax() + 1; }
  constexpr int size() const { return rmin() + 1; }
};

// codes[i - begin] = the certificate code (detail/certificates-inl.hpp) of pairs
// [begin, end), read from columns laid out as in Pairs<T, dim>.
void certify_pairs(int dim, BatchQuery query, const double* const* columns, std::size_t begin, std::size_t end,
                   double tol, signed char* codes);
// Pairs<float, dim>'s columns: overlap and classify by the float certificates
// (detail/certificates_float-inl.hpp), which may leave open pairs the double filter
// decides; first_contact as above (it reads only columns that are exact in float).
void certify_pairs(int dim, BatchQuery query, const float* const* columns, std::size_t begin, std::size_t end,
                   double tol, signed char* codes);

}  // namespace ellipsect::detail
