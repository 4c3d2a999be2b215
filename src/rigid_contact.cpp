// First contact under rigid motion (contact.hpp): conservative advancement on the slab gap
// along the direction of closest approach, with a first-order and a second-order lower
// bound on the gap (docs/method.md, section 9).
//
// Bounds. With e(s) = exp(-s [omega]x) n, body X's support radius along the fixed world
// direction n is rho(s) = |w(s)|, w = diag(radii) axes_0^T e(s) (the body's axes turn by
// exp(s [omega]x), which is the same as n turning back in the body's frame). Then
//   |rho'| <= |w'| <= R |omega x n|,                      (|D x| <= R |x|, |e'| = |omega x n|)
//   |rho'| = |u^T (D^2 - c I) u'| / |D u| <= (R^2 - r^2) / (2 r) |omega x n|
//                                       (u = axes_0^T e, u' orthogonal to u, c = (R^2 + r^2) / 2),
//   rho'' <= |w'|^2 / |w| + |w''| <= R^2 |omega x n|^2 / r + R |omega| |omega x n|,
// with R, r the largest and smallest radius (|w| >= r). The centers move linearly, so
// g_n = n . (c_b - c_a) - rho_a - rho_b has g_n' >= -V and g_n'' >= -K as in contact.hpp,
// and rho'(s) = (omega x s_X) . n at s, where s_X is the support point's offset from the
// center (envelope theorem), which gives g_n' exactly.
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>

#include "detail/contact_start.hpp"
#include "detail/instantiate.hpp"
#include "detail/rigid_motion.hpp"
#include "detail/scale.hpp"
#include "detail/shape_access.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ellipsect {

using namespace detail::rigid;

namespace {

// The other body as the second party of the advancement (detail/rigid_motion.hpp).
template <class T, int N>
struct BodyParty {
  R big_a;
  Vec<R, N> velocity_a;
  const Ellipsoid<T, N>& b;
  const RigidMotion<T, N>& motion_b;
  const Options& options;
  Turning<T, N> turning;
  Vec<R, N> velocity;
  R t = 0;
  Ellipsoid<T, N> body_b;

  BodyParty(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Ellipsoid<T, N>& b_,
            const RigidMotion<T, N>& m, const Options& o) noexcept
      : big_a(R(a.radii().maxCoeff())), velocity_a(motion_a.velocity.template cast<R>()), b(b_), motion_b(m),
        options(o), turning(b_, m), velocity(m.velocity.template cast<R>()) {}

  bool at(R time) noexcept {
    t = time;
    body_b = moved(b, motion_b, T(t));
    return body_b.center().allFinite() && body_b.axes().allFinite();
  }
  // Bounding balls (radius R) apart by more than their radii: the direction between the
  // centers gives a gap of at least R_a + R_b, and distance() is left for the near phase.
  Distance<T, N> near(const Ellipsoid<T, N>& body_a, bool touched) const noexcept {
    const Vec<R, N> between = body_b.center().template cast<R>() - body_a.center().template cast<R>();
    if (touched || !(between.stableNorm() > 2 * (big_a + turning.big))) return distance(body_a, body_b, options);
    Distance<T, N> d;
    d.status = DistanceStatus::separated;
    d.distance = std::numeric_limits<T>::quiet_NaN();
    d.point_a = d.point_b = detail::nan_vec<T, N>();
    d.normal = (between / between.stableNorm()).template cast<T>();
    return d;
  }
  Distance<T, N> exact(const Ellipsoid<T, N>& body_a) const noexcept { return signed_distance(body_a, body_b, options); }
  Side side(const Vec<R, N>& n, const Ellipsoid<T, N>&) const noexcept {
    Vec<R, N> offset;
    const R rho = support(body_b, n, offset);
    const R center = n.dot(body_b.center().template cast<R>());
    const R across = turning.across(n);
    return {center - rho,
            n.dot(velocity) - turning.rate(n, offset),
            -n.dot(velocity) + turning.sweep * across,
            turning.curvature(across),
            turning.configuration(t),
            std::abs(center) + rho,
            turning.speed + turning.spin * turning.big,
            turning.small};
  }
  // The bounding balls (radius R about the centers) never meet from t on.
  bool never(const Vec<R, N>&, const Ellipsoid<T, N>& body_a, R margin) const noexcept {
    constexpr R ulp = R(std::numeric_limits<T>::epsilon());
    const Vec<R, N> rel_v = velocity - velocity_a;
    const Vec<R, N> apart = body_b.center().template cast<R>() - body_a.center().template cast<R>();
    const R ahead = rel_v.squaredNorm() > R(0) ? std::max(R(0), -apart.dot(rel_v) / rel_v.squaredNorm()) : R(0);
    const R closest = (apart + ahead * rel_v).norm();  // of the centers, from t on
    return closest > (big_a + turning.big) * (1 + 64 * ulp) + margin;
  }
};

// first_contact with lengths scaled by 2^-e and time by 2^f (exact but for underflow far
// below rounding): velocities times 2^-(e + f), angular velocities 2^-f, all finite.
template <class T, int N>
Contact<T, N> rescaled_first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a,
                                     const Ellipsoid<T, N>& b, const RigidMotion<T, N>& motion_b, T t_max,
                                     const Options& options, int e, int f) noexcept {
  RigidMotion<T, N> ma = motion_a, mb = motion_b;
  ma.velocity = detail::times_pow2(motion_a.velocity, -e - f);
  mb.velocity = detail::times_pow2(motion_b.velocity, -e - f);
  if constexpr (N == 2) {
    ma.angular_velocity = std::ldexp(motion_a.angular_velocity, -f);
    mb.angular_velocity = std::ldexp(motion_b.angular_velocity, -f);
  } else {
    ma.angular_velocity = detail::times_pow2(motion_a.angular_velocity, -f);
    mb.angular_velocity = detail::times_pow2(motion_b.angular_velocity, -f);
  }
  // Centers that the scaling would overflow (bodies far smaller than their coordinates):
  // the pair is moved to a's center first (an exact difference for nearby centers).
  const bool move = std::max(detail::max_abs(a.center()), detail::max_abs(b.center())) >= std::ldexp(T(1), 1000 + e);
  const Vec<T, N> origin = move ? Vec<T, N>(a.center()) : Vec<T, N>::Zero();
  auto prepared = [&](const Ellipsoid<T, N>& x) {
    return detail::scaled(detail::ShapeAccess::unchecked<T, N>(x.center() - origin, x.axes(), x.radii()), -e);
  };
  Contact<T, N> c = first_contact(prepared(a), ma, prepared(b), mb, std::ldexp(t_max, f), options);
  c.time = std::ldexp(c.time, -f);
  c.point = detail::times_pow2(c.point, e);
  if (move) c.point += origin;
  return c;
}

}  // namespace

template <class T, int N>
Ellipsoid<T, N> body_at(const Ellipsoid<T, N>& body, const RigidMotion<T, N>& motion, T t) {
  if (!motion.velocity.allFinite()) throw InputError("velocity", "must be finite");
  if (!all_finite<N>(motion.angular_velocity)) throw InputError("angular_velocity", "must be finite");
  if (!std::isfinite(t)) throw InputError("time", "must be finite");
  const Ellipsoid<T, N> out = moved(body, motion, t);
  if (!out.center().allFinite()) throw InputError("time", "moves the center beyond the range of the type");
  if (!out.axes().allFinite()) throw InputError("time", "turns the body by an angle beyond the range of the type");
  return out;
}

template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Ellipsoid<T, N>& b,
                            const RigidMotion<T, N>& motion_b, T t_max, const Options& options) noexcept {
  constexpr T nan = std::numeric_limits<T>::quiet_NaN();
  Contact<T, N> out;
  out.time = nan;
  out.point.setConstant(nan);
  out.normal.setConstant(nan);
  if (!motion_a.velocity.allFinite() || !motion_b.velocity.allFinite() || !all_finite<N>(motion_a.angular_velocity) ||
      !all_finite<N>(motion_b.angular_velocity) || std::isnan(t_max) || t_max < T(0))
    return out;
  const R spin_a = magnitude<N>(motion_a.angular_velocity), spin_b = magnitude<N>(motion_b.angular_velocity);
  if (spin_a == R(0) && spin_b == R(0))
    return first_contact(a, motion_a.velocity, b, motion_b.velocity, t_max, options);
  // Beyond the bounds' range: |omega| overflows (here or in the time unit chosen below), or
  // the pair needs more than double (radius ratios beyond 2^160, coordinates beyond 2^340
  // radii; detail/scale.hpp). Only the start state is decided there; otherwise
  // did_not_converge at 0.
  bool out_of_range =
      !std::isfinite(spin_a) || !std::isfinite(spin_b) || detail::scale_of(a, b).range == detail::Range::wide;

  // Lengths rescaled by 2^-e (exact) where the radii leave 2^+-64, so that squares of radii
  // stay normal; where the speeds in those lengths would leave the range of the type, time
  // is rescaled too, by 2^f (velocities times 2^-(e + f), angular velocities 2^-f).
  if constexpr (std::is_same_v<T, double>) {
    const int e = std::ilogb(std::max(a.radii().maxCoeff(), b.radii().maxCoeff()));
    if ((e > detail::native_exponent || e < -detail::native_exponent) && !out_of_range) {
      const T speed = std::max(detail::max_abs(motion_a.velocity), detail::max_abs(motion_b.velocity));
      const int g = speed > T(0) ? std::ilogb(speed) - e : 0;
      const int f = g > 960 || g < -960 ? g : 0;
      // Bodies 2^963 across moving 1 per unit time and turning at 2^500 rad per unit time:
      // in the time unit where they move about a radius, the spin overflows.
      if (std::isfinite(std::ldexp(std::max(spin_a, spin_b), -f)))
        return rescaled_first_contact(a, motion_a, b, motion_b, t_max, options, e, f);
      out_of_range = true;
    }
  }

  return advance<T, N>(a, motion_a, t_max, options, out_of_range, BodyParty<T, N>(a, motion_a, b, motion_b, options));
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                 \
  template Ellipsoid<T, N> body_at<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, T);                    \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, const Ellipsoid<T, N>&, \
                                             const RigidMotion<T, N>&, T, const Options&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
