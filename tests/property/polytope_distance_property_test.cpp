// signed_distance of bodies and triangles or boxes (triangle.hpp, box.hpp) against the
// 50-digit reference (tests/reference/support_gap_reference.hpp: the support gap maximized
// over the sphere of directions by search).
//
// Claims under test, with scale = largest radius + largest |vertex - center| (the pair's
// size):
//   distance  within 1e-12 scale of the reference's signed distance;
//   normal    optimal: the reference's support gap at the returned normal within 1e-12 scale
//             of the reference's maximum;
//   point_a   on the body (its quadric within 1e-12 of 1) with `normal` its outward normal;
//             point_b = point_a + distance * normal;
//   status    classify's (overlapping for containment).
// Cases: the triangle scenarios (scenarios/triangle.hpp: random, aspect ratios to 1e4, near
// tangency at faces, edges and vertices, containment, triangles 1e3 to 1e12 radii across,
// needles, segments and points, scale 1e-6 and 1e6), and boxes: random, around the body, inside
// it, thin (aspect 1e4), near tangency at faces, edges and corners (aspect ratios to 1e4, scale
// 1e-6 and 1e6).
#include <ellipsect/box.hpp>
#include <ellipsect/triangle.hpp>

#include "scenarios/box.hpp"
#include "scenarios/triangle.hpp"
#include "tests/reference/bridge.hpp"
#include "tests/reference/support_gap_reference.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
namespace ref = ellipsect::reference;
using Real = ref::Real;

// Cases per kind: the reference searches the sphere (about 50 ms a case in 3D), so the
// sanitizer pass runs a quarter.
int seeds() { return full_case_counts() ? 16 : 4; }

DistanceStatus status_of(Relation r) {
  return r == Relation::separated ? DistanceStatus::separated
         : r == Relation::touching ? DistanceStatus::touching
                                   : DistanceStatus::overlapping;
}

template <int N>
void check(const Ellipsoid<double, N>& a, const std::vector<Vec<double, N>>& vertices, const Distance<double, N>& got,
           Relation relation, const std::string& what, std::map<std::string, int>& tally) {
  const auto body = ref::to_ref(a);
  std::vector<ref::DVec<N>> v(vertices.begin(), vertices.end());
  const ref::SupportGapMaximum<N> want = ref::max_support_gap<N>(body, v);
  double scale = a.radii().maxCoeff();
  for (const auto& x : vertices) scale = std::max(scale, a.radii().maxCoeff() + (x - a.center()).norm());
  const double tol = 1e-12 * scale;
  ASSERT_EQ(got.status, status_of(relation)) << what;
  ASSERT_NEAR(got.normal.norm(), 1, 1e-15) << what;
  const Real at_normal = ref::support_gap_at<N>(body, v, got.normal);
  ASSERT_NEAR(got.distance, ref::to_double(want.gap), tol)
      << what << "\n  the reference's gap at the returned normal: " << at_normal.str(17);
  ASSERT_LE(ref::to_double(Real(want.gap - at_normal)), tol) << what;
  // point_a on the body, normal its outward normal there.
  const Vec<double, N> u = a.axes().transpose() * (got.point_a - a.center());
  ASSERT_NEAR(u.cwiseQuotient(a.radii()).norm(), 1, 1e-12) << what;
  const Vec<double, N> outward = (a.axes() * u.cwiseQuotient(a.radii().cwiseAbs2())).normalized();
  ASSERT_GT(outward.dot(got.normal), 1 - 1e-9) << what;
  ASSERT_LE((got.point_b - got.point_a - got.distance * got.normal).norm(), 1e-14 * scale) << what;
  tally[std::string(to_string(got.status))]++;
}

template <int N>
void run_triangles() {
  std::map<std::string, int> tally;
  for (const auto kind : scenarios::triangle_kinds)
    for (int seed = 0; seed < seeds(); ++seed) {
      const auto c = scenarios::make_triangle_case<N>(kind, seed);
      const Distance<double, N> got = signed_distance(c.a, c.b);
      check<N>(c.a, {c.b.vertex(0), c.b.vertex(1), c.b.vertex(2)}, got, classify(c.a, c.b), scenarios::describe(c), tally);
      if (::testing::Test::HasFatalFailure()) return;
      // distance(): the same where not overlapping, 0 and NaN points where overlapping.
      const Distance<double, N> plain = distance(c.a, c.b);
      if (got.status == DistanceStatus::overlapping) {
        ASSERT_EQ(plain.distance, 0.0);
        ASSERT_TRUE(std::isnan(plain.point_a[0]) && std::isnan(plain.normal[0]));
      } else {
        ASSERT_EQ(plain.distance, got.distance);
      }
    }
  std::printf("triangles %dD:", N);
  for (const auto& [outcome, count] : tally) std::printf(" %s=%d", outcome.c_str(), count);
  std::printf("\n");
  for (const char* outcome : {"separated", "overlapping"}) EXPECT_GT(tally[outcome], 0) << outcome;
}

template <int N>
void run_boxes() {
  std::map<std::string, int> tally;
  for (int kind = 0; kind < scenarios::box_kinds; ++kind)
    for (int seed = 0; seed < seeds(); ++seed) {
      const auto [a, b] = scenarios::make_box_pair<N>(kind, seed);
      std::vector<Vec<double, N>> corners;
      for (int k = 0; k < (1 << N); ++k) corners.push_back(b.corner(k));
      const std::string what = "box kind " + std::to_string(kind) + " seed " + std::to_string(seed);
      check<N>(a, corners, signed_distance(a, b), classify(a, b), what, tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  std::printf("boxes %dD:", N);
  for (const auto& [outcome, count] : tally) std::printf(" %s=%d", outcome.c_str(), count);
  std::printf("\n");
  for (const char* outcome : {"separated", "overlapping"}) EXPECT_GT(tally[outcome], 0) << outcome;
}

TEST(PolytopeDistanceProperty, Triangles2D) { run_triangles<2>(); }
TEST(PolytopeDistanceProperty, Triangles3D) { run_triangles<3>(); }
TEST(PolytopeDistanceProperty, Boxes2D) { run_boxes<2>(); }
TEST(PolytopeDistanceProperty, Boxes3D) { run_boxes<3>(); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
