// Regressions of classify, intersect_boundaries and overlap_area found by fuzzing; each test
// names the case and explains its cause. Expected answers come from the geometry (closed
// forms) or from the 50-digit reference in tests/reference.
#include <ellipsect/batch.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/intersect2.hpp>

#include "tests/reference/bridge.hpp"
#include "tests/reference/distance_reference.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
namespace ref = ellipsect::reference;

constexpr double pi = std::numbers::pi;
constexpr double subnormal = 2.4031353013718232e-320;

// Center offsets from a concentric position: exactly 0, a subnormal, far below and around
// eps relative (where the secular terms e_i k_i underflow or cancel), and the fuzzed ones.
const double offsets[] = {0, subnormal, 1e-300, 1e-100, 1e-20, 0.1 + 0.2 - 0.3, 1e-16, 4e-16, 1e-15, 1e-14, 1e-12};

// A circle of radius 40 around an ellipse with radii (2, 1), its center a tiny offset off
// the ellipse's: the circle contains the ellipse by 38 units, so there is no common
// boundary point and the overlap is the ellipse's area 2 pi. In the reduced frame O's center
// k is ~1e-18 and its middle-branch critical points of h have multipliers within |c_hi| ~
// 1e-19 of the pole e_hi^2 ~ 2e-3: the right root was solved in a and u_hi = -c_hi /
// (delta - a) formed by subtraction, which cancelled to 0 and gave an infinite h, read as a
// transverse crossing (two at the same vertex of the ellipse). The roots are now solved in
// their distance from the nearer pole, and components of k below eps * e_max are zero.
TEST(IntersectClassify, NearlyConcentricCircleAroundEllipse) {
  for (const double off : offsets) {
    const auto a = make_ellipse<double>({0, 0}, 0.5, {2, 1});
    const auto c = make_ball<double, 2>({0, off}, 40);
    EXPECT_EQ(classify(a, c), Relation::b_contains_a) << off;
    const auto x = intersect_boundaries(a, c);
    EXPECT_EQ(x.status, BoundaryStatus::points) << off;
    EXPECT_EQ(x.count, 0) << off;
    const auto area = overlap_area(a, c);
    EXPECT_NEAR(area.area, 2 * pi, 1e-14) << off;
  }
}

// A needle (51.2 x 0.246) across an ellipse (2 x 1) with almost the same center: four
// transverse crossings, and the lens the reference integrates (1.4757 at offset 0). The
// same cancellation as above lost the middle critical points; the area came out 20.53 (the
// ellipse's whole area is 6.28) with two crossings. Below 1e-100 the secular terms also
// underflowed (cbrt(c^2) = 0) and a subnormal offset made the farthest point infinite.
TEST(IntersectClassify, NearlyConcentricNeedleAcrossEllipse) {
  for (const double off : offsets) {
    const auto a = make_ellipse<double>({0, 0}, 0.527, {2, 1});
    const auto b = make_ellipse<double>({0, off}, 0, {51.19921875, 0.24609375});
    const auto want = ref::boundary_intersection(ref::to_ref(a), ref::to_ref(b));
    ASSERT_EQ(want.size(), 4u) << off;
    EXPECT_EQ(classify(a, b), Relation::overlapping) << off;
    const auto x = intersect_boundaries(a, b);
    ASSERT_EQ(x.count, 4) << off;
    const double tol = 1e-12 * (2 + 51.19921875);
    for (int i = 0; i < x.count; ++i) {
      EXPECT_EQ(x.kinds[i], CrossingKind::transverse) << off;
      double best = std::numeric_limits<double>::infinity();
      for (const auto& p : want) best = std::min(best, ref::to_double((p - x.points[i].cast<ref::Real>()).norm()));
      EXPECT_LE(best, tol) << off << " point " << i;
    }
    const double area = ref::to_double(ref::overlap_area(ref::to_ref(a), ref::to_ref(b)));
    EXPECT_NEAR(overlap_area(a, b).area, area, 1e-12 * pi * 51.19921875 * 0.24609375) << off;
    EXPECT_EQ(overlap_area(b, a).area, overlap_area(a, b).area) << off;
  }
}

// A body and itself (or a bit-identical copy) are the same set. The reduction maps one onto
// the other through R0^T R1 = I + E with E the rounding of the axes (~1e-16 for double,
// ~1e-7 for float data, orthonormal only to float precision) scaled by the aspect ratio,
// which left the tangency band: float ellipses came out `a_contains_b`, rotated float
// ellipsoids and double ellipsoids of aspect >= 3e4 `overlapping`. Identical data is now
// `equal` before any reduction.
TEST(IntersectClassify, BodyEqualsItself) {
  const auto ef = make_ellipse<float>({0, 0}, 0.5f, {2, 1});
  const Ellipse2<float> ef_copy = ef;
  EXPECT_EQ(classify(ef, ef), Relation::equal);
  EXPECT_EQ(classify(ef, ef_copy), Relation::equal);
  EXPECT_EQ(intersect_boundaries(ef, ef_copy).status, BoundaryStatus::equal);
  EXPECT_NEAR(overlap_area(ef, ef_copy).area, 2 * pi, 1e-5);
  EXPECT_TRUE(overlap(ef, ef_copy));

  const Eigen::Quaternionf qf(Eigen::AngleAxisf(0.7f, Eigen::Vector3f(1, 2, 3).normalized()));
  const auto bf = make_ellipsoid<float>({1, -2, 3}, qf, {3, 1, 0.5f});
  EXPECT_EQ(classify(bf, bf), Relation::equal);

  const Eigen::Quaterniond qd(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  for (const double aspect : {3e4, 1e6, 1e8}) {
    const auto b = make_ellipsoid<double>({0, 0, 0}, qd, {aspect, 1, 1});
    const Ellipsoid3<double> copy = b;
    EXPECT_EQ(classify(b, copy), Relation::equal) << aspect;
    EXPECT_TRUE(overlap(b, copy)) << aspect;
  }
}

// A ball of radius 47 and one of 1e-106 near its center (4e-12 away): the big ball contains
// the small one, and swapping the arguments must mirror the answer bit for bit. The
// Perram-Wertheim certificate started at l = rho_a / (rho_a + rho_b) and used 1 - l as the
// other weight: in one order 1 - l rounded to 0 (no certificate), in the other C =
// (1 - l) Sa + l Sb ~ 5e-105 I had the subnormal determinant 1e-313, whose reciprocal
// overflowed, so F = inf "proved" separation. The weights are now carried separately (each
// from its own formula, swapped exactly with the bodies) and a subnormal determinant or
// pivot leaves the pair to the exact path.
TEST(IntersectClassify, SwapSymmetryAtRadiusRatio1e107) {
  const auto a = make_ball<double, 3>({-69.2734375, -69.2734375, -69.2734375}, 46.731640624999997);
  const auto b = make_ball<double, 3>({-69.273437500001648, -69.273437500002473, -69.273437500003297},
                                      1.0795000000000001e-106);
  EXPECT_EQ(classify(a, b), Relation::a_contains_b);
  EXPECT_EQ(classify(b, a), Relation::b_contains_a);
  EXPECT_TRUE(overlap(a, b));
  EXPECT_TRUE(overlap(b, a));
  // The batch filter runs the same certificate: the same answers.
  const std::array<Ellipsoid3<double>, 2> first{a, b}, second{b, a};
  std::array<Relation, 2> batch;
  classify<double, 3>(first, second, batch);
  EXPECT_EQ(batch[0], Relation::a_contains_b);
  EXPECT_EQ(batch[1], Relation::b_contains_a);
}

// An ellipse 1e81 times smaller inside another, well away from its boundary: contained, so
// overlap is true. In the reduced frame (the small ellipse is the unit ball) L has entries
// ~1e81, and one-sided Jacobi measured a column pair's orthogonality as
// |gamma| / sqrt(|w_p|^2 |w_q|^2): the product of the squared norms overflowed, the ratio
// was 0, no rotation ran, and the "semi-axes" were L's non-orthogonal columns. classify
// escaped through its wide-type re-decision; overlap, certain of its wrong gap, said false.
// The norms are now square-rooted before the product.
TEST(IntersectClassify, OverlapAtRadiusRatio1e81) {
  const auto a = make_ellipse<double>({-7.5, -7.5}, std::atan2(0.97356397407241135, 0.2284145100214369),
                                      {2.1022593045130522, 0.36228745053187528});
  const auto b = make_ellipse<double>({-7.9563219788585373, -8.4864279106587581},
                                      std::atan2(0.68654837078633391, 0.72708413170047281),
                                      {2.3944199762187534e-81, 3.671045459046027e-81});
  // b's center is well inside a (a's quadric there, in closed form), and b is 1e-81 small.
  const Vec2<double> d = a.axes().transpose() * (b.center() - a.center());
  ASSERT_LT(d.cwiseQuotient(a.radii()).squaredNorm(), 0.7);
  EXPECT_EQ(classify(a, b), Relation::a_contains_b);
  EXPECT_TRUE(overlap(a, b));
  EXPECT_TRUE(overlap(b, a));
  const double area_b = pi * 2.3944199762187534e-81 * 3.671045459046027e-81;
  EXPECT_NEAR(overlap_area(a, b).area, area_b, 1e-15 * area_b);
}

// A circle of radius 0.05 a subnormal 2.4e-320 off the unit circle's center: contained.
// In the reduced frame (the small circle is the unit ball) the farthest point of O was
// k_i (x + e^2) / (g_i + x) with g_i + x ~ e_i k_i subnormal, so the quotient overflowed and
// the farthest point was infinite: `overlapping`. Such offsets are now exactly zero.
TEST(IntersectClassify, SubnormalCenterOffset) {
  const auto a = make_ball<double, 2>({0, 0}, 1);
  const auto b = make_ball<double, 2>({subnormal, 0}, 0.05);
  EXPECT_EQ(classify(a, b), Relation::a_contains_b);
  EXPECT_EQ(classify(b, a), Relation::b_contains_a);
  EXPECT_EQ(intersect_boundaries(a, b).count, 0);
  EXPECT_NEAR(overlap_area(a, b).area, pi * 0.05 * 0.05, 1e-16);
}

// An ellipse of radii (3, 1) at the origin on the boundary of a ball of radius R = 1e20
// whose top is at the origin. The tangency band is relative to the rounder body, the ball,
// so the pair is `touching` (every point of the small ellipse lies within 1e-12 R of the
// ball's boundary), and every critical point of the ellipse's distance from the ball's
// center fell in the band: intersect_boundaries returned two tangent points, the same
// point twice, where a touching pair (disjoint interiors) has exactly one.
TEST(IntersectClassify, TouchingSmallEllipseOnHugeBallHasOnePoint) {
  Mat2<double> axes;
  axes << -0x1.29fbebf632f94p-3, 0x1.fa8d2a028cf7bp-1, -0x1.fa8d2a028cf7bp-1, -0x1.29fbebf632f94p-3;
  const auto a = Ellipse2<double>::from_axes({0x1p-991, 0}, axes, {3, 1});
  for (const double r : {1e20, 1e100, 0x1.3c76f17ef8c82p+951}) {
    const auto b = make_ball<double, 2>({0x0.00000fcfcfcfcp-1022, -r}, r);
    ASSERT_EQ(classify(a, b), Relation::touching) << r;
    for (const auto& x : {intersect_boundaries(a, b), intersect_boundaries(b, a)}) {
      ASSERT_EQ(x.count, 1) << r;
      EXPECT_EQ(x.kinds[0], CrossingKind::tangent);
      // Within the accuracy the header states: 1e-12 * (3 + r) of both boundaries.
      EXPECT_LE(std::abs((x.points[0] - b.center()).stableNorm() - r), 1e-12 * (3 + r)) << r;
    }
  }
}

// A circle of radius r ~ 1.9e-295 at (r, r) against a circle of radius R ~ 1.7e-19 at
// (~0, R): the small one sits on the x axis where the large one touches it, inside the large
// one to within r^2 / R. At this radius ratio (2^916) the lens between the crossings is
// rounding noise in any frame: overlap_area summed its polygon and segments to -1.8e-94.
// The area is now bounded to [0, the smaller area] (intersect2.hpp), here pi r^2, which
// underflows to 0; scaled by 2^k the bound scales exactly.
TEST(IntersectClassify, OverlapAreaNegativeNear1e294) {
  const double r = 0x1.dcdcdcdcdcdcdp-979, big = 0x1.8181818p-63;
  Mat2<double> axes_a, axes_b;
  axes_a << 1, -r, r, 1;
  axes_b << 1, -big, big, 1;
  for (const int k : {0, 600, 900}) {
    const double s = std::ldexp(1.0, k);
    const auto a = Ellipse2<double>::from_axes({s * r, s * r}, axes_a, {s * r, s * r});
    const auto b = Ellipse2<double>::from_axes({s * 0x1.0030303030303p-1007, s * big}, axes_b, {s * big, s * big});
    const double smaller = pi * (s * r) * (s * r);
    for (const auto& area : {overlap_area(a, b), overlap_area(b, a)}) {
      EXPECT_GE(area.area, 0) << k;
      EXPECT_LE(area.area, smaller) << k;
      EXPECT_NE(area.relation, Relation::separated) << k;
    }
  }
}

// A ball of radius R ~ 3e47 whose top is at the origin and a ball of radius 8 centered 7
// below it: the small ball's center is 7 inside the large one and it pokes out by 1, a gap
// of -15 / R relative to the large ball, within the tangency band. With the small ball as
// the unit ball (ties of aspect ratio went to the smaller radii) the large one's center was
// 2^154 units away, rounded by far more than the small one's size: classify (deciding in
// long double) said separated while overlap (in double) said true and first_contact
// overlapping_at_start. Ties now go to the larger radii, where the pair is resolved, and
// every query reports the touching pair.
TEST(IntersectClassify, OverlapClassifyContactAgreeSmallBallOnHugeBall) {
  const double r = 0x1.9c9c9c9c9c9c9p+157;
  Mat3<double> axes_a, axes_b;
  axes_a << 0x1.f8p-47, 0x1.f4p-47, 0x1.fffffffffffffp-1, 0x1.fffffffffffffp-1, 0x1.f8p-47, -0x1.f4p-47, -0x1.f4p-47,
      0x1.fffffffffffffp-1, -0x1.fp-47;
  axes_b = Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized().toRotationMatrix();
  const auto a = Ellipsoid3<double>::from_axes({0, 0x1.9c9c9c9c9c9c9p-1011, -r}, axes_a, {r, r, r});
  const auto b = Ellipsoid3<double>::from_axes({-8, -8, -7}, axes_b, {8, 8, 8});
  EXPECT_EQ(classify(a, b), Relation::touching);
  EXPECT_EQ(classify(b, a), Relation::touching);
  EXPECT_TRUE(overlap(a, b));
  EXPECT_TRUE(overlap(b, a));
  EXPECT_EQ(distance(a, b).status, DistanceStatus::touching);
  const Vec3<double> va(1, 0, 0), vb(0, 0, -0.0625);
  EXPECT_EQ(first_contact(a, va, b, vb, 1.0).status, ContactStatus::touching_at_start);
  EXPECT_EQ(first_contact(b, vb, a, va, 1.0).status, ContactStatus::touching_at_start);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
