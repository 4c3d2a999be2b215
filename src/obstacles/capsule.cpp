// Bodies against capsules (capsule.hpp): every answer from the support maxima of the body
// and the capsule's segment (detail/polytope_distance.hpp), less the capsule's radius.
#include <ellipsect/capsule.hpp>

#include "detail/at_body.hpp"
#include "detail/contact_start.hpp"
#include "detail/gradient.hpp"
#include "detail/instantiate.hpp"
#include "detail/polytope_distance.hpp"
#include "detail/scale.hpp"
#include "detail/math.hpp"
#include "detail/obstacle_motion.hpp"
#include "detail/validate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

namespace ellipsect {

namespace {

constexpr std::array<std::array<int, 2>, 1> segment_edge{{{0, 1}}};

// The support maxima of the body and the segment moved by `shift` (reach and farthest over
// every stationary direction with `containment`, detail::max_support_gap).
template <class T, int N>
detail::Support<T, N> support_of(const Ellipsoid<T, N>& a, const Capsule<T, N>& b, const Vec<T, N>& shift,
                                 bool containment = false) noexcept {
  const std::array<Vec<T, N>, 2> p{Vec<T, N>(b.point(0) + shift), Vec<T, N>(b.point(1) + shift)};
  return detail::polytope_support<T, N>(a, p, segment_edge, {}, {}, containment);
}

// The body's center against the segment, with the body between the balls of its smallest
// and largest radius: -1 where they surely overlap (the center nearer the segment than r_min
// + R), +1 where they are surely apart by more than the tangency band (farther than r_max +
// R, by 1e-9 of the lengths: the relative gap is then above 1e-9), 0 otherwise.
// Computed on lengths scaled by a power of two (exact) that brings the largest into [1, 2):
// squared lengths of a scene at 1e-299 underflowed to 0 and read as overlapping.
template <class T, int N>
int by_spheres(const Ellipsoid<T, N>& a, const Capsule<T, N>& b) noexcept {
  using W = std::conditional_t<(sizeof(T) < sizeof(double)), double, T>;
  const Vec<W, N> p0 = b.point(0).template cast<W>();
  Vec<W, N> w = a.center().template cast<W>() - p0, e = b.point(1).template cast<W>() - p0;
  W r_max = W(a.radii().maxCoeff()), r_min = W(a.radii().minCoeff()), R = W(b.radius());
  const W size = std::max({w.cwiseAbs().maxCoeff(), e.cwiseAbs().maxCoeff(), r_max, R});
  if (!(size > W(0)) || !isfinite(size)) return 0;
  const W unit = detail::unit_scale(size);
  w *= unit;
  e *= unit;
  r_max *= unit;
  r_min *= unit;
  R *= unit;
  const W ee = e.squaredNorm();
  const W u = ee > W(0) ? std::clamp(w.dot(e) / ee, W(0), W(1)) : W(0);
  const W d = (w - u * e).norm();
  const W margin = W(1e-9) * (d + r_max + R);  // lengths below 2: d and margin are finite
  if (d - r_max - R > margin) return 1;
  if (d - r_min - R < -margin) return -1;
  return 0;
}

// classify's relation from the support maxima `s` of a and b's segment: the spheres' test
// first (where it is surely apart, T's rounding of `s` may still read a touch), then the gap.
// Containment needs reach and farthest over every stationary direction: where the segment
// lies off the body (s.gap > 0) but within R of it, `s` holds only the largest roots' (a
// needle sticking out of a capsule read as inside), and they are computed again.
template <class T, int N>
Relation relation_of(const Ellipsoid<T, N>& a, const Capsule<T, N>& b, const detail::Support<T, N>& s,
                     const Options& options) noexcept {
  if (options.tolerance < 1e-9 && by_spheres(a, b) > 0) return Relation::separated;
  const T radius = b.radius();
  const T band = T(double(options.tolerance)) * s.radius;
  const T gap = s.gap - radius;
  if (gap > band) return Relation::separated;
  if (gap >= -band) return Relation::touching;
  const detail::Support<T, N> all = s.complete ? s : support_of<T, N>(a, b, Vec<T, N>::Zero(), true);
  if (all.farthest + radius <= band) return Relation::a_contains_b;
  if (all.reach - radius <= band) return Relation::b_contains_a;
  return Relation::overlapping;
}

// Every query runs on the pair moved by minus the body's center (detail/at_body.hpp), so
// that the segment, also as moved by t w in first_contact, is rounded to ulps of the pair's
// extent, and all of them decide the relation on the same rounded pair.
template <class T, int N>
struct CapsuleAtBody : detail::AtBody<T, N, Capsule<T, N>> {
  CapsuleAtBody(const Ellipsoid<T, N>& a_world, const Capsule<T, N>& b_world) noexcept
      : detail::AtBody<T, N, Capsule<T, N>>(a_world, b_world, b_world.point(0), b_world.point(1)) {}
};

// first_contact of the moved pair (CapsuleAtBody).
template <class T, int N>
Contact<T, N> contact_at_body(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const Capsule<T, N>& b,
                              const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  Contact<T, N> out = detail::unanswered_contact<T, N>();
  if (!detail::valid_motion<T, N>(velocity_a, velocity_b, t_max)) return out;
  detail::Support<T, N> s = support_of<T, N>(a, b, Vec<T, N>::Zero());
  const Relation start = relation_of(a, b, s, options);
  if (start != Relation::separated) {
    out.time = 0;
    if (start != Relation::touching) {
      out.status = ContactStatus::overlapping_at_start;
      return out;
    }
    out.status = ContactStatus::touching_at_start;
    out.point = s.point;
    out.normal = s.normal;
    return out;
  }
  out.status = ContactStatus::no_contact_in_window;
  // The capsule relative to the body: its points move at w; the gap L(t) is convex in t
  // with slope n*(t) . w, and Newton from 0 stays at or below its first root.
  const Vec<T, N> w = Vec<T, N>(velocity_b) - Vec<T, N>(velocity_a);
  T size = a.radii().maxCoeff() + b.radius();
  for (int k = 0; k < 2; ++k) size = std::max(size, a.radii().maxCoeff() + b.radius() + (b.point(k) - a.center()).norm());
  const T close = T(1e-14) * size;
  T t = 0;
  for (int step = 0; step < options.max_contact_iterations; ++step) {
    const T gap = s.gap - b.radius();
    if (gap <= close) {
      out.status = ContactStatus::hit;
      out.time = t;
      out.point = s.point + t * Vec<T, N>(velocity_a);
      out.normal = s.normal;
      return out;
    }
    const T slope = s.normal.dot(w);
    if (!(slope < T(0))) return out;  // the gap never closes
    const T next = t - gap / slope;
    out.iterations = step + 1;
    if (!(next <= t_max)) {
      // The first root lies beyond next > t_max: none in the window.
      return out;
    }
    if (!(next > t)) break;  // no progress in T: reported below
    t = next;
    s = support_of<T, N>(a, b, Vec<T, N>(t * w));
  }
  out.status = ContactStatus::did_not_converge;
  out.time = t;
  return out;
}

}  // namespace

template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a_world, const Capsule<T, N>& b_world, const Options& options) noexcept {
  const CapsuleAtBody<T, N> p(a_world, b_world);
  return relation_of(p.a, p.b, support_of<T, N>(p.a, p.b, Vec<T, N>::Zero()), options);
}

template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const Capsule<T, N>& b, const Options& options) noexcept {
  if (options.tolerance < 1e-9) {
    const int spheres = by_spheres(a, b);
    if (spheres != 0) return spheres < 0;
  }
  return classify(a, b, options) != Relation::separated;
}

template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a_world, const Capsule<T, N>& b_world,
                               const Options& options) noexcept {
  const CapsuleAtBody<T, N> p(a_world, b_world);
  const detail::Support<T, N> s = support_of<T, N>(p.a, p.b, Vec<T, N>::Zero());
  Distance<T, N> out = detail::distance_of(s, p.b.radius(), relation_of(p.a, p.b, s, options));
  out.point_a += p.shift;  // NaN stays NaN
  out.point_b += p.shift;
  return out;
}

template <class T, int N>
DistanceGradient<T, N, CapsuleGradient<T, N>> signed_distance_gradient(const Ellipsoid<T, N>& a,
                                                                       const Capsule<T, N>& b,
                                                                       const Options& options) noexcept {
  // The segment's point touching a moved by -d n, y + R n with y = p + d n (less a's
  // center), as (1 - l) p0 + l p1.
  const auto along = [&](const auto& n, const auto& p, auto d) {
    using R = decltype(d);
    const Vec<R, N> y = p + d * n;
    const Vec<R, N> c = a.center().template cast<R>();
    const Vec<R, N> p0 = b.point(0).template cast<R>() - c, e = b.point(1).template cast<R>() - c - p0;
    const R ee = e.squaredNorm();
    return ee > R(0) ? std::clamp((y + R(b.radius()) * n - p0).dot(e) / ee, R(0), R(1)) : R(0.5);
  };
  const auto stratum = [&](const auto& n, const auto& p, auto d, auto& out) {
    const auto l = along(n, p, d);
    if constexpr (N == 3)
      if (l > 0 && l < 1 && b.point(0) != b.point(1))
        detail::set_edge<decltype(d)>(out, a, Vec<T, 3>(b.point(0)), Vec<T, 3>(b.point(1)));
  };
  return detail::shape_distance_gradient<T, N, CapsuleGradient<T, N>>(
      a, signed_distance(a, b, options), stratum, [&](const auto& n, const auto& p, auto d) {
        using R = decltype(d);
        const R l = along(n, p, d);
        return CapsuleGradient<T, N>{((R(1) - l) * n).template cast<T>(), (l * n).template cast<T>(),
                                     n.allFinite() ? T(-1) : std::numeric_limits<T>::quiet_NaN()};
      });
}

template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Capsule<T, N>& b, const Options& options) noexcept {
  return detail::unsigned_distance(signed_distance(a, b, options));
}

template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a_world, const VecArg<T, N>& velocity_a, const Capsule<T, N>& b_world,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  const CapsuleAtBody<T, N> p(a_world, b_world);
  Contact<T, N> out = contact_at_body<T, N>(p.a, velocity_a, p.b, velocity_b, t_max, options);
  out.point += p.shift;  // NaN stays NaN
  return out;
}

// ---- Rigid motion (detail/obstacle_motion.hpp) --------------------------------------------

namespace detail::obstacle {
template <class T, int N>
struct ObstacleTraits<Capsule<T, N>> {
  static Lowest lowest(const Vec<R, N>& n, const Capsule<T, N>& c) noexcept {
    return lowest_of<T, N, 2>(n, {c.point(0), c.point(1)}, R(c.radius()));
  }
  static std::optional<Vec<R, N>> inner_point(const Capsule<T, N>& c) noexcept {
    return (c.point(0).template cast<R>() + c.point(1).template cast<R>()) / 2;
  }
  static T coordinate(const Capsule<T, N>& c) noexcept {
    return largest<T, N, 2>({c.point(0), c.point(1)}) + c.radius();
  }
};
}  // namespace detail::obstacle

ELLIPSECT_RIGID_OBSTACLE_CONTACT(Capsule)

// ---- The factories -----------------------------------------------------------------------

template <class T, int N>
Capsule<T, N> Capsule<T, N>::from_segment(const Vec<T, N>& p0, const Vec<T, N>& p1, T radius) {
  detail::require_finite(p0, "p0");
  detail::require_finite(p1, "p1");
  detail::require_positive(radius, "radius");
  Capsule c;
  Eigen::Map<Vec<T, N>>(c.points_[0].data()) = p0;
  Eigen::Map<Vec<T, N>>(c.points_[1].data()) = p1;
  c.radius_ = radius;
  return c;
}

template <class T, int N>
Capsule<T, N> Capsule<T, N>::translated(const Vec<T, N>& offset) const {
  Capsule c = *this;
  for (int k = 0; k < 2; ++k)
    Eigen::Map<Vec<T, N>>(c.points_[k].data()) = detail::moved<T, N>(point(k), offset, "an end point");
  return c;
}

#define ELLIPSECT_INSTANTIATE(T, N) ELLIPSECT_INSTANTIATE_OBSTACLE(Capsule, CapsuleGradient, T, N)
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
