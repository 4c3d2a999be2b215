// Factories validate once and name the offending field.
#include <ellipsect/shapes.hpp>
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using namespace ellipsect;
using ellipsect::testing::expect_field;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

TEST(Shapes, EllipseFromAngle) {
  const auto e = make_ellipse<double>({1, 2}, M_PI / 2, {3, 1});
  EXPECT_NEAR(e.axes()(0, 0), 0.0, 1e-16);
  EXPECT_NEAR(e.axes()(1, 0), 1.0, 1e-16);
  EXPECT_EQ(e.radii(), Vec2<double>(3, 1));
  // The quadric of a point on the first axis, at distance 3, is exactly 1.
  const Vec2<double> p = e.center() + 3 * e.axes().col(0);
  EXPECT_NEAR((p - e.center()).dot(e.quadric() * (p - e.center())), 1.0, 1e-15);
}

TEST(Shapes, RejectsBadRadiiNamingTheField) {
  expect_field([] { make_ellipse<double>({0, 0}, 0, {1, 0}); }, "radii[1]");
  expect_field([] { make_ellipse<double>({0, 0}, 0, {-1, 1}); }, "radii[0]");
  expect_field([] { make_ellipse<double>({0, 0}, 0, {nan, 1}); }, "radii[0]");
  expect_field([] { make_ellipse<double>({0, 0}, 0, {1, inf}); }, "radii[1]");
  expect_field([] { make_ball<float, 3>({0, 0, 0}, 0.0f); }, "radius");
}

TEST(Shapes, RejectsNonFiniteCenterAndAngle) {
  expect_field([] { make_ellipse<double>({0, nan}, 0, {1, 1}); }, "center[1]");
  expect_field([] { make_ellipse<double>({inf, 0}, 0, {1, 1}); }, "center[0]");
  expect_field([] { make_ellipse<double>({0, 0}, nan, {1, 1}); }, "angle");
  expect_field([] { make_ball<double, 3>({0, 0, 0}, 1).translated({0, 0, nan}); }, "center[2]");
}

TEST(Shapes, RejectsNonOrthonormalAxes) {
  Mat3<double> m = Mat3<double>::Identity();
  m(0, 1) = 1e-6;
  expect_field([&] { make_ellipsoid<double>({0, 0, 0}, m, {1, 2, 3}); }, "axes");
  m = 2 * Mat3<double>::Identity();
  expect_field([&] { make_ellipsoid<double>({0, 0, 0}, m, {1, 2, 3}); }, "axes");
  m = Mat3<double>::Identity();
  m(2, 2) = nan;
  expect_field([&] { make_ellipsoid<double>({0, 0, 0}, m, {1, 2, 3}); }, "axes(2,2)");
}

TEST(Shapes, AcceptsSlightlyOffAxesAndOrthonormalizesThem) {
  Mat3<double> m = Eigen::AngleAxisd(0.3, Vec3<double>(1, 2, 3).normalized()).toRotationMatrix();
  m(0, 0) += 1e-11;
  const auto e = make_ellipsoid<double>({0, 0, 0}, m, {1, 2, 3});
  EXPECT_LT((e.axes().transpose() * e.axes() - Mat3<double>::Identity()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((e.axes() - m).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(Shapes, QuaternionMustBeUnit) {
  expect_field([] { make_ellipsoid<double>({0, 0, 0}, Eigen::Quaterniond(2, 0, 0, 0), {1, 1, 1}); }, "quaternion");
  expect_field([] { make_ellipsoid<double>({0, 0, 0}, Eigen::Quaterniond(0, 0, 0, 0), {1, 1, 1}); }, "quaternion");
  expect_field([] { make_ellipsoid<double>({0, 0, 0}, Eigen::Quaterniond(nan, 0, 0, 0), {1, 1, 1}); },
               "quaternion.w");
  const Eigen::Quaterniond q(Eigen::AngleAxisd(1.0, Vec3<double>::UnitZ()));
  const auto e = make_ellipsoid<double>({0, 0, 0}, q, {1, 2, 3});
  EXPECT_NEAR(e.axes()(1, 0), std::sin(1.0), 1e-15);
}

TEST(Shapes, QuadricRoundTrip) {
  const auto e = make_ellipsoid<double>({1, -2, 3}, Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Vec3<double>(1, 1, 0).normalized())),
                                        {0.5, 2, 7});
  const auto f = Ellipsoid3<double>::from_quadric(e.center(), e.quadric());
  EXPECT_LT((f.quadric() - e.quadric()).cwiseAbs().maxCoeff(), 1e-14 * e.quadric().cwiseAbs().maxCoeff());
  // Radii come back (as a set) to a few ulps.
  Vec3<double> r = f.radii();
  std::sort(r.data(), r.data() + 3);
  EXPECT_NEAR(r[0], 0.5, 1e-15);
  EXPECT_NEAR(r[1], 2, 1e-14);
  EXPECT_NEAR(r[2], 7, 1e-13);
}

TEST(Shapes, QuadricMustBeSymmetricPositiveDefinite) {
  Mat2<double> m;
  m << 1, 0.5, 0.4, 1;
  expect_field([&] { Ellipse2<double>::from_quadric({0, 0}, m); }, "M");
  m << 1, 0, 0, -1;
  expect_field([&] { Ellipse2<double>::from_quadric({0, 0}, m); }, "M");
  m << 1, 1, 1, 1;  // singular
  expect_field([&] { Ellipse2<double>::from_quadric({0, 0}, m); }, "M");
  m << 0, 0, 0, 0;
  expect_field([&] { Ellipse2<double>::from_quadric({0, 0}, m); }, "M");
  m << 1, nan, nan, 1;
  expect_field([&] { Ellipse2<double>::from_quadric({0, 0}, m); }, "M(1,0)");
}

}  // namespace
