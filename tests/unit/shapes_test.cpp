// Factories validate once and name the offending field.
#include <ellipsect/shapes.hpp>
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

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

// The messages the factories' good-path rewrite (no string built until a check fails) must keep.
TEST(Shapes, MessagesNameFieldAndValue) {
  const auto what = [](auto make) {
    try {
      make();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(what([] { make_ellipse<double>({0, 0}, 0, {1, 0}); }), "ellipsect: radii[1]: must be > 0 (got 0)");
  EXPECT_EQ(what([] { make_ellipse<double>({0, 0}, 0, {inf, 1}); }), "ellipsect: radii[0]: must be finite (got inf)");
  EXPECT_EQ(what([] { make_ellipse<double>({0, 0}, 0, {1, 1e9}); }),
            "ellipsect: radii: aspect ratio 1000000000 exceeds the largest supported, 100000000");
  EXPECT_EQ(what([] { make_ellipse<double>({0, nan}, 0, {1, 1}); }), "ellipsect: center[1]: must be finite (got nan)");
  EXPECT_EQ(what([] { make_ellipse<double>({0, 0}, inf, {1, 1}); }), "ellipsect: angle: must be finite (got inf)");
  EXPECT_EQ(what([] { make_ball<double, 3>({0, 0, 0}, -2); }), "ellipsect: radius: must be > 0 (got -2)");
  EXPECT_EQ(what([] { make_ellipsoid<double>({0, 0, 0}, Eigen::Quaterniond(1, 0, nan, inf), {1, 1, 1}); }),
            "ellipsect: quaternion.y: must be finite (got nan)");
  EXPECT_EQ(what([] { make_ellipsoid<double>({0, 0, 0}, Eigen::Quaterniond(2, 0, 0, 0), {1, 1, 1}); }),
            "ellipsect: quaternion: must have unit norm (got |q| = 2)");
  EXPECT_EQ(what([] { make_ellipsoid<double>({0, 0, 0}, Mat3<double>(2 * Mat3<double>::Identity()), {1, 1, 1}); }),
            "ellipsect: axes: columns must be orthonormal (max |axes^T axes - I| = 3 > 1.0000000000000001e-09)");
  Mat3<double> m = Mat3<double>::Identity();
  m(1, 2) = -inf;
  EXPECT_EQ(what([&] { make_ellipsoid<double>({0, 0, 0}, m, {1, 1, 1}); }),
            "ellipsect: axes(1,2): must be finite (got -inf)");
}

// A quaternion's axes are the rotation matrix of q / |q| to a few ulps (the factory forms it
// without a square root or a division): against that matrix in long double, for unit
// quaternions and for ones off unit norm by up to 0.9 of the accepted 1e-9 (double) or 1e-5
// (float), entrywise within 8 ulps of 1 (shapes.hpp); the rest of the body is as given.
template <class T>
void quaternion_axes_are_its_rotation_matrix(double off) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-off, off);
  const long double ulp = std::numeric_limits<T>::epsilon();
  long double worst = 0;
  for (int k = 0; k < 100000; ++k) {
    const Eigen::Quaterniond unit = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    const Eigen::Quaternion<T> q((unit.coeffs() * (1 + u(rng))).template cast<T>());
    const Vec3<T> c(T(g(rng)), T(g(rng)), T(g(rng))), r(T(1 + std::abs(g(rng))), T(1 + std::abs(g(rng))), 2);
    const auto e = make_ellipsoid<T>(c, q, r);
    const Mat3<long double> want = q.template cast<long double>().normalized().toRotationMatrix();
    worst = std::max(worst, (e.axes().template cast<long double>() - want).cwiseAbs().maxCoeff() / ulp);
    ASSERT_TRUE(e.center() == c && e.radii() == r) << k;
  }
  std::printf("quaternion axes, largest error %.2Lf ulps of 1\n", worst);
  EXPECT_LE(worst, 8);
}

TEST(Shapes, QuaternionAxesAreItsRotationMatrix) {
  quaternion_axes_are_its_rotation_matrix<double>(0);
  quaternion_axes_are_its_rotation_matrix<double>(0.9e-9);
  quaternion_axes_are_its_rotation_matrix<float>(0);
  quaternion_axes_are_its_rotation_matrix<float>(0.9e-5);
}

// The factories over arrays build what the single-body factories build, row by row.
TEST(Shapes, ArrayFactoriesEqualSingleBodyFactories) {
  const std::vector<double> c2 = {0, 1, -2, 3, 4, 5}, a2 = {0.1, -2, 7}, r2 = {1, 2, 3, 0.5, 1e-3, 1e3};
  std::vector<Ellipse2<double>> e2(3);
  make_ellipses<double>(c2, a2, r2, e2);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto want = make_ellipse<double>({c2[2 * i], c2[2 * i + 1]}, a2[i], {r2[2 * i], r2[2 * i + 1]});
    EXPECT_EQ(std::memcmp(&e2[i], &want, sizeof want), 0) << i;
  }
  make_ellipses<double>(c2, {}, r2, e2);
  EXPECT_EQ(e2[1].axes(), Mat2<double>::Identity());

  const std::vector<double> c3 = {0, 1, 2, -3, 4, 5}, r3 = {1, 2, 3, 4, 5, 6};
  const std::vector<double> q3 = {0.5, 0.5, 0.5, 0.5, 0.8, 0, 0.6, 0};  // (w, x, y, z) rows
  std::vector<Ellipsoid3<double>> e3(2);
  make_ellipsoids<double>(c3, q3, r3, e3);
  for (std::size_t i = 0; i < 2; ++i) {
    const Eigen::Quaterniond q(q3[4 * i], q3[4 * i + 1], q3[4 * i + 2], q3[4 * i + 3]);
    const auto want = make_ellipsoid<double>({c3[3 * i], c3[3 * i + 1], c3[3 * i + 2]}, q,
                                             {r3[3 * i], r3[3 * i + 1], r3[3 * i + 2]});
    EXPECT_EQ(std::memcmp(&e3[i], &want, sizeof want), 0) << i;
  }
  // Rotations row by row; the axes are their columns.
  std::vector<double> rot3;
  for (const auto& e : e3)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) rot3.push_back(e.axes()(i, j));
  std::vector<Ellipsoid3<double>> f3(2);
  make_bodies<double, 3>(c3, rot3, r3, f3);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(std::memcmp(&e3[i], &f3[i], sizeof f3[i]), 0) << i;
  make_ellipsoids<double>(c3, {}, r3, e3);
  EXPECT_EQ(e3[0].axes(), Mat3<double>::Identity());
}

TEST(Shapes, ArrayFactoriesNameRowAndField) {
  const auto error = [](auto make) -> std::pair<std::size_t, std::string> {
    try {
      make();
    } catch (const RowInputError& e) {
      EXPECT_EQ(std::string(e.what()), "ellipsect: row " + std::to_string(e.row()) + ": " + e.field() + ": " + e.detail());
      return {e.row(), e.field()};
    }
    return {0, "no error"};
  };
  const std::vector<double> c = {0, 0, 0, 1, 1, 1, 2, 2, 2}, r = {1, 1, 1, 1, -1, 1, 1, 1, 1};
  std::vector<Ellipsoid3<double>> out(3);
  EXPECT_EQ(error([&] { make_ellipsoids<double>(c, {}, r, out); }), std::make_pair(std::size_t{1}, std::string("radii[1]")));
  const std::vector<double> q = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, nan, 0};
  const std::vector<double> good_r(9, 1.0);
  EXPECT_EQ(error([&] { make_ellipsoids<double>(c, q, good_r, out); }),
            std::make_pair(std::size_t{2}, std::string("quaternion.y")));
  std::vector<double> rot(27, 0.0);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) rot[9 * i + 4 * k] = 1;
  rot[9 * 2 + 1] = 0.5;  // row 2: axes(0,1) off
  EXPECT_EQ(error([&] { make_bodies<double, 3>(c, rot, good_r, out); }), std::make_pair(std::size_t{2}, std::string("axes")));
  const std::vector<double> c2 = {0, 0, inf, 0}, r2 = {1, 1, 1, 1};
  std::vector<Ellipse2<double>> out2(2);
  EXPECT_EQ(error([&] { make_ellipses<double>(c2, {}, r2, out2); }), std::make_pair(std::size_t{1}, std::string("center[0]")));
  // An array of the wrong length names the array.
  expect_field([&] { make_ellipses<double>(c2, std::vector<double>{0.0}, r2, out2); }, "angles");
  expect_field([&] { make_bodies<double, 3>(c, rot, r2, out); }, "radii");
}

// Orientations rounded to float (about 6e-8 off, beyond the 1e-9 double accepts) made exact
// by the array factories' Orientations::normalized, and by normalized_quaternion and
// normalized_rotation alone: the quaternion's direction kept at unit norm; the rotation
// replaced by an orthonormal matrix no farther from the given one than the true rotation
// (the polar factor is the nearest, in the Frobenius norm); a row beyond 1e-5 kept as given,
// so that the factory names it.
TEST(Shapes, NormalizedOrientations) {
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal;
  constexpr int n = 50;
  std::vector<double> c(3 * n), r(3 * n, 1.0), q(4 * n), rot(9 * n);
  std::vector<Eigen::Matrix3d> exact(n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector4d v(normal(rng), normal(rng), normal(rng), normal(rng));
    v.normalize();
    exact[i] = Eigen::Quaterniond(v[0], v[1], v[2], v[3]).toRotationMatrix();
    for (int k = 0; k < 4; ++k) q[4 * i + k] = double(float(v[k]));
    for (int k = 0; k < 9; ++k) rot[9 * i + k] = double(float(exact[i](k / 3, k % 3)));
  }
  std::vector<Ellipsoid3<double>> out(n), again(n);
  expect_field([&] { make_ellipsoids<double>(c, q, r, out); }, "quaternion");
  expect_field([&] { make_bodies<double, 3>(c, rot, r, out); }, "axes");
  make_ellipsoids<double>(c, q, r, out, Orientations::normalized);
  make_bodies<double, 3>(c, rot, r, again, Orientations::normalized);
  for (int i = 0; i < n; ++i) {
    const Quat<double> given(q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]);
    const Quat<double> unit = normalized_quaternion(given);
    EXPECT_NEAR(unit.coeffs().norm(), 1.0, 4e-16);
    EXPECT_LE((unit.coeffs() - given.coeffs() / given.coeffs().norm()).norm(), 4e-16);
    EXPECT_TRUE(out[i].axes() == make_ellipsoid<double>(Vec3<double>::Zero(), unit, Vec3<double>::Ones()).axes());
    const Mat3<double> given_r = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(rot.data() + 9 * i);
    const Mat3<double> polar = normalized_rotation<double, 3>(given_r);
    EXPECT_LE((polar.transpose() * polar - Mat3<double>::Identity()).cwiseAbs().maxCoeff(),
              12 * std::numeric_limits<double>::epsilon());  // kept as given by from_axes
    EXPECT_LE((polar - given_r).norm(), (exact[i] - given_r).norm() * (1 + 1e-9));
    EXPECT_LE((polar - exact[i]).cwiseAbs().maxCoeff(), 2e-7);
    EXPECT_TRUE(again[i].axes() == polar);
  }
  q[4 * 7] *= 2;  // |q| near 2: left as given, and named
  expect_field([&] { make_ellipsoids<double>(c, q, r, out, Orientations::normalized); }, "quaternion");
  EXPECT_TRUE(normalized_quaternion(Quat<double>(2, 0, 0, 0)).coeffs() == Quat<double>(2, 0, 0, 0).coeffs());
  const Mat3<double> sheared = (Mat3<double>() << 1, 1e-3, 0, 0, 1, 0, 0, 0, 1).finished();
  EXPECT_TRUE((normalized_rotation<double, 3>(sheared) == sheared));
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
