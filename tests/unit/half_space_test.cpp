// half_space.hpp: the factory's checks, closed-form answers, the statuses of first_contact,
// and the range (rescaled and long double pairs give the unit-scale answers scaled exactly).
#include <ellipsect/half_space.hpp>

#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using ellipsect::testing::expect_field;
using V3 = Vec3<double>;
using V2 = Vec2<double>;
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// z <= -2.
HalfSpace<double, 3> floor_at(double z) { return make_half_space<double, 3>(V3(0, 0, z), V3(0, 0, 1)); }

TEST(HalfSpace, FactoryNormalizesTheNormalAndNamesBadFields) {
  const auto h = make_half_space<double, 3>(V3(1, 2, 3), V3(0, 0, 7));
  EXPECT_EQ(h.normal(), V3(0, 0, 1));
  EXPECT_EQ(h.point(), V3(1, 2, 3));
  const auto tiny = make_half_space<double, 2>(V2(0, 0), V2(3e-320, 4e-320));
  EXPECT_NEAR(tiny.normal()[0], 0.6, 1e-3);  // subnormal input: |n|^2 underflows, still unit
  EXPECT_NEAR(tiny.normal().norm(), 1.0, 1e-15);
  EXPECT_NEAR((make_half_space<double, 2>(V2(0, 0), V2(3e300, 4e300)).normal()[1]), 0.8, 1e-15);
  expect_field([] { make_half_space<double, 3>(V3(0, nan, 0), V3(0, 0, 1)); }, "point[1]");
  expect_field([] { make_half_space<double, 3>(V3(0, 0, 0), V3(inf, 0, 1)); }, "normal[0]");
  expect_field([] { make_half_space<double, 3>(V3(0, 0, 0), V3(0, 0, 0)); }, "normal");
  expect_field([&] { h.translated(V3(nan, 0, 0)); }, "offset[0]");
  expect_field([] { make_half_space<double, 2>(V2(1e308, 0), V2(1, 0)).translated(V2(1e308, 0)); }, "offset");
  EXPECT_EQ(h.translated(V3(1, 1, 1)).point(), V3(2, 3, 4));
  EXPECT_EQ((HalfSpace<float, 2>().normal()), Vec2<float>(0, 1));
}

TEST(HalfSpace, UnitBallAboveAndInsideAFloor) {
  const auto ball = make_ball<double, 3>(V3(0, 0, 0), 1);
  EXPECT_EQ(classify(ball, floor_at(-2)), Relation::separated);
  EXPECT_FALSE(overlap(ball, floor_at(-2)));
  const auto d = signed_distance(ball, floor_at(-2));
  EXPECT_EQ(d.status, DistanceStatus::separated);
  EXPECT_EQ(d.distance, 1.0);
  EXPECT_EQ(d.point_a, V3(0, 0, -1));
  EXPECT_EQ(d.point_b, V3(0, 0, -2));
  EXPECT_EQ(d.normal, V3(0, 0, -1));
  EXPECT_EQ(d.iterations, 0);
  EXPECT_EQ(classify(ball, floor_at(-1)), Relation::touching);
  EXPECT_EQ(classify(ball, floor_at(0.5)), Relation::overlapping);
  EXPECT_EQ(classify(ball, floor_at(1)), Relation::b_contains_a);  // tangent from inside
  EXPECT_EQ(classify(ball, floor_at(5)), Relation::b_contains_a);
  // Inside, 5 - 1 = 4 below the plane's... its lowest point is 6 below: signed distance -6.
  const auto deep = signed_distance(ball, floor_at(5));
  EXPECT_EQ(deep.status, DistanceStatus::overlapping);
  EXPECT_EQ(deep.distance, -6.0);
  EXPECT_EQ(deep.point_a, V3(0, 0, -1));
  EXPECT_EQ(deep.point_b, V3(0, 0, 5));
  const auto unsigned_deep = distance(ball, floor_at(5));
  EXPECT_EQ(unsigned_deep.distance, 0.0);
  EXPECT_TRUE(std::isnan(unsigned_deep.point_a[0]) && std::isnan(unsigned_deep.normal[2]));
}

TEST(HalfSpace, TiltedEllipseClosedForm) {
  // Radii 3 and 1, long axis along (1, 1) / sqrt 2; the half-plane y <= -5.
  const auto e = make_ellipse<double>(V2(0, 0), M_PI / 4, V2(3, 1));
  const auto h = make_half_space<double, 2>(V2(7, -5), V2(0, 1));
  // rho = |diag(3, 1) A^T (0, 1)| = sqrt(9 / 2 + 1 / 2) = sqrt 5.
  const auto d = signed_distance(e, h);
  EXPECT_NEAR(d.distance, 5 - std::sqrt(5.0), 1e-15);
  // Lowest point: -A diag(9, 1) A^T n / rho = -(9 - 1, 9 + 1) / (2 sqrt 5).
  EXPECT_NEAR(d.point_a[0], -4 / std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(d.point_a[1], -5 / std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(d.point_b[1], -5, 1e-15);
}

TEST(HalfSpace, FirstContactStatuses) {
  const auto ball = make_ball<double, 3>(V3(0, 0, 0), 1);
  const V3 zero(0, 0, 0), down(0, 0, -1);
  auto hit = first_contact(ball, down, floor_at(-2), zero, inf);
  EXPECT_EQ(hit.status, ContactStatus::hit);
  EXPECT_EQ(hit.time, 1.0);
  EXPECT_EQ(hit.point, V3(0, 0, -2));
  EXPECT_EQ(hit.normal, V3(0, 0, -1));
  // The floor rising at speed 1 as well: half the time.
  hit = first_contact(ball, down, floor_at(-2), V3(5, 0, 1), 10.0);
  EXPECT_EQ(hit.status, ContactStatus::hit);
  EXPECT_EQ(hit.time, 0.5);
  EXPECT_EQ(hit.point, V3(0, 0, -1.5));
  EXPECT_EQ(first_contact(ball, down, floor_at(-2), zero, 0.999).status, ContactStatus::no_contact_in_window);
  EXPECT_EQ(first_contact(ball, down, floor_at(-2), zero, 1.0).status, ContactStatus::hit);
  EXPECT_EQ(first_contact(ball, V3(0, 0, 1), floor_at(-2), zero, inf).status, ContactStatus::no_contact_in_window);
  EXPECT_EQ(first_contact(ball, V3(1, 0, 0), floor_at(-2), zero, inf).status, ContactStatus::no_contact_in_window);
  EXPECT_EQ(first_contact(ball, zero, floor_at(-2), zero, inf).status, ContactStatus::no_contact_in_window);
  // A contact beyond the largest double: none in the window.
  EXPECT_EQ(first_contact(ball, V3(0, 0, -1e-300), floor_at(-1e300), zero, inf).status,
            ContactStatus::no_contact_in_window);
  const auto touching = first_contact(ball, down, floor_at(-1), zero, inf);
  EXPECT_EQ(touching.status, ContactStatus::touching_at_start);
  EXPECT_EQ(touching.time, 0.0);
  EXPECT_EQ(touching.point, V3(0, 0, -1));
  const auto inside = first_contact(ball, down, floor_at(0), zero, inf);
  EXPECT_EQ(inside.status, ContactStatus::overlapping_at_start);
  EXPECT_TRUE(std::isnan(inside.point[0]));
  for (const auto& [va, vb, t_max] : {std::tuple{V3(nan, 0, 0), zero, 1.0}, std::tuple{zero, V3(0, inf, 0), 1.0},
                                      std::tuple{down, zero, nan}, std::tuple{down, zero, -1.0}}) {
    const auto bad = first_contact(ball, va, floor_at(-2), vb, t_max);
    EXPECT_EQ(bad.status, ContactStatus::invalid_input);
    EXPECT_TRUE(std::isnan(bad.time));
  }
}

// Scaled by 2^k the answers are the unit-scale answers times 2^k, bit for bit: rescaled
// (k = +-600) and long double pairs (radius 2^-700 far from the origin) alike.
// A hit so late that the body has left the range of double by then (radius 1e200, closing
// at 1e-70 with a speed of 1e100 along the plane: at t = 2e270 the point's second coordinate
// is 2e370) was a hit with an infinite point; it is did_not_converge, the time still the
// hit's, the point and normal NaN (linear and rigid, which answers the same at zero spin).
TEST(HalfSpace, HitBeyondTheRangeIsNotAHit) {
  const auto a = make_ball<double, 2>(V2(0, 0), 1e200);
  const auto h = make_half_space<double, 2>(V2(3e200, 0), V2(-1, 0));
  const double inf = std::numeric_limits<double>::infinity();
  const Contact<double, 2> linear = first_contact(a, V2(1e-70, 1e100), h, V2(0, 0), inf);
  const Contact<double, 2> rigid = first_contact(a, RigidMotion<double, 2>{V2(1e-70, 1e100), 0.0}, h, V2(0, 0), inf);
  for (const Contact<double, 2>& c : {linear, rigid}) {
    EXPECT_EQ(c.status, ContactStatus::did_not_converge);
    EXPECT_DOUBLE_EQ(c.time, 2e270);
    EXPECT_TRUE(c.point.array().isNaN().all());
    EXPECT_TRUE(c.normal.array().isNaN().all());
  }
  // Along the plane at 1e30 instead, the point stays in range (2e300): a hit.
  const Contact<double, 2> hit = first_contact(a, V2(1e-70, 1e30), h, V2(0, 0), inf);
  EXPECT_EQ(hit.status, ContactStatus::hit);
  EXPECT_TRUE(hit.point.allFinite());
}

TEST(HalfSpace, AnswersScaleExactlyAcrossTheRange) {
  const auto e = make_ellipsoid<double>(V3(0.3, -0.2, 0.9), Quat<double>(0.8, 0.2, -0.4, 0.4).normalized(), V3(1.5, 0.25, 0.7));
  const auto h = make_half_space<double, 3>(V3(0.1, 0.4, -0.6), V3(0.3, -0.5, 0.8));
  const V3 va(0.2, 0.1, -1), vb(0, 0.3, 0.5);
  const auto d = signed_distance(e, h);
  const auto hit = first_contact(e, va, h, vb, inf);
  ASSERT_EQ(hit.status, ContactStatus::hit);
  for (const int k : {-600, 600}) {
    const double s = std::ldexp(1.0, k);
    const auto es = Ellipsoid<double, 3>::from_axes(e.center() * s, e.axes(), e.radii() * s);
    const auto hs = make_half_space<double, 3>(h.point() * s, h.normal());
    const auto ds = signed_distance(es, hs);
    EXPECT_EQ(ds.distance, d.distance * s) << k;
    EXPECT_EQ(ds.point_a, V3(d.point_a * s)) << k;
    EXPECT_EQ(ds.point_b, V3(d.point_b * s)) << k;
    const auto hits = first_contact(es, V3(va * s), hs, V3(vb * s), inf);
    EXPECT_EQ(hits.time, hit.time) << k;
    EXPECT_EQ(hits.point, V3(hit.point * s)) << k;
  }
  // A body 2^-700 across, 2^300 from the origin (beyond double's reach): its answer matches
  // the same pair moved next to the origin.
  const double tiny = std::ldexp(1.0, -700), far = std::ldexp(1.0, 300);
  const auto small = make_ball<double, 3>(V3(far, 0, 3 * tiny), tiny);
  const auto small_floor = make_half_space<double, 3>(V3(far, 5, tiny), V3(0, 0, 1));
  const auto ds = signed_distance(small, small_floor);
  EXPECT_EQ(ds.distance, tiny);
  EXPECT_EQ(ds.point_a, V3(far, 0, 2 * tiny));
  EXPECT_EQ(classify(small, small_floor), Relation::separated);
  EXPECT_EQ(first_contact(small, V3(0, 0, -1), small_floor, V3(0, 0, 0), inf).time, tiny);
}

TEST(HalfSpace, FloatQueriesRoundTheDoubleAnswer) {
  const auto ball = make_ball<float, 2>(Vec2<float>(0, 0), 1);
  const auto h = make_half_space<float, 2>(Vec2<float>(0, -3), Vec2<float>(0, 1));
  EXPECT_EQ(classify(ball, h), Relation::separated);
  EXPECT_EQ(signed_distance(ball, h).distance, 2.0f);
  const auto hit = first_contact(ball, Vec2<float>(0, -2), h, Vec2<float>(0, 0), 10.0f);
  EXPECT_EQ(hit.status, ContactStatus::hit);
  EXPECT_EQ(hit.time, 1.0f);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
