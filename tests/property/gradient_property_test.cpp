// Gradients (gradient.hpp) against 50-digit central differences of the values, each value
// computed by a route of its own in the world frame: the maximum of the support gap polished
// by Newton on the sphere (signed distance), golden-section search on lambda (the
// Perram-Wertheim F, and sigma = 1 / sqrt(F) of closest approach), the secant root in time of
// that maximum and a's support point there (the contact time and point), and
// Gauss-Kronrod quadrature of the chord lengths (the overlap area).
// Bodies are moved in Real: centers, radii and velocities by h, orientations by the world
// rotation exp(h [e_j]x), so the differences see no rounding of the perturbed bodies.
#include <ellipsect/contact.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/intersect2.hpp>

#include "scenarios/rigid.hpp"
#include "tests/property/common.hpp"
#include "tests/property/gradient_common.hpp"
#include "tests/reference/contact_function_reference.hpp"
#include "tests/reference/distance_reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

namespace ellipsect::testing {
namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace gradient;
using ref::Real;

// Central differences of value(a', b') over every parameter of both bodies, h relative to
// the pair's scale for lengths.
template <int N>
void differentiate(const RBody<N>& a, const RBody<N>& b, const BodyGradient<double, N>& ga,
                   const BodyGradient<double, N>& gb, const std::function<Real(const RBody<N>&, const RBody<N>&)>& value,
                   Comparison& out) {
  const Real scale = std::max(a.rmax, b.rmax);
  out.scale = scale;
  for (int body = 0; body < 2; ++body)
    for (int k = 0; k < params<N>; ++k) {
      const Real h = kind_of<N>(k) == 1 ? Real("1e-15") : Real("1e-15") * scale;
      const Real plus = body == 0 ? value(moved<N>(a, k, h), b) : value(a, moved<N>(b, k, h));
      const Real minus = body == 0 ? value(moved<N>(a, k, -h), b) : value(a, moved<N>(b, k, -h));
      out.add(kind_of<N>(k), component<N>(body == 0 ? ga : gb, k), (plus - minus) / (2 * h));
    }
}

// The pair, also moved by `offset` (bodies far from the origin).
template <int N>
std::pair<Ellipsoid<double, N>, Ellipsoid<double, N>> placed(const scenarios::Case<N>& c, const Vec<double, N>& offset) {
  return {c.a.translated(offset), c.b.translated(offset)};
}

constexpr std::array<scenarios::Category, 8> distance_categories = {
    scenarios::Category::random,       scenarios::Category::high_aspect,  scenarios::Category::near_tangent,
    scenarios::Category::containment,  scenarios::Category::spheres,      scenarios::Category::scaled_small,
    scenarios::Category::scaled_large, scenarios::Category::far_apart};

std::string scientific(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%.2e", x);
  return s;
}

// The accuracies the headers state, of each component relative to its unit (Comparison):
// the static gradients are exact up to rounding at the returned normal; the contact time's
// carry the rounding of the hit's time and normal (contact.hpp).
constexpr double static_tolerance = 1e-12;
// closest_approach's normal is known to 1e-12 of the pair's size over a radius of curvature
// (contact_function.hpp), and moves the support points.
constexpr double approach_tolerance = 1e-11;
constexpr double rigid_contact_tolerance = 1e-11;
// Linear motion's, at closing angle alpha (|n . (v_a - v_b)| / |v_a - v_b|): the derivatives
// grow as 1 / alpha towards a graze, and the rounding of the hit's time and normal reaches them
// divided by alpha^2.
double linear_contact_tolerance(double alpha) { return 2e-12 + 1e-13 / (alpha * alpha); }
constexpr double area_tolerance = 1e-9;

template <int N>
void signed_distance_matches_differences() {
  Tally tally;
  double worst = 0;
  const int n = static_cast<int>(distance_categories.size());
  for (int i = 0; i < cases(480); ++i) {
    const auto category = distance_categories[i % n];
    const int far = i / n % 2;
    const scenarios::Case<N> c = scenarios::make_case<N>(category, 7000 + i);
    const double size = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
    const auto [a, b] = placed<N>(c, Vec<double, N>::Constant(far ? 1e6 * size : 0.0));
    const DistanceGradient<double, N> g = signed_distance_gradient(a, b);
    const ref::SignedDistance<N> r = ref::signed_distance<N>(to_ref(a), to_ref(b));
    // Several deepest directions (or nearly): not differentiable there (distance.hpp).
    if (g.value.status == DistanceStatus::overlapping && r.runner_up > r.distance - 1e-6 * size) {
      tally.add(scenarios::name(category), "tied maxima, skipped");
      continue;
    }
    const RBody<N> ra = ref::detail::make_rbody<N>(to_ref(a)), rb = ref::detail::make_rbody<N>(to_ref(b));
    Comparison cmp;
    differentiate<N>(ra, rb, g.a, g.b,
                     [&](const RBody<N>& x, const RBody<N>& y) { return ref::gap_maximum<N>(x, y, r.normal); }, cmp);
    const double e = cmp.worst();
    worst = std::max(worst, e);
    EXPECT_LE(e, static_tolerance) << describe(c) << "\n far " << far << "\n" << cmp.show();
    tally.add(scenarios::name(category), to_string(g.value.status));
  }
  tally.print("signed_distance_gradient, worst relative error " + scientific(worst));
}

template <int N>
void perram_wertheim_matches_differences() {
  Tally tally;
  double worst = 0;
  const int n = static_cast<int>(distance_categories.size());
  for (int i = 0; i < cases(240); ++i) {
    const auto category = distance_categories[i % n];
    const int far = i / n % 2;
    const scenarios::Case<N> c = scenarios::make_case<N>(category, 7100 + i);
    const double size = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
    const auto [a, b] = placed<N>(c, Vec<double, N>::Constant(far ? 1e6 * size : 0.0));
    const ContactFunctionGradient<double, N> g = perram_wertheim_gradient(a, b);
    if (g.value.status == ContactFunctionStatus::concentric) {
      // F vanishes to second order in the centers' difference: every derivative is 0.
      for (const auto& x : {g.a, g.b}) {
        EXPECT_EQ(x.center, (Vec<double, N>::Zero()));
        EXPECT_EQ(x.radii, (Vec<double, N>::Zero()));
      }
      tally.add(scenarios::name(category), "concentric");
      continue;
    }
    ASSERT_EQ(g.value.status, ContactFunctionStatus::ok) << describe(c);
    const RBody<N> ra = ref::detail::make_rbody<N>(to_ref(a)), rb = ref::detail::make_rbody<N>(to_ref(b));
    Comparison cmp;
    differentiate<N>(ra, rb, g.a, g.b,
                     [](const RBody<N>& x, const RBody<N>& y) { return ref::contact_function<N>(x, y).f; }, cmp);
    const double e = cmp.worst();
    worst = std::max(worst, e);
    EXPECT_LE(e, static_tolerance) << describe(c) << "\n far " << far << "\n" << cmp.show();
    tally.add(scenarios::name(category), "ok");
  }
  tally.print("perram_wertheim_gradient, worst relative error " + scientific(worst));
}

// sigma = 1 / sqrt(F(a, b at center(a) + u)), u = direction / |direction|, in Real.
template <int N>
Real approach_distance(const RBody<N>& a, RBody<N> b, const RVec<N>& direction) {
  b.c = a.c + direction / sqrt(direction.dot(direction));
  return 1 / sqrt(ref::contact_function<N>(a, b).f);
}

template <int N>
void closest_approach_matches_differences() {
  Tally tally;
  double worst = 0;
  const int n = static_cast<int>(distance_categories.size());
  for (int i = 0; i < cases(160); ++i) {
    const auto category = distance_categories[i % n];
    const int far = i / n % 2;
    const scenarios::Case<N> c = scenarios::make_case<N>(category, 7400 + i);
    scenarios::detail::Rng rng(static_cast<std::uint64_t>(7400 + i));
    const Vec<double, N> direction =
        scenarios::detail::unit_vector<N>(rng) * scenarios::detail::log_uniform(rng, 1e-3, 1e3);
    const double size = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
    const auto [a, b] = placed<N>(c, Vec<double, N>::Constant(far ? 1e6 * size : 0.0));
    const ClosestApproachGradient<double, N> g = closest_approach_gradient(a, b, direction);
    ASSERT_EQ(g.value.status, ContactFunctionStatus::ok) << describe(c);
    const RBody<N> ra = ref::detail::make_rbody<N>(to_ref(a)), rb = ref::detail::make_rbody<N>(to_ref(b));
    const RVec<N> d = ref::to_real<N>(direction);
    Comparison cmp;
    cmp.per_speed_floor = g.value.distance / direction.norm();  // a ball's direction derivative is 0
    differentiate<N>(ra, rb, g.a, g.b,
                     [&](const RBody<N>& x, const RBody<N>& y) { return approach_distance<N>(x, y, d); }, cmp);
    for (int k = 0; k < N; ++k) {
      const Real h = Real("1e-15") * sqrt(d.dot(d));
      const RVec<N> step = h * RVec<N>::Unit(k);
      cmp.add(3, g.direction[k],
              (approach_distance<N>(ra, rb, RVec<N>(d + step)) - approach_distance<N>(ra, rb, RVec<N>(d - step))) / (2 * h));
    }
    const double e = cmp.worst();
    worst = std::max(worst, e);
    EXPECT_LE(e, approach_tolerance) << describe(c) << "\n far " << far << "\n" << cmp.show();
    tally.add(scenarios::name(category), "ok");
  }
  tally.print("closest_approach_gradient, worst relative error " + scientific(worst));
}

// A motion in Real: velocity and angular velocity (one component in 2D).
template <int N>
struct RMotion {
  RVec<N> velocity;
  Eigen::Matrix<Real, turns<N>, 1> omega;
};

template <int N>
RMotion<N> to_real_motion(const RigidMotion<double, N>& m) {
  RMotion<N> out{ref::to_real<N>(m.velocity), {}};
  if constexpr (N == 2) {
    out.omega(0) = m.angular_velocity;
  } else {
    out.omega = ref::to_real<3>(m.angular_velocity);
  }
  return out;
}

// exp([w]x) by Rodrigues' formula in Real.
template <int N>
ref::RMat<N> rotation_of(const Eigen::Matrix<Real, turns<N>, 1>& w) {
  ref::RMat<N> q = ref::RMat<N>::Identity();
  if constexpr (N == 2) {
    q << cos(w(0)), -sin(w(0)), sin(w(0)), cos(w(0));
  } else {
    const Real angle = sqrt(w.dot(w));
    if (angle == 0) return q;
    const RVec<3> u = w / angle;
    ref::RMat<3> k;
    k << 0, -u(2), u(1), u(2), 0, -u(0), -u(1), u(0), 0;
    q += sin(angle) * k + (1 - cos(angle)) * k * k;
  }
  return q;
}

template <int N>
RBody<N> at_time(RBody<N> b, const RMotion<N>& m, const Real& t) {
  b.c += t * m.velocity;
  b.axes = rotation_of<N>(Eigen::Matrix<Real, turns<N>, 1>(t * m.omega)) * b.axes;
  ref::detail::complete_rbody<N>(b);
  return b;
}

// The hit: its time and the point where the bodies touch then.
template <int N>
struct RHit {
  Real time;
  RVec<N> point;
};

// The root in time of the gap's maximum for a and b in their motions, by the secant method
// from t0 (the root near it), the direction carried from step to step; the point is a's
// support point along the maximizing direction there, c_a + P_a n / sqrt(n . P_a n).
template <int N>
RHit<N> contact_hit(const RBody<N>& a, const RMotion<N>& ma, const RBody<N>& b, const RMotion<N>& mb, const Real& t0,
                    RVec<N> n) {
  auto data_at = [&](const Real& t) {
    const RBody<N> x = at_time<N>(a, ma, t), y = at_time<N>(b, mb, t);
    return std::pair{x, ref::detail::GapData<Real, N>{x.P, y.P, RVec<N>(y.c - x.c)}};
  };
  auto gap_at = [&](const Real& t) {
    const auto d = data_at(t).second;
    n = ref::detail::ascend<Real, N>(d, n, 24, Real("1e-44"));
    return ref::detail::gap<Real, N>(d, n);
  };
  Real t_prev = t0 * (1 + Real("1e-9")), t = t0;
  Real g_prev = gap_at(t_prev), g = gap_at(t);
  for (int step = 0; step < 40 && g != 0 && g != g_prev; ++step) {
    const Real next = t - g * (t - t_prev) / (g - g_prev);
    t_prev = t;
    g_prev = g;
    t = next;
    g = gap_at(t);
    if (abs(t - t_prev) <= Real("1e-45") * abs(t)) break;
  }
  // n is ascend's at t. Its line search compares values, which settle once the direction is
  // within the square root of the precision: the point needs Newton steps on the gradient
  // alone.
  const auto [x, d] = data_at(t);
  for (int step = 0; step < 3; ++step) {
    const Eigen::Matrix<Real, N, N - 1> q = ref::detail::tangent_basis<Real, N>(n);
    Eigen::Matrix<Real, N - 1, 1> grad;
    Eigen::Matrix<Real, N - 1, N - 1> hess;
    ref::detail::gap_derivatives<Real, N>(d, n, q, grad, hess);
    n -= q * (hess.inverse() * grad);
    n /= sqrt(n.dot(n));
  }
  const RVec<N> pn = x.P * n;
  return {t, RVec<N>(x.c + pn / sqrt(n.dot(pn)))};
}

// Entry (i, k) of a point's Jacobian by a body's parameter k (gradient.hpp's order).
template <int N>
double entry(const BodyJacobian<double, N>& j, int i, int k) {
  if (kind_of<N>(k) == 0) return j.center(i, k);
  if (kind_of<N>(k) == 2) return j.radii(i, k - N - turns<N>);
  return j.orientation(i, k - N);
}

// The contact time's gradient and the point's Jacobian of a pair that the library reports
// hit, against central differences of contact_hit over every parameter of the bodies and their
// motions. Returns the two errors, each relative to its units (Comparison).
template <int N>
std::pair<double, double> compare_contact_time(const Ellipsoid<double, N>& a, const RigidMotion<double, N>& ma,
                            const Ellipsoid<double, N>& b, const RigidMotion<double, N>& mb,
                            const ContactGradient<double, N>& g, std::string& shown) {
  const RBody<N> ra = ref::detail::make_rbody<N>(to_ref(a)), rb = ref::detail::make_rbody<N>(to_ref(b));
  const RMotion<N> rma = to_real_motion<N>(ma), rmb = to_real_motion<N>(mb);
  const RVec<N> n0 = ref::to_real<N>(Vec<double, N>(g.value.normal));
  const Real t0 = g.value.time;
  const Real scale = std::max(ra.rmax, rb.rmax);
  Comparison time, point;
  time.scale = point.scale = scale;
  // One parameter, moved by +-h: its time derivative and the point's column.
  auto add = [&](int kind, double dt, const std::function<double(int)>& dx, const Real& h,
                 const std::function<RHit<N>(const Real&)>& hit) {
    const RHit<N> plus = hit(h), minus = hit(-h);
    time.add(kind, dt, (plus.time - minus.time) / (2 * h));
    for (int i = 0; i < N; ++i) point.add(kind, dx(i), (plus.point(i) - minus.point(i)) / (2 * h));
  };
  for (int body = 0; body < 2; ++body) {
    const BodyGradient<double, N>& gt = body == 0 ? g.a : g.b;
    const BodyJacobian<double, N>& gx = body == 0 ? g.point.a : g.point.b;
    for (int k = 0; k < params<N>; ++k) {
      const Real h = kind_of<N>(k) == 1 ? Real("1e-15") : Real("1e-15") * scale;
      add(kind_of<N>(k), component<N>(gt, k), [&](int i) { return entry<N>(gx, i, k); }, h, [&](const Real& dh) {
        return body == 0 ? contact_hit<N>(moved<N>(ra, k, dh), rma, rb, rmb, t0, n0)
                         : contact_hit<N>(ra, rma, moved<N>(rb, k, dh), rmb, t0, n0);
      });
    }
    // Steps that move the bodies at the contact time by 1e-15 of their scale, or turn them by
    // 1e-15 rad.
    for (int k = 0; k < N + turns<N>; ++k) {
      const bool linear = k < N;
      const Real h = (linear ? Real("1e-15") * scale : Real("1e-15")) / t0;
      const double dt = linear ? (body == 0 ? g.velocity_a : g.velocity_b)[k]
                               : angular_component<N>(body == 0 ? g.angular_velocity_a : g.angular_velocity_b, k - N);
      auto dx = [&](int i) {
        return linear ? (body == 0 ? g.point.velocity_a : g.point.velocity_b)(i, k)
                      : (body == 0 ? g.point.angular_velocity_a : g.point.angular_velocity_b)(i, k - N);
      };
      add(linear ? 3 : 4, dt, dx, h, [&](const Real& dh) {
        RMotion<N> x = rma, y = rmb;
        RMotion<N>& m = body == 0 ? x : y;
        if (linear) {
          m.velocity(k) += dh;
        } else {
          m.omega(k - N) += dh;
        }
        return contact_hit<N>(ra, x, rb, y, t0, n0);
      });
    }
  }
  shown = "time:\n" + time.show() + "point:\n" + point.show();
  return {time.worst(), point.worst()};
}

template <int N>
void linear_contact_time_matches_differences() {
  Tally tally;
  double worst = 0, worst_scaled = 0, worst_point = 0, worst_point_scaled = 0;
  constexpr std::array<scenarios::Category, 5> categories = {
      scenarios::Category::random, scenarios::Category::high_aspect, scenarios::Category::scaled_small,
      scenarios::Category::scaled_large, scenarios::Category::far_apart};
  const int n = static_cast<int>(categories.size());
  for (int i = 0; i < cases(N == 2 ? 100 : 50); ++i) {
    const auto category = categories[i % n];
    const int far = i / n % 2;
    const scenarios::Case<N> c = scenarios::make_contact_case<N>(category, 7200 + i, 1e-3);
    const double size = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
    const auto [a, b] = placed<N>(c, Vec<double, N>::Constant(far ? 1e6 * size : 0.0));
    const ContactGradient<double, N> g = first_contact_gradient(a, c.va, b, c.vb, c.t_max);
    tally.add(scenarios::name(category), to_string(g.value.status));
    if (g.value.status != ContactStatus::hit) {
      EXPECT_TRUE(g.value.status == ContactStatus::overlapping_at_start ? g.a.center.isZero(0)
                                                                         : std::isnan(g.a.center[0]))
          << describe(c);
      continue;
    }
    RigidMotion<double, N> ma, mb;
    ma.velocity = c.va;
    mb.velocity = c.vb;
    std::string shown;
    const auto [e, ex] = compare_contact_time<N>(a, ma, b, mb, g, shown);
    worst = std::max(worst, e);
    worst_point = std::max(worst_point, ex);
    const Vec<double, N> dv = c.va - c.vb;
    const double angle = std::abs(g.value.normal.dot(dv)) / dv.norm();
    worst_scaled = std::max(worst_scaled, e * angle * angle);
    worst_point_scaled = std::max(worst_point_scaled, ex * angle * angle);
    EXPECT_LE(e, linear_contact_tolerance(angle)) << describe(c) << "\n far " << far << "\n angle " << angle << "\n" << shown;
    EXPECT_LE(ex, linear_contact_tolerance(angle)) << describe(c) << "\n far " << far << "\n angle " << angle << "\n" << shown;
  }
  tally.print("first_contact_gradient (linear), worst relative error of the time " + scientific(worst) +
              " (times the closing angle squared " + scientific(worst_scaled) + "), of the point " +
              scientific(worst_point) + " (" + scientific(worst_point_scaled) + ")");
}

template <int N>
void rigid_contact_time_matches_differences() {
  Tally tally;
  double worst = 0, worst_point = 0;
  constexpr std::array<scenarios::Spin, 6> spins = {scenarios::Spin::random, scenarios::Spin::slow,
                                                    scenarios::Spin::fast,   scenarios::Spin::needles,
                                                    scenarios::Spin::scaled_small, scenarios::Spin::scaled_large};
  for (int i = 0; i < cases(120); ++i) {
    const auto spin = spins[i % spins.size()];
    const scenarios::Moving<N> m = scenarios::make_moving<N>(spin, 7300 + i);
    const ContactGradient<double, N> g = first_contact_gradient(m.a, m.ma, m.b, m.mb, m.t_max);
    tally.add(scenarios::name(spin), to_string(g.value.status));
    if (g.value.status != ContactStatus::hit) continue;
    std::string shown;
    const auto [e, ex] = compare_contact_time<N>(m.a, m.ma, m.b, m.mb, g, shown);
    worst = std::max(worst, e);
    worst_point = std::max(worst_point, ex);
    EXPECT_LE(e, rigid_contact_tolerance) << scenarios::describe_moving<N>(spin, 7300 + i, m) << "\n" << shown;
    EXPECT_LE(ex, rigid_contact_tolerance) << scenarios::describe_moving<N>(spin, 7300 + i, m) << "\n" << shown;
  }
  tally.print("first_contact_gradient (rigid), worst relative error of the time " + scientific(worst) +
              ", of the point " + scientific(worst_point));
}

// overlap_area_gradient and intersection_over_union_gradient against central differences of
// the reference's area (Gauss-Kronrod quadrature, ~1e-25 relative) and of the IoU formed from
// it and the moved bodies' areas in Real, the bodies moved by 1e-10 of their scale (the
// quadrature's error over the step stays near 1e-15).
void area_matches_differences() {
  Tally tally;
  double worst_area = 0, worst_iou = 0;
  constexpr std::array<scenarios::Category, 6> categories = {
      scenarios::Category::random,       scenarios::Category::high_aspect,  scenarios::Category::containment,
      scenarios::Category::scaled_small, scenarios::Category::scaled_large, scenarios::Category::far_apart};
  const int n = static_cast<int>(categories.size());
  const Real pi = boost::math::constants::pi<Real>();
  auto area = [&](const RBody<2>& x) { return pi * x.radii(0) * x.radii(1); };
  for (int i = 0; i < cases(60); ++i) {
    const auto category = categories[i % n];
    const int far = i / n % 2;
    scenarios::Case<2> c = scenarios::make_case<2>(category, 7400 + i);
    const double size = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
    // The centers drawn to at most 0.6 of the radii's sum apart, so that most pairs overlap.
    const Vec<double, 2> apart = c.b.center() - c.a.center();
    if (apart.norm() > 0.6 * size) c.b = c.b.translated(Vec<double, 2>(apart * (0.6 * size / apart.norm() - 1)));
    const auto [a, b] = placed<2>(c, Vec<double, 2>::Constant(far ? 1e6 * size : 0.0));
    const OverlapAreaGradient<double> g = overlap_area_gradient(a, b);
    const IouGradient<double> u = intersection_over_union_gradient(a, b);
    tally.add(scenarios::name(category), to_string(g.value.relation));
    ASSERT_NE(g.value.relation, Relation::equal) << describe(c);
    const RBody<2> ra = ref::detail::make_rbody<2>(to_ref(a)), rb = ref::detail::make_rbody<2>(to_ref(b));
    const Real scale = std::max(ra.rmax, rb.rmax);
    // A sliver's derivatives are small, and they are formed from crossings known to
    // 1e-12 of the sizes: the units are at least those of a full overlap of the smaller
    // ellipse (its largest radius for the area, its inverse for the IoU).
    const Real smaller = area(ra) < area(rb) ? ra.rmax : rb.rmax;
    Comparison area_cmp, iou_cmp;
    area_cmp.scale = iou_cmp.scale = scale;
    area_cmp.per_length_floor = smaller;
    iou_cmp.per_length_floor = 1 / smaller;
    for (int body = 0; body < 2; ++body)
      for (int k = 0; k < params<2>; ++k) {
        const Real h = kind_of<2>(k) == 1 ? Real("1e-10") : Real("1e-10") * scale;
        Real area_at[2], iou_at[2];
        for (int side = 0; side < 2; ++side) {
          const Real step = side == 0 ? h : Real(-h);
          const RBody<2> x = body == 0 ? moved<2>(ra, k, step) : ra, y = body == 1 ? moved<2>(rb, k, step) : rb;
          area_at[side] = ref::overlap_area(x, y);
          iou_at[side] = area_at[side] / (area(x) + area(y) - area_at[side]);
        }
        area_cmp.add(kind_of<2>(k), component<2>(body == 0 ? g.a : g.b, k), (area_at[0] - area_at[1]) / (2 * h));
        iou_cmp.add(kind_of<2>(k), component<2>(body == 0 ? u.a : u.b, k), (iou_at[0] - iou_at[1]) / (2 * h));
      }
    worst_area = std::max(worst_area, area_cmp.worst());
    worst_iou = std::max(worst_iou, iou_cmp.worst());
    EXPECT_LE(area_cmp.worst(), area_tolerance) << describe(c) << "\n far " << far << "\n" << area_cmp.show();
    EXPECT_LE(iou_cmp.worst(), area_tolerance) << describe(c) << "\n far " << far << "\n" << iou_cmp.show();
  }
  tally.print("overlap_area_gradient, worst relative error " + scientific(worst_area) +
              "; intersection_over_union_gradient " + scientific(worst_iou));
}

// Where there is no derivative or it is 0 in closed form: equal ellipses (NaN), separated
// and touching (0), containment (the inner one's area derivatives).
TEST(GradientProperty, AreaAtItsSpecialSets) {
  const Ellipse2<double> e = make_ellipse<double>(Vec2<double>(1, 2), 0.3, Vec2<double>(2, 0.5));
  const OverlapAreaGradient<double> same = overlap_area_gradient(e, e);
  EXPECT_EQ(same.value.relation, Relation::equal);
  EXPECT_TRUE(std::isnan(same.a.center[0]) && std::isnan(same.b.orientation) && std::isnan(same.a.radii[1]));
  const Ellipse2<double> far = make_ellipse<double>(Vec2<double>(10, 2), 0.3, Vec2<double>(2, 0.5));
  const Ellipse2<double> touching = make_ellipse<double>(Vec2<double>(5, 2), 0.0, Vec2<double>(1, 1));
  const Ellipse2<double> at_origin = make_ellipse<double>(Vec2<double>(1, 2), 0.0, Vec2<double>(3, 1));
  for (const auto& [x, y] : {std::pair{e, far}, std::pair{at_origin, touching}}) {
    const IouGradient<double> g = intersection_over_union_gradient(x, y);
    EXPECT_TRUE(g.relation == Relation::separated || g.relation == Relation::touching);
    for (const BodyGradient<double, 2>& d : {g.a, g.b}) {
      EXPECT_EQ(d.center, Vec2<double>::Zero());
      EXPECT_EQ(d.orientation, 0.0);
      EXPECT_EQ(d.radii, Vec2<double>::Zero());
    }
  }
  const Ellipse2<double> inner = make_ellipse<double>(Vec2<double>(1.2, 2.1), 1.0, Vec2<double>(0.5, 0.2));
  const OverlapAreaGradient<double> in = overlap_area_gradient(e, inner);
  EXPECT_EQ(in.value.relation, Relation::a_contains_b);
  EXPECT_EQ(in.a.radii, Vec2<double>::Zero());
  EXPECT_DOUBLE_EQ(in.b.radii[0], std::numbers::pi * 0.2);
  EXPECT_DOUBLE_EQ(in.b.radii[1], std::numbers::pi * 0.5);
  EXPECT_EQ(in.b.center, Vec2<double>::Zero());
}

TEST(GradientProperty, SignedDistance2D) { signed_distance_matches_differences<2>(); }
TEST(GradientProperty, SignedDistance3D) { signed_distance_matches_differences<3>(); }
TEST(GradientProperty, PerramWertheim2D) { perram_wertheim_matches_differences<2>(); }
TEST(GradientProperty, PerramWertheim3D) { perram_wertheim_matches_differences<3>(); }
TEST(GradientProperty, ClosestApproach2D) { closest_approach_matches_differences<2>(); }
TEST(GradientProperty, ClosestApproach3D) { closest_approach_matches_differences<3>(); }
TEST(GradientProperty, LinearContactTime2D) { linear_contact_time_matches_differences<2>(); }
TEST(GradientProperty, LinearContactTime3D) { linear_contact_time_matches_differences<3>(); }
TEST(GradientProperty, RigidContactTime2D) { rigid_contact_time_matches_differences<2>(); }
TEST(GradientProperty, RigidContactTime3D) { rigid_contact_time_matches_differences<3>(); }
TEST(GradientProperty, OverlapAreaAndIou) { area_matches_differences(); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
}  // namespace ellipsect::testing
