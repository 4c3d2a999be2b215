#include <ellipsect/point.hpp>

#include "detail/reduce.hpp"
#include "detail/instantiate.hpp"
#include "detail/scale.hpp"
#include "detail/secular.hpp"
#include "detail/math.hpp"

#include <cmath>
#include <limits>

namespace ellipsect {

namespace {

// The query in working precision R.
template <class R, class T, int N>
ClosestPoint<T, N> solve(const Ellipsoid<T, N>& body, const Vec<T, N>& x) noexcept {
  // Frame of the body's axes with the query point at the origin, the center at k. Components
  // of k within eps of the radii underflow the secular terms e_i k_i and its root (a
  // subnormal offset from a ball's center put the point 1.7 radii from it): where all of k
  // is that small it is scaled up by a power of two to about eps e_max / 16 (exact, its
  // direction kept: the nearest point is where k points), else those components are 0
  // (detail::settled). Either moves the query point by less than eps e_max.
  const Mat<R, N> axes = detail::work_axes<R>(body);
  const Vec<R, N> e = body.radii().template cast<R>();
  Vec<R, N> k = axes.transpose() * (body.center().template cast<R>() - x.template cast<R>());
  const R small = k.cwiseAbs().maxCoeff(), floor = std::numeric_limits<R>::epsilon() * e.maxCoeff();
  if (small > R(0) && small <= floor)
    k = detail::times_pow2(k, ilogb(floor) - 4 - ilogb(small));
  else
    k = detail::settled<R, N>(e, k);
  const bool outside = detail::level_at_origin<R, N>(e, k) > R(0);
  const auto p = outside ? detail::closest_from_outside<R, N>(e, k) : detail::closest_from_inside<R, N>(e, k);
  return {(body.center().template cast<R>() + axes * p.offset).template cast<T>(), T(outside ? p.norm : -p.norm)};
}

}  // namespace

// At the scale of the body and the point (detail/scale.hpp): as given, rescaled by 2^-e
// with the lengths scaled back, or in the wide type.
template <class T, int N>
ClosestPoint<T, N> closest_point(const Ellipsoid<T, N>& body, const VecArg<T, N>& x) noexcept {
  const detail::Scale scale = detail::scale_of<T>(body.radii().maxCoeff(), body.radii().minCoeff(),
                                                  std::max(detail::max_abs(body.center()), detail::max_abs(x)));
  return detail::at_scale<detail::Work<T>>(scale, [&]<class W>(auto units) {
    ClosestPoint<T, N> p = solve<W>(units.body(body), units.length(x));
    units.lengths_out(p.point, p.signed_distance);
    return p;
  });
}

#define ELLIPSECT_INSTANTIATE(T, N) \
  template ClosestPoint<T, N> closest_point<T, N>(const Ellipsoid<T, N>&, const VecArg<T, N>&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
