// capsule.hpp on cases solved by hand: the factory's checks; a ball and a capsule (the
// distance between the center and the segment less both radii), an ellipsoid's long axis
// meeting the capsule's end, containment both ways, a ball falling onto a lying capsule, a
// graze, statuses, float.
#include <ellipsect/capsule.hpp>

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

TEST(Capsule, FactoryChecksItsFields) {
  const auto c = make_capsule<double, 3>(V3(0, 0, 0), V3(1, 0, 0), 0.5);
  EXPECT_EQ(c.point(1), V3(1, 0, 0));
  EXPECT_EQ(c.radius(), 0.5);
  expect_field([] { make_capsule<double, 3>(V3(0, std::nan(""), 0), V3(1, 0, 0), 0.5); }, "p0[1]");
  expect_field([] { make_capsule<double, 3>(V3(0, 0, 0), V3(inf, 0, 0), 0.5); }, "p1[0]");
  expect_field([] { make_capsule<double, 3>(V3(0, 0, 0), V3(1, 0, 0), 0.0); }, "radius");
  expect_field([] { make_capsule<double, 3>(V3(0, 0, 0), V3(1, 0, 0), -1.0); }, "radius");
  expect_field([] { make_capsule<double, 2>(V2(0, 0), V2(1, 0), std::nan("")); }, "radius");
  expect_field([&] { (void)c.translated(V3(0, inf, 0)); }, "offset[1]");
  expect_field([] { (void)make_capsule<double, 2>(V2(1e308, 0), V2(0, 0), 1.0).translated(V2(1e308, 0)); }, "offset");
  EXPECT_EQ(c.translated(V3(0, 2, 0)).point(0), V3(0, 2, 0));
}

TEST(Capsule, BallAndCapsule) {
  const auto ball = make_ball<double, 3>(V3(0, 0, 5), 1.0);
  const auto lying = make_capsule<double, 3>(V3(-3, 0, 0), V3(3, 0, 0), 0.5);
  const Distance<double, 3> d = signed_distance(ball, lying);
  EXPECT_EQ(d.status, DistanceStatus::separated);
  EXPECT_NEAR(d.distance, 5 - 1 - 0.5, 1e-14);
  EXPECT_LE((d.normal - V3(0, 0, -1)).norm(), 1e-14);
  EXPECT_LE((d.point_a - V3(0, 0, 4)).norm(), 1e-14);
  EXPECT_LE((d.point_b - V3(0, 0, 0.5)).norm(), 1e-14);
  EXPECT_EQ(classify(ball, lying), Relation::separated);
  // Beyond the end: the distance to the end point.
  const auto beyond = make_ball<double, 3>(V3(7, 0, 3), 1.0);
  EXPECT_NEAR(signed_distance(beyond, lying).distance, 5 - 1 - 0.5, 1e-14);
  // Overlapping by 0.25: pushed out along the normal.
  const auto sunk = make_ball<double, 3>(V3(1, 0, 1.25), 1.0);
  EXPECT_EQ(classify(sunk, lying), Relation::overlapping);
  EXPECT_NEAR(signed_distance(sunk, lying).distance, -0.25, 1e-14);
  EXPECT_EQ(distance(sunk, lying).distance, 0.0);
  EXPECT_TRUE(std::isnan(distance(sunk, lying).normal[0]));
}

TEST(Capsule, LongAxisMeetsTheEnd) {
  // Ellipse radii (4, 1) along x; a vertical stadium whose lower end ball is centered at (6, 0).
  const auto e = make_ellipse<double>(V2::Zero(), 0.0, V2(4, 1));
  const auto s = make_capsule<double, 2>(V2(6, 0), V2(6, 9), 1.0);
  EXPECT_NEAR(signed_distance(e, s).distance, 1, 1e-14);
  EXPECT_EQ(classify(e, s), Relation::separated);
  const auto touching = make_capsule<double, 2>(V2(5, 0), V2(5, 9), 1.0);
  EXPECT_EQ(classify(e, touching), Relation::touching);
}

TEST(Capsule, Containment) {
  const auto big = make_ball<double, 3>(V3::Zero(), 10.0);
  EXPECT_EQ(classify(big, make_capsule<double, 3>(V3(-1, 0, 0), V3(1, 0, 0), 1.0)), Relation::a_contains_b);
  // The end ball pokes out: 8.5 + 2 > 10.
  EXPECT_EQ(classify(big, make_capsule<double, 3>(V3(-1, 0, 0), V3(8.5, 0, 0), 2.0)), Relation::overlapping);
  const auto small = make_ellipsoid<double>(V3(0, 0, 0), Eigen::Quaterniond::Identity(), V3(2, 1, 1));
  EXPECT_EQ(classify(small, make_capsule<double, 3>(V3(0, 0, -5), V3(0, 0, 5), 2.5)), Relation::b_contains_a);
  // Radius 1.5 < 2: the body's long axis crosses the capsule's surface. The least push is
  // along y, where the body reaches 1: 1 + 1.5 (along x it would take 2 + 1.5).
  EXPECT_EQ(classify(small, make_capsule<double, 3>(V3(0, 0, -5), V3(0, 0, 5), 1.5)), Relation::overlapping);
  const Distance<double, 3> deep = signed_distance(small, make_capsule<double, 3>(V3(0, 0, -5), V3(0, 0, 5), 1.5));
  EXPECT_NEAR(deep.distance, -2.5, 1e-13);
  EXPECT_NEAR(std::abs(deep.normal[1]), 1, 1e-13);
}

TEST(Capsule, BallFallsOntoALyingCapsule) {
  const auto ball = make_ball<double, 3>(V3(1, 0, 5), 1.0);
  const auto lying = make_capsule<double, 3>(V3(-3, 0, 0), V3(3, 0, 0), 0.5);
  const Contact<double, 3> c = first_contact(ball, V3(0, 0, -2), lying, V3::Zero(), inf);
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_NEAR(c.time, 3.5 / 2, 1e-14);
  EXPECT_LE((c.point - V3(1, 0, 0.5)).norm(), 1e-13);
  EXPECT_LE((c.normal - V3(0, 0, -1)).norm(), 1e-13);
  // The capsule moving instead, and a window that ends before the contact.
  EXPECT_NEAR(first_contact(ball, V3::Zero(), lying, V3(0, 0, 2), inf).time, 1.75, 1e-14);
  EXPECT_EQ(first_contact(ball, V3(0, 0, -2), lying, V3::Zero(), 1.7).status, ContactStatus::no_contact_in_window);
  // Passing beside it, and moving away.
  EXPECT_EQ(first_contact(ball, V3(0, 2, 0), lying, V3::Zero(), inf).status, ContactStatus::no_contact_in_window);
  EXPECT_EQ(first_contact(ball, V3(0, 0, 1), lying, V3::Zero(), inf).status, ContactStatus::no_contact_in_window);
  // Falling past the end: meets the end ball (center (3, 0, 0)) when the centers are 1.5
  // apart: (1.2, 0, 5 - t), 5 - t = 0.9.
  const auto side = make_ball<double, 3>(V3(4.2, 0, 5), 1.0);
  const Contact<double, 3> end = first_contact(side, V3(0, 0, -1), lying, V3::Zero(), inf);
  ASSERT_EQ(end.status, ContactStatus::hit);
  EXPECT_NEAR(end.time, 4.1, 1e-13);
  // A graze (the centers 1.5 apart at closest approach, t = 5: a double root of the gap):
  // found where the gap is within 1e-14 of the size, the time to about its square root.
  const auto graze = make_ball<double, 3>(V3(4.5, 0, 5), 1.0);
  const Contact<double, 3> g = first_contact(graze, V3(0, 0, -1), lying, V3::Zero(), inf);
  ASSERT_EQ(g.status, ContactStatus::hit);
  EXPECT_NEAR(g.time, 5, 1e-6);
}

// Options::max_contact_iterations caps the contact-time Newton: a graze (a double root,
// which Newton approaches linearly) stopped after one step is did_not_converge, its time an
// iterate short of the contact.
TEST(Capsule, ContactIterationCapIsReported) {
  const auto graze = make_ball<double, 3>(V3(4.5, 0, 5), 1.0);
  const auto lying = make_capsule<double, 3>(V3(-3, 0, 0), V3(3, 0, 0), 0.5);
  const Contact<double, 3> full = first_contact(graze, V3(0, 0, -1), lying, V3::Zero(), inf);
  ASSERT_EQ(full.status, ContactStatus::hit);
  const Contact<double, 3> one =
      first_contact(graze, V3(0, 0, -1), lying, V3::Zero(), inf, Options{.max_contact_iterations = 1});
  EXPECT_EQ(one.status, ContactStatus::did_not_converge);
  EXPECT_LT(one.time, full.time);
}

TEST(Capsule, StatusesAtTheStartAndBadMotion) {
  const auto ball = make_ball<double, 3>(V3(0, 0, 1.5), 1.0);
  const auto lying = make_capsule<double, 3>(V3(-3, 0, 0), V3(3, 0, 0), 0.5);
  const Contact<double, 3> t = first_contact(ball, V3(0, 0, -1), lying, V3::Zero(), inf);
  EXPECT_EQ(t.status, ContactStatus::touching_at_start);
  EXPECT_EQ(t.time, 0.0);
  const auto inside = make_ball<double, 3>(V3(0, 0, 1), 1.0);
  EXPECT_EQ(first_contact(inside, V3(0, 0, -1), lying, V3::Zero(), inf).status, ContactStatus::overlapping_at_start);
  EXPECT_EQ(first_contact(ball, V3(0, std::nan(""), 0), lying, V3::Zero(), inf).status, ContactStatus::invalid_input);
  EXPECT_EQ(first_contact(ball, V3::Zero(), lying, V3::Zero(), -1.0).status, ContactStatus::invalid_input);
}

TEST(Capsule, FloatBodies) {
  const auto ball = make_ball<float, 2>(Vec2<float>(0, 5), 1.0f);
  const auto lying = make_capsule<float, 2>(Vec2<float>(-3, 0), Vec2<float>(3, 0), 0.5f);
  EXPECT_NEAR(signed_distance(ball, lying).distance, 3.5f, 1e-6f);
  const Contact<float, 2> c = first_contact(ball, Vec2<float>(0, -1), lying, Vec2<float>(0, 0), 100.0f);
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_NEAR(c.time, 3.5f, 1e-5f);
}

// A scene at 1e-299 (found by the queries fuzz target): the spheres' pre-test of overlap
// squared lengths that underflowed to 0 and read a ball 2.3 radii from the capsule as
// overlapping, while classify said separated. The pre-test now works on lengths scaled by
// a power of two.
TEST(Capsule, OverlapAtTinyScaleAgreesWithClassify) {
  const double x = 0x1.dddddddddddddp-994;
  const auto ball = make_ball<double, 3>({x, x, x}, x);
  for (const double scale : {1.0, 0x1p-60, 0x1p+900}) {
    const double s = x * scale;
    const auto ball_s = make_ball<double, 3>({s, s, s}, s);
    const auto capsule = make_capsule<double, 3>({0, 5.3 * s, s}, {2 * s, 5.3 * s, s}, s);
    EXPECT_EQ(classify(ball_s, capsule), Relation::separated) << scale;
    EXPECT_FALSE(overlap(ball_s, capsule)) << scale;
  }
  EXPECT_TRUE(overlap(ball, make_capsule<double, 3>({0, 2.5 * x, x}, {2 * x, 2.5 * x, x}, x)));
}

// A needle whose center lies inside the capsule while its tip sticks out (the tip (1, 0, 0)
// is 0.989 from the segment, R = 0.6) read as b_contains_a: the segment lies off the needle
// (the gap of body and segment is positive), so the support maxima held reach (the body's
// support function against the segment's) only at the largest roots' directions, none of
// which looks along the needle. Containment is now decided on every stationary direction.
// A needle short enough to fit (tips 0.58 from the segment, R = 0.7) is inside.
TEST(Capsule, NeedleStickingOutIsNotInside) {
  const auto needle = Ellipsoid<double, 3>::from_axes(V3::Zero(), Mat3<double>::Identity(), V3(1, 0.01, 0.01));
  const auto capsule = make_capsule<double, 3>(V3(0, 0.5, -0.3), V3(0.2, 0.5, 0.3), 0.6);
  EXPECT_EQ(classify(needle, capsule), Relation::overlapping);
  EXPECT_TRUE(overlap(needle, capsule));
  EXPECT_EQ(signed_distance(needle, capsule).status, DistanceStatus::overlapping);
  const auto fits = Ellipsoid<double, 3>::from_axes(V3::Zero(), Mat3<double>::Identity(), V3(0.2, 0.01, 0.01));
  EXPECT_EQ(classify(fits, make_capsule<double, 3>(V3(0, 0.5, -0.3), V3(0.2, 0.5, 0.3), 0.7)), Relation::b_contains_a);
  // 2D: the tip (1, 0) is 0.943 from the segment's end (0.2, 0.5).
  const auto needle2 = make_ellipse<double>(V2::Zero(), 0.0, V2(1, 0.01));
  EXPECT_EQ(classify(needle2, make_capsule<double, 2>(V2(0, 0.5), V2(0.2, 0.5), 0.6)), Relation::overlapping);
}

// A ball whose center is a subnormal offset from a zero-length capsule (a ball of radius 1):
// in the ball's frame the capsule's point had coordinates whose squares underflowed the
// secular terms, and a ball's hard-case directions need them 0: no direction came out,
// and the signed distance was -infinity with a zero normal. Coordinates within eps of the
// radii are now 0: the penetration depth r + R.
TEST(Capsule, PointCapsuleSubnormalOffFromABallsCenter) {
  const double s = 4.058311769621644e-312, r = 11.594921875000001;
  const auto ball = make_ball<double, 3>({s, 1.1 * s, 1.2 * s}, r);
  const auto point = make_capsule<double, 3>(V3::Zero(), V3::Zero(), 1.0);
  const Distance<double, 3> d = signed_distance(ball, point);
  EXPECT_EQ(d.status, DistanceStatus::overlapping);
  EXPECT_NEAR(d.distance, -(r + 1), 1e-14 * r);
  EXPECT_NEAR(d.normal.norm(), 1, 1e-15);
  EXPECT_NEAR((d.point_a - ball.center()).norm(), r, 1e-14 * r);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
