// Self-test of the distance, intersection and area reference (distance_reference.hpp)
// against closed forms in 50 digits. Inputs are exactly representable, so the distances
// and points hold to ~1e-44; the area quadrature is asked for 1e-24.
#include "distance_reference.hpp"

#include <boost/math/constants/constants.hpp>
#include <gtest/gtest.h>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect::reference;

template <int N> Body<N> aligned(const DVec<N>& c, const DVec<N>& radii) { return Body<N>{c, DMat<N>::Identity(), radii}; }
template <int N> Body<N> ball(const DVec<N>& c, double r) { return aligned<N>(c, DVec<N>::Constant(r)); }

bool near(const Real& a, const Real& b, const Real& tol) { return abs(a - b) <= tol * std::max(Real(1), Real(abs(b))); }

const Real kTol("1e-44");

TEST(DistanceReference, BallsApartAndOverlapping) {
  // Centers 5 apart along (3, 4): gap 5 - 2 - 1.5, or overlap 5 - 4 - 2.
  const auto d = signed_distance<3>(ball<3>(DVec<3>(1, 2, 3), 2), ball<3>(DVec<3>(4, 6, 3), 1.5));
  EXPECT_TRUE(near(d.distance, Real("1.5"), kTol));
  EXPECT_TRUE(near(d.normal(0), Real("0.6"), kTol) && near(d.normal(1), Real("0.8"), kTol));
  EXPECT_TRUE(near(d.point_a(0), Real("2.2"), kTol) && near(d.point_b(1), Real("4.8"), kTol));
  const auto p = signed_distance<2>(ball<2>(DVec<2>(0, 0), 4), ball<2>(DVec<2>(3, 4), 2));
  EXPECT_TRUE(near(p.distance, Real(-1), kTol));
}

TEST(DistanceReference, EllipsoidContainingABall) {
  // The ball (radius 0.25) at the center of (3, 2, 1) leaves through the poles of the
  // shortest axis: depth 1 + 0.25.
  const auto d = signed_distance<3>(aligned<3>(DVec<3>(1, -2, 0.5), DVec<3>(3, 2, 1)), ball<3>(DVec<3>(1, -2, 0.5), 0.25));
  EXPECT_TRUE(near(d.distance, Real("-1.25"), kTol));
  EXPECT_TRUE(near(abs(d.normal(2)), Real(1), kTol));
  // An ellipse (2, 1) and a ball of radius 0.5 at (4, 0): gap 1.5 along the axis.
  const auto e = signed_distance<2>(aligned<2>(DVec<2>(0, 0), DVec<2>(2, 1)), ball<2>(DVec<2>(4, 0), 0.5));
  EXPECT_TRUE(near(e.distance, Real("1.5"), kTol));
}

TEST(DistanceReference, IntersectionOfCirclesAndOfACross) {
  const auto circles = boundary_intersection(ball<2>(DVec<2>(0, 0), 1), ball<2>(DVec<2>(1, 0), 1));
  ASSERT_EQ(circles.size(), 2u);
  for (const auto& p : circles) {
    EXPECT_TRUE(near(p(0), Real("0.5"), kTol));
    EXPECT_TRUE(near(abs(p(1)), sqrt(Real(3)) / 2, kTol));
  }
  const auto cross = boundary_intersection(aligned<2>(DVec<2>(0, 0), DVec<2>(2, 1)), aligned<2>(DVec<2>(0, 0), DVec<2>(1, 2)));
  ASSERT_EQ(cross.size(), 4u);
  for (const auto& p : cross) {
    EXPECT_TRUE(near(abs(p(0)), 2 / sqrt(Real(5)), kTol));
    EXPECT_TRUE(near(abs(p(1)), 2 / sqrt(Real(5)), kTol));
  }
  EXPECT_TRUE(boundary_intersection(ball<2>(DVec<2>(0, 0), 1), ball<2>(DVec<2>(3, 0), 1)).empty());
}

TEST(DistanceReference, AreasInClosedForm) {
  const Real pi = boost::math::constants::pi<Real>(), tol("1e-22");
  EXPECT_TRUE(near(overlap_area(ball<2>(DVec<2>(0, 0), 1), ball<2>(DVec<2>(1, 0), 1)), 2 * pi / 3 - sqrt(Real(3)) / 2, tol));
  EXPECT_TRUE(near(overlap_area(aligned<2>(DVec<2>(0, 0), DVec<2>(2, 1)), aligned<2>(DVec<2>(0, 0), DVec<2>(1, 2))),
                   8 * atan(Real("0.5")), tol));
  EXPECT_TRUE(near(overlap_area(aligned<2>(DVec<2>(0, 0), DVec<2>(2, 1)), ball<2>(DVec<2>(0.5, 0), 0.25)), pi / 16, tol));
  EXPECT_EQ(overlap_area(ball<2>(DVec<2>(0, 0), 1), ball<2>(DVec<2>(3, 0), 1)), 0);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
