// Niemitalo's polygonal tests on configurations whose answer follows from elementary
// geometry: segment-circle, the document's two worked examples, every status, and the
// document's error bound itself.
#include <ellipsect/classify.hpp>
#include <ellipsect/point.hpp>
#include <ellipsect/polygonal2.hpp>

#include "detail/niemitalo_polygon.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// Center of a circle of radius r on the outward normal at the boundary point with
// parameter theta, r + g from it: the nearest point of the convex ellipse to the center
// is that boundary point, so the signed gap between the bodies is g.
Vec2<double> center_at_gap(const Ellipse2<double>& e, double theta, double r, double g) {
  const Vec2<double> on(e.radii()[0] * std::cos(theta), e.radii()[1] * std::sin(theta));
  const Vec2<double> normal = on.cwiseQuotient(e.radii().cwiseAbs2()).normalized();
  return e.center() + e.axes() * (on + (r + g) * normal);
}

TEST(SegmentCircle, MiddleEndpointsAndSide) {
  const Vec2<double> a(0, 0), b(4, 0);
  auto test = [&](Vec2<double> c, double r) { return segment_circle<double>(a, b, make_circle(c, r)); };
  EXPECT_EQ(test({2, 1.5}, 1).verdict, Verdict::no_collision);  // beside the middle, too far
  EXPECT_EQ(test({2, 1.5}, 1).side, Side::left);
  EXPECT_EQ(test({2, -0.5}, 1).verdict, Verdict::collision);    // crosses the middle
  EXPECT_EQ(test({2, -0.5}, 1).side, Side::right);
  EXPECT_EQ(test({2, 0}, 0.1).side, Side::on_line);
  EXPECT_EQ(test({5, 0.5}, 1.2).verdict, Verdict::collision);   // end point inside: 1.118 < 1.2
  EXPECT_EQ(test({5.5, 0}, 1).verdict, Verdict::no_collision);  // on the line, beyond the end
  EXPECT_EQ(test({-3, 4}, 5).verdict, Verdict::collision);  // start point on the circle
  EXPECT_EQ(test({-3, 4}, 4.999).verdict, Verdict::no_collision);
  // Swapping the end points mirrors the side.
  EXPECT_EQ(segment_circle<double>(b, a, make_circle<double>({2, 1.5}, 1)).side, Side::right);
}

// Small integers are exact in float: a tangent circle (distance == radius) touches.
TEST(SegmentCircle, ExactTangencyInFloat) {
  EXPECT_EQ(segment_circle<float>({1, 1}, {7, 1}, make_circle<float>({4, 4}, 3)).verdict, Verdict::collision);
  EXPECT_EQ(segment_circle<float>({1, 1}, {7, 1}, make_circle<float>({4, 4}, 2.9999998f)).verdict, Verdict::no_collision);
  // Along a slanted segment (3, 4) with the center 5 to its left.
  EXPECT_EQ(segment_circle<float>({0, 0}, {6, 8}, make_circle<float>({-1, 7}, 5)).verdict, Verdict::collision);
  EXPECT_EQ(segment_circle<float>({0, 0}, {6, 8}, make_circle<float>({-1, 7}, 5)).side, Side::left);
}

TEST(SegmentCircle, DegenerateSegmentIsAPoint) {
  EXPECT_EQ(segment_circle<double>({1, 1}, {1, 1}, make_circle<double>({1.5, 1}, 1)).verdict, Verdict::collision);
  EXPECT_EQ(segment_circle<double>({1, 1}, {1, 1}, make_circle<double>({3, 1}, 1)).verdict, Verdict::no_collision);
  EXPECT_EQ(segment_circle<double>({1, 1}, {1, 1}, make_circle<double>({1, 1}, 0)).verdict, Verdict::collision);
}

TEST(SegmentCircle, InvalidInput) {
  const auto c = make_circle<double>({0, 0}, 1);
  EXPECT_EQ(segment_circle<double>({nan, 0}, {1, 0}, c).verdict, Verdict::invalid_input);
  EXPECT_EQ(segment_circle<double>({0, 0}, {1, std::numeric_limits<double>::infinity()}, c).verdict,
            Verdict::invalid_input);
  EXPECT_EQ(segment_circle<double>({0, 0}, {1, 0}, c).verdict, Verdict::collision);
  EXPECT_EQ(to_string(Verdict::undecided), "undecided");
  EXPECT_EQ(to_string(Side::on_line), "on_line");
}

// The circle is validated once; the error names the field.
TEST(Circle, FactoryValidatesAndNamesTheField) {
  auto field = [](auto make) {
    try {
      make();
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("no error");
  };
  EXPECT_EQ(field([] { make_circle<double>({nan, 0}, 1); }), "center[0]");
  EXPECT_EQ(field([] { make_circle<double>({0, std::numeric_limits<double>::infinity()}, 1); }), "center[1]");
  EXPECT_EQ(field([] { make_circle<double>({0, 0}, -1); }), "radius");
  EXPECT_EQ(field([] { make_circle<float>({0, 0}, nan); }), "radius");
  EXPECT_EQ(field([] { make_circle<double>({0, 0}, 0).ellipse(); }), "radius");  // a point is no Ellipse2
  const auto c = make_circle<double>({1, -2}, 3);
  EXPECT_EQ(c.center(), Vec2<double>(1, -2));
  EXPECT_EQ(c.radius(), 3);
  const Ellipse2<double> e = c.ellipse();
  EXPECT_EQ(e.center(), c.center());
  EXPECT_EQ(e.radii(), Vec2<double>(3, 3));
}

// The document's first example: ellipse at (-1, 5) with horizontal radius 10 and vertical
// radius 20, circle at (25, 7) of radius 15. Independently: the ellipse lies in x <= 9, the
// circle in x >= 10, so the line x = 9.5 separates them with a gap of at least 1. No
// iteration count may report a collision, and once the error bound 2^(0.303 - 2n) * 20 is
// below 1 (n >= 3) the answer must be no_collision.
TEST(PolygonalOverlap, DocumentExampleEllipseCircle) {
  const auto e = make_ellipse<double>({-1, 5}, 0, {10, 20});
  const Vec2<double> c(25, 7);
  for (int n = 0; n <= 20; ++n) {
    const auto r = polygonal_overlap(e, make_circle(c, 15.0), n);
    EXPECT_NE(r.verdict, Verdict::collision) << n;
    if (niemitalo_error_bound(20.0, n) < 1) {
      EXPECT_EQ(r.verdict, Verdict::no_collision) << n;
    }
    // The same pair as two ellipses (parallel axes), and in float.
    const auto rr = polygonal_overlap(e, make_circle(c, 15.0).ellipse(), n);
    EXPECT_NE(rr.verdict, Verdict::collision) << n;
    if (niemitalo_error_bound(20.0, n) < 1) {
      EXPECT_EQ(rr.verdict, Verdict::no_collision) << n;
    }
    const auto rf = polygonal_overlap(make_ellipse<float>({-1, 5}, 0, {10, 20}), make_circle<float>({25, 7}, 15), n);
    if (niemitalo_error_bound(20.0, n) < 1) {
      EXPECT_EQ(rf.verdict, Verdict::no_collision) << n;
    }
  }
  EXPECT_EQ(polygonal_overlap(e, make_circle(c, 15.0), 10).verdict, Verdict::no_collision);
  // Moving the circle 2 to the left makes x = 8..9 shared on the line y = 7 (the ellipse
  // reaches x = -1 + 10 sqrt(1 - (2/20)^2) = 8.95 there): a collision.
  EXPECT_EQ(polygonal_overlap(e, make_circle<double>({23, 7}, 15), 10).verdict, Verdict::collision);
}

// The document's second example: ellipse 0 at (-10, 5) with radius vector (10, 20) and the
// perpendicular radius 3 times as long; ellipse 1 at (3, 4) with radius vector (5, -4) and
// the other radius 0.75 times as long. By hand: ellipse 1's center, seen from ellipse 0's
// center, is (13, -1); along the unit axes (1, 2) / sqrt(5) and (-2, 1) / sqrt(5) that is
// 11 / sqrt(5) and -27 / sqrt(5), and with radii sqrt(500) and 3 sqrt(500) the quadric is
// (11 / 50)^2 + (27 / 150)^2 = 0.0808 < 1: the center of ellipse 1 is inside ellipse 0,
// a common point, so they collide.
TEST(PolygonalOverlap, DocumentExampleTwoRotatedEllipses) {
  const auto e0 = make_ellipse<double>({-10, 5}, std::atan2(20.0, 10.0), {std::sqrt(500.0), 3 * std::sqrt(500.0)});
  const auto e1 = make_ellipse<double>({3, 4}, std::atan2(-4.0, 5.0), {std::sqrt(41.0), 0.75 * std::sqrt(41.0)});
  for (int n = 0; n <= 20; ++n) EXPECT_NE(polygonal_overlap(e0, e1, n).verdict, Verdict::no_collision) << n;
  EXPECT_EQ(polygonal_overlap(e0, e1, 10).verdict, Verdict::collision);
  EXPECT_EQ(polygonal_overlap(e1, e0, 10).verdict, Verdict::collision);
  const auto f0 = make_ellipse<float>({-10, 5}, std::atan2(20.0f, 10.0f), {std::sqrt(500.0f), 3 * std::sqrt(500.0f)});
  const auto f1 = make_ellipse<float>({3, 4}, std::atan2(-4.0f, 5.0f), {std::sqrt(41.0f), 0.75f * std::sqrt(41.0f)});
  EXPECT_EQ(polygonal_overlap(f0, f1, 10).verdict, Verdict::collision);
}

// The document's code answers `true` here (its bisection treats a circle center on the
// inner side of a new chord, within the chord's extent, as a collision; after the
// non-parallel stretch that region reaches outside the ellipse). The pair is separated:
// the Perram-Wertheim factor is 1.003 (classify, exact outside a 2e-12 band).
TEST(PolygonalOverlap, DocumentShortcutSeparatedPair) {
  const auto a = make_ellipse<double>({0, 0}, 0.086, {0.83, 0.74});
  const auto b = make_ellipse<double>({5.39, -2.45}, -0.53, {5.31, 0.188});
  ASSERT_EQ(classify(a, b), Relation::separated);
  EXPECT_EQ(polygonal_overlap(a, b, 10).verdict, Verdict::no_collision);
  EXPECT_EQ(polygonal_overlap(b, a, 10).verdict, Verdict::no_collision);
}

// The documented rounding allowance rho and the exact band of level n (polygonal2.hpp, "The band").
double rho(const Ellipse2<double>& e, const Vec2<double>& c, double r, int n) {
  const Vec2<double> d = c - e.center();
  return 16 * (n + 2) * std::numeric_limits<double>::epsilon() * (std::abs(d.x()) + std::abs(d.y()) + e.radii().maxCoeff() + r);
}
double half_angle(int n) { return M_PI / std::ldexp(1.0, n + 2); }

// Ellipse (2, 1) and a unit circle at signed gap g from a boundary point that is not a
// vertex of any level (parameter 0.3): decided once the bound is below |g|, undecided
// (at level n) before. The band always holds g; an undecided one is the polygon's band of
// level n, (1 / cos h - 1) * 2 above and (1 - cos h) * 2 below, widened by rho.
TEST(PolygonalOverlap, GapAtABoundaryPoint) {
  const auto e = make_ellipse<double>({1, -2}, 0.7, {2, 1});
  for (double g : {0.5, 1e-3, -1e-3, -0.5}) {
    const Vec2<double> c = center_at_gap(e, 0.3, 1.0, g);
    for (int n = 0; n <= 12; ++n) {
      const auto r = polygonal_overlap(e, make_circle(c, 1.0), n);
      const Verdict want = g > 0 ? Verdict::no_collision : Verdict::collision;
      if (niemitalo_error_bound(2.0, n) < std::abs(g)) {
        EXPECT_EQ(r.verdict, want) << g << " " << n;
      } else {
        EXPECT_TRUE(r.verdict == want || r.verdict == Verdict::undecided) << g << " " << n;
      }
      EXPECT_EQ(r.iterations, r.level);  // one triangle followed: one bisection per level
      EXPECT_LE(r.level, n);
      EXPECT_LE(r.gap_lo, g) << g << " " << n;
      EXPECT_GE(r.gap_hi, g) << g << " " << n;
      const double slack = rho(e, c, 1.0, r.level);
      if (r.verdict == Verdict::undecided) {
        EXPECT_EQ(r.level, n);
        EXPECT_NEAR(r.gap_hi, 2 * (1 / std::cos(half_angle(n)) - 1) + slack, 1e-15) << n;
        EXPECT_NEAR(r.gap_lo, -2 * (1 - std::cos(half_angle(n))) - slack, 1e-15) << n;
        EXPECT_LE(std::max(r.gap_hi, -r.gap_lo), niemitalo_error_bound(e, n) + slack);
      } else if (r.verdict == Verdict::collision) {
        EXPECT_EQ(r.gap_lo, -std::numeric_limits<double>::infinity());
        EXPECT_EQ(r.gap_hi, slack);
      } else {
        EXPECT_EQ(r.gap_lo, -slack);
        EXPECT_EQ(r.gap_hi, std::numeric_limits<double>::infinity());
      }
    }
  }
  // A gap of 1e-9 needs about 15 levels (the exact band is a quarter of the bound).
  const Vec2<double> c = center_at_gap(e, 0.3, 1.0, 1e-9);
  const auto r5 = polygonal_overlap(e, make_circle(c, 1.0), 5);
  EXPECT_EQ(r5.verdict, Verdict::undecided);
  EXPECT_EQ(r5.level, 5);
  EXPECT_EQ(r5.iterations, 5);
  EXPECT_EQ(polygonal_overlap(e, make_circle(c, 1.0), 25).verdict, Verdict::no_collision);
  // Where the contact is a vertex of the level-0 polygon, level 0 decides at once.
  const auto at_vertex = polygonal_overlap(e, make_circle(center_at_gap(e, 0.0, 1.0, 1e-9), 1.0), 5);
  EXPECT_EQ(at_vertex.verdict, Verdict::no_collision);
  EXPECT_EQ(at_vertex.level, 0);
  EXPECT_EQ(at_vertex.iterations, 0);
}

// Containment either way is a collision, decided at level 0 (the center is inside the
// inscribed polygon, or the circle covers its edges).
TEST(PolygonalOverlap, ContainmentAndFarApart) {
  const auto e = make_ellipse<double>({0, 0}, 0.3, {5, 1});
  EXPECT_EQ(polygonal_overlap(e, make_circle<double>({0.5, 0.1}, 0.1), 0).verdict, Verdict::collision);
  EXPECT_EQ(polygonal_overlap(e, make_circle<double>({0, 0}, 100), 0).verdict, Verdict::collision);
  EXPECT_EQ(polygonal_overlap(e, make_circle<double>({1e4, 1e4}, 1), 0).verdict, Verdict::no_collision);
  EXPECT_EQ(polygonal_overlap(e, make_circle<double>({0, 0}, 0), 0).verdict, Verdict::collision);  // a point
}

// Two ellipses with the same axes (up to order and sign) take the scaling route, others
// the rotation-stretch route; both give the same answers away from the band.
TEST(PolygonalOverlap, ParallelAndStretchRoutesAgree) {
  const auto a = make_ellipse<double>({0, 0}, 0, {3, 1});
  Mat2<double> quarter;
  quarter << 0, -1, 1, 0;
  for (double x : {3.5, 4.5}) {  // b reaches x - 1: overlapping, then at least 0.5 apart
    const auto b = make_ellipse<double>({x, 0.2}, 0, {1, 2});
    const Verdict want = x < 4 ? Verdict::collision : Verdict::no_collision;
    EXPECT_EQ(polygonal_overlap(a, b, 10).verdict, want);
    const auto swapped = Ellipse2<double>::from_axes({x, 0.2}, quarter, {2, 1});  // same set
    ASSERT_EQ(swapped.axes(), quarter);
    EXPECT_EQ(polygonal_overlap(a, swapped, 10).verdict, want);
    // The scene rotated by 0.9, b's axes off by an ulp: parallel, but not bit for bit.
    const Mat2<double> q = make_ellipse<double>({0, 0}, 0.9, {1, 1}).axes();
    Mat2<double> q_off = q;
    q_off(0, 0) = std::nextafter(q(0, 0), 2.0);
    const auto ar = Ellipse2<double>::from_axes(q * a.center(), q, a.radii());
    const auto br = Ellipse2<double>::from_axes(q * b.center(), q_off, b.radii());
    ASSERT_NE(ar.axes(), br.axes());
    EXPECT_EQ(polygonal_overlap(ar, br, 10).verdict, want);
  }
}

TEST(PolygonalOverlap, InvalidInput) {
  const auto e = make_ellipse<double>({0, 0}, 0, {2, 1});
  const auto c = make_circle<double>({0, 0}, 1);
  for (int bad : {-1, niemitalo_max_level + 1}) {
    for (const auto& r : {polygonal_overlap(e, c, bad), polygonal_overlap(e, e, bad), circle_cover_overlap(e, c, bad)}) {
      EXPECT_EQ(r.verdict, Verdict::invalid_input) << bad;
      EXPECT_TRUE(std::isnan(r.gap_lo) && std::isnan(r.gap_hi)) << bad;
    }
  }
  EXPECT_EQ(polygonal_overlap(e, make_circle<double>({9, 0}, 1), niemitalo_max_level).verdict, Verdict::no_collision);
}

// The circle cover: same answers away from its (wider) band, undecided inside it; the band
// holds g (its upper side is sin h * major); the search may follow more than one arc, so
// it can perform more bisections than levels.
TEST(CircleCoverOverlap, GapAtABoundaryPoint) {
  const auto e = make_ellipse<double>({0, 0}, 0, {2, 1});
  int more_bisections_than_levels = 0;
  for (double g : {0.5, 1e-2, -1e-2, -0.5}) {
    const Vec2<double> c = center_at_gap(e, 0.3, 1.0, g);
    for (int n = 0; n <= 12; ++n) {
      const auto r = circle_cover_overlap(e, make_circle(c, 1.0), n);
      const Verdict want = g > 0 ? Verdict::no_collision : Verdict::collision;
      const double band = g > 0 ? 2 * std::sin(half_angle(n)) : niemitalo_error_bound(2.0, n);
      if (band < std::abs(g)) {
        EXPECT_EQ(r.verdict, want) << g << " " << n;
      } else {
        EXPECT_TRUE(r.verdict == want || r.verdict == Verdict::undecided) << g << " " << n;
      }
      EXPECT_LE(r.gap_lo, g) << g << " " << n;
      EXPECT_GE(r.gap_hi, g) << g << " " << n;
      EXPECT_GE(r.iterations, r.level);
      EXPECT_LE(r.iterations, (2 << n) - 1);
      more_bisections_than_levels += r.iterations > r.level;
      if (r.verdict == Verdict::undecided) {
        EXPECT_EQ(r.level, n);
        EXPECT_NEAR(r.gap_hi, 2 * std::sin(half_angle(n)) + rho(e, c, 1.0, n), 1e-15) << n;
      }
    }
  }
  EXPECT_GT(more_bisections_than_levels, 0);
  EXPECT_EQ(circle_cover_overlap(e, make_circle<double>({0.5, 0.2}, 0.1)).verdict, Verdict::collision);
  EXPECT_EQ(circle_cover_overlap(make_ellipse<float>({0, 0}, 0, {2, 1}), make_circle<float>({3.5f, 0}, 1)).verdict,
            Verdict::no_collision);
}

// The document's bound, checked on the polygons themselves: after n bisections every
// corner of the circumscribed polygon, and every point of the inscribed polygon's edges,
// lies within 2^(0.303 - 2n) * major of the ellipse. The polygons are niemitalo_polygons'
// (the coefficients the tests run with); distances come from closest_point. The worst case
// found is also checked against the exact circle-frame value
// (1 / cos(pi / 2^(n+2)) - 1) * major, which is about a quarter of the document's bound.
TEST(NiemitaloErrorBound, PolygonWithinTheBound) {
  const auto& k = detail::niemitalo_coefficients<double>();
  for (double aspect : {1.0, 1.5, 4.0, 30.0, 1e3, 1e4}) {
    for (double angle : {0.0, 0.4}) {
      const auto e = make_ellipse<double>({0.3, -0.2}, angle, {1.0, 1.0 / aspect});
      for (int n = 0; n <= 12; ++n) {
        const NiemitaloPolygons<double> p = niemitalo_polygons(e, n);
        double out = 0, in = 0;  // farthest corner outside, deepest chord point inside
        for (std::size_t i = 0; i < p.inscribed.size() / 4; ++i) {  // first quadrant; the rest is symmetric
          out = std::max(out, closest_point(e, p.circumscribed[i]).signed_distance);
          for (int j = 1; j < 8; ++j) {
            const Vec2<double> on_chord = p.inscribed[i] + (j / 8.0) * (p.inscribed[i + 1] - p.inscribed[i]);
            in = std::max(in, -closest_point(e, on_chord).signed_distance);
          }
        }
        // The tabulated band of the results (above: corners, below: chords), major radius 1.
        EXPECT_LE(out, k.above[n] + 1e-14) << aspect << " " << n;
        EXPECT_LE(in, k.below[n] + 1e-14) << aspect << " " << n;
        const double worst = std::max(out, in);
        const double exact = (1 / std::cos(M_PI / std::ldexp(1.0, n + 2)) - 1) * 1.0;
        EXPECT_LE(worst, niemitalo_error_bound(1.0, n)) << aspect << " " << n;
        EXPECT_LE(worst, exact + 1e-14) << aspect << " " << n;
        if (aspect == 1.0) {
          EXPECT_GT(worst, 0.99 * exact) << n;  // attained by a circle
          EXPECT_GT(in, 0.9 * k.below[n]) << n;
        }
      }
    }
  }
  EXPECT_NEAR(niemitalo_error_bound(1.0, 0), std::exp2(0.303), 1e-15);
  EXPECT_NEAR(niemitalo_error_bound(1.0, 3) / niemitalo_error_bound(1.0, 2), 0.25, 1e-15);
  EXPECT_EQ(niemitalo_error_bound(make_ellipse<double>({5, 5}, 0.3, {0.5, 3}), 4), niemitalo_error_bound(3.0, 4));
}

// niemitalo_polygons: 2^(n+2) vertices on the ellipse in parametrization order (level 0:
// the ends of the semi-axes), each level keeping the previous one's vertices, and corners
// where neighbouring tangents meet (the corner is on both tangent lines).
TEST(NiemitaloPolygons, VerticesOnTheEllipseCornersOnTheTangents) {
  const auto e = make_ellipse<double>({1.5, -2}, 0.7, {3, 0.5});
  const Mat2<double> m = e.quadric();
  const auto p0 = niemitalo_polygons(e, 0);
  ASSERT_EQ(p0.inscribed.size(), 4u);
  EXPECT_LT((p0.inscribed[1] - (e.center() + 0.5 * e.axes().col(1))).norm(), 1e-15);
  EXPECT_LT((p0.circumscribed[0] - (e.center() + 3 * e.axes().col(0) + 0.5 * e.axes().col(1))).norm(), 1e-14);
  const auto p = niemitalo_polygons(e, 5);
  ASSERT_EQ(p.inscribed.size(), 128u);
  ASSERT_EQ(p.circumscribed.size(), 128u);
  for (std::size_t i = 0; i < p.inscribed.size(); ++i) {
    const Vec2<double> x = p.inscribed[i] - e.center(), y = p.inscribed[(i + 1) % 128] - e.center();
    EXPECT_NEAR(x.dot(m * x), 1, 1e-14) << i;
    const double t = std::atan2(e.axes().col(1).dot(x) / 0.5, e.axes().col(0).dot(x) / 3);
    EXPECT_NEAR(std::remainder(t - i * M_PI / 64, 2 * M_PI), 0, 1e-13) << i;
    const Vec2<double> c = p.circumscribed[i] - e.center();
    EXPECT_NEAR(c.dot(m * x), 1, 1e-13) << i;  // the tangent at x is {z : z . M x = 1}
    EXPECT_NEAR(c.dot(m * y), 1, 1e-13) << i;
  }
  EXPECT_EQ(p.inscribed[4], niemitalo_polygons(e, 3).inscribed[1]);
  EXPECT_EQ(niemitalo_polygons(e, niemitalo_polygons_max_level).inscribed.size(),
            std::size_t{4} << niemitalo_polygons_max_level);
  for (int bad : {-1, niemitalo_polygons_max_level + 1}) {
    try {
      (void)niemitalo_polygons(e, bad);
      ADD_FAILURE() << bad;
    } catch (const InputError& err) {
      EXPECT_EQ(err.field(), "level");
    }
  }
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
