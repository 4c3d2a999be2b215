// perram_wertheim and closest_approach on closed forms, every status, bad input, and the
// extremes of the weights.
#include <ellipsect/contact_function.hpp>

#include "tests/reference/bridge.hpp"
#include "tests/reference/contact_function_reference.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
namespace ref = ellipsect::reference;

// Two balls: F = |r|^2 / (ra + rb)^2 at lambda = ra / (ra + rb); sigma = ra + rb along any
// direction, touching at ca + ra u with normal u.
template <class T, int N>
void balls() {
  Vec<T, N> ca = Vec<T, N>::Zero(), cb = Vec<T, N>::Zero(), u = Vec<T, N>::Zero();
  ca[0] = T(1);
  cb[0] = T(4);
  cb[1] = T(4);  // |r| = 5
  u[1] = T(-2);
  const auto a = make_ball<T, N>(ca, T(1.5)), b = make_ball<T, N>(cb, T(1));
  const T eps = std::numeric_limits<T>::epsilon();
  const auto f = perram_wertheim(a, b);
  ASSERT_EQ(f.status, ContactFunctionStatus::ok);
  EXPECT_NEAR(f.f, T(4), 8 * eps);  // 25 / 2.5^2
  EXPECT_EQ(f.f_upper, f.f);
  EXPECT_NEAR(f.lambda, T(0.6), 4 * eps);
  const auto s = closest_approach(a, b, u);
  ASSERT_EQ(s.status, ContactFunctionStatus::ok);
  EXPECT_NEAR(s.distance, T(2.5), 8 * eps);
  EXPECT_EQ(s.distance_lower, s.distance);
  Vec<T, N> point = ca, normal = Vec<T, N>::Zero();
  point[1] = T(-1.5);
  normal[1] = T(-1);
  EXPECT_LE((s.point - point).norm(), 8 * eps);
  EXPECT_LE((s.normal - normal).norm(), 8 * eps);
}

TEST(PerramWertheim, Balls) {
  balls<double, 2>();
  balls<double, 3>();
  balls<float, 2>();
  balls<float, 3>();
}

// Axis-aligned ellipses (2, 1) at the origin and (1, 3) at (x, 0): along x they touch when
// the centers are 3 apart, so F = (x / 3)^2, and sigma along x is 3 with the point (2, 0).
TEST(PerramWertheim, AxisAlignedEllipses) {
  const auto a = make_ellipse<double>({0, 0}, 0, {2, 1});
  const auto b = make_ellipse<double>({6, 0}, 0.0, {1, 3});
  const auto f = perram_wertheim(a, b);
  ASSERT_EQ(f.status, ContactFunctionStatus::ok);
  EXPECT_NEAR(f.f, 4.0, 1e-14);
  const auto s = closest_approach(a, b, {7, 0});
  EXPECT_NEAR(s.distance, 3.0, 1e-15);
  EXPECT_LE((s.point - Vec2<double>(2, 0)).norm(), 1e-15);
  EXPECT_LE((s.normal - Vec2<double>(1, 0)).norm(), 1e-15);
}

TEST(PerramWertheim, Concentric) {
  const auto a = make_ellipsoid<double>({1, 2, 3}, Quat<double>(0.5, 0.5, 0.5, 0.5), {1, 2, 3});
  const auto b = make_ellipsoid<double>({1, 2, 3}, Mat3<double>::Identity(), {3, 0.5, 1});
  for (const auto& f : {perram_wertheim(a, b), perram_wertheim(b, a), perram_wertheim(a, a)}) {
    EXPECT_EQ(f.status, ContactFunctionStatus::concentric);
    EXPECT_EQ(f.f, 0.0);
    EXPECT_EQ(f.f_upper, 0.0);
    EXPECT_TRUE(std::isnan(f.lambda));
  }
  // closest_approach is defined for concentric bodies (b leaves a's center along u).
  const auto s = closest_approach(a, b, {0, 0, 1});
  EXPECT_EQ(s.status, ContactFunctionStatus::ok);
  EXPECT_GT(s.distance, 0.0);
}

TEST(PerramWertheim, BadDirection) {
  const auto a = make_ball<double, 3>({0, 0, 0}, 1), b = make_ball<double, 3>({3, 0, 0}, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  ellipsect::testing::expect_field([&] { closest_approach(a, b, {0, 0, 0}); }, "direction");
  ellipsect::testing::expect_field([&] { closest_approach(a, b, {nan, 1, 0}); }, "direction");
  ellipsect::testing::expect_field([&] { closest_approach(a, b, {0, inf, 0}); }, "direction");
  const auto af = make_ball<float, 2>({0, 0}, 1), bf = make_ball<float, 2>({3, 0}, 1);
  ellipsect::testing::expect_field([&] { closest_approach(af, bf, {0.0f, -0.0f}); }, "direction");
  // Directions of any length are normalized, subnormal and huge ones included.
  EXPECT_EQ(closest_approach(a, b, {5e-324, 0, 0}).distance, 2.0);
  EXPECT_EQ(closest_approach(a, b, {1e308, 0, 0}).distance, 2.0);
}

TEST(PerramWertheim, ToString) {
  EXPECT_EQ(to_string(ContactFunctionStatus::ok), "ok");
  EXPECT_EQ(to_string(ContactFunctionStatus::concentric), "concentric");
  EXPECT_EQ(to_string(ContactFunctionStatus::did_not_converge), "did_not_converge");
}

// Weights far below eps keep their digits: balls of radii 1 and 1e-30 (lambda = 1 / (1 +
// 1e-30), 1 - lambda = 1e-30 reported by the swapped call), and 1e100 apart in size (the
// pair is computed rescaled or in long double).
TEST(PerramWertheim, ExtremeWeights) {
  for (const double small : {1e-30, 1e-100}) {
    const auto big = make_ball<double, 3>({0, 0, 0}, 1), tiny = make_ball<double, 3>({3, 0, 0}, small);
    const auto f = perram_wertheim(big, tiny), g = perram_wertheim(tiny, big);
    ASSERT_EQ(f.status, ContactFunctionStatus::ok);
    ASSERT_EQ(g.status, ContactFunctionStatus::ok);
    EXPECT_NEAR(f.f, 9 / ((1 + small) * (1 + small)), 1e-15);
    EXPECT_EQ(g.f, f.f);
    EXPECT_EQ(f.lambda, 1.0);
    EXPECT_NEAR(g.lambda, small, 1e-14 * small);
    EXPECT_NEAR(closest_approach(big, tiny, {0, 1, 0}).distance, 1.0, 1e-15);
  }
}

// Centers far closer than the bodies' size: F underflows to 0 but the direction, and with it
// lambda, is kept (a subnormal offset of unit balls; balls of radius 1e300 whose centers are
// 1e-300 apart, which rescaling to unit size would merge).
TEST(PerramWertheim, TinyOffsets) {
  for (const double radius : {1.0, 1e300}) {
    const double offset = radius == 1.0 ? 5e-324 : 1e-300;
    const auto a = make_ball<double, 2>({0, 0}, radius), b = make_ball<double, 2>({0, offset}, 3 * radius);
    const auto f = perram_wertheim(a, b);
    ASSERT_EQ(f.status, ContactFunctionStatus::ok);
    EXPECT_EQ(f.f, 0.0);
    EXPECT_NEAR(f.lambda, 0.25, 1e-15);
  }
}

// Options::max_contact_function_iterations reached: the status says so and the bounds hold the 50-digit value.
TEST(PerramWertheim, DidNotConvergeGivesBounds) {
  const auto a = make_ellipsoid<double>({0, 0, 0}, Quat<double>(0.8, 0.6, 0, 0), {3, 0.2, 1});
  const auto b = make_ellipsoid<double>({2, 1.5, -1}, Quat<double>(0.6, 0, 0.8, 0), {0.05, 2, 4});
  Options once;
  once.max_contact_function_iterations = 1;
  const auto f = perram_wertheim(a, b, once);
  ASSERT_EQ(f.status, ContactFunctionStatus::did_not_converge);
  EXPECT_EQ(f.iterations, 1);
  const double exact = ref::to_double(ref::contact_function<3>(ref::to_ref(a), ref::to_ref(b)).f);
  EXPECT_LE(f.f, exact);
  EXPECT_GE(f.f_upper, exact);
  EXPECT_LT(f.f, f.f_upper);
  const Vec3<double> u(-1, 0.5, 2);
  const auto s = closest_approach(a, b, u, once);
  ASSERT_EQ(s.status, ContactFunctionStatus::did_not_converge);
  const double sigma = ref::to_double(ref::closest_approach<3>(ref::to_ref(a), ref::to_ref(b), u));
  EXPECT_LE(s.distance_lower, sigma);
  EXPECT_GE(s.distance, sigma);
  // The default cap converges, to the accuracy the header states.
  const auto full = perram_wertheim(a, b);
  ASSERT_EQ(full.status, ContactFunctionStatus::ok);
  EXPECT_NEAR(full.f, exact, 1e-12 * exact);
  EXPECT_NEAR(closest_approach(a, b, u).distance, sigma, 1e-12 * sigma);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
