// Regression tests for bodies beyond the supported aspect ratio and for the sign of a
// separated distance.
#include <ellipsect/ellipsect.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ellipsect {
namespace {
namespace ELLIPSECT_UNITY_ID {

// A needle of aspect 2e19 (radii 8 and 4.3e-19) across a circle of radius 8 got an
// overlap_area of 402, twice the circle's area, and in 3D such needles gave distance and
// classify statuses that disagree. At that aspect the rounding of the stored axes (eps times
// the major radius, ~1e-15) is a million times the minor radius, so the body no longer has
// the shape its radii describe. The factories now reject every body beyond
// max_aspect_ratio (1e8, the range the queries are tested in) with InputError("radii").
TEST(Aspect, NeedleBeyondTheSupportedAspectRatioIsRejected) {
  EXPECT_EQ(Ellipse2<double>::max_aspect_ratio, 1e8);
  try {
    (void)make_ellipse<float>({-7, 0}, 0.3f, {8, 0x1.ff8p-62f});
    FAIL() << "accepted a needle of aspect 2e19";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "radii");
  }
  EXPECT_THROW((void)make_ellipsoid<double>({0, 0, 0}, Eigen::Quaterniond::Identity(), {0x1.129bb1a79ed7cp+505, 8, 1}),
               InputError);
  EXPECT_THROW((void)Ellipsoid3<double>::from_axes({0, 0, 0}, Mat3<double>::Identity(), {1, 1, 0.9999999e-8}),
               InputError);
  // At the limit itself the body is accepted, and the queries answer it (the circle of
  // radius 8 meets the needle's tip region: the needle is centred on the circle's boundary).
  const auto needle = make_ellipse<double>({8, 0}, 0, {1, 1e-8});
  const auto circle = make_ball<double, 2>({0, 0}, 8);
  EXPECT_EQ(classify(needle, circle), Relation::overlapping);
  const double half = std::numbers::pi * 1e-8 / 2;  // the half of the needle inside the circle, to 1e-8 relative
  EXPECT_NEAR(overlap_area(needle, circle).area, half, 1e-8 * half);
}

// Two spheres (radius 383479222 at (0, 2.4e-320, 383479222), radius 8 at (-8, 0, -8)) whose
// true gap is 8.3e-8: separated (the gap is far outside the tangency band of the smaller
// sphere), but the gap is below the rounding of the larger one's size (eps * 3.8e8 = 8.5e-8),
// and distance came back as -0 with status separated. A separated distance is now never
// negative (clamping moves it towards the true value, within the stated accuracy).
TEST(Aspect, SeparatedDistanceIsNeverNegative) {
  const double r = 0x1.6d6d6d6cp+28;
  const auto a = make_ball<double, 3>({0, 0x0.00101p-1022, r}, r);
  const auto b = make_ball<double, 3>({-8, 0, -8}, 8);
  ASSERT_EQ(classify(a, b), Relation::separated);
  for (const auto& d : {distance(a, b), signed_distance(a, b), distance(b, a)}) {
    EXPECT_EQ(d.status, DistanceStatus::separated);
    EXPECT_GE(d.distance, 0.0);
    EXPECT_FALSE(std::signbit(d.distance));
    // Exact gap: |c_a - c_b| - r - 8 = sqrt(64 + (r + 8)^2) - (r + 8) = 64 / (sqrt(...) + r + 8).
    const double gap = 64 / (std::hypot(8.0, r + 8) + r + 8);
    EXPECT_NEAR(d.distance, gap, 1e-12 * (r + 8 + gap));
  }
  // Four times larger (a radius ratio beyond 2^26) the large sphere is the unit ball
  // (reduce.hpp), and a gap of 2e-8 relative to the small one is 5e-17 of the large one's
  // radius: inside the band, touching, whatever the rounding of the small one's position.
  const auto large = make_ball<double, 3>({0, 0x0.00101p-1022, 4 * r}, 4 * r);
  EXPECT_EQ(classify(large, b), Relation::touching);
  EXPECT_EQ(distance(large, b).status, DistanceStatus::touching);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
}  // namespace ellipsect
