// The axes and unit vectors every query computes with. A body's stored axes are orthonormal to the rounding
// of T: ~1e-16 for double, well inside the tangency band; ~6e-8 for float, far outside it,
// and then A diag(r^2) A^T and A diag(r^-2) A^T (the support function and the quadric)
// would describe bodies 1e-7 apart, so that queries reading one or the other disagreed
// near tangency. float axes are therefore replaced by their orthonormal polar factor,
// computed in the working precision R by two Newton-Schulz steps X <- X (3 I - X^T X) / 2
// (quadratic convergence: 6e-8 -> 1e-14 -> rounding of R): every query sees the same body.
#pragma once

#include <ellipsect/shapes.hpp>

#include <cmath>
#include <limits>
#include "math.hpp"

namespace ellipsect::detail {

template <class R, class T, int N>
Mat<R, N> work_axes(const Ellipsoid<T, N>& e) noexcept {
  Mat<R, N> x = e.axes().template cast<R>();
  if constexpr (sizeof(T) < sizeof(double)) {
    for (int step = 0; step < 2; ++step) {
      const Mat<R, N> g = x.transpose() * x;
      x = x * (R(1.5) * Mat<R, N>::Identity() - R(0.5) * g);
    }
  }
  return x;
}

// v / |v|, also where |v|^2 leaves the normal range (Eigen's normalized() then loses digits
// or returns v unchanged: a direction from centers 1e-162 apart came back 1e-164 long).
// Zero and non-finite vectors come back unchanged.
template <class R, int N>
Vec<R, N> unit_vector(Vec<R, N> v) noexcept {
  const R s = v.squaredNorm();
  if (s >= std::numeric_limits<R>::min() && s <= std::numeric_limits<R>::max()) return v / sqrt(s);
  const R m = v.cwiseAbs().maxCoeff();
  if (!(m > R(0)) || !isfinite(m)) return v;
  v /= m;
  return v / v.norm();
}

}  // namespace ellipsect::detail
