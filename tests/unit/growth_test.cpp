// Growing bodies (RigidMotion::growth): closed forms for balls and for bodies growing at one
// rate at rest (the Perram-Wertheim scale factor), restarting from body_at, bodies against
// shapes, the broad phase and earliest_contact in a periodic box, input errors (the
// comparison with the 50-digit reference is tests/property/rigid_contact_property_test.cpp).
#include <ellipsect/box.hpp>
#include <ellipsect/broad_phase.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/triangle.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using ellipsect::testing::expect_field;

constexpr double inf = std::numeric_limits<double>::infinity();

// At rest, not turning, growing at g.
RigidMotion<double, 3> growing(double g) { return {Vec<double, 3>::Zero(), Vec<double, 3>::Zero(), g}; }

// The stated accuracy (contact.hpp): 1e-12 of the time, never later than it.
void expect_time(const Contact<double, 3>& c, double want) {
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_LE(c.time, want * (1 + 1e-15));
  EXPECT_NEAR(c.time, want, 1e-12 * want);
}

// Balls at rest: r_a (1 + g_a t) + r_b (1 + g_b t) = d; moving towards each other at speed v
// as well: the closing rate is v + g_a r_a + g_b r_b.
TEST(Growth, BallsMeetAtTheClosedFormTime) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.1, 3);
  for (int i = 0; i < 200; ++i) {
    const double ra = u(rng), rb = u(rng), d = ra + rb + u(rng), ga = i % 3 == 0 ? 0.0 : u(rng), gb = u(rng);
    const double v = i % 2 == 0 ? 0.0 : u(rng);
    const Vec<double, 3> dir = Vec<double, 3>(u(rng) - 1.5, u(rng) - 1.5, u(rng) - 1.5).normalized();
    const auto a = make_ball<double, 3>(Vec<double, 3>::Zero(), ra), b = make_ball<double, 3>(dir * d, rb);
    const RigidMotion<double, 3> ma{Vec<double, 3>::Zero(), Vec<double, 3>::Zero(), ga};
    const RigidMotion<double, 3> mb{-v * dir, Vec<double, 3>(0, 0, u(rng)), gb};  // a ball's spin changes nothing
    const Contact<double, 3> c = first_contact(a, ma, b, mb, inf);
    SCOPED_TRACE(i);
    // The closed form in long double from the stored data (b's center is rounded).
    using L = long double;
    const L apart = b.center().cast<L>().norm(), closing = -b.center().cast<L>().dot(mb.velocity.cast<L>()) / apart;
    expect_time(c, double((apart - L(ra) - L(rb)) / (closing + L(ga) * L(ra) + L(gb) * L(rb))));
    EXPECT_NEAR(c.normal.dot(dir), 1.0, 1e-9);
    EXPECT_NEAR((c.point - dir * (ra * (1 + ga * c.time))).norm(), 0.0, 1e-9 * d);
  }
}

// One growth rate for both, centers at rest, no turning: at time t both bodies are (1 + g t)
// times themselves about their centers, so they touch at 1 + g t = mu, the Perram-Wertheim
// scale factor of the bodies at 0 (contact_function.hpp).
TEST(Growth, EqualGrowthAtRestMeetsAtThePerramWertheimScale) {
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    const scenarios::Case<3> k = scenarios::make_case<3>(scenarios::Category::random, seed);
    const ContactFunction<double> pw = perram_wertheim(k.a, k.b);
    if (!(pw.f > 1.01)) continue;  // overlapping or nearly touching at the start
    const double g = 0.37 + 0.01 * double(seed);
    const RigidMotion<double, 3> m{Vec<double, 3>::Zero(), Vec<double, 3>::Zero(), g};
    SCOPED_TRACE(seed);
    expect_time(first_contact(k.a, m, k.b, m, inf), (std::sqrt(pw.f) - 1) / g);
  }
}

// With spins the bodies at the reported time touch: their Perram-Wertheim scale is 1 there
// (within the tangency band), above 1 a little before.
TEST(Growth, TurningGrowingBodiesTouchAtTheReportedTime) {
  int hits = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const scenarios::Case<3> k = scenarios::make_case<3>(scenarios::Category::random, seed);
    const RigidMotion<double, 3> ma{k.va, Vec<double, 3>(0.3, 1.1, -0.4), 0.2};
    const RigidMotion<double, 3> mb{k.vb, Vec<double, 3>(-0.9, 0.2, 0.5), 0.05};
    const Contact<double, 3> c = first_contact(k.a, ma, k.b, mb, inf);
    if (c.status != ContactStatus::hit) continue;
    ++hits;
    SCOPED_TRACE(seed);
    const double mu = std::sqrt(perram_wertheim(body_at(k.a, ma, c.time), body_at(k.b, mb, c.time)).f);
    EXPECT_NEAR(mu, 1.0, 1e-9);
    EXPECT_GE(mu, 1.0 - 1e-12);  // never late
  }
  EXPECT_GE(hits, 20);
}

// Translation invariance (contact.hpp: the bodies are formed in a's frame): the same turning,
// growing pairs moved about 1e6 sizes from the origin meet at the same time, within the stated
// 1e-12. The centers lie on a grid of 2^-24 and the offset is a multiple of 2^20, so that the
// moved pair is exactly the same pair.
TEST(Growth, FarFromTheOriginTheSameContact) {
  int hits = 0;
  auto on_grid = [](const Ellipsoid<double, 3>& x) {
    const Vec<double, 3> c = (x.center() * 0x1p24).array().round().matrix() * 0x1p-24;
    return Ellipsoid<double, 3>::from_axes(c, x.axes(), x.radii());
  };
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const scenarios::Case<3> k = scenarios::make_case<3>(scenarios::Category::random, seed);
    const Ellipsoid<double, 3> a = on_grid(k.a), b = on_grid(k.b);
    const RigidMotion<double, 3> ma{k.va, Vec<double, 3>(0.3, 1.1, -0.4), 0.2};
    const RigidMotion<double, 3> mb{k.vb, Vec<double, 3>(-0.9, 0.2, 0.5), 0.05};
    const Contact<double, 3> near = first_contact(a, ma, b, mb, inf);
    const double size = a.radii().maxCoeff() + b.radii().maxCoeff();
    const Vec<double, 3> far = Vec<double, 3>(3, -2, 1) * 0x1p20 * std::exp2(std::ceil(std::log2(size)));
    ASSERT_EQ(a.translated(far).center() - far, a.center());  // exact
    const Contact<double, 3> moved = first_contact(a.translated(far), ma, b.translated(far), mb, inf);
    SCOPED_TRACE(seed);
    ASSERT_EQ(moved.status, near.status);
    if (near.status != ContactStatus::hit) continue;
    ++hits;
    const double scale = std::max(near.time, size / ((k.vb - k.va).norm() + 1e-300));
    EXPECT_NEAR((moved.point - far - near.point).norm(), 0.0, 1e-10 * size + 1e-15 * far.norm());
    EXPECT_NEAR(moved.time, near.time, 1e-12 * scale);
  }
  EXPECT_GE(hits, 15);
}

// A motion restarted from body_at(t1) with growth g / (1 + g t1) is the same motion: the
// contact comes t1 later than from the start.
TEST(Growth, RestartingFromBodyAtKeepsTheContact) {
  const auto a = Ellipsoid<double, 3>::from_axes({0, 0, 0}, Mat<double, 3>::Identity(), {1, 0.5, 0.3});
  const auto b = Ellipsoid<double, 3>::from_axes({4, 0.3, 0}, Mat<double, 3>::Identity(), {0.8, 0.8, 0.2});
  const RigidMotion<double, 3> ma{{0.2, 0, 0}, {0, 0, 0.7}, 0.3}, mb{{-0.1, 0, 0}, {0.4, 0, 0}, 0.1};
  const Contact<double, 3> c = first_contact(a, ma, b, mb, inf);
  ASSERT_EQ(c.status, ContactStatus::hit);
  const double t1 = 0.4 * c.time;
  auto restarted = [&](const RigidMotion<double, 3>& m) {
    return RigidMotion<double, 3>{m.velocity, m.angular_velocity, m.growth / (1 + m.growth * t1)};
  };
  const Contact<double, 3> later = first_contact(body_at(a, ma, t1), restarted(ma), body_at(b, mb, t1), restarted(mb), inf);
  ASSERT_EQ(later.status, ContactStatus::hit);
  EXPECT_NEAR(later.time + t1, c.time, 1e-12 * c.time);
  EXPECT_NEAR((later.point - c.point).norm(), 0.0, 1e-9);
}

TEST(Growth, BodyAtScalesTheRadii) {
  const auto a = Ellipsoid<double, 2>::from_axes({1, 2}, Mat<double, 2>::Identity(), {2, 0.5});
  const RigidMotion<double, 2> m{{1, 0}, 0.0, 0.25};
  const Ellipsoid<double, 2> at = body_at(a, m, 2.0);
  EXPECT_EQ(at.radii(), (Vec<double, 2>(3, 0.75)));
  EXPECT_EQ(at.center(), (Vec<double, 2>(3, 2)));
  expect_field([&] { body_at(a, RigidMotion<double, 2>{{1, 0}, 0.0, -1.0}, 1.0); }, "growth");
  expect_field([&] { body_at(a, RigidMotion<double, 2>{{1, 0}, 0.0, std::nan("")}, 1.0); }, "growth");
  expect_field([&] { body_at(a, m, -4.0); }, "time");  // radii times 0
  expect_field([&] { body_at(a, RigidMotion<double, 2>{{0, 0}, 0.0, 1e300}, 1e300); }, "time");
}

TEST(Growth, BadGrowthIsInvalidInput) {
  const auto a = make_ball<double, 3>({0, 0, 0}, 1), b = make_ball<double, 3>({3, 0, 0}, 1);
  for (const double g : {-1.0, std::nan(""), inf}) {
    const RigidMotion<double, 3> bad = growing(g), good{};
    EXPECT_EQ(first_contact(a, bad, b, good, 1.0).status, ContactStatus::invalid_input);
    EXPECT_EQ(first_contact(a, good, b, bad, 1.0).status, ContactStatus::invalid_input);
    const auto plane = make_half_space<double, 3>({3, 0, 0}, {1, 0, 0});
    EXPECT_EQ(first_contact(a, bad, plane, Vec<double, 3>::Zero(), 1.0).status, ContactStatus::invalid_input);
    const std::vector<Ellipsoid<double, 3>> bodies{a, b};
    const std::vector<RigidMotion<double, 3>> motions{good, bad};
    expect_field([&] { earliest_contact<double, 3>(bodies, motions, 1.0); }, "motions[1].growth");
    expect_field([&] { candidate_pairs<double, 3>(bodies, motions, 0.0, 1.0); }, "motions[1].growth");
  }
}

// Options: the exact mode takes the narrowest band (the same contact); a step cap gives
// did_not_converge with a lower bound on the time; an out-of-range cap is named.
TEST(Growth, OptionsApply) {
  const auto a = Ellipsoid<double, 3>::from_axes({0, 0, 0}, Mat<double, 3>::Identity(), {1, 0.5, 0.3});
  const auto b = Ellipsoid<double, 3>::from_axes({4, 0.3, 0}, Mat<double, 3>::Identity(), {0.8, 0.8, 0.2});
  const RigidMotion<double, 3> ma{{0.2, 0, 0}, {0, 0, 0.7}, 0.3}, mb{{-0.1, 0, 0}, {0.4, 0, 0}, 0.1};
  const Contact<double, 3> c = first_contact(a, ma, b, mb, inf);
  ASSERT_EQ(c.status, ContactStatus::hit);
  const Contact<double, 3> exact = first_contact(a, ma, b, mb, inf, ellipsect::testing::exact_options);
  ASSERT_EQ(exact.status, ContactStatus::hit);
  EXPECT_NEAR(exact.time, c.time, 1e-12 * c.time);
  Options capped;
  capped.max_motion_steps = 1;
  const Contact<double, 3> k = first_contact(a, ma, b, mb, inf, capped);
  ASSERT_EQ(k.status, ContactStatus::did_not_converge);
  EXPECT_LE(k.time, c.time);
  expect_field([&] { capped.max_motion_steps = 0; }, "max_motion_steps");
}

// Derivatives are not formed for growing bodies: the value, NaN derivatives.
TEST(Growth, GradientGivesTheValueOnly) {
  const auto a = make_ball<double, 3>({0, 0, 0}, 1), b = make_ball<double, 3>({3, 0, 0}, 1);
  const RigidMotion<double, 3> m = growing(0.5);
  const ContactGradient<double, 3> g = first_contact_gradient(a, m, b, m, inf);
  ASSERT_EQ(g.value.status, ContactStatus::hit);
  EXPECT_NEAR(g.value.time, 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(g.a.center[0]));
  EXPECT_TRUE(std::isnan(g.point.a.center(0, 0)));
}

// A ball of radius r whose center lies d from the shape, growing at g and moving towards it
// at v: it touches at (d - r) / (v + g r).
TEST(Growth, BallAgainstShapes) {
  const double r = 0.5, g = 0.8, v = 0.3, d = 2.0;
  const Vec<double, 3> c(0.1, 0.2, 0.0), toward(0, 0, -1);
  const auto ball = make_ball<double, 3>(c, r);
  const RigidMotion<double, 3> m{v * toward, {0.2, 0.1, 0.3}, g};
  const double want = (d - r) / (v + g * r);
  const Vec<double, 3> still = Vec<double, 3>::Zero();
  expect_time(first_contact(ball, m, make_half_space<double, 3>({0, 0, -d}, {0, 0, 1}), still, inf), want);
  expect_time(first_contact(ball, m, make_triangle<double, 3>({-1, -1, -d}, {2, -1, -d}, {0, 2, -d}), still, inf),
              want);
  expect_time(first_contact(ball, m, make_box<double, 3>({0, 0, -d - 1}, Mat<double, 3>::Identity(), {3, 3, 1}), still,
                            inf),
              want);
  expect_time(first_contact(ball, m, make_capsule<double, 3>({-2, 0.2, -d - 0.25}, {2, 0.2, -d - 0.25}, 0.25), still,
                              inf),
              want);
  // Growing but moving away faster than it grows: never, certified.
  const RigidMotion<double, 3> away{-v * toward * 2, Vec<double, 3>::Zero(), 0.1};
  EXPECT_EQ(first_contact(ball, away, make_half_space<double, 3>({0, 0, -d}, {0, 0, 1}), still, inf).status,
            ContactStatus::no_contact_in_window);
}

// Open space: two growing balls approaching, and a third far off; the earliest contact is the
// pair's closed form.
TEST(Growth, EarliestContactInOpenSpace) {
  const std::vector<Ellipsoid<double, 3>> bodies{make_ball<double, 3>({0, 0, 0}, 1), make_ball<double, 3>({5, 0, 0}, 0.5),
                                                 make_ball<double, 3>({0, 40, 0}, 1)};
  std::vector<RigidMotion<double, 3>> motions{growing(0.5), growing(0.2), growing(0.1)};
  motions[1].velocity = Vec<double, 3>(-1, 0, 0);
  const double want = (5.0 - 1.5) / (1.0 + 0.5 + 0.1);  // closing at 1 + 0.5 * 1 + 0.2 * 0.5
  const PairContact<double, 3> first = earliest_contact<double, 3>(bodies, motions, inf);
  ASSERT_EQ(first.contact.status, ContactStatus::hit);
  EXPECT_EQ(first.pair.i, 0u);
  EXPECT_EQ(first.pair.j, 1u);
  EXPECT_LE(first.contact.time, want * (1 + 1e-15));
  EXPECT_NEAR(first.contact.time, want, 1e-12 * want);
  // The swept boxes over [0, t] hold the pair from the time the grown bodies can reach.
  const auto swept = candidate_pairs<double, 3>(bodies, motions, 0.0, want);
  EXPECT_TRUE(std::find(swept.begin(), swept.end(), IndexPair{0, 1}) != swept.end());
}

// Equal balls at rest on a periodic lattice, growing at one rate: the first contact is the
// nearest pair (through any image), at (d_min / (2 r) - 1) / g; the swept candidates hold it.
TEST(Growth, EarliestContactInAPeriodicBox) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 10);
  const double r = 0.2, g = 0.05;
  std::vector<Ellipsoid<double, 3>> bodies;
  std::vector<RigidMotion<double, 3>> motions;
  const PeriodicBox<3> box{{10, 10, 10}};
  while (bodies.size() < 60) {
    const Vec<double, 3> c(u(rng), u(rng), u(rng));
    bool clear = true;
    for (const auto& b : bodies) {
      Vec<double, 3> dc = b.center() - c;
      for (int k = 0; k < 3; ++k) dc[k] -= 10 * std::round(dc[k] / 10);
      clear = clear && dc.norm() > 3 * r;
    }
    if (!clear) continue;
    bodies.push_back(make_ball<double, 3>(c, r));
    motions.push_back(growing(g));
  }
  double nearest = inf;
  std::uint32_t bi = 0, bj = 0;
  for (std::uint32_t i = 0; i < bodies.size(); ++i)
    for (std::uint32_t j = i + 1; j < bodies.size(); ++j) {
      Vec<double, 3> dc = bodies[j].center() - bodies[i].center();
      for (int k = 0; k < 3; ++k) dc[k] -= 10 * std::round(dc[k] / 10);
      if (dc.norm() < nearest) nearest = dc.norm(), bi = i, bj = j;
    }
  const double want = (nearest / (2 * r) - 1) / g;
  const PairContact<double, 3> first = earliest_contact<double, 3>(bodies, motions, inf, box);
  ASSERT_EQ(first.contact.status, ContactStatus::hit);
  EXPECT_EQ(first.pair.i, bi);
  EXPECT_EQ(first.pair.j, bj);
  EXPECT_LE(first.contact.time, want * (1 + 1e-15));
  EXPECT_NEAR(first.contact.time, want, 1e-12 * want);
  const auto swept = candidate_pairs<double, 3>(bodies, motions, 0.0, want * 1.001, box);
  EXPECT_TRUE(std::any_of(swept.begin(), swept.end(), [&](const ImagePair<3>& p) { return p.i == bi && p.j == bj; }));
  // A body that grows past a quarter of the side before any contact: named.
  const std::vector<Ellipsoid<double, 3>> two{make_ball<double, 3>({1, 1, 1}, r), make_ball<double, 3>({6, 6, 6}, r)};
  const std::vector<RigidMotion<double, 3>> grow{growing(100), growing(0)};
  expect_field([&] { earliest_contact<double, 3>(two, grow, inf, PeriodicBox<3>{{30, 30, 30}}); }, "box");
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
