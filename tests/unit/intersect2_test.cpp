// intersect_boundaries, overlap_area and intersection_over_union against closed forms:
// crossing circles, the four-crossing cross of two ellipses, concentric pairs, tangency
// from outside and inside, equal ellipses, separation and containment.
#include <ellipsect/intersect2.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;

Ellipse2<double> ellipse(double x, double y, double angle, double r0, double r1) {
  return make_ellipse<double>({x, y}, angle, {r0, r1});
}

// Distance of p to the boundary of e, to first order: |sqrt(q) - 1| / |grad sqrt(q)|.
double off_boundary(const Ellipse2<double>& e, const Vec2<double>& p) {
  const Vec2<double> d = e.axes().transpose() * (p - e.center());
  const double q = std::sqrt(d.cwiseQuotient(e.radii()).squaredNorm());
  const double grad = d.cwiseQuotient(e.radii().cwiseAbs2()).norm() / q;
  return std::abs(q - 1) / grad;
}

int count(const BoundaryIntersection<double>& x, CrossingKind kind) {
  int n = 0;
  for (int i = 0; i < x.count; ++i) n += x.kinds[i] == kind;
  return n;
}

// Each expected point is matched by one reported point.
void expect_points(const BoundaryIntersection<double>& x, const std::vector<Vec2<double>>& want, double tol) {
  ASSERT_EQ(x.count, static_cast<int>(want.size()));
  for (const auto& w : want) {
    double best = 1e300;
    for (int i = 0; i < x.count; ++i) best = std::min(best, (x.points[i] - w).norm());
    EXPECT_LT(best, tol) << w.transpose();
  }
}

TEST(Intersect2, CrossingCircles) {
  const auto a = make_ball<double, 2>({0, 0}, 1.0), b = make_ball<double, 2>({1, 0}, 1.0);
  const auto x = intersect_boundaries(a, b);
  EXPECT_EQ(x.status, BoundaryStatus::points);
  expect_points(x, {{0.5, std::sqrt(0.75)}, {0.5, -std::sqrt(0.75)}}, 1e-15);
  EXPECT_EQ(count(x, CrossingKind::transverse), 2);
  // Counter-clockwise around a: the lower point (angle -60 degrees) first.
  EXPECT_LT(x.points[0].y(), 0.0);
  const auto area = overlap_area(a, b);
  EXPECT_EQ(area.relation, Relation::overlapping);
  EXPECT_NEAR(area.area, 2 * M_PI / 3 - std::sqrt(0.75), 1e-15);
}

// x^2/4 + y^2 = 1 and x^2 + y^2/4 = 1 cross at (+-2/sqrt5, +-2/sqrt5); the common area is
// 4 a b atan(b / a).
TEST(Intersect2, FourCrossingsOfACross) {
  const auto a = ellipse(0, 0, 0, 2, 1), b = ellipse(0, 0, M_PI / 2, 2, 1);
  const double c = 2 / std::sqrt(5.0);
  const auto x = intersect_boundaries(a, b);
  expect_points(x, {{c, c}, {-c, c}, {-c, -c}, {c, -c}}, 1e-14);
  EXPECT_EQ(count(x, CrossingKind::transverse), 4);
  EXPECT_NEAR(overlap_area(a, b).area, 8 * std::atan(0.5), 4e-15);
  // The same moved and rotated rigidly.
  const double t = 0.7, dx = 3, dy = -2;
  const auto am = ellipse(dx, dy, t, 2, 1), bm = ellipse(dx, dy, t + M_PI / 2, 2, 1);
  EXPECT_EQ(count(intersect_boundaries(am, bm), CrossingKind::transverse), 4);
  EXPECT_NEAR(overlap_area(am, bm).area, 8 * std::atan(0.5), 1e-14);
}

// A circle concentric with an ellipse, its radius between the semi-axes: four crossings
// at x^2 = (R^2 - b^2) / (1 - b^2/a^2); the area is 2 R^2 phi0 + 2 a b (pi/2 - t0), phi0 the
// polar angle and t0 the ellipse's parameter of the first-quadrant crossing.
TEST(Intersect2, ConcentricCircleAndEllipse) {
  const double a = 2, b = 1, r = 1.5;
  const double x0 = std::sqrt((r * r - b * b) / (1 - b * b / (a * a))), y0 = std::sqrt(r * r - x0 * x0);
  const auto e = ellipse(0, 0, 0, a, b), c = make_ball<double, 2>({0, 0}, r);
  const auto x = intersect_boundaries(e, c);
  expect_points(x, {{x0, y0}, {-x0, y0}, {-x0, -y0}, {x0, -y0}}, 1e-15);
  const double phi0 = std::atan2(y0, x0), t0 = std::atan2(y0 / b, x0 / a);
  EXPECT_NEAR(overlap_area(e, c).area, 2 * r * r * phi0 + 2 * a * b * (M_PI / 2 - t0), 1e-14);
  EXPECT_NEAR(overlap_area(c, e).area, overlap_area(e, c).area, 1e-15);
}

// A circle centered on the minor axis of an ellipse (the symmetric "hard case" of the
// critical points): crossings come in mirror pairs x -> -x and lie on both curves. The
// circle of radius 1.9 about (0, 0.9) also touches the bottom vertex (0, -1) from inside
// (its radius of curvature, 1.9, is below the ellipse's, a^2 / b = 4).
TEST(Intersect2, CircleOnTheAxis) {
  const auto e = ellipse(0, 0, 0, 2, 1);
  for (const double y : {0.0, 0.3, 0.9}) {
    for (const double r : {0.5, 1.2, 1.9}) {
      const auto c = make_ball<double, 2>({0, y}, r);
      const auto x = intersect_boundaries(e, c);
      for (int i = 0; i < x.count; ++i) {
        EXPECT_LT(off_boundary(e, x.points[i]), 4e-15) << y << " " << r;
        EXPECT_LT(off_boundary(c, x.points[i]), 4e-15) << y << " " << r;
        double mirror = 1e300;
        for (int j = 0; j < x.count; ++j)
          mirror = std::min(mirror, (x.points[j] - Vec2<double>(-x.points[i].x(), x.points[i].y())).norm());
        EXPECT_LT(mirror, 1e-14) << y << " " << r;
      }
      EXPECT_EQ(count(x, CrossingKind::transverse) % 2, 0) << y << " " << r;
      EXPECT_EQ(count(x, CrossingKind::tangent), y == 0.9 && r == 1.9 ? 1 : 0) << y << " " << r;
    }
  }
}

// Tangent from outside (a touching pair), from inside (containment with a common point),
// and the same pairs moved off by more than the band.
TEST(Intersect2, Tangency) {
  const auto e = ellipse(0, 0, 0, 2, 1);
  const auto out = intersect_boundaries(e, make_ball<double, 2>({3, 0}, 1.0));
  expect_points(out, {{2, 0}}, 1e-15);
  EXPECT_EQ(out.kinds[0], CrossingKind::tangent);
  const auto touching = overlap_area(e, make_ball<double, 2>({3, 0}, 1.0));
  EXPECT_EQ(touching.relation, Relation::touching);
  EXPECT_EQ(touching.area, 0.0);
  // Radius 0.25 < the radius of curvature at the vertex (b^2 / a = 0.5): inside, touching.
  const auto inner = make_ball<double, 2>({1.75, 0}, 0.25);
  const auto in = intersect_boundaries(e, inner);
  expect_points(in, {{2, 0}}, 1e-15);
  EXPECT_EQ(in.kinds[0], CrossingKind::tangent);
  const auto contained = overlap_area(e, inner);
  EXPECT_EQ(contained.relation, Relation::a_contains_b);
  EXPECT_NEAR(contained.area, M_PI / 16, 1e-16);
  EXPECT_EQ(intersect_boundaries(e, make_ball<double, 2>({3 + 1e-9, 0}, 1.0)).count, 0);
  const auto crossing = intersect_boundaries(e, make_ball<double, 2>({3 - 1e-9, 0}, 1.0));
  EXPECT_EQ(count(crossing, CrossingKind::transverse), 2);
  EXPECT_EQ(intersect_boundaries(e, make_ball<double, 2>({1.75 - 1e-9, 0}, 0.25)).count, 0);
}

TEST(Intersect2, EqualSeparatedContained) {
  const auto e = ellipse(1, 2, 0.4, 3, 0.5);
  const auto same = intersect_boundaries(e, e);
  EXPECT_EQ(same.status, BoundaryStatus::equal);
  EXPECT_EQ(same.count, 0);
  EXPECT_EQ(overlap_area(e, e).relation, Relation::equal);
  EXPECT_NEAR(overlap_area(e, e).area, M_PI * 1.5, 1e-15);
  const auto far = ellipse(10, 2, 0.1, 1, 2);
  EXPECT_EQ(intersect_boundaries(e, far).count, 0);
  EXPECT_EQ(overlap_area(e, far).area, 0.0);
  EXPECT_EQ(overlap_area(e, far).relation, Relation::separated);
  const auto small = ellipse(1.5, 2.1, -0.3, 0.3, 0.2);
  EXPECT_EQ(intersect_boundaries(e, small).count, 0);
  EXPECT_NEAR(overlap_area(small, e).area, M_PI * 0.06, 1e-16);
  EXPECT_EQ(overlap_area(small, e).relation, Relation::b_contains_a);
}

// Swapping the arguments gives the same points (in a's order) and the same area.
TEST(Intersect2, SwapSymmetry) {
  const auto a = ellipse(0.2, -0.1, 0.3, 2, 0.6), b = ellipse(0.5, 0.4, -1.1, 1.5, 0.4);
  const auto ab = intersect_boundaries(a, b), ba = intersect_boundaries(b, a);
  ASSERT_EQ(ab.count, ba.count);
  for (int i = 0; i < ab.count; ++i) {
    bool found = false;
    for (int j = 0; j < ba.count; ++j) found = found || ab.points[i] == ba.points[j];
    EXPECT_TRUE(found) << i;
  }
  EXPECT_EQ(overlap_area(a, b).area, overlap_area(b, a).area);
}

TEST(Intersect2, FloatInstantiation) {
  const auto a = make_ball<float, 2>({0, 0}, 1.0f), b = make_ball<float, 2>({1, 0}, 1.0f);
  const auto x = intersect_boundaries(a, b);
  EXPECT_EQ(x.count, 2);
  EXPECT_NEAR(x.points[1].y(), std::sqrt(0.75f), 1e-6f);
  EXPECT_NEAR(overlap_area(a, b).area, 2 * M_PI / 3 - std::sqrt(0.75), 1e-6);
}

TEST(Intersect2, Names) {
  EXPECT_EQ(to_string(CrossingKind::transverse), "transverse");
  EXPECT_EQ(to_string(CrossingKind::tangent), "tangent");
  EXPECT_EQ(to_string(BoundaryStatus::points), "points");
  EXPECT_EQ(to_string(BoundaryStatus::equal), "equal");
}

// intersection_over_union: 1 for equal ellipses, the ratio of the areas under containment,
// 0 apart, 8 atan(1/2) / (4 pi - 8 atan(1/2)) for the cross, unchanged by a 2^600 scale.
TEST(Intersect2, IntersectionOverUnion) {
  const auto e = ellipse(1, 2, 0.4, 3, 0.5);
  EXPECT_NEAR(intersection_over_union(e, e), 1.0, 1e-15);
  EXPECT_EQ(intersection_over_union(e, ellipse(10, 2, 0.1, 1, 2)), 0.0);
  const auto small = ellipse(1.5, 2.1, -0.3, 0.3, 0.2);
  EXPECT_NEAR(intersection_over_union(small, e), 0.06 / 1.5, 1e-15);
  const auto a = ellipse(0, 0, 0, 2, 1), b = ellipse(0, 0, M_PI / 2, 2, 1);
  const double common = 8 * std::atan(0.5);
  EXPECT_NEAR(intersection_over_union(a, b), common / (4 * M_PI - common), 1e-14);
  EXPECT_EQ(intersection_over_union(b, a), intersection_over_union(a, b));
  const double s = std::ldexp(1.0, 600);
  const auto as = make_ellipse<double>({0, 0}, 0, {2 * s, s}), bs = make_ellipse<double>({0, 0}, M_PI / 2, {2 * s, s});
  EXPECT_EQ(intersection_over_union(as, bs), intersection_over_union(a, b));
  EXPECT_NEAR(intersection_over_union(make_ellipse<float>({0, 0}, 0, {2, 1}), make_ellipse<float>({0, 0}, 1.5707964f, {2, 1})),
              common / (4 * M_PI - common), 1e-6);
}

// Bodies within a hair of equal. With tolerance 0 they are overlapping, but offsets below eps
// of the radii leave no crossing to resolve: the intersection is the smaller body to rounding
// (its area was 0, the IoU 0 for an ellipse offset by 1e-14 of its size). With the default
// tolerance they are equal or contained, and the IoU is exactly 1, or the ratio of the areas,
// never above 1 where the "contained" body is the larger by a hair.
TEST(Intersect2, NearlyEqualBodies) {
  const Options exact{.tolerance = 0};
  const auto b = ellipse(0, 0, 0.3, 2, 1);
  for (const double offset : {1e-13, 3e-14, 1e-14, 1e-15, 1e-16, 1e-300}) {
    const auto a = ellipse(offset, 0, 0.3, 2, 1);
    const OverlapArea<double> i = overlap_area(a, b, exact);
    EXPECT_EQ(i.relation, Relation::overlapping) << offset;
    // The lens misses two slivers of width offset along the boundary: 4 offset sizes at most.
    EXPECT_NEAR(i.area, 2 * M_PI, 4 * 2 * offset + 1e-14) << offset;
    EXPECT_NEAR(intersection_over_union(a, b, exact), 1.0, 4 * offset + 1e-14) << offset;
  }
  EXPECT_EQ(intersection_over_union(ellipse(1e-14, 0, 0.3, 2, 1), b), 1.0);  // equal in the band
  for (int k = -8; k <= 8; ++k) {
    const double grow = 1 + k * 2.5e-13;
    const auto a = ellipse(k * 1e-13, 0, 0.3, 2 * grow, 1 / std::sqrt(grow));
    const double iou = intersection_over_union(a, b);
    EXPECT_GE(iou, 0.0) << k;
    EXPECT_LE(iou, 1.0) << k;
    EXPECT_LE(overlap_area(a, b).area, std::min(2 * M_PI * grow / std::sqrt(grow), 2 * M_PI)) << k;
  }
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
