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

// Boxes: random, around the body, inside it, thin; near tangency at a face, an edge and a
// corner (kinds 4 to 6: the feature placed at a relative gap of 1e-11 to 1e-3, either side,
// from the body's support point along a random direction, the rest of the box beyond it);
// and the same features 0.1 to 10 sizes away (kind 7).
constexpr int box_kinds = 8;

template <int N>
Box<double, N> box_case(int kind, int seed, const Ellipsoid<double, N>& a) {
  using namespace scenarios::detail;
  Rng rng(static_cast<std::uint64_t>(seed) * 7727 + static_cast<std::uint64_t>(kind) * 31 + 5);
  Mat<double, N> axes = rotation<N>(rng);
  using V = Vec<double, N>;
  if (kind == 1) return make_box<double, N>(a.center(), axes, V::Constant(3 * a.radii().maxCoeff()));
  if (kind == 2) return make_box<double, N>(a.center(), axes, V::Constant(0.2 * a.radii().minCoeff()));
  if (kind <= 3) {
    const V c = V::NullaryExpr([&](Eigen::Index) { return uniform(rng, -6, 6); });
    return make_box<double, N>(c, axes, kind == 3 ? radii<N>(rng, 2.0, 1e4) : radii<N>(rng, 2.0, 10));
  }
  const double size = a.radii().maxCoeff();
  const V n = unit_vector<N>(rng);
  const V w = a.radii().cwiseProduct(a.axes().transpose() * n);
  const V support = a.center() + a.axes() * a.radii().cwiseProduct(w) / w.norm();
  const double gap = kind == 7 ? log_uniform(rng, 0.1, 10) * size : (seed % 2 ? -1 : 1) * log_uniform(rng, 1e-11, 1e-3) * size;
  if (kind == 7) kind = 4 + seed % 3;
  const V q = support + gap * n;  // the feature's point nearest the body
  const V h = radii<N>(rng, 2 * size, 100);
  // Face (kind 4) and edge (kind 5, 3D): axis 0 along n, resp. axis 0 orthogonal to n (the
  // edge's direction) with n in the plane of the others; corner (kind 6 and the 2D edge): any.
  if (kind == 4) {
    axes.col(0) = n;
    axes = axes.householderQr().householderQ();
    if (axes.col(0).dot(n) < 0) axes.col(0) = -axes.col(0);
  } else if (kind == 5 && N == 3) {
    axes.col(0) -= axes.col(0).dot(n) * n;
    axes.col(1) = n;
    axes = axes.householderQr().householderQ();
  }
  if (axes.determinant() < 0) axes.col(N - 1) = -axes.col(N - 1);  // a free axis or a corner's
  // The center: q less the offset of the corner with the least n . x, and moved along the
  // free axes (a face's two, an edge's one) to a random point of the feature.
  V center = q;
  for (int i = 0; i < N; ++i) {
    const double along = axes.col(i).dot(n);
    const bool free = (kind == 4 && i > 0) || (kind == 5 && N == 3 && i == 0);
    center += (free ? uniform(rng, -0.9, 0.9) : (along < 0 ? -1.0 : 1.0)) * h[i] * axes.col(i);
  }
  return make_box<double, N>(center, axes, h);
}

template <int N>
void run_boxes() {
  using namespace scenarios::detail;
  std::map<std::string, int> tally;
  for (int kind = 0; kind < box_kinds; ++kind)
    for (int seed = 0; seed < seeds(); ++seed) {
      Rng rng(static_cast<std::uint64_t>(seed) * 104729 + static_cast<std::uint64_t>(kind) + 1);
      // The near-tangent kinds at scale 1e-6, 1 or 1e6 and aspect ratios to 1e4.
      const double scale = kind < 4 ? 1.0 : std::pow(1e6, seed % 3 - 1);
      const Vec<double, N> center =
          Vec<double, N>::NullaryExpr([&](Eigen::Index) { return scale * uniform(rng, -2, 2); });
      const auto a = Ellipsoid<double, N>::from_axes(center, rotation<N>(rng), radii<N>(rng, scale, kind < 4 ? 10 : 1e4));
      const Box<double, N> b = box_case<N>(kind, seed, a);
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

}  // namespace
