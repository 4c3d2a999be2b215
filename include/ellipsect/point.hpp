// Point queries: the closest point of an ellipsoid's boundary to a point.
//
// Method: the secular equation of seed section 4 (Lagrange condition x - p = s grad q(p)),
// solved by Newton on the concave function S^-1/2 (exact in one step for a ball),
// safeguarded by a bracket and finished by bisection, so it always terminates; zero
// components and repeated radii are handled exactly (the "hard case" of interior points).
// Accuracy: the point lies on the boundary to a few ulps relative to the radii; the
// distance has absolute error below 1e-14 * (largest radius + |x - center|). Scaling body
// and point by 2^k multiplies point and distance by exactly 2^k (docs/method.md, section 7).
#pragma once

#include <ellipsect/shapes.hpp>

namespace ellipsect {

template <class T, int N>
struct ClosestPoint {
  Vec<T, N> point;         // on the boundary, world frame
  T signed_distance;       // |x - point|, negative when x is inside the body
};
static_assert(detail::has_plain_layout<ClosestPoint<float, 2>, float[2], float> &&
              detail::has_plain_layout<ClosestPoint<double, 3>, double[3], double>);

template <class T, int N>
ClosestPoint<T, N> closest_point(const Ellipsoid<T, N>& body, const VecArg<T, N>& x) noexcept;

}  // namespace ellipsect
