// Closest boundary point of an ellipse(oid) to a point, against closed forms.
#include <ellipsect/point.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;

TEST(ClosestPoint, BallIsRadialProjection) {
  const auto ball = make_ball<double, 3>({1, 2, 3}, 2.0);
  const Vec3<double> x(4, 6, 3);  // 5 from the center
  const auto c = closest_point(ball, x);
  EXPECT_NEAR(c.signed_distance, 3.0, 1e-15);
  EXPECT_LT((c.point - Vec3<double>(1 + 1.2, 2 + 1.6, 3)).norm(), 1e-15);
  const auto inside = closest_point(ball, Vec3<double>(1.5, 2, 3));
  EXPECT_NEAR(inside.signed_distance, -1.5, 1e-15);
  EXPECT_LT((inside.point - Vec3<double>(3, 2, 3)).norm(), 1e-15);
}

TEST(ClosestPoint, OnAxisOutside) {
  const auto e = make_ellipse<double>({0, 0}, 0, {2, 1});
  for (double d : {1e-12, 1e-6, 1.0, 1e6}) {
    const auto c = closest_point(e, Vec2<double>(2 + d, 0));
    EXPECT_NEAR(c.signed_distance, d, 4e-16 * (2 + d)) << d;
    EXPECT_NEAR(c.point.x(), 2.0, 4e-16 * (2 + d));
    EXPECT_EQ(c.point.y(), 0.0);
  }
}

// Interior point on the major axis closer to the center than the evolute cusp
// (a^2 - b^2)/a: the nearest points are off the axis (the "hard case", k_minor = 0):
// x = a^2 x0 / (a^2 - b^2), y = +-b sqrt(1 - (a x0 / (a^2 - b^2))^2),
// distance b sqrt(1 - x0^2 / (a^2 - b^2)).
TEST(ClosestPoint, InteriorHardCase2D) {
  const double a = 2, b = 1;
  const auto e = make_ellipse<double>({0, 0}, 0, {a, b});
  for (double x0 : {0.0, 0.5, 1.4}) {
    const auto c = closest_point(e, Vec2<double>(x0, 0));
    const double dist = b * std::sqrt(1 - x0 * x0 / (a * a - b * b));
    EXPECT_NEAR(c.signed_distance, -dist, 1e-15) << x0;
    EXPECT_NEAR(c.point.x(), a * a * x0 / (a * a - b * b), 1e-15);
    EXPECT_NEAR(std::abs(c.point.y()), b * std::sqrt(1 - std::pow(a * x0 / (a * a - b * b), 2)), 1e-15);
  }
  // Beyond the cusp the nearest point is the vertex.
  const auto c = closest_point(e, Vec2<double>(1.8, 0));
  EXPECT_NEAR(c.signed_distance, -0.2, 1e-15);
}

// Repeated radii: a prolate spheroid (2, 1, 1) seen from its center; every point of the
// unit circle of the minor axes is nearest, at distance 1.
TEST(ClosestPoint, RepeatedRadiiHardCase3D) {
  const auto e = make_ellipsoid<double>({0, 0, 0}, Mat3<double>::Identity(), {2, 1, 1});
  const auto c = closest_point(e, Vec3<double>(0, 0, 0));
  EXPECT_NEAR(c.signed_distance, -1.0, 1e-15);
  EXPECT_NEAR(c.point.x(), 0.0, 1e-15);
  EXPECT_NEAR(std::hypot(c.point.y(), c.point.z()), 1.0, 1e-15);
  // Oblate (2, 2, 1) from the center: nearest points are the poles (0, 0, +-1).
  const auto o = make_ellipsoid<double>({0, 0, 0}, Mat3<double>::Identity(), {2, 2, 1});
  const auto p = closest_point(o, Vec3<double>(0, 0, 0.25));
  EXPECT_NEAR(p.signed_distance, -0.75, 1e-15);
  EXPECT_NEAR(p.point.z(), 1.0, 1e-15);
}

// Far points: the answer is on the boundary and the offset is along the outward normal,
// with relative accuracy (no absolute tolerance breaks at large distance).
TEST(ClosestPoint, FarPointsAreOptimal) {
  const auto e = make_ellipsoid<double>({0.5, -1, 2}, Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Vec3<double>(1, 2, 2).normalized())),
                                        {3, 1e-3, 0.2});
  for (double r : {1e2, 1e6, 1e12}) {
    const Vec3<double> x = e.center() + r * Vec3<double>(0.3, -0.5, 0.81).normalized();
    const auto c = closest_point(e, x);
    // In the body frame (the world-frame quadric has entries up to 1e6 here and would
    // lose the digits this test is about).
    const Vec3<double> d = e.axes().transpose() * (c.point - e.center());
    EXPECT_NEAR(d.cwiseQuotient(e.radii()).squaredNorm(), 1.0, 1e-14) << r;
    const Vec3<double> n = (e.axes() * d.cwiseQuotient(e.radii().cwiseAbs2())).normalized();
    // The normal turns by (position rounding) / (radius of curvature): here
    // 1e-16 / (1e-3^2 / 3), so alignment to 1e-10 is all a double point can show.
    EXPECT_LT(n.cross((x - c.point).normalized()).norm(), 1e-10) << r;
    EXPECT_GT(n.dot(x - c.point), 0.0);
    EXPECT_NEAR(c.signed_distance, (x - c.point).norm(), 1e-15 * r);
  }
}

TEST(ClosestPoint, FloatInstantiation) {
  const auto e = make_ellipse<float>({0, 0}, 0, {2, 1});
  const auto c = closest_point(e, Vec2<float>(5, 0));
  EXPECT_FLOAT_EQ(c.signed_distance, 3.0f);
}

// The query point at the center of a ball whose center is a subnormal offset from it: the
// secular equation's terms e_i k_i were subnormal, its root kept a few digits, and the
// point came back at (-11.59, -11.59, -11.59), 20.08 from the center. An offset that small
// is now scaled up by a power of two to about eps of the radii (its direction kept): the
// point on the sphere, away from the center.
TEST(ClosestPoint, SubnormalOffsetFromTheCenter) {
  const double r = 11.594921875000001;
  const auto ball = make_ball<double, 3>({4.058311769621644e-312, 4.0583117696265846e-312, 4.0583117696315253e-312}, r);
  const auto c = closest_point(ball, Vec3<double>(0, 0, 0));
  EXPECT_NEAR(c.signed_distance, -r, 1e-14 * r);
  EXPECT_NEAR((c.point - ball.center()).norm(), r, 4e-16 * r);
  // The offsets are equal to 1e-12: the point along -(1, 1, 1).
  EXPECT_LE((c.point.normalized() + Vec3<double>(1, 1, 1).normalized()).norm(), 1e-10);
  // An ellipsoid (3, 2, 1) whose center is 1e-310 off the query point: the nearest points
  // are the poles (0, 0, +-1), at distance 1.
  const auto e = make_ellipsoid<double>({1e-310, 0, -2e-311}, Mat3<double>::Identity(), {3, 2, 1});
  const auto p = closest_point(e, Vec3<double>(0, 0, 0));
  EXPECT_NEAR(p.signed_distance, -1.0, 1e-15);
  EXPECT_NEAR(std::abs(p.point.z()), 1.0, 1e-15);
  const auto disc = make_ellipse<double>({-3e-320, 5e-321}, 0.3, {2, 1});
  EXPECT_NEAR(closest_point(disc, Vec2<double>(0, 0)).signed_distance, -1.0, 1e-15);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
