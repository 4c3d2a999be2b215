#include <ellipsect/point.hpp>

#include "detail/reduce.hpp"
#include "detail/instantiate.hpp"
#include "detail/secular.hpp"

namespace ellipsect {

template <class T, int N>
ClosestPoint<T, N> closest_point(const Ellipsoid<T, N>& body, const VecArg<T, N>& x) noexcept {
  using R = detail::Work<T>;
  // Frame of the body's axes with the query point at the origin.
  const Mat<R, N> axes = body.axes().template cast<R>();
  const Vec<R, N> e = body.radii().template cast<R>();
  const Vec<R, N> k = axes.transpose() * (body.center().template cast<R>() - x.template cast<R>());
  const bool outside = detail::level_at_origin<R, N>(e, k) > R(0);
  const auto p = outside ? detail::closest_from_outside<R, N>(e, k) : detail::closest_from_inside<R, N>(e, k);
  return {(body.center().template cast<R>() + axes * p.offset).template cast<T>(), T(outside ? p.norm : -p.norm)};
}

#define ELLIPSECT_INSTANTIATE(T, N) \
  template ClosestPoint<T, N> closest_point<T, N>(const Ellipsoid<T, N>&, const Vec<T, N>&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
