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
#include "detail/gradient.hpp"
#include "detail/instantiate.hpp"
#include "detail/reduce.hpp"
#include "detail/rigid_motion.hpp"
#include "detail/scale.hpp"
#include "detail/shape_access.hpp"
#include "detail/math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ellipsect {

using namespace detail::rigid;

namespace {

// The other body as the second party of the advancement (detail/rigid_motion.hpp).
template <class T, int N>
struct BodyParty {
  Turning<T, N> turning_a;  // a's bounding ball and growth
  Vec<R, N> velocity_a;
  const Ellipsoid<T, N>& b;
  const RigidMotion<T, N>& motion_b;
  const Options& options;
  Turning<T, N> turning;
  Vec<R, N> velocity;
  Turn<T, N> turn;
  R t = 0;
  Ellipsoid<T, N> body_b;
  bool first = true;

  BodyParty(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Ellipsoid<T, N>& b_,
            const RigidMotion<T, N>& m, const Options& o) noexcept
      : turning_a(a, motion_a), velocity_a(motion_a.velocity.template cast<R>()), b(b_), motion_b(m), options(o),
        turning(b_, m), velocity(m.velocity.template cast<R>()), turn(m.angular_velocity) {}

  bool at(R time) noexcept {
    t = time;
    body_b = moved(b, motion_b, turn, T(t));
    return finite(body_b);
  }
  // Bounding balls (radius R at t) apart by more than their radii: the direction between the
  // centers gives a gap of at least R_a + R_b, and distance() is left for the near phase.
  // Also where the slab gap along that direction exceeds an eighth of the largest radii (at
  // the first step 1e-6 of them: far above the tangency band, at most 1e-9 of the size, so
  // the bodies are separated and not touching at the start) plus 64 ulps of T of the
  // separation (the slab's rounding), for radii above 2^-960 (no subnormal products): a
  // step on that slab costs two support points where a distance costs a solve.
  Distance<T, N> near(const Ellipsoid<T, N>& body_a, bool touched, const Vec<T, N>& hint) noexcept {
    const Vec<R, N> between = body_b.center().template cast<R>() - body_a.center().template cast<R>();
    const R apart = detail::stable_norm<R, N>(between);
    const R size = turning_a.big * turning_a.scale(t) + turning.big * turning.scale(t);
    bool far = apart > 2 * size;
    if (!touched && !far && apart > R(0) && std::min(turning_a.small, turning.small) > ldexp(R(1), -960)) {
      const R ulp = R(std::numeric_limits<T>::epsilon());
      const Vec<R, N> u = between / apart;
      Vec<R, N> offset;
      const R gap = apart - support(body_a, u, offset) - support(body_b, u, offset);
      far = gap > (first ? R(1e-6) : R(1) / 8) * size + 64 * ulp * (apart + size);
    }
    first = false;
    if (touched || !far) return distance(body_a, body_b, options, hint);
    return slab_step<T, N>(between / apart);
  }
  Distance<T, N> exact(const Ellipsoid<T, N>& body_a) const noexcept { return signed_distance(body_a, body_b, options); }
  Party side(const Vec<R, N>& n, const Ellipsoid<T, N>&) const noexcept {
    Vec<R, N> offset;
    const R rho = support(body_b, n, offset);
    const R center = n.dot(body_b.center().template cast<R>());
    const R across = turning.across(n), turned = turning.turn(n, offset);
    return {center - rho,
            n.dot(velocity) - turning.rate(t, rho, turned),
            -n.dot(velocity) + turning.rising(t, across),
            turning.curvature(t, across, turned),
            turning.configuration(t),
            abs(center) + rho,
            turning.rates(t),
            turning.small * turning.scale(t),
            turning.reach(t)};
  }
  // The bounding balls (radius R about the centers, growing at g_a R_a + g_b R_b) never meet
  // from t on: |p + s u| > rad + G s for every s >= 0 (p, u the centers' offset and relative
  // velocity), that is q(s) = (|u|^2 - G^2) s^2 + 2 (p . u - rad G) s + |p|^2 - rad^2 > 0,
  // decided with a margin far above its rounding.
  bool never(const Vec<R, N>&, const Ellipsoid<T, N>& body_a, R margin) const noexcept {
    const R ulp = R(std::numeric_limits<T>::epsilon());
    const Vec<R, N> rel_v = velocity - velocity_a;
    const Vec<R, N> apart = body_b.center().template cast<R>() - body_a.center().template cast<R>();
    const R radius = (turning_a.big * turning_a.scale(t) + turning.big * turning.scale(t)) * (1 + 64 * ulp) + margin;
    const R grow = (turning_a.growth * turning_a.big + turning.growth * turning.big) * (1 + 64 * ulp);
    if (grow == R(0)) {
      const R ahead = rel_v.squaredNorm() > R(0) ? std::max(R(0), -apart.dot(rel_v) / rel_v.squaredNorm()) : R(0);
      return (apart + ahead * rel_v).norm() > radius;  // the centers' closest approach from t on
    }
    const R speed2 = rel_v.squaredNorm(), a2 = speed2 - grow * grow, b1 = apart.dot(rel_v) - radius * grow;
    const R c0 = apart.squaredNorm() - radius * radius;
    const R slack = 64 * ulp * (apart.squaredNorm() + radius * radius);
    if (!(c0 > slack) || !(a2 > 64 * ulp * (speed2 + grow * grow))) return false;  // touching, or the balls catch up
    return b1 >= R(0) || c0 - b1 / a2 * b1 > slack + 64 * ulp * (b1 / a2 * abs(b1));
  }
};

// first_contact in the rescaled units (detail/scale.hpp; exact but for underflow far below
// rounding): velocities, angular velocities and growth rates all finite there.
template <class T, int N>
Contact<T, N> rescaled_first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a,
                                     const Ellipsoid<T, N>& b, const RigidMotion<T, N>& motion_b, T t_max,
                                     const Options& options, const detail::Units<true>& units) noexcept {
  auto motion = [&](const RigidMotion<T, N>& m) {
    return RigidMotion<T, N>{units.velocity(m.velocity), units.rate(m.angular_velocity), units.rate(m.growth)};
  };
  // Centers that the scaling would overflow (bodies far smaller than their coordinates):
  // the pair is moved to a's center first (an exact difference for nearby centers).
  const bool move =
      std::max(detail::max_abs(a.center()), detail::max_abs(b.center())) >= ldexp(T(1), 1000 + units.exponent);
  const Vec<T, N> origin = move ? Vec<T, N>(a.center()) : Vec<T, N>::Zero();
  auto prepared = [&](const Ellipsoid<T, N>& x) {
    return units.body(detail::ShapeAccess::unchecked<T, N>(x.center() - origin, x.axes(), x.radii()));
  };
  Contact<T, N> c = first_contact(prepared(a), motion(motion_a), prepared(b), motion(motion_b), units.time(t_max), options);
  units.times_out(c.time);
  units.lengths_out(c.point);
  if (move) c.point += origin;
  return c;
}

// The hit's last steps in the wide type (detail/wide.hpp), along the hit's normal n held fixed. The slab gap
// along any unit n is a lower bound on the distance, so advancing to the first zero of its
// lower bounds (as advance does) stays early; the bodies are formed from the given data in a's
// frame (c = c_b - c_a + t (v_b - v_a), axes exp(t [omega]x) axes_0), and the margins for
// their rounding, in the wide type's epsilon, are 2^11 times narrower than advance's, which
// stop about 70 ulps of the size short of contact: 1.5e-11 of the time scale where the
// approach's sine is 1e-3. A few steps, each a lower bound: the result is never late.
// Where neither body turns, g_n is linear in time and a lower bound on the distance before t
// as after it: one step to its root, less its rounding, certifies a time before the contact
// even where `time` lies after it (the translational answer, which is not certified); the
// result is the smaller of the two, or NaN where the slab along n does not close.
template <class T, int N>
T refined(T time, const Vec<T, N>& normal, const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a,
          const Ellipsoid<T, N>& b, const RigidMotion<T, N>& motion_b, T t_max) noexcept {
  using L = detail::WideFloat;
  const L eps = std::numeric_limits<L>::epsilon();
  const Vec<L, N> r0 = b.center().template cast<L>() - a.center().template cast<L>();
  const Vec<L, N> u = motion_b.velocity.template cast<L>() - motion_a.velocity.template cast<L>();
  const Vec<L, N> n = normal.template cast<L>().normalized();
  const Turning<T, N> ta(a, motion_a), tb(b, motion_b);
  RigidMotion<L, N> wa, wb;  // the angular velocities in L
  if constexpr (N == 2) {
    wa.angular_velocity = L(motion_a.angular_velocity);
    wb.angular_velocity = L(motion_b.angular_velocity);
  } else {
    wa.angular_velocity = motion_a.angular_velocity.template cast<L>();
    wb.angular_velocity = motion_b.angular_velocity.template cast<L>();
  }
  const L ga = L(motion_a.growth), gb = L(motion_b.growth);
  const Turn<L, N> turn_a(wa.angular_velocity), turn_b(wb.angular_velocity);
  // Support radius along n at time t, its rate (1 + g t) (omega x s) . n + g rho_0 (s the
  // support offset, rho_0 the radius at the radii at 0) and the turn's part of it (`turned`).
  auto support_at = [&](const Ellipsoid<T, N>& x, const RigidMotion<L, N>& m, const Turn<L, N>& turn, L g, L t, L& rate,
                        L& turned) {
    const Mat<L, N> axes = turn.at(t) * x.axes().template cast<L>();
    const Vec<L, N> radii = x.radii().template cast<L>();
    const Vec<L, N> w = radii.cwiseProduct(axes.transpose() * n);
    const L rho = w.norm(), scale = 1 + g * t;
    turned = scale * n.dot(spin_cross<N>(m.angular_velocity, Vec<L, N>(axes * radii.cwiseProduct(w) / rho)));
    rate = turned + g * rho;
    return scale * rho;
  };
  // A body whose axes A are orthonormal only to T's rounding has several readings: the image
  // of the ball under A diag(radii) (the support radii above), the quadric formed from A
  // (exact classification's), and A orthonormalized (Gram-Schmidt, the reference's). Along n
  // their support radii are |D A^T e|, |D A^-1 e| and |D Q^T e| (e the direction in the body's
  // frame at t, D the radii): the gap keeps the largest difference, along this n (a bound
  // over all directions, 2 |A^T A - I| R, was 2.7e-15 on axes 3 ulps from orthonormal, 2.7e-12
  // in time at sine 1e-3), so the time is early for every reading.
  struct Readings {
    Mat<L, N> stored, inverse, orthonormal;
  };
  auto readings = [](const Ellipsoid<T, N>& x) {
    Readings out{x.axes().template cast<L>(), {}, x.axes().template cast<L>()};
    out.inverse = out.stored.inverse();
    for (int pass = 0; pass < 2; ++pass)
      for (int j = 0; j < N; ++j) {
        for (int k = 0; k < j; ++k)
          out.orthonormal.col(j) -= out.orthonormal.col(k).dot(out.orthonormal.col(j)) * out.orthonormal.col(k);
        out.orthonormal.col(j).normalize();
      }
    return out;
  };
  const Readings read_a = readings(a), read_b = readings(b);
  auto spread = [&](const Ellipsoid<T, N>& x, const Readings& r, const Turn<L, N>& turn, L t) {
    const Vec<L, N> e = turn.at(t).transpose() * n;
    const Vec<L, N> radii = x.radii().template cast<L>();
    const L stored = radii.cwiseProduct(r.stored.transpose() * e).norm();
    const L quadric = radii.cwiseProduct(r.inverse * e).norm();
    const L orthonormal = radii.cwiseProduct(r.orthonormal.transpose() * e).norm();
    return std::max(abs(stored - quadric), abs(stored - orthonormal)) + 16 * eps * L(x.radii().maxCoeff());
  };
  const L speed = u.norm(), apart = r0.norm();
  // The bounds of advance (detail/rigid_motion.hpp, Turning) at t, with |omega x n| in L and
  // the factors computed in double (sweep, spin) widened by far more than their rounding.
  const L across_a = spin_cross<N>(wa.angular_velocity, n).norm();
  const L across_b = spin_cross<N>(wb.angular_velocity, n).norm();
  auto bend = [](const Turning<T, N>& x, L across) {
    return L(x.big) * L(x.big) * across * across / L(x.small) + L(x.big) * L(x.spin) * across;
  };
  auto curving = [&](const Turning<T, N>& x, L across, L g, L scale, L turned) {
    return g == 0 ? bend(x, across) * scale : L(1.125) * bend(x, across) * scale + 2 * g / scale * abs(turned);
  };
  const L inf = std::numeric_limits<L>::infinity();
  const bool still = ta.spin == 0 && tb.spin == 0;
  L t = time;
  for (int step = 0; step < 8; ++step) {
    L rate_a, rate_b, turned_a, turned_b;
    const L rho_a = support_at(a, wa, turn_a, ga, t, rate_a, turned_a),
            rho_b = support_at(b, wb, turn_b, gb, t, rate_b, turned_b);
    const L sa = 1 + ga * t, sb = 1 + gb * t;
    const L ambiguity = spread(a, read_a, turn_a, t) * sa + spread(b, read_b, turn_b, t) * sb;
    const L rate_margin =
        32 * eps * (speed + L(ta.spin * ta.big + tb.spin * tb.big) * std::max(sa, sb) + L(ga * ta.big + gb * tb.big));
    const Vec<L, N> c = r0 + t * u;
    const L along = n.dot(c);
    const L configuration =
        4 * (apart + t * speed + L(ta.big) * sa * (8 + L(ta.spin) * t) + L(tb.big) * sb * (8 + L(tb.spin) * t));
    const L gap = along - rho_a - rho_b - eps * (configuration + 8 * (abs(along) + rho_a + rho_b)) - ambiguity;
    if (still) {
      // g_n is linear in time (the radii grow linearly); the closing speed's rounding taken so
      // that the step, forward or back, falls short.
      const L closing = -n.dot(u) + rate_a + rate_b + (gap > 0 ? rate_margin : -rate_margin);
      if (!(closing > 0)) return std::numeric_limits<T>::quiet_NaN();
      const L step_to_root = gap / closing, root = t + step_to_root;
      const L early = root - 64 * eps * (abs(root) + abs(step_to_root));
      T out = T(early);
      if (L(out) > early) out = nextafter(out, T(0));
      return std::min(out, time);
    }
    if (!(gap > 0)) break;
    const L fastest = -n.dot(u) +
                      (L(ta.sweep) * across_a * sa + L(tb.sweep) * across_b * sb + ga * L(ta.big) + gb * L(tb.big)) *
                          (1 + 1e-12L) +
                      rate_margin;
    const L curvature = (curving(ta, across_a, ga, sa, turned_a) + curving(tb, across_b, gb, sb, turned_b)) * (1 + 1e-12L);
    const L reach = std::min(ga > 0 ? sa / (8 * ga) : inf, gb > 0 ? sb / (8 * gb) : inf);
    const L slope = n.dot(u) - rate_a - rate_b - rate_margin;
    const L first_order = fastest > 0 ? gap / fastest : inf;
    const L root = sqrt(slope * slope + 2 * curvature * gap);
    const L second_order = curvature > 0 ? (slope <= 0 ? 2 * gap / (root - slope) : (slope + root) / curvature)
                           : slope < 0   ? gap / -slope
                                         : inf;
    const L next = std::min(t + std::max(first_order, std::min(second_order, reach)) * (1 - 64 * eps), L(t_max));
    if (!(next > t)) break;
    t = next;
  }
  T out = T(t);
  if (L(out) > t) out = nextafter(out, T(0));
  return std::max(out, time);
}

}  // namespace

template <class T, int N>
Ellipsoid<T, N> body_at(const Ellipsoid<T, N>& body, const RigidMotion<T, N>& motion, T t) {
  if (!motion.velocity.allFinite()) throw InputError("velocity", "must be finite");
  if (!all_finite<N>(motion.angular_velocity)) throw InputError("angular_velocity", "must be finite");
  if (!(motion.growth >= T(0)) || !isfinite(motion.growth)) throw InputError("growth", "must be finite and >= 0");
  if (!isfinite(t)) throw InputError("time", "must be finite");
  const Ellipsoid<T, N> out = moved(body, motion, t);
  if (!out.center().allFinite()) throw InputError("time", "moves the center beyond the range of the type");
  if (!out.axes().allFinite()) throw InputError("time", "turns the body by an angle beyond the range of the type");
  if (!(out.radii().minCoeff() > T(0)) || !out.radii().allFinite())
    throw InputError("time", "scales the radii to zero or beyond the range of the type");
  return out;
}

template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Ellipsoid<T, N>& b,
                            const RigidMotion<T, N>& motion_b, T t_max, const Options& options) noexcept {
  if (options.tolerance.is_exact()) {  // the narrowest band (options.hpp): the advancement's statuses need one
    Options band = options;
    band.tolerance = Tolerance::min;
    return first_contact(a, motion_a, b, motion_b, t_max, band);
  }
  constexpr T nan = std::numeric_limits<T>::quiet_NaN();
  Contact<T, N> out;
  out.time = nan;
  out.point.setConstant(nan);
  out.normal.setConstant(nan);
  if (!motion_a.velocity.allFinite() || !motion_b.velocity.allFinite() || !all_finite<N>(motion_a.angular_velocity) ||
      !all_finite<N>(motion_b.angular_velocity) || !valid_growth(motion_a.growth) || !valid_growth(motion_b.growth) ||
      isnan(t_max) || t_max < T(0))
    return out;
  const R spin_a = magnitude<N>(motion_a.angular_velocity), spin_b = magnitude<N>(motion_b.angular_velocity);
  // Neither turns nor grows: the translational answer, its hit time certified early by
  // refined (where that fails, the advancement below).
  if (spin_a == R(0) && spin_b == R(0) && motion_a.growth == T(0) && motion_b.growth == T(0)) {
    Contact<T, N> c = first_contact(a, motion_a.velocity, b, motion_b.velocity, t_max, options);
    if (c.status != ContactStatus::hit) return c;
    const T t = refined<T, N>(c.time, c.normal, a, motion_a, b, motion_b, t_max);
    if (t > T(0)) {
      c.time = t;
      return c;
    }
  }
  // Beyond the bounds' range: |omega| overflows (here or in the time unit chosen below), or
  // the pair needs more than double (radius ratios beyond 2^160, the centers' offset beyond
  // 2^340 radii; detail/scale.hpp): the pair as it is solved, in a's frame below (radii of
  // 2^-550 at 2^516 from the origin, overlapping, got did_not_converge where the start state
  // is decided). Only the start state is decided there; otherwise did_not_converge at 0.
  const Vec<T, N> offset = b.center() - a.center();
  const Ellipsoid<T, N> a_rel = detail::ShapeAccess::unchecked<T, N>(Vec<T, N>::Zero(), a.axes(), a.radii());
  const Ellipsoid<T, N> b_rel = detail::ShapeAccess::unchecked<T, N>(offset, b.axes(), b.radii());
  detail::Scale scale = offset.allFinite() ? detail::scale_of(a_rel, b_rel) : detail::scale_of(a, b);
  bool out_of_range = !isfinite(spin_a) || !isfinite(spin_b) || !scale.representable();

  // Lengths rescaled by 2^-e (exact) where the radii leave 2^+-64, so that squares of radii
  // stay normal; where the speeds in those lengths would leave the range of the type, time
  // is rescaled too (detail::rigid_time_window). This query has no wide path (beyond the
  // range it decides the start state only), so it rescales through the Units alone.
  if (!scale.as_given() && !out_of_range) {
    scale.time = detail::time_exponent(scale, motion_a.velocity, motion_b.velocity, detail::rigid_time_window);
    const detail::Units<true> units{scale.exponent, scale.time};
    // Bodies 2^963 across moving 1 per unit time and turning at 2^500 rad per unit time:
    // in the time unit where they move about a radius, the spin overflows; so does a growth
    // (radii 2^996 moving at 2^-592 and growing at 2^996 per unit time: it was taken for an
    // invalid one).
    if (isfinite(units.rate(std::max(spin_a, spin_b))) && isfinite(units.rate(std::max(motion_a.growth, motion_b.growth))))
      return rescaled_first_contact(a, motion_a, b, motion_b, t_max, options, units);
    out_of_range = true;
  }

  // In a's frame (translated, not turning): a at rest at the origin, b at c_b - c_a moving
  // at v_b - v_a. The bodies formed at t and the margins for their rounding are then
  // relative to the pair's separation and its relative path, not to the distance from the
  // origin (at 8e5 sizes from it, the world frame's margins stopped the advancement 1e-9 of
  // the size early). The point is moved back with a's center at the contact time.
  const Vec<T, N> velocity = motion_b.velocity - motion_a.velocity;
  // float: the offset must be exact, or the start state in a's frame is not that of the stored
  // bodies (touching circles 4.58 apart went overlapping by the offset's last bit); double's
  // rounding lies far inside the tangency band.
  bool exact = true;
  if constexpr (sizeof(T) < sizeof(double))
    for (int i = 0; i < N; ++i) exact = exact && R(offset[i]) == R(b.center()[i]) - R(a.center()[i]);
  if (!offset.allFinite() || !velocity.allFinite() || !exact)  // differences beyond the type's range
    return advance<T, N>(a, motion_a, t_max, options, out_of_range, BodyParty<T, N>(a, motion_a, b, motion_b, options));
  RigidMotion<T, N> ma = motion_a, mb = motion_b;
  ma.velocity.setZero();
  mb.velocity = velocity;
  Contact<T, N> c = advance<T, N>(a_rel, ma, t_max, options, out_of_range, BodyParty<T, N>(a_rel, ma, b_rel, mb, options));
  if (c.status == ContactStatus::hit) c.time = refined<T, N>(c.time, c.normal, a, motion_a, b, motion_b, t_max);
  for (int i = 0; i < N; ++i)
    c.point[i] = T(detail::mul_add(R(c.time), R(motion_a.velocity[i]), R(a.center()[i])) + R(c.point[i]));
  return c;
}

template <class T, int N>
ContactGradient<T, N> first_contact_gradient(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a,
                                             const Ellipsoid<T, N>& b, const RigidMotion<T, N>& motion_b, T t_max,
                                             const Options& options) noexcept {
  using W = detail::Work<T>;
  ContactGradient<T, N> out = detail::unanswered_gradient(first_contact(a, motion_a, b, motion_b, t_max, options));
  if (out.value.status != ContactStatus::hit || motion_a.growth != T(0) || motion_b.growth != T(0)) return out;
  auto omega = [](const RigidMotion<T, N>& m) {
    if constexpr (N == 2) {
      return W(m.angular_velocity);
    } else {
      return Vec<W, 3>(m.angular_velocity.template cast<W>());
    }
  };
  try {
    const T t = out.value.time;
    detail::contact_time_gradient<T, N, W>(out, body_at(a, motion_a, t), body_at(b, motion_b, t),
                                           Vec<W, N>(b.center().template cast<W>() - a.center().template cast<W>()),
                                           motion_a.velocity.template cast<W>(), motion_b.velocity.template cast<W>(),
                                           omega(motion_a), omega(motion_b));
  } catch (const InputError&) {  // the bodies at the hit's time leave the range of T: no derivatives
  }
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                 \
  template Ellipsoid<T, N> body_at<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, T);                    \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, const Ellipsoid<T, N>&, \
                                             const RigidMotion<T, N>&, T, const Options&) noexcept;                \
  template ContactGradient<T, N> first_contact_gradient<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&,   \
                                                              const Ellipsoid<T, N>&, const RigidMotion<T, N>&, T, \
                                                              const Options&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
