// Rigid motion (contact.hpp): the body at time t and the pieces of conservative advancement
// shared by body pairs (rigid_contact.cpp) and bodies against obstacles (obstacle_motion.hpp).
#pragma once

#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>

#include "contact_start.hpp"
#include "shape_access.hpp"
#include "math.hpp"
#include "secular.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ellipsect::detail::rigid {

using R = double;  // every step's arithmetic; float bodies keep float rounding margins

template <class T, int N>
using Omega = decltype(RigidMotion<T, N>::angular_velocity);

// omega x v; in 2D omega is the rate about the normal of the plane.
template <int N, class W, class S>
Vec<S, N> spin_cross(const W& omega, const Vec<S, N>& v) noexcept {
  if constexpr (N == 2) {
    return Vec<S, 2>(-S(omega) * v[1], S(omega) * v[0]);
  } else {
    return Vec<S, 3>(omega.template cast<S>().cross(v));
  }
}

template <int N, class W>
R magnitude(const W& omega) noexcept {
  if constexpr (N == 2) {
    return abs(R(omega));
  } else {
    return stable_norm<R, 3>(omega.template cast<R>());
  }
}

template <int N, class W>
bool all_finite(const W& omega) noexcept {
  if constexpr (N == 2) {
    return isfinite(omega);
  } else {
    return omega.allFinite();
  }
}

template <class T>
bool valid_growth(T growth) noexcept {
  return growth >= T(0) && isfinite(growth);
}

// exp(t [omega]x) (Rodrigues' formula in 3D), its factors formed once per angular velocity.
template <class T, int N>
class Turn {
 public:
  explicit Turn(const Omega<T, N>& omega) noexcept : omega_(omega) {
    if constexpr (N == 3) {
      rate_ = stable_norm<T, 3>(omega);
      if (!(rate_ > T(0))) return;
      const Vec<T, 3> k = omega / rate_;
      kx_ << T(0), -k[2], k[1], k[2], T(0), -k[0], -k[1], k[0], T(0);
      kx2_ = kx_ * kx_;
    }
  }
  Mat<T, N> at(T t) const noexcept {
    if constexpr (N == 2) {
      const T angle = omega_ * t, c = cos(angle), s = sin(angle);
      Mat<T, 2> rot;
      rot << c, -s, s, c;
      return rot;
    } else {
      if (!(rate_ > T(0)) || t == T(0)) return Mat<T, 3>::Identity();
      const T angle = rate_ * t, c = cos(angle), s = sin(angle);
      return Mat<T, 3>(Mat<T, 3>::Identity() + s * kx_ + (T(1) - c) * kx2_);
    }
  }

 private:
  Omega<T, N> omega_;
  T rate_ = 0;
  Mat<T, 3> kx_, kx2_;
};

// The body at t, unchecked: the moved center or the grown radii may be infinite (callers
// test them). Radii times exactly 1 where nothing grows.
template <class T, int N>
Ellipsoid<T, N> moved(const Ellipsoid<T, N>& body, const RigidMotion<T, N>& motion, const Turn<T, N>& turn, T t) noexcept {
  const Vec<T, N> center = body.center() + t * motion.velocity;
  return detail::ShapeAccess::unchecked<T, N>(center, turn.at(t) * body.axes(), body.radii() * (T(1) + motion.growth * t));
}
template <class T, int N>
Ellipsoid<T, N> moved(const Ellipsoid<T, N>& body, const RigidMotion<T, N>& motion, T t) noexcept {
  return moved(body, motion, Turn<T, N>(motion.angular_velocity), t);
}

template <class T, int N>
bool finite(const Ellipsoid<T, N>& body) noexcept {
  return body.center().allFinite() && body.axes().allFinite() && body.radii().allFinite();
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

// One turning, growing body's part in the bounds of conservative advancement
// (rigid_contact.cpp, top). All at time t, where its radii are scale = 1 + g t times those
// at 0 (R, r the largest and smallest of those): along a fixed unit n its support radius
// changes at rate (omega x s) . n + gamma rho (s the support point's offset, rho the support
// radius, gamma = g / scale the growth relative to the radii at t); over [t, t + h] it
// rises by at most (sweep |omega x n| + g R) h (sweep = scale min(R, (R^2 - r^2) / (2 r)),
// zero for a ball); its second derivative is at most scale ((R^2 / r) |omega x n|^2 + R
// |omega| |omega x n|) without growth, and with growth at most 9/8 of that plus 2 gamma
// |(omega x s) . n| over steps h <= 1 / (8 gamma) (`reach`: rho(t + h) = (1 + gamma h)
// rho_t(t + h), rho_t the support radius of the body at t turning on).
template <class T, int N>
struct Turning {
  const RigidMotion<T, N>& motion;
  R big, small, sweep, spin, speed, center, growth;

  Turning(const Ellipsoid<T, N>& b, const RigidMotion<T, N>& m) noexcept
      : motion(m),
        big(R(b.radii().maxCoeff())),
        small(R(b.radii().minCoeff())),
        sweep(std::min(big, (big - small) * (big + small) / (2 * small))),
        spin(magnitude<N>(m.angular_velocity)),
        speed(m.velocity.template cast<R>().norm()),
        center(b.center().template cast<R>().norm()),
        growth(R(m.growth)) {}

  R scale(R t) const noexcept { return growth == R(0) ? R(1) : 1 + growth * t; }
  // The rounding of the body formed at t (center c_0 + t v, the angle |omega| t, Rodrigues'
  // products, the grown radii, t itself in T), in units of T's epsilon: none at t = 0, where
  // it is the given one.
  R configuration(R t) const noexcept {
    return t == R(0) ? R(0) : 4 * (center + t * speed + big * scale(t) * (8 + spin * t));
  }
  R across(const Vec<R, N>& n) const noexcept { return stable_norm<R, N>(spin_cross<N>(motion.angular_velocity, n)); }
  // (omega x s) . n: the turn's part of the support radius's rate.
  R turn(const Vec<R, N>& n, const Vec<R, N>& offset) const noexcept {
    return n.dot(spin_cross<N>(motion.angular_velocity, offset));
  }
  // The support radius's rate at t, its rise rate bound and its curvature bound (above).
  R rate(R t, R rho, R turned) const noexcept { return growth == R(0) ? turned : turned + growth / scale(t) * rho; }
  R rising(R t, R across) const noexcept { return sweep * scale(t) * across + growth * big; }
  R curvature(R t, R across, R turned) const noexcept {
    const R rigid = scale(t) * (big * big * across * across / small + big * spin * across);
    return growth == R(0) ? rigid : R(1.125) * rigid + 2 * growth / scale(t) * abs(turned);
  }
  R reach(R t) const noexcept {
    return growth == R(0) ? std::numeric_limits<R>::infinity() : scale(t) / (8 * growth);
  }
  // Bounds on the speeds the rates are formed from (for their rounding).
  R rates(R t) const noexcept { return speed + (spin + growth) * big * scale(t); }
};

// What near() returns for a step on the slab along the unit direction u instead of a
// distance: separated, no distance and no points.
template <class T, int N>
Distance<T, N> slab_step(const Vec<R, N>& u) noexcept {
  Distance<T, N> d;
  d.status = DistanceStatus::separated;
  d.distance = std::numeric_limits<T>::quiet_NaN();
  d.point_a = d.point_b = nan_vec<T, N>();
  d.normal = u.template cast<T>();
  return d;
}

// The other party of a step along the unit n (from the body towards it), at time t: its least
// n . x (`low`), that value's rate at fixed n, a bound on how fast it may fall (low(s) >= low -
// falling (s - t)) and on its second derivative's fall over steps up to `reach`, and its
// rounding: `configuration` in units of T's epsilon, `magnitude` the size of what low is
// computed from (for the gap's own rounding), `speed` for the rates' rounding, `small` its
// smallest radius (0 for a shape).
struct Party {
  R low, rate, falling, curvature, configuration, magnitude, speed, small;
  R reach = std::numeric_limits<R>::infinity();
};

// First contact of `a` in rigid motion with another party, by conservative advancement
// (contact.hpp) that keeps each distance's normal for the steps after it (docs/method.md,
// section 9, "The kept axis"). Other provides, at a time t:
//   bool at(R t)                          forms the party at t (false: beyond the type's range);
//   Distance<T, N> near(body, bool touched, hint)  the distance at t (may be a far estimate:
//                                         slab_step; never with touched, which asks for the
//                                         distance itself), `hint` the last distance's normal
//                                         (NaN at the first) to start its descent from;
//   Distance<T, N> exact(body)            the signed distance at t (for a hit found overlapping);
//   Party side(n, body)                   as above;
//   bool never(n, body, margin)           certifies that the two never meet from t on.
template <class T, int N, class Other>
Contact<T, N> advance(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion, T t_max, const Options& options,
                      bool out_of_range, Other&& other) noexcept {
  constexpr T nan = std::numeric_limits<T>::quiet_NaN();
  const R ulp = R(std::numeric_limits<T>::epsilon()), eps = std::numeric_limits<R>::epsilon();
  const Turning<T, N> turning(a, motion);
  const Turn<T, N> turn(motion.angular_velocity);
  const Vec<R, N> v = motion.velocity.template cast<R>();
  Contact<T, N> out;
  out.time = nan;
  out.point.setConstant(nan);
  out.normal.setConstant(nan);
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
  touch.distance = nan;
  Distance<T, N> d = touch;  // the last distance: its normal is the steps' axis and the next one's hint
  R taken_advance = 0;       // the advance of the step that took it
  bool take = true;          // the next step takes a distance
  for (int step = 0; step < options.max_motion_steps; ++step) {
    out.iterations = step;
    const Ellipsoid<T, N> body = moved(a, motion, turn, T(t));
    if (!finite(body) || !other.at(t)) break;  // moved, turned or grown beyond the type's range
    // The gap g_n along the axis n at t, less the rounding of this step's bodies and its own,
    // and the step to the first zero of the larger of its two lower bounds (infinite where
    // neither has one; the second holds up to `reach`).
    struct Gap {
      R gap, margin, fastest, advance, small;  // small: the other party's smallest radius
    };
    auto gap_along = [&](const Vec<R, N>& n) {
      Vec<R, N> offset;
      const R rho = support(body, n, offset);
      const R along = n.dot(body.center().template cast<R>());
      const Party b = other.side(n, body);
      Gap g;
      g.small = b.small;
      g.margin = ulp * (turning.configuration(t) + b.configuration) + 8 * eps * (abs(along) + rho + b.magnitude);
      g.gap = b.low - along - rho - g.margin;
      const R rate_margin = 32 * ulp * (turning.rates(t) + b.speed);
      const R across = turning.across(n), turned = turning.turn(n, offset);
      const R slope = b.rate - n.dot(v) - turning.rate(t, rho, turned) - rate_margin;
      g.fastest = b.falling + n.dot(v) + turning.rising(t, across) + rate_margin;
      const R curvature = (turning.curvature(t, across, turned) + b.curvature) * (1 + 32 * ulp);
      const R reach = std::min(turning.reach(t), b.reach);
      const R inf = std::numeric_limits<R>::infinity();
      g.advance = 0;
      if (g.gap > R(0)) {
        const R first_order = g.fastest > R(0) ? g.gap / g.fastest : inf;
        R second_order;
        if (curvature > R(0)) {
          const R root = sqrt(slope * slope + 2 * curvature * g.gap);
          second_order = slope <= R(0) ? 2 * g.gap / (root - slope) : (slope + root) / curvature;
        } else {
          second_order = slope < R(0) ? g.gap / -slope : inf;
        }
        g.advance = std::max(first_order, std::min(second_order, reach)) * (1 - 8 * ulp);
      }
      return g;
    };
    Gap g;
    if (!take) {
      // Bilateral advancement: the last distance's axis kept while its own steps make
      // progress (two support points where a distance costs a descent); a step below
      // an eighth of the one that took the distance means the axis has done its work.
      g = gap_along(d.normal.template cast<R>());
      take = !(8 * g.advance > taken_advance && t + g.advance > t);
    }
    if (take) {
      d = other.near(body, touched, d.normal);
      if (step == 0 && d.status == DistanceStatus::overlapping) {
        out.status = ContactStatus::overlapping_at_start;
        out.time = T(0);
        return out;
      }
      if (step == 0 && d.status == DistanceStatus::touching) return fill(ContactStatus::touching_at_start, 0, d);
      if (out_of_range) break;
      if (d.status == DistanceStatus::overlapping)  // within rounding of the contact
        return touched ? fill(ContactStatus::hit, touch_time, touch) : fill(ContactStatus::hit, t, other.exact(body));
      if (d.status == DistanceStatus::separated && touched)  // grazed within the band
        return fill(ContactStatus::hit, touch_time, touch);
      g = gap_along(d.normal.template cast<R>());
      taken_advance = g.advance;
      if (d.status == DistanceStatus::touching) {
        if (!touched) {
          touched = true;
          touch_time = t;
          touch = d;
        }
        // Converged: no certified progress left at the resolution of the claim.
        if (!(g.advance > 1e-14 * t)) return fill(ContactStatus::hit, t, d);
        touch_time = t;
        touch = d;
      }
    }
    R advance = g.advance;
    if (other.never(d.normal.template cast<R>(), body, g.margin)) advance = std::numeric_limits<R>::infinity();
    if (advance == std::numeric_limits<R>::infinity() || t + advance > R(t_max)) {
      if (touched) return fill(ContactStatus::hit, touch_time, touch);
      out.status = ContactStatus::no_contact_in_window;
      return out;
    }
    if (!(t + advance > t)) {
      // No certified progress. Where the gap is within the rounding margin of the
      // configuration (thin bodies have a tangency band narrower than it) or its step below
      // the resolution of t, that is contact, as closely as the type resolves it; otherwise
      // the bounds are beyond the range of the type (speeds or spins near overflow).
      // (A slab step carries no points: the distance gives them. At times far beyond the
      // bodies' size over their speed, 4 ulps of t can exceed that slab's gap.)
      const bool resolved = g.margin <= (turning.small * turning.scale(t) + g.small) / 4;
      if (t > R(0) && resolved && g.gap <= g.margin + 4 * ulp * t * g.fastest)
        return fill(ContactStatus::hit, t, d.point_a.allFinite() ? d : other.near(body, true, d.normal));
      break;
    }
    t += advance;
    take = touched;
  }
  if (touched) return fill(ContactStatus::hit, touch_time, touch);
  out.status = ContactStatus::did_not_converge;
  out.time = T(t);
  return out;
}

}  // namespace ellipsect::detail::rigid
