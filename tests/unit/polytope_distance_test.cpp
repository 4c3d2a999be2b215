// signed_distance and distance of bodies and triangles or boxes (triangle.hpp, box.hpp) on
// cases solved by hand: a face, an edge and a vertex nearest, a plane through the body, a box
// around the body and one inside it, degenerate triangles, float.
#include <ellipsect/box.hpp>
#include <ellipsect/triangle.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using V3 = Vec3<double>;
using V2 = Vec2<double>;

template <class T, int N>
void expect_vec(const Vec<T, N>& got, const Vec<T, N>& want, double tol) {
  EXPECT_LE((got - want).norm(), tol) << got.transpose() << " vs " << want.transpose();
}

// The unit ball and a large triangle in the plane z = h, around the z axis.
Triangle<double, 3> floor_at(double h) {
  return make_triangle<double, 3>(V3(-10, -10, h), V3(10, -10, h), V3(0, 20, h));
}

TEST(PolytopeDistance, FaceNearestSeparated) {
  const auto ball = make_ball<double, 3>(V3::Zero(), 1.0);
  const Distance<double, 3> d = signed_distance(ball, floor_at(3));
  EXPECT_EQ(d.status, DistanceStatus::separated);
  EXPECT_NEAR(d.distance, 2, 1e-15);
  expect_vec<double, 3>(d.normal, V3(0, 0, 1), 1e-15);
  expect_vec<double, 3>(d.point_a, V3(0, 0, 1), 1e-15);
  expect_vec<double, 3>(d.point_b, V3(0, 0, 3), 1e-15);
  EXPECT_EQ(distance(ball, floor_at(3)).distance, d.distance);
}

TEST(PolytopeDistance, PlaneThroughTheBodyIsPushedOut) {
  const auto ball = make_ball<double, 3>(V3::Zero(), 1.0);
  const Distance<double, 3> d = signed_distance(ball, floor_at(0.5));
  EXPECT_EQ(d.status, DistanceStatus::overlapping);
  EXPECT_NEAR(d.distance, -0.5, 1e-15);  // the triangle moved up by 0.5 touches
  expect_vec<double, 3>(d.normal, V3(0, 0, 1), 1e-15);
  expect_vec<double, 3>(d.point_b, V3(0, 0, 0.5), 1e-15);
  const Distance<double, 3> plain = distance(ball, floor_at(0.5));
  EXPECT_EQ(plain.status, DistanceStatus::overlapping);
  EXPECT_EQ(plain.distance, 0.0);
  EXPECT_TRUE(std::isnan(plain.point_a[0]) && std::isnan(plain.point_b[0]) && std::isnan(plain.normal[0]));
}

TEST(PolytopeDistance, EdgeAndVertexNearest) {
  // Ellipsoid radii (3, 2, 1); a segment along x at y = 0, z = 5: the support in z is 1.
  const auto body = make_ellipsoid<double>(V3::Zero(), Eigen::Quaterniond::Identity(), V3(3, 2, 1));
  const auto segment = make_triangle<double, 3>(V3(-4, 0, 5), V3(4, 0, 5), V3(0, 0, 5));
  const Distance<double, 3> e = signed_distance(body, segment);
  EXPECT_NEAR(e.distance, 4, 1e-14);
  expect_vec<double, 3>(e.normal, V3(0, 0, 1), 1e-14);
  // A vertex on the long axis: the nearest point is the axis' end.
  const auto far = make_triangle<double, 3>(V3(7, 0, 0), V3(9, 1, 0), V3(9, -1, 1));
  const Distance<double, 3> v = signed_distance(body, far);
  EXPECT_NEAR(v.distance, 4, 1e-14);
  expect_vec<double, 3>(v.point_a, V3(3, 0, 0), 1e-14);
  // 2D: the ellipse (3, 1) and a point-like triangle at (0, 4): distance 3.
  const auto ellipse = make_ellipse<double>(V2::Zero(), 0.0, V2(3, 1));
  const auto dot = make_triangle<double, 2>(V2(0, 4), V2(0, 4), V2(0, 4));
  EXPECT_NEAR(signed_distance(ellipse, dot).distance, 3, 1e-14);
}

TEST(PolytopeDistance, BoxesAroundAndInside) {
  const auto ball = make_ball<double, 3>(V3(1, 2, 3), 1.0);
  const auto around = make_box<double, 3>(V3(1, 2, 3), Mat<double, 3>::Identity(), V3(10, 10, 10));
  const Distance<double, 3> d = signed_distance(ball, around);
  EXPECT_EQ(d.status, DistanceStatus::overlapping);
  EXPECT_NEAR(d.distance, -11, 1e-13);  // the box moved by 11 along an axis clears the ball
  // A cube of half side 0.1 at the ball's center: the cube's corner reaches 0.1 sqrt(3), its
  // face 0.1, so the least push is along a face normal: 1 + 0.1.
  const auto inside = make_box<double, 3>(V3(1, 2, 3), Mat<double, 3>::Identity(), V3(0.1, 0.1, 0.1));
  EXPECT_NEAR(signed_distance(ball, inside).distance, -1.1, 1e-14);
  // Apart along x: the face at x = 1 + 5 - 1 = 5 from the ball's surface at x = 2.
  const auto apart = make_box<double, 3>(V3(7, 2, 3), Mat<double, 3>::Identity(), V3(1, 4, 4));
  const Distance<double, 3> s = signed_distance(ball, apart);
  EXPECT_EQ(s.status, DistanceStatus::separated);
  EXPECT_NEAR(s.distance, 4, 1e-14);
  expect_vec<double, 3>(s.normal, V3(1, 0, 0), 1e-14);
  // 2D: a rectangle's corner nearest the unit circle.
  const auto circle = make_ball<double, 2>(V2::Zero(), 1.0);
  const auto rect = make_box<double, 2>(V2(4, 5), Mat<double, 2>::Identity(), V2(1, 1));
  EXPECT_NEAR(signed_distance(circle, rect).distance, 5 - 1, 1e-14);  // corner (3, 4)
}

TEST(PolytopeDistance, FloatBodies) {
  const auto ball = make_ball<float, 3>(Vec3<float>::Zero(), 1.0f);
  const auto tri = make_triangle<float, 3>(Vec3<float>(-10, -10, 3), Vec3<float>(10, -10, 3), Vec3<float>(0, 20, 3));
  const Distance<float, 3> d = signed_distance(ball, tri);
  EXPECT_NEAR(d.distance, 2.0f, 1e-6f);
  EXPECT_NEAR(d.normal[2], 1.0f, 1e-6f);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
