// Regressions: pairs at the ends of the double range (docs/method.md, section 7). Every
// expected value is a closed form (balls, axis-aligned ellipses on a line).
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/intersect2.hpp>
#include <ellipsect/point.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using V2 = Vec2<double>;
using V3 = Vec3<double>;
constexpr double inf = std::numeric_limits<double>::infinity();

void expect_relative(double got, double want, double tol = 1e-12) {
  EXPECT_LE(std::abs(got - want), tol * std::abs(want)) << "got " << got << ", want " << want;
}

// The distance's solve forms products of up to four lengths in 2D (six in 3D), such as the
// determinant of the Perram-Wertheim matrix: at 1e100 they overflow, the descent ran on NaN
// to the iteration cap and answered did_not_converge with a NaN distance, where a
// non-converged answer promises a lower bound. Pairs outside 2^+-64 now run rescaled to
// unit size by a power of two, and the lengths are scaled back exactly.
TEST(Scales, EllipsesOfSize1e100HaveADistance) {
  const double s = 1e100;
  const auto a = make_ellipse<double>(V2(0, 0), 0, V2(2 * s, s));
  const auto b = make_ellipse<double>(V2(5 * s, 0), 0, V2(1.5 * s, 0.7 * s));
  for (const auto& d : {distance(a, b), signed_distance(a, b)}) {
    EXPECT_EQ(d.status, DistanceStatus::separated);
    expect_relative(d.distance, 1.5 * s);
    EXPECT_LE((d.point_a - V2(2 * s, 0)).norm(), 1e-12 * s);
    EXPECT_LE((d.point_b - V2(3.5 * s, 0)).norm(), 1e-12 * s);
    EXPECT_LE((d.normal - V2(1, 0)).norm(), 1e-12);
  }
  // The rotated pair of the report: a finite, converged answer.
  const auto c = make_ellipse<double>(V2(0, 0), 0.3, V2(2e100, 1e100));
  const auto e = make_ellipse<double>(V2(5e100, 1e100), 1.1, V2(1.5e100, 0.7e100));
  const auto d = distance(c, e);
  EXPECT_EQ(d.status, DistanceStatus::separated);
  EXPECT_TRUE(std::isfinite(d.distance) && d.distance > 0);
  EXPECT_NEAR(d.normal.norm(), 1, 1e-15);
}

// The contact normal is S's quadric gradient, of size 1 / radius = 1e300, normalized by its
// norm, whose square overflows: (0, 1e300) / inf gave the normal [0, -0].
TEST(Scales, CirclesOfRadius1e300thHitWithAUnitNormal) {
  const double r = 1e-300;
  const auto a = make_ball<double, 2>(V2(0, 0), r);
  const auto b = make_ball<double, 2>(V2(0, 3 * r), r);
  const auto c = first_contact(a, V2(0, 0), b, V2(0, -r), 10.0);  // gap r closed at speed r
  ASSERT_EQ(c.status, ContactStatus::hit);
  expect_relative(c.time, 1);
  EXPECT_LE((c.point - V2(0, r)).norm(), 1e-12 * r);
  EXPECT_LE((c.normal - V2(0, 1)).norm(), 1e-12);
}

// Two balls of radius k, 3k apart: the distance's solve forms products of up to six lengths
// (the 3x3 Perram-Wertheim determinant is of order k^6: 1e-312 at k = 1e-52, 1e462 at 1e77),
// and the descent ran on NaN to the iteration cap (did_not_converge, distance NaN).
TEST(Scales, BallsOfRadius1e52thAnd1e77HaveADistance) {
  for (const double k : {1e-52, 1e77}) {
    const auto a = make_ball<double, 3>(V3(0, 0, 0), k);
    const auto b = make_ball<double, 3>(V3(3 * k, 0, 0), k);
    for (const auto& d : {distance(a, b), signed_distance(a, b)}) {
      EXPECT_EQ(d.status, DistanceStatus::separated) << k;
      expect_relative(d.distance, k);
      EXPECT_LE((d.point_a - V3(k, 0, 0)).norm(), 1e-12 * k);
      EXPECT_LE((d.point_b - V3(2 * k, 0, 0)).norm(), 1e-12 * k);
      EXPECT_LE((d.normal - V3(1, 0, 0)).norm(), 1e-12);
    }
  }
}

// from_quadric(denorm_min I) gives radii 4.5e161, whose squares overflow: signed_distance
// returned -inf. Bodies the factories accept are now all rescaled into range.
TEST(Scales, RadiiFromASubnormalQuadricHaveASignedDistance) {
  const auto a = Ellipsoid3<double>::from_quadric(V3(0, 0, 0), Mat3<double>::Identity() * std::numeric_limits<double>::denorm_min());
  const double r = a.radii()[0];
  ASSERT_GT(r, 4e161);
  const auto apart = signed_distance(a, make_ball<double, 3>(V3(4 * r, 0, 0), r));
  EXPECT_EQ(apart.status, DistanceStatus::separated);
  expect_relative(apart.distance, 2 * r);
  const auto deep = signed_distance(a, make_ball<double, 3>(V3(r, 0, 0), r));  // depth 2r - r
  EXPECT_EQ(deep.status, DistanceStatus::overlapping);
  expect_relative(deep.distance, -r);
  EXPECT_LE((deep.normal - V3(1, 0, 0)).norm(), 1e-12);
}

// A ball of radius 1e300 around one of 1e-300: classify (decided in long double) said
// a_contains_b while first_contact, in double, lost the pair's radius ratio (1e600, squared
// beyond the range) and answered no_contact_in_window. The pair is not representable in
// double (radius ratio 1e600), so every query now runs it in long double.
TEST(Scales, HugeBallAroundATinyOneOverlapsInEveryQuery) {
  const auto a = make_ball<double, 3>(V3(0, 0, 0), 1e300);
  const auto b = make_ball<double, 3>(V3(0, 0, 0), 1e-300);
  EXPECT_EQ(classify(a, b), Relation::a_contains_b);
  EXPECT_EQ(classify(b, a), Relation::b_contains_a);
  EXPECT_TRUE(overlap(a, b));
  EXPECT_EQ(first_contact(a, V3(0, 0, 0), b, V3(1, 0, 0), 1.0).status, ContactStatus::overlapping_at_start);
  EXPECT_EQ(distance(a, b).status, DistanceStatus::overlapping);
  const auto d = signed_distance(a, b);  // the small ball leaves after moving 1e300 + 1e-300
  EXPECT_EQ(d.status, DistanceStatus::overlapping);
  expect_relative(d.distance, -1e300);
}

// Balls of radius 1e-200 three radii apart: every squared length of the pair (about 1e-400)
// underflows to zero, and distance answered overlapping.
TEST(Scales, BallsOfRadius1e200thApartAreSeparated) {
  const double r = 1e-200;
  const auto a = make_ball<double, 3>(V3(0, 0, 0), r);
  const auto b = make_ball<double, 3>(V3(3 * r, 0, 0), r);
  EXPECT_EQ(classify(a, b), Relation::separated);
  EXPECT_FALSE(overlap(a, b));
  const auto d = distance(a, b);
  EXPECT_EQ(d.status, DistanceStatus::separated);
  expect_relative(d.distance, r);
}

// Radii 1e299 closing at speed 2e-300 would touch at t = 5e598, beyond the largest double:
// the time overflowed and a `hit` at t = inf came back. Such a contact is outside every
// window; a representable time on the same pair is still a hit.
TEST(Scales, ContactBeyondTheLargestTimeIsNoContact) {
  const double r = 1e299;
  const auto a = make_ball<double, 3>(V3(0, 0, 0), r);
  const auto b = make_ball<double, 3>(V3(3 * r, 0, 0), r);
  const auto never = first_contact(a, V3(1e-300, 0, 0), b, V3(-1e-300, 0, 0), inf);
  EXPECT_EQ(never.status, ContactStatus::no_contact_in_window);
  EXPECT_TRUE(std::isnan(never.time));
  const auto hit = first_contact(a, V3(1e290, 0, 0), b, V3(-1e290, 0, 0), inf);  // gap r at 2e290
  ASSERT_EQ(hit.status, ContactStatus::hit);
  expect_relative(hit.time, 5e8);
  EXPECT_LE((hit.point - V3(r + 5e8 * 1e290, 0, 0)).norm(), 1e-10 * r);
  EXPECT_LE((hit.normal - V3(1, 0, 0)).norm(), 1e-12);
}

// A unit circle meeting a circle R times larger: for R beyond 1/eps the unit body is
// smaller than the rounding of the other's coordinates in the reduced frame, and at R = 1e30
// (and in a fuzzed pair of radii 8 and 1.2e294 in long double) the reduced closest point
// rounded to the origin: `hit` with the right time but a NaN point and normal. There the
// normal now comes from the large body's quadric at the small one's center. Closed form:
// b's center runs along y = 0.6 R and touches when its distance from a's is R + 1.
TEST(Scales, HitOfASmallCircleOnAHugeOneHasAPointAndNormal) {
  for (const double big : {1e3, 1e16, 1e20, 1e30, 1e50, 1e100, 1e200, 1e294}) {
    SCOPED_TRACE("R = " + std::to_string(big));
    const auto a = make_ball<double, 2>(V2(0, 0), big);
    const auto b = make_ball<double, 2>(V2(3 * big, 0.6 * big), 1.0);
    const long double R = big, x = std::sqrt((R + 1) * (R + 1) - 0.36L * R * R);
    const V2 n(double(x / (R + 1)), double(0.6L * R / (R + 1)));
    for (const bool swap : {false, true}) {
      const auto c = swap ? first_contact(b, V2(-1, 0), a, V2(0, 0), inf) : first_contact(a, V2(0, 0), b, V2(-1, 0), inf);
      ASSERT_EQ(c.status, ContactStatus::hit);
      expect_relative(c.time, double(3 * R - x));
      EXPECT_LE((c.point - double(R) * n).norm(), 1e-10 * big);
      EXPECT_LE((c.normal - (swap ? V2(-n) : n)).norm(), 1e-9);
    }
  }
}

// Both bodies at speed 8, closing at a subnormal 5e-318: they would touch at about 1e317,
// beyond the largest double. Time rescaling looks at the speeds (8), not at how fast the
// bodies close, so the native solve ran Newton to t = inf and returned `hit` at time inf
// with a NaN point (found by fuzzing). It is now no contact, as at every other scale.
// Closing at 1e-300 instead, they touch at 1e300; the swept-ball certificate formed |v|^2,
// which underflowed to 0 below relative speeds of 1e-154, took the closest approach at t = 0
// and answered no contact, silently. Such pairs now take the exact path.
TEST(Scales, ClosingAtASubnormalSpeedIsNoContact) {
  const auto a = make_ball<double, 2>(V2(0, 0), 1);
  const auto b = make_ball<double, 2>(V2(0, 3), 1);
  for (const bool swap : {false, true}) {
    const V2 va(-8, 0), vb(-8, -0x0.00000000301p-1022);
    const auto c = swap ? first_contact(b, vb, a, va, inf) : first_contact(a, va, b, vb, inf);
    EXPECT_EQ(c.status, ContactStatus::no_contact_in_window);
    EXPECT_TRUE(std::isnan(c.time) && c.point.hasNaN() && c.normal.hasNaN());
  }
  for (const double closing : {1e-160, 1e-170, 1e-300}) {  // gap 1
    const auto hit = first_contact(a, V2(-8, 0), b, V2(-8, -closing), inf);
    ASSERT_EQ(hit.status, ContactStatus::hit);
    expect_relative(hit.time, 1 / closing);
  }
}

// Query point 1e-200 from a ball's center, on its diagonal: the secular bracket's upper end
// |c| = |radius * offset| was formed as sqrt(sum c_i^2), whose squares (1e-397) underflow
// to zero, so the bracket collapsed onto the largest single term and the point landed off
// the sphere (signed distance -58.3 = -radius sqrt(3)).
TEST(Scales, ClosestPointNearABallsCenter) {
  const double t = 1e-200, r = 33.680859374999997;
  const auto ball = make_ball<double, 3>(V3(t, t, t), r);
  const auto p = closest_point(ball, V3(0, 0, 0));
  expect_relative(p.signed_distance, -r, 1e-15);
  expect_relative((p.point - ball.center()).norm(), r, 1e-15);
  EXPECT_LE((p.point.normalized() + V3(1, 1, 1).normalized()).norm(), 1e-15);  // away from the center
}

// A query point 1e-310 (subnormal) from the center of radii (1, 2, 3): the secular root is
// subnormal and the point's coordinate k * (u / (g + x)) overflowed u / x to infinity
// (point (inf, nan, nan)). The ratio is now formed as (k / (g + x)) * u there.
TEST(Scales, ClosestPointFromASubnormalOffset) {
  const auto body = make_ellipsoid<double>(V3(0, 0, 0), Mat3<double>::Identity(), V3(1, 2, 3));
  const double x = 1e-310;
  const auto p = closest_point(body, V3(x, x, x));
  ASSERT_TRUE(p.point.allFinite());
  expect_relative(p.signed_distance, -1, 1e-15);  // the end of the shortest axis, 1 - 1e-310 away
  EXPECT_LE((p.point - V3(1, 0, 0)).norm(), 1e-15);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
