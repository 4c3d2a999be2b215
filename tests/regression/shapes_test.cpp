// Regressions of the queries against shapes (half_space.hpp, triangle.hpp, box.hpp,
// capsule.hpp), each named after its case.
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;

// A float ellipsoid of radii (1, 8, 8) against a box of half extents (1, 8, 8) with the same
// float axes (orthonormal to a few ulps), the body's x-extreme on the box's face to within
// 3e-9: signed_distance said overlapping at -3.7e-8 where classify said separated. The gap
// comes from the face planes through three of each face's four corners, classify from the
// twelve triangles over all four; in float those corners (magnitude 14) are coplanar only to
// about 1e-6, and the body's axes orthonormal only to about 1e-7 of its radii, so the two
// routes may differ by that much while the band that sent a pair to classify was 8e-9 wide.
// The band now holds 16 ulps of T of the radius and of the coordinates, and the status is
// classify's.
TEST(ShapesRegression, BoxSignedDistanceStatusFloatFaceCornersOffPlane) {
  Mat<float, 3> axes;
  axes << 0x1.b6db6ep-1f, 0x1.b6db6ep-2f, -0x1.24924ap-2f, -0x1.24924ap-2f, 0x1.b6db6ep-1f, 0x1.b6db6ep-2f,
      0x1.b6db6ep-2f, -0x1.24924ap-2f, 0x1.b6db6ep-1f;
  const auto a = Ellipsoid<float, 3>::from_axes({-0x1p-28f, 0, -8}, axes, {1, 8, 8});
  const auto box = make_box<float, 3>({1, 1, -14}, axes, {1, 8, 8});
  const Relation relation = classify(a, box);
  ASSERT_TRUE(relation == Relation::separated || relation == Relation::touching ||
              relation == Relation::overlapping);
  const Distance<float, 3> d = signed_distance(a, box);
  EXPECT_EQ(d.status, relation == Relation::separated  ? DistanceStatus::separated
                      : relation == Relation::touching ? DistanceStatus::touching
                                                       : DistanceStatus::overlapping);
  // Whatever the status, the body's face lies within float's rounding of the box's.
  EXPECT_LE(std::abs(d.distance), 1e-5f);
}

// A float body of radii (3, 2, 1) at the origin against the capsule of radius 1 along y from
// (4, y0, z0) to (4, y0 + 2, z0), y0 = 0x1.01p-12, z0 = 0x1.e5e4p-13: the body's x-extreme
// (3, 0, 0) is 1 from (4, 0, 0), and the curvature radii there (4/3 in y, 1/3 in z) put the
// true gap at about y0^2 / (2 (1 + 4/3)) + z0^2 / (2 (1 + 1/3)) = 3.3e-8, under one ulp of
// float at 4. classify said separated (the body's bounding ball is 1.9e-6 from the capsule),
// signed_distance touching from the float support gap; first_contact began from the latter.
// All three now read the same relation.
TEST(ShapesRegression, CapsuleFloatGapBelowOneUlpSameStatusEverywhere) {
  const auto a = make_ellipsoid<float>({0, 0, 0}, Mat<float, 3>::Identity(), {3, 2, 1});
  const Vec<float, 3> c{4, 0x1.00101p+0f, 0x1.e5e4p-13f}, y{0, 1, 0};
  const auto capsule = make_capsule<float, 3>(Vec<float, 3>(c - y), Vec<float, 3>(c + y), 1);
  // The bounding ball of radius 3 is |(4, y0, z0)| - 4 = 1.9e-6 from the segment: separated.
  EXPECT_EQ(classify(a, capsule), Relation::separated);
  const Distance<float, 3> d = signed_distance(a, capsule);
  EXPECT_EQ(d.status, DistanceStatus::separated);
  EXPECT_GE(d.distance, 0.0f);
  EXPECT_LE(d.distance, 1e-6f);
  const Contact<float, 3> hit = first_contact(a, Vec<float, 3>{1, 0, 0}, capsule, Vec<float, 3>{0, 0, 0}, 1.0f);
  EXPECT_EQ(hit.status, ContactStatus::hit);
  EXPECT_GE(hit.time, 0.0f);
  EXPECT_LE(hit.time, 1e-6f);  // the gap, 3.3e-8, closed at speed 1
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
