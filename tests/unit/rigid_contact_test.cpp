// first_contact under rigid motion and body_at: closed-form cases, the translational
// special cases, input errors, the iteration cap and power-of-two scaling (the comparison
// with the 50-digit reference is tests/property/rigid_contact_property_test.cpp).
#include <ellipsect/contact.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using ellipsect::testing::expect_field;

template <int N>
using Omega = decltype(RigidMotion<double, N>::angular_velocity);

template <int N>
Omega<N> some_spin(double rate) {
  if constexpr (N == 2) {
    return rate;
  } else {
    return Vec<double, 3>(0.3, -0.5, 0.81).normalized() * rate;
  }
}

// Both angular velocities zero: the translational answer, its time certified early: no later
// than the translational time, and within the stated accuracy of it (1e-12 of max(t, size /
// speed)) with point and normal bit for bit; on grazing paths, where the time is accurate to
// about sqrt(tolerance) and the slab along the hit's normal may not close (the advancement
// answers then), within 1e-6.
template <int N>
void zero_spin_is_translational() {
  for (scenarios::Category category : scenarios::all_categories) {
    const bool grazing = category == scenarios::Category::grazing;
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
      const auto c = scenarios::make_case<N>(category, seed);
      const Contact<double, N> want = first_contact(c.a, c.va, c.b, c.vb, c.t_max);
      const Contact<double, N> got = first_contact(c.a, RigidMotion<double, N>{c.va}, c.b,
                                                   RigidMotion<double, N>{c.vb}, c.t_max);
      SCOPED_TRACE(std::string(scenarios::name(category)) + " seed " + std::to_string(seed));
      ASSERT_EQ(got.status, want.status);
      if (std::isnan(want.time)) {
        EXPECT_TRUE(std::isnan(got.time));
      } else if (want.status == ContactStatus::hit) {
        const double scale = std::max(c.a.radii().maxCoeff(), c.b.radii().maxCoeff()) / (c.vb - c.va).norm();
        EXPECT_LE(got.time, want.time);
        EXPECT_LE(want.time - got.time, (grazing ? 1e-6 : 1e-12) * std::max(want.time, scale));
      } else {
        EXPECT_EQ(got.time, want.time);
      }
      if (grazing) continue;
      for (int i = 0; i < N; ++i) {
        if (std::isnan(want.point[i])) continue;
        EXPECT_EQ(got.point[i], want.point[i]);
        EXPECT_EQ(got.normal[i], want.normal[i]);
      }
      EXPECT_EQ(got.iterations, want.iterations);
    }
  }
}

TEST(RigidContact, ZeroSpinIsTranslational2D) { zero_spin_is_translational<2>(); }
TEST(RigidContact, ZeroSpinIsTranslational3D) { zero_spin_is_translational<3>(); }

// Balls look the same at every orientation: a spinning ball meets another exactly when the
// translating one does (head-on: |d| - 2 v t = r_a + r_b), though the advancement runs.
template <int N>
void spinning_balls() {
  Vec<double, N> far = Vec<double, N>::Zero();
  far[0] = 10;
  const auto a = Ellipsoid<double, N>::from_axes(Vec<double, N>::Zero(), Mat<double, N>::Identity(),
                                                 Vec<double, N>::Constant(1.5));
  const auto b = Ellipsoid<double, N>::from_axes(far, Mat<double, N>::Identity(), Vec<double, N>::Constant(0.5));
  Vec<double, N> v = Vec<double, N>::Zero();
  v[0] = 2;
  const RigidMotion<double, N> ma{v, some_spin<N>(7.0)}, mb{-v, some_spin<N>(-3.0)};
  const Contact<double, N> c = first_contact(a, ma, b, mb, 100.0);
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_NEAR(c.time, 2.0, 1e-12 * 2.0);  // (10 - 2) / 4
  EXPECT_NEAR(c.point[0], 1.5 + 2 * c.time, 1e-10 * 2);
  EXPECT_NEAR(c.normal[0], 1.0, 1e-9);
  EXPECT_GT(c.iterations, 0);
  EXPECT_LE(c.time, 2.0);  // never later than the contact
}

TEST(RigidContact, SpinningBalls2D) { spinning_balls<2>(); }
TEST(RigidContact, SpinningBalls3D) { spinning_balls<3>(); }

// A thin needle of half-length L (half-width 1e-6 L) turning about its center (2D) reaches
// a ball of radius r centered at (0, D) with its tip: |L (cos phi, sin phi) - (0, D)| = r,
// sin(phi) = (L^2 + D^2 - r^2) / (2 L D), where the side of the segment would reach the
// ball only at the angle with D cos(phi) = r, whose foot sqrt(D^2 - r^2) lies beyond L. The
// needle's rounded tip makes the time that of the segment to about its half-width.
TEST(RigidContact, TurningNeedleHitsBallWithItsTip2D) {
  const double L = 2, r = 0.5, D = 2.2, omega = 1.0;  // counterclockwise, from +x towards +y
  ASSERT_GT(std::sqrt(D * D - r * r), L);
  const auto needle = Ellipsoid<double, 2>::from_axes(Vec<double, 2>::Zero(), Mat<double, 2>::Identity(),
                                                      Vec<double, 2>(L, L * 1e-6));
  const auto ball = Ellipsoid<double, 2>::from_axes(Vec<double, 2>(0, D), Mat<double, 2>::Identity(),
                                                    Vec<double, 2>::Constant(r));
  const Contact<double, 2> c = first_contact(needle, RigidMotion<double, 2>{{0, 0}, omega}, ball,
                                             RigidMotion<double, 2>{}, 10.0);
  ASSERT_EQ(c.status, ContactStatus::hit);
  const double phi = std::asin((L * L + D * D - r * r) / (2 * L * D));
  EXPECT_NEAR(c.time, phi / omega, 1e-5);
  EXPECT_LE(c.time, phi / omega);  // the real needle is no shorter than the segment
  EXPECT_NEAR((c.point - Vec<double, 2>(L * std::cos(phi), L * std::sin(phi))).norm(), 0, 1e-4);
}

TEST(RigidContact, StartStates) {
  const auto a = Ellipsoid<double, 3>::from_axes(Vec<double, 3>::Zero(), Mat<double, 3>::Identity(),
                                                 Vec<double, 3>(2, 1, 0.5));
  const auto inside = Ellipsoid<double, 3>::from_axes(Vec<double, 3>(0.5, 0, 0), Mat<double, 3>::Identity(),
                                                      Vec<double, 3>::Constant(0.2));
  const auto touching = Ellipsoid<double, 3>::from_axes(Vec<double, 3>(3, 0, 0), Mat<double, 3>::Identity(),
                                                        Vec<double, 3>::Constant(1));
  const RigidMotion<double, 3> spin{Vec<double, 3>::Zero(), Vec<double, 3>(0, 0, 1)};
  EXPECT_EQ(first_contact(a, spin, inside, RigidMotion<double, 3>{}, 1.0).status, ContactStatus::overlapping_at_start);
  const Contact<double, 3> t = first_contact(a, spin, touching, RigidMotion<double, 3>{}, 1.0);
  EXPECT_EQ(t.status, ContactStatus::touching_at_start);
  EXPECT_EQ(t.time, 0.0);
  EXPECT_NEAR(t.point[0], 2.0, 1e-10);
}

TEST(RigidContact, NeverClosingSlabMeansNoContact) {
  // Two balls moving apart, spinning: the slab between them only widens.
  const auto a = Ellipsoid<double, 2>::from_axes(Vec<double, 2>::Zero(), Mat<double, 2>::Identity(),
                                                 Vec<double, 2>::Constant(1));
  const auto b = Ellipsoid<double, 2>::from_axes(Vec<double, 2>(5, 0), Mat<double, 2>::Identity(),
                                                 Vec<double, 2>(1, 0.5));
  const Contact<double, 2> c = first_contact(a, RigidMotion<double, 2>{{-1, 0}, 3.0}, b,
                                             RigidMotion<double, 2>{{3, 0}, 0.0},
                                             std::numeric_limits<double>::infinity());
  EXPECT_EQ(c.status, ContactStatus::no_contact_in_window);
  EXPECT_TRUE(std::isnan(c.time));
}

TEST(RigidContact, InvalidInput) {
  const Ellipsoid<double, 3> a, b;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const RigidMotion<double, 3> ok{Vec<double, 3>(1, 0, 0), Vec<double, 3>(0, 0, 1)};
  RigidMotion<double, 3> bad_v = ok, bad_w = ok;
  bad_v.velocity[1] = nan;
  bad_w.angular_velocity[2] = inf;
  EXPECT_EQ(first_contact(a, bad_v, b, ok, 1.0).status, ContactStatus::invalid_input);
  EXPECT_EQ(first_contact(a, ok, b, bad_w, 1.0).status, ContactStatus::invalid_input);
  EXPECT_EQ(first_contact(a, ok, b, ok, nan).status, ContactStatus::invalid_input);
  EXPECT_EQ(first_contact(a, ok, b, ok, -1.0).status, ContactStatus::invalid_input);
  expect_field([&] { (void)body_at(a, bad_v, 1.0); }, "velocity");
  expect_field([&] { (void)body_at(a, bad_w, 1.0); }, "angular_velocity");
  expect_field([&] { (void)body_at(a, ok, inf); }, "time");
  const RigidMotion<double, 3> huge{Vec<double, 3>(1e308, 0, 0), Vec<double, 3>::Zero()};
  expect_field([&] { (void)body_at(a, huge, 1e10); }, "time");
}

TEST(RigidContact, BodyAtTurnsAboutTheCenter) {
  const auto a = Ellipsoid<double, 3>::from_axes(Vec<double, 3>(1, 2, 3), Mat<double, 3>::Identity(),
                                                 Vec<double, 3>(3, 2, 1));
  const RigidMotion<double, 3> m{Vec<double, 3>(1, 0, 0), Vec<double, 3>(0, 0, M_PI / 2)};
  const Ellipsoid<double, 3> at = body_at(a, m, 1.0);  // a quarter turn about z
  EXPECT_NEAR((at.center() - Vec<double, 3>(2, 2, 3)).norm(), 0, 1e-15);
  EXPECT_NEAR((at.axes().col(0) - Vec<double, 3>(0, 1, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((at.axes().col(1) - Vec<double, 3>(-1, 0, 0)).norm(), 0, 1e-15);
  EXPECT_TRUE((at.axes().col(2) == Vec<double, 3>(0, 0, 1)));
  EXPECT_TRUE(at.radii() == a.radii());
  const auto e = Ellipsoid<double, 2>::from_axes(Vec<double, 2>::Zero(), Mat<double, 2>::Identity(), Vec<double, 2>(2, 1));
  const Ellipsoid<double, 2> turned = body_at(e, RigidMotion<double, 2>{{0, 0}, -M_PI}, 0.5);
  EXPECT_NEAR((turned.axes().col(0) - Vec<double, 2>(0, -1)).norm(), 0, 1e-15);
}

// The iteration cap: did_not_converge with a certified lower bound on the contact time.
TEST(RigidContact, CapGivesLowerBound) {
  const auto a = Ellipsoid<double, 3>::from_axes(Vec<double, 3>::Zero(), Mat<double, 3>::Identity(),
                                                 Vec<double, 3>(2, 0.5, 0.5));
  const auto b = Ellipsoid<double, 3>::from_axes(Vec<double, 3>(20, 1, 0), Mat<double, 3>::Identity(),
                                                 Vec<double, 3>(1, 1, 0.2));
  const RigidMotion<double, 3> ma{Vec<double, 3>(1, 0, 0), Vec<double, 3>(0, 0.7, 2)}, mb{};
  const Contact<double, 3> full = first_contact(a, ma, b, mb, 100.0);
  ASSERT_EQ(full.status, ContactStatus::hit);
  ASSERT_GT(full.iterations, 3);
  Options capped;
  capped.max_motion_steps = 2;
  const Contact<double, 3> c = first_contact(a, ma, b, mb, 100.0, capped);
  EXPECT_EQ(c.status, ContactStatus::did_not_converge);
  EXPECT_GT(c.time, 0.0);
  EXPECT_LT(c.time, full.time);
  EXPECT_TRUE(std::isnan(c.point[0]));
}

// Scaling lengths and velocities by 2^k (angular velocities and times unchanged) leaves the
// time unchanged and scales the point, also beyond the native range (rescaled inside).
TEST(RigidContact, PowerOfTwoScaling) {
  const auto c = scenarios::make_contact_case<3>(scenarios::Category::random, 11, 0.3);
  const RigidMotion<double, 3> ma{c.va, Vec<double, 3>(0.2, 0.1, -0.3)}, mb{c.vb, Vec<double, 3>(-0.1, 0.4, 0)};
  const Contact<double, 3> base = first_contact(c.a, ma, c.b, mb, c.t_max);
  ASSERT_EQ(base.status, ContactStatus::hit);
  for (int k : {-200, -80, 80, 200}) {
    auto scale = [&](const Ellipsoid<double, 3>& e) {
      return Ellipsoid<double, 3>::from_axes(std::ldexp(1.0, k) * e.center(), e.axes(), std::ldexp(1.0, k) * e.radii());
    };
    RigidMotion<double, 3> sa = ma, sb = mb;
    sa.velocity *= std::ldexp(1.0, k);
    sb.velocity *= std::ldexp(1.0, k);
    const Contact<double, 3> s = first_contact(scale(c.a), sa, scale(c.b), sb, c.t_max);
    SCOPED_TRACE(k);
    ASSERT_EQ(s.status, ContactStatus::hit);
    EXPECT_EQ(s.time, base.time);
    EXPECT_TRUE((s.point == Vec<double, 3>(std::ldexp(1.0, k) * base.point)));
    EXPECT_TRUE(s.normal == base.normal);
  }
}

// Fuzzing (the CI mutation run): circles of radius 2^963 moving 1 per unit time, one turning
// at 2^500 rad per unit time, answered invalid_input. Time is rescaled to the unit in which
// they move about a radius (2^-963), where that spin overflowed. Such a pair is beyond the
// bounds' range (contact.hpp): its start state, or did_not_converge at 0. Expected from
// geometry: centers 1 apart overlap; 3 radii apart they are separated.
TEST(RigidContact, SpinOverflowingInTheRescaledTimeGivesTheStartState) {
  const double r = 0x1p963;
  const RigidMotion<double, 2> ma{{1, 1}, 1.0}, mb{{1, 1}, 0x1p500};
  const auto circle = [&](double x) { return make_ball<double, 2>({x, -r}, r); };
  const Contact<double, 2> near = first_contact(circle(1), ma, circle(2), mb, 1.0);
  EXPECT_EQ(near.status, ContactStatus::overlapping_at_start);
  const Contact<double, 2> far = first_contact(circle(0), ma, circle(3 * r), mb, 1.0);
  EXPECT_EQ(far.status, ContactStatus::did_not_converge);
  EXPECT_EQ(far.time, 0.0);
  // A spin that fits that time unit (2^40 rad per unit time, 2^1003 per new unit) still runs.
  const RigidMotion<double, 2> slower{{1, 1}, 0x1p40};
  const Contact<double, 2> runs = first_contact(circle(0), ma, circle(3 * r), slower, 1.0);
  EXPECT_EQ(runs.status, ContactStatus::no_contact_in_window);
}

TEST(RigidContact, FloatAgreesWithDouble) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const auto c = scenarios::make_contact_case<2>(scenarios::Category::random, seed, 0.3);
    const RigidMotion<double, 2> ma{c.va, 0.3}, mb{c.vb, -0.2};
    const Contact<double, 2> d = first_contact(c.a, ma, c.b, mb, c.t_max);
    const auto af = Ellipsoid<float, 2>::from_axes(c.a.center().cast<float>(), c.a.axes().cast<float>(),
                                                   c.a.radii().cast<float>());
    const auto bf = Ellipsoid<float, 2>::from_axes(c.b.center().cast<float>(), c.b.axes().cast<float>(),
                                                   c.b.radii().cast<float>());
    const Contact<float, 2> f = first_contact(af, RigidMotion<float, 2>{c.va.cast<float>(), 0.3f}, bf,
                                              RigidMotion<float, 2>{c.vb.cast<float>(), -0.2f}, float(c.t_max));
    SCOPED_TRACE(seed);
    ASSERT_EQ(f.status, d.status);
    if (d.status != ContactStatus::hit) continue;
    const double scale = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
    const double speed = (c.vb - c.va).norm() + 0.3 * c.a.radii().maxCoeff() + 0.2 * c.b.radii().maxCoeff();
    EXPECT_NEAR(f.time, d.time, 1e-4 * std::max(d.time, scale / speed));
  }
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
