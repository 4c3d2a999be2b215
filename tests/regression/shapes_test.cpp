// Regressions of the queries against shapes (half_space.hpp, triangle.hpp, box.hpp,
// capsule.hpp), each named after its case.
#include <ellipsect/box.hpp>
#include <ellipsect/distance.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace {

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

}  // namespace
