// The factories' checks, shared by the bodies' (shapes.cpp) and the obstacles' (obstacles/):
// each names the field and quotes the value (InputError).
#pragma once

#include <ellipsect/shapes.hpp>

#include "show.hpp"
#include "math.hpp"

#include <limits>
#include <string>

namespace ellipsect::detail {

// The ordered checks (the factories' path for input their good path rejects; from_quadric's
// and translated's only path) build no string while the input is good: a failure calls one
// of these out-of-line functions, which name the field and quote the value.
template <class T>
[[noreturn, gnu::cold, gnu::noinline]] void throw_not_finite(const std::string& field, T value) {
  throw InputError(field, "must be finite (got " + show(value) + ")");
}

// field, field[i] (index >= 0).
[[gnu::cold, gnu::noinline]] inline std::string element_name(const char* field, Eigen::Index i) {
  return i < 0 ? std::string(field) : std::string(field) + '[' + std::to_string(i) + ']';
}

// field(i,j).
[[gnu::cold, gnu::noinline]] inline std::string element_name(const char* field, Eigen::Index i, Eigen::Index j) {
  return std::string(field) + '(' + std::to_string(i) + ',' + std::to_string(j) + ')';
}

template <class T>
[[noreturn, gnu::cold, gnu::noinline]] void throw_not_positive(const std::string& field, T value) {
  if (!isfinite(value)) throw_not_finite(field, value);
  throw InputError(field, "must be > 0 (got " + show(value) + ")");
}

template <class Derived>
void require_finite(const Eigen::MatrixBase<Derived>& m, const char* field) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (!isfinite(m(i, j)))
        throw_not_finite(m.cols() == 1 ? element_name(field, i) : element_name(field, i, j), m(i, j));
}

// point + offset for a shape's translated(): InputError "offset[i]" for a non-finite offset,
// "offset" where the sum leaves the range of T (`what` names the moved point).
template <class T, int N>
Vec<T, N> moved(const Vec<T, N>& point, const Vec<T, N>& offset, const char* what) {
  require_finite(offset, "offset");
  const Vec<T, N> out = point + offset;
  if (!out.allFinite()) [[unlikely]]
    throw InputError("offset", std::string("moves ") + what + " beyond the range of the type");
  return out;
}

// value finite and > 0; the field is named field[index], or field when index < 0.
template <class T>
void require_positive(T value, const char* field, int index = -1) {
  if (!(value > T(0) && value <= std::numeric_limits<T>::max())) throw_not_positive(element_name(field, index), value);
}

}  // namespace ellipsect::detail
