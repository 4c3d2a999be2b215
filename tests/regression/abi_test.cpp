// The public types' layout, the default body, and the factories' field names.
//
// LayoutFollowedTheConsumersFlags: Vec and Mat were aligned Eigen types, whose alignment
// (and so the size and member offsets of Ellipsoid and of every result struct holding one)
// follows EIGEN_MAX_STATIC_ALIGN_BYTES, which Eigen derives from the compiler's SIMD flags.
// The installed library was built with 16-byte alignment; a program built with
// -march=native (AVX: 32 bytes) saw sizeof(Ellipse2<double>) = 96 instead of 64 and read
// the radii at the wrong offsets, silently (radii printed as 0 0). Vec and Mat are now
// Eigen::DontAlign types, laid out as plain arrays of T, and the headers assert each public
// type's size and alignment. The flag variants themselves (-march=native, -mavx512f,
// EIGEN_MAX_STATIC_ALIGN_BYTES = 0 and 64) are built against the installed package by the
// test consumer_project (tests/consumer/abi.cpp): one program cannot mix them without
// breaking the one-definition rule for Eigen's own types.
//
// QuaternionComponentsNamedInConstructorOrder: a NaN w was reported as "quaternion[3]",
// Eigen's storage index (x, y, z, w), which names nothing the caller wrote; the
// components are now named quaternion.w, .x, .y, .z.
//
// BallRadiusNamedRadius: make_ball checked its radius as the radii vector it builds and
// reported "radii[0]", a field the caller never passed; it now reports "radius".
#include <ellipsect/ellipsect.hpp>
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using ellipsect::testing::expect_field;
using namespace ellipsect;

// The layout rule the headers' asserts rely on, checked against layouts known by hand
// (x86-64 and every other platform where double and int are naturally aligned).
struct Known {
  int i;
  double d[3];
  char c;
};
static_assert(detail::PlainLayout<int, double[3], char>::size == sizeof(Known));
static_assert(detail::PlainLayout<int, double[3], char>::align == alignof(Known));
static_assert(detail::PlainLayout<char, char[3]>::size == 4 && detail::PlainLayout<char, char[3]>::align == 1);

TEST(Abi, LayoutFollowedTheConsumersFlags) {
  // Plain arrays of T, whatever the flags of this translation unit.
  EXPECT_EQ(sizeof(Ellipse2<double>), (2 + 4 + 2) * sizeof(double));
  EXPECT_EQ(sizeof(Ellipsoid3<double>), (3 + 9 + 3) * sizeof(double));
  EXPECT_EQ(sizeof(Ellipsoid3<float>), (3 + 9 + 3) * sizeof(float));
  EXPECT_EQ(alignof(Ellipsoid3<double>), alignof(double));
  if constexpr (sizeof(void*) == 8 && alignof(double) == 8 && sizeof(int) == 4) {
    EXPECT_EQ(sizeof(Contact<double, 2>), 56u);   // status, pad, time, point, normal, iterations, pad
    EXPECT_EQ(sizeof(Contact<double, 3>), 72u);
    EXPECT_EQ(sizeof(Distance<double, 3>), 96u);  // status, pad, distance, 3 vectors, iterations, pad
    EXPECT_EQ(sizeof(ClosestPoint<double, 3>), 32u);
    EXPECT_EQ(sizeof(ContactFunction<double>), 40u);       // status, pad, f, f_upper, lambda, iterations, pad
    EXPECT_EQ(sizeof(ClosestApproach<double, 3>), 88u);  // status, pad, 2 distances, 2 vectors, lambda, iterations, pad
    EXPECT_EQ(sizeof(BoundaryIntersection<double>), 88u);  // status, count, 8 doubles, 4 kinds
    EXPECT_EQ(sizeof(QuarticPoint<float>), 16u);
  }

  // A body made by the library reads back field by field, at the documented offsets.
  const auto e = make_ellipse<double>({1, 2}, 0.3, {3, 4});
  EXPECT_EQ(e.radii()[0], 3);
  EXPECT_EQ(e.radii()[1], 4);
  double row[8];
  std::memcpy(row, &e, sizeof row);
  EXPECT_EQ(row[0], 1);
  EXPECT_EQ(row[1], 2);
  EXPECT_EQ(row[2], std::cos(0.3));  // axes, column by column
  EXPECT_EQ(row[3], std::sin(0.3));
  EXPECT_EQ(row[4], -std::sin(0.3));
  EXPECT_EQ(row[5], std::cos(0.3));
  EXPECT_EQ(row[6], 3);
  EXPECT_EQ(row[7], 4);
}

TEST(Abi, BodiesAreTriviallyCopyable) {
  static_assert(std::is_trivially_copyable_v<Ellipse2<double>> && std::is_trivially_copyable_v<Ellipsoid3<float>>);
  static_assert(std::is_standard_layout_v<Ellipse2<float>>);
  const Ellipsoid3<double> bodies[2] = {make_ball<double, 3>({1, 2, 3}, 4),
                                        make_ellipsoid<double>({0, 0, 5}, Mat3<double>::Identity(), {1, 2, 3})};
  Ellipsoid3<double> copies[2];
  std::memcpy(copies, bodies, sizeof bodies);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(copies[i].center(), bodies[i].center());
    EXPECT_EQ(copies[i].axes(), bodies[i].axes());
    EXPECT_EQ(copies[i].radii(), bodies[i].radii());
  }
  EXPECT_EQ(distance(copies[0], copies[1]).distance, distance(bodies[0], bodies[1]).distance);
}

template <class T, int N>
void expect_unit_ball(const Ellipsoid<T, N>& e) {
  EXPECT_EQ(e.center(), (Vec<T, N>::Zero()));
  EXPECT_EQ(e.axes(), (Mat<T, N>::Identity()));
  EXPECT_EQ(e.radii(), (Vec<T, N>::Ones()));
}

TEST(Abi, DefaultBodyIsTheUnitBallAtTheOrigin) {
  constexpr Ellipsoid3<double> e;  // a constant expression
  expect_unit_ball(e);
  expect_unit_ball(Ellipse2<float>());
  std::vector<Ellipse2<double>> v;
  v.resize(3);
  for (const auto& b : v) expect_unit_ball(b);
  Ellipsoid3<float> array[4];
  for (const auto& b : array) expect_unit_ball(b);
  // A valid body like any other: the same set as the ball the factory makes, and two
  // default bodies one unit apart along x (centers 0 and 3, radii 1) are 1 apart.
  EXPECT_EQ(classify(e, make_ball<double, 3>({0, 0, 0}, 1)), Relation::equal);
  EXPECT_NEAR(distance(e, e.translated({3, 0, 0})).distance, 1.0, 1e-15);
}

TEST(Abi, QuaternionComponentsNamedInConstructorOrder) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  constexpr double inf = std::numeric_limits<double>::infinity();
  const Vec3<double> c(0, 0, 0), r(1, 2, 3);
  expect_field([&] { make_ellipsoid<double>(c, Eigen::Quaterniond(nan, 0, 0, 1), r); }, "quaternion.w");
  expect_field([&] { make_ellipsoid<double>(c, Eigen::Quaterniond(1, nan, 0, 0), r); }, "quaternion.x");
  expect_field([&] { make_ellipsoid<double>(c, Eigen::Quaterniond(1, 0, -inf, 0), r); }, "quaternion.y");
  expect_field([&] { make_ellipsoid<float>(Vec3<float>::Zero(), Eigen::Quaternionf(1, 0, 0, NAN), Vec3<float>::Ones()); },
               "quaternion.z");
}

TEST(Abi, BallRadiusNamedRadius) {
  expect_field([] { make_ball<double, 2>({0, 0}, 0); }, "radius");
  expect_field([] { make_ball<double, 3>({0, 0, 0}, -1); }, "radius");
  expect_field([] { make_ball<float, 2>({0, 0}, std::numeric_limits<float>::quiet_NaN()); }, "radius");
  expect_field([] { make_ball<float, 3>({0, 0, 0}, std::numeric_limits<float>::infinity()); }, "radius");
  expect_field([] { make_ball<double, 3>({0, std::numeric_limits<double>::infinity(), 0}, 1); }, "center[1]");
}

TEST(Abi, AlignedEigenArgumentsConvert) {
  // Aligned Eigen types and expressions are accepted where Vec, Mat and Quat are taken,
  // and the queries' T and N are deduced from the bodies.
  const Eigen::Vector3d center(1, 2, 3);
  const auto e = make_ellipsoid<double>(center, Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ())),
                                        Eigen::Vector3d(2, 3, 4));
  EXPECT_EQ(e.center(), center);
  EXPECT_NEAR(e.axes()(0, 0), std::cos(0.5), 4e-16);  // through the quaternion
  EXPECT_NEAR(e.axes()(1, 0), std::sin(0.5), 4e-16);
  // Unit circles 10 apart closing at speed 2 touch at t = (10 - 2) / 2 = 4, at (5, 0).
  const auto a = make_ball<double, 2>(Eigen::Vector2d(0, 0), 1);
  const auto b = make_ball<double, 2>(Eigen::Vector2d(10, 0), 1);
  const auto c = first_contact(a, Eigen::Vector2d(1, 0), b, -Eigen::Vector2d(1, 0), 100.0);
  EXPECT_EQ(c.status, ContactStatus::hit);
  EXPECT_NEAR(c.time, 4, 1e-14);
  EXPECT_NEAR((c.point - Eigen::Vector2d(5, 0)).norm(), 0, 1e-13);
  // The point (0, 0, 7) is 7 - 3 = 4 from a sphere of radius 3 at the origin.
  const auto p = closest_point(make_ball<double, 3>({0, 0, 0}, 3), Eigen::Vector3d(0, 0, 7));
  EXPECT_NEAR(p.signed_distance, 4, 1e-14);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
