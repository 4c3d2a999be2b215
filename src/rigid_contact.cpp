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

#include "detail/instantiate.hpp"
#include "detail/scale.hpp"
#include "detail/shape_access.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ellipsect {
namespace {

using R = double;  // every step's arithmetic; float bodies keep float rounding margins

template <class T, int N>
using Omega = decltype(RigidMotion<T, N>::angular_velocity);

// omega x v; in 2D omega is the rate about the normal of the plane.
template <int N, class W>
Vec<R, N> cross(const W& omega, const Vec<R, N>& v) noexcept {
  if constexpr (N == 2) {
    return Vec<R, 2>(-R(omega) * v[1], R(omega) * v[0]);
  } else {
    return Vec<R, 3>(omega.template cast<R>().cross(v));
  }
}

template <int N, class W>
R magnitude(const W& omega) noexcept {
  if constexpr (N == 2) {
    return std::abs(R(omega));
  } else {
    return omega.template cast<R>().stableNorm();
  }
}

template <int N, class W>
bool all_finite(const W& omega) noexcept {
  if constexpr (N == 2) {
    return std::isfinite(omega);
  } else {
    return omega.allFinite();
  }
}

// exp(t [omega]x) (Rodrigues' formula in 3D).
template <class T, int N>
Mat<T, N> rotation(const Omega<T, N>& omega, T t) noexcept {
  if constexpr (N == 2) {
    const T angle = omega * t, c = std::cos(angle), s = std::sin(angle);
    Mat<T, 2> rot;
    rot << c, -s, s, c;
    return rot;
  } else {
    const T rate = omega.stableNorm();
    if (!(rate > T(0)) || t == T(0)) return Mat<T, 3>::Identity();
    const Vec<T, 3> k = omega / rate;
    const T angle = rate * t, c = std::cos(angle), s = std::sin(angle);
    Mat<T, 3> kx;
    kx << T(0), -k[2], k[1], k[2], T(0), -k[0], -k[1], k[0], T(0);
    return Mat<T, 3>(Mat<T, 3>::Identity() + s * kx + (T(1) - c) * (kx * kx));
  }
}

// The body at t, unchecked: the moved center may be infinite (callers test it).
template <class T, int N>
Ellipsoid<T, N> moved(const Ellipsoid<T, N>& body, const RigidMotion<T, N>& motion, T t) noexcept {
  const Vec<T, N> center = body.center() + t * motion.velocity;
  return detail::ShapeAccess::unchecked<T, N>(center, rotation<T, N>(motion.angular_velocity, t) * body.axes(),
                                              body.radii());
}

// Support radius of `body` along the unit n, and the support point's offset from the center.
template <class T, int N>
R support(const Ellipsoid<T, N>& body, const Vec<R, N>& n, Vec<R, N>& offset) noexcept {
  const Mat<R, N> axes = body.axes().template cast<R>();
  const Vec<R, N> radii = body.radii().template cast<R>();
  const Vec<R, N> w = radii.cwiseProduct(axes.transpose() * n);
  const R rho = w.norm();
  offset = axes * radii.cwiseProduct(w) / rho;
  return rho;
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
  // Beyond the bounds' range: |omega| overflows, or the pair needs more than double (radius
  // ratios beyond 2^160, coordinates beyond 2^340 radii; detail/scale.hpp). Only the start
  // state is decided there; otherwise did_not_converge at 0.
  const bool out_of_range =
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
  }

  // Per-body constants of the bounds.
  const R big_a = R(a.radii().maxCoeff()), small_a = R(a.radii().minCoeff());
  const R big_b = R(b.radii().maxCoeff()), small_b = R(b.radii().minCoeff());
  // How fast a turn moves the support plane, per unit of |omega x n|: at most R, and at most
  // (R^2 - r^2) / (2 r) (zero for a ball; see the top of this file).
  const R sweep_a = std::min(big_a, (big_a - small_a) * (big_a + small_a) / (2 * small_a));
  const R sweep_b = std::min(big_b, (big_b - small_b) * (big_b + small_b) / (2 * small_b));
  const Vec<R, N> va = motion_a.velocity.template cast<R>(), vb = motion_b.velocity.template cast<R>();
  const Vec<R, N> rel_v = vb - va;
  // Rounding margins: the bodies at each step are formed afresh (center + t v, rotated
  // axes, in T), so the gap carries the rounding of their coordinates and orientations.
  constexpr R ulp = R(std::numeric_limits<T>::epsilon());
  const R speed = va.norm() + vb.norm(), turn = spin_a * big_a + spin_b * big_b;
  const R rate_margin = 32 * ulp * (speed + turn);

  auto fill = [&](ContactStatus status, R t, const Distance<T, N>& d) {
    out.status = status;
    out.time = T(t);
    out.point = ((d.point_a + d.point_b) / T(2)).eval();
    out.normal = d.normal;
    return out;
  };

  R t = 0;
  bool touched = false;  // an earlier step was within the tangency band
  R touch_time = 0;
  Distance<T, N> touch;
  touch.point_a.setConstant(nan);
  touch.point_b.setConstant(nan);
  touch.normal.setConstant(nan);
  for (int step = 0; step < options.max_motion_steps; ++step) {
    out.iterations = step;
    const Ellipsoid<T, N> body_a = moved(a, motion_a, T(t)), body_b = moved(b, motion_b, T(t));
    if (!body_a.center().allFinite() || !body_b.center().allFinite() || !body_a.axes().allFinite() ||
        !body_b.axes().allFinite())
      break;  // moved or turned beyond the type's range
    // Bounding balls (radius R) apart by more than their radii: the direction between the
    // centers gives a gap of at least R_a + R_b, and distance() is left for the near phase.
    const Vec<R, N> between = body_b.center().template cast<R>() - body_a.center().template cast<R>();
    const bool far = !touched && between.stableNorm() > 2 * (big_a + big_b);
    Distance<T, N> d;
    if (far) {
      d.status = DistanceStatus::separated;
      d.point_a.setConstant(nan);
      d.point_b.setConstant(nan);
      d.normal = (between / between.stableNorm()).template cast<T>();
    } else {
      d = distance(body_a, body_b, options);
    }
    if (step == 0 && d.status == DistanceStatus::overlapping) {
      out.status = ContactStatus::overlapping_at_start;
      out.time = T(0);
      return out;
    }
    if (step == 0 && d.status == DistanceStatus::touching)
      return fill(ContactStatus::touching_at_start, 0, d);
    if (out_of_range) break;
    if (d.status == DistanceStatus::overlapping)  // within rounding of the contact
      return touched ? fill(ContactStatus::hit, touch_time, touch)
                     : fill(ContactStatus::hit, t, signed_distance(body_a, body_b, options));
    if (d.status == DistanceStatus::separated && touched)  // grazed within the band
      return fill(ContactStatus::hit, touch_time, touch);

    const Vec<R, N> n = far ? Vec<R, N>(between / between.stableNorm()) : Vec<R, N>(d.normal.template cast<R>());
    Vec<R, N> s_a, s_b;
    const R rho_a = support(body_a, n, s_a), rho_b = support(body_b, n, s_b);
    const Vec<R, N> ca = body_a.center().template cast<R>(), cb = body_b.center().template cast<R>();
    // The rounding of this step's bodies (none at t = 0, where they are the given ones):
    // centers c_0 + t v, the angle |omega| t, Rodrigues' products and t itself in T; and the
    // gap's own rounding in R.
    const R configuration =
        t == R(0) ? R(0)
                  : 4 * ulp *
                        (a.center().template cast<R>().norm() + b.center().template cast<R>().norm() + t * speed +
                         big_a * (8 + spin_a * t) + big_b * (8 + spin_b * t));
    const R along = n.dot(cb - ca);
    const R margin = configuration + 8 * std::numeric_limits<R>::epsilon() * (std::abs(along) + rho_a + rho_b);
    const R gap = along - rho_a - rho_b - margin;
    const R slope = n.dot(rel_v) - n.dot(cross<N>(motion_a.angular_velocity, s_a)) -
                    n.dot(cross<N>(motion_b.angular_velocity, s_b)) - rate_margin;
    const R across_a = cross<N>(motion_a.angular_velocity, n).stableNorm();
    const R across_b = cross<N>(motion_b.angular_velocity, n).stableNorm();
    const R fastest = -n.dot(rel_v) + sweep_a * across_a + sweep_b * across_b + rate_margin;
    const R curvature = (big_a * big_a * across_a * across_a / small_a + big_a * spin_a * across_a +
                         big_b * big_b * across_b * across_b / small_b + big_b * spin_b * across_b) *
                        (1 + 32 * ulp);
    // The first zero of each lower bound of g_n beyond t (infinite where it has none).
    constexpr R inf = std::numeric_limits<R>::infinity();
    R advance = 0;
    if (gap > R(0)) {
      const R first_order = fastest > R(0) ? gap / fastest : inf;
      R second_order;
      if (curvature > R(0)) {
        const R root = std::sqrt(slope * slope + 2 * curvature * gap);
        second_order = slope <= R(0) ? 2 * gap / (root - slope) : (slope + root) / curvature;
      } else {
        second_order = slope < R(0) ? gap / -slope : inf;
      }
      advance = std::max(first_order, second_order) * (1 - 8 * ulp);
    }
    if (d.status == DistanceStatus::touching) {
      if (!touched) {
        touched = true;
        touch_time = t;
        touch = d;
      }
      // Converged: no certified progress left at the resolution of the claim.
      if (!(advance > 1e-14 * t)) return fill(ContactStatus::hit, t, d);
      touch_time = t;
      touch = d;
    }
    // The bounding balls (radius R about the centers) never meet from t on: no contact ever.
    const Vec<R, N> apart = cb - ca;
    const R ahead = rel_v.squaredNorm() > R(0) ? std::max(R(0), -apart.dot(rel_v) / rel_v.squaredNorm()) : R(0);
    const R closest = (apart + ahead * rel_v).norm();  // of the centers, from t on
    if (closest > (big_a + big_b) * (1 + 64 * ulp) + margin) advance = inf;
    if (advance == inf || t + advance > R(t_max)) {
      if (touched) return fill(ContactStatus::hit, touch_time, touch);
      out.status = ContactStatus::no_contact_in_window;
      return out;
    }
    if (!(t + advance > t)) {
      // No certified progress. Where the gap is within the rounding margin of the
      // configuration (thin bodies have a tangency band narrower than it) or its step below
      // the resolution of t, that is contact, as closely as the type resolves it; otherwise
      // the bounds are beyond the range of the type (speeds or spins near overflow).
      const bool resolved = margin <= (small_a + small_b) / 4;
      if (t > R(0) && resolved && gap <= margin + 4 * ulp * t * fastest) return fill(ContactStatus::hit, t, d);
      break;
    }
    t += advance;
  }
  if (touched) return fill(ContactStatus::hit, touch_time, touch);
  out.status = ContactStatus::did_not_converge;
  out.time = T(t);
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                 \
  template Ellipsoid<T, N> body_at<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, T);                    \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, const Ellipsoid<T, N>&, \
                                             const RigidMotion<T, N>&, T, const Options&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
