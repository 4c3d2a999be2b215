// mesh.hpp and collide_and_slide through meshes: the factory's checks; the hierarchy's
// answers equal to those of every triangle tested in turn (random soups, 2D and 3D: same
// relation, same triangle, the same contact time bit for bit); a tiled floor (no snag on the
// seams between its triangles; floors split into collinear or coplanar pieces slide as the
// whole one); steps lower and higher than the body; random soups slid
// through (never inside, never farther than asked).
#include <ellipsect/mesh.hpp>
#include <ellipsect/slide.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using ellipsect::testing::expect_field;
using V3 = Vec3<double>;
using V2 = Vec2<double>;
constexpr double inf = std::numeric_limits<double>::infinity();

TEST(TriangleMesh, FactoryChecksItsArrays) {
  const std::vector<double> v{0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<std::int64_t> t{0, 1, 2};
  const auto mesh = make_triangle_mesh<double, 3>(v, t);
  EXPECT_EQ(mesh.vertex_count(), 3u);
  EXPECT_EQ(mesh.triangle_count(), 1u);
  EXPECT_EQ(mesh.triangle(0).vertex(1), V3(1, 0, 0));
  expect_field([&] { (void)mesh.triangle(1); }, "triangle");
  expect_field([&] { make_triangle_mesh<double, 3>(std::span(v).first(8), t); }, "vertices");
  expect_field([&] { make_triangle_mesh<double, 3>(v, std::span(t).first(2)); }, "triangles");
  std::vector<double> bad = v;
  bad[4] = std::nan("");
  expect_field([&] { make_triangle_mesh<double, 3>(bad, t); }, "vertices[1][1]");
  expect_field([&] { make_triangle_mesh<double, 3>(v, std::vector<std::int64_t>{0, 3, 1}); }, "triangles[0][1]");
  expect_field([&] { make_triangle_mesh<double, 3>(v, std::vector<std::int64_t>{0, 1, -1}); }, "triangles[0][2]");
  // No triangles: separated from everything, never hit.
  const TriangleMesh<double, 3> empty;
  const auto ball = make_ball<double, 3>(V3(0, 0, 0), 1);
  EXPECT_EQ(classify(ball, empty).relation, Relation::separated);
  EXPECT_EQ(classify(ball, empty).triangle, -1);
  EXPECT_EQ(first_contact(ball, V3(1, 0, 0), empty, V3(0, 0, 0), inf).contact.status,
            ContactStatus::no_contact_in_window);
}

// A soup of `count` random triangles of size about `size` in the cube [-8, 8]^N.
template <int N>
TriangleMesh<double, N> soup(scenarios::detail::Rng& rng, int count, double size) {
  using namespace scenarios::detail;
  std::vector<double> v;
  std::vector<std::int64_t> t;
  for (int k = 0; k < count; ++k) {
    const Vec<double, N> c = Vec<double, N>::NullaryExpr([&](Eigen::Index) { return uniform(rng, -8, 8); });
    for (int j = 0; j < 3; ++j) {
      const Vec<double, N> x = c + unit_vector<N>(rng) * size * uniform(rng, 0.2, 1);
      for (int i = 0; i < N; ++i) v.push_back(x[i]);
      t.push_back(3 * k + j);
    }
  }
  return make_triangle_mesh<double, N>(v, t);
}

// The mesh's answers against every triangle tested in turn.
template <int N>
void matches_every_triangle() {
  using namespace scenarios::detail;
  Rng rng(5);
  std::map<std::string, int> tally;
  for (int m = 0; m < ellipsect::testing::cases(20); ++m) {
    const auto mesh = soup<N>(rng, N == 2 ? 60 : 400, log_uniform(rng, 0.1, 3));
    for (int q = 0; q < 20; ++q) {
      const Vec<double, N> c = Vec<double, N>::NullaryExpr([&](Eigen::Index) { return uniform(rng, -9, 9); });
      const auto body = Ellipsoid<double, N>::from_axes(c, rotation<N>(rng), radii<N>(rng, 0.7, 20));
      const Vec<double, N> va = unit_vector<N>(rng) * log_uniform(rng, 0.1, 10), vb = Vec<double, N>::Zero();
      const double t_max = uniform(rng, 0, 1) < 0.3 ? inf : log_uniform(rng, 0.1, 10);
      MeshRelation want;
      Contact<double, N> want_hit;
      std::int64_t want_k = -1;
      std::size_t contained = 0;
      for (std::size_t k = 0; k < mesh.triangle_count(); ++k) {
        Relation r = classify(body, mesh.triangle(k));
        if (r == Relation::a_contains_b) ++contained, r = Relation::overlapping;
        const auto rank = [](Relation x) { return x == Relation::separated ? 0 : x == Relation::touching ? 1 : 2; };
        if (rank(r) > rank(want.relation)) want = {r, static_cast<std::int64_t>(k)};
        const auto c = first_contact(body, va, mesh.triangle(k), vb, t_max);
        if (c.status == ContactStatus::hit && (want_k < 0 || c.time < want_hit.time)) want_hit = c, want_k = k;
      }
      if (contained == mesh.triangle_count()) want = {Relation::a_contains_b, 0};
      const MeshRelation got = classify(body, mesh);
      ASSERT_EQ(got.relation, want.relation) << m << " " << q;
      ASSERT_EQ(got.triangle, want.triangle) << m << " " << q;
      tally[std::string(to_string(got.relation))]++;
      if (want.relation != Relation::separated) continue;
      const MeshContact<double, N> hit = first_contact(body, va, mesh, vb, t_max);
      tally[std::string("contact ") + std::string(to_string(hit.contact.status))]++;
      if (want_k < 0) {
        ASSERT_EQ(hit.contact.status, ContactStatus::no_contact_in_window) << m << " " << q;
        ASSERT_EQ(hit.triangle, -1);
      } else {
        ASSERT_EQ(hit.contact.status, ContactStatus::hit) << m << " " << q;
        ASSERT_EQ(hit.triangle, want_k) << m << " " << q;
        ASSERT_EQ(hit.contact.time, want_hit.time) << m << " " << q;
        ASSERT_EQ(hit.contact.point, want_hit.point) << m << " " << q;
      }
    }
  }
  std::printf("%dD:", N);
  for (const auto& [outcome, count] : tally) std::printf(" %s=%d", outcome.c_str(), count);
  std::printf("\n");
  if (!ellipsect::testing::full_case_counts()) return;
  for (const char* outcome : {"separated", "overlapping", "contact hit", "contact no_contact_in_window"})
    EXPECT_GT(tally[outcome], 0) << outcome;
}

TEST(TriangleMesh, HierarchyMatchesEveryTriangle2D) { matches_every_triangle<2>(); }
TEST(TriangleMesh, HierarchyMatchesEveryTriangle3D) { matches_every_triangle<3>(); }

// signed_distance through the hierarchy against the least over every triangle in turn: the
// same distance and triangle, bit for bit (nearest boxes first, farther ones skipped).
template <int N>
void distance_matches_every_triangle() {
  using namespace scenarios::detail;
  Rng rng(11);
  std::map<std::string, int> tally;
  for (int m = 0; m < 6; ++m) {
    const auto mesh = soup<N>(rng, N == 2 ? 40 : 120, log_uniform(rng, 0.1, 3));
    for (int q = 0; q < 8; ++q) {
      const Vec<double, N> c = Vec<double, N>::NullaryExpr([&](Eigen::Index) { return uniform(rng, -9, 9); });
      const auto body = Ellipsoid<double, N>::from_axes(c, rotation<N>(rng), radii<N>(rng, 0.7, 20));
      Distance<double, N> want;
      std::int64_t want_k = -1;
      for (std::size_t k = 0; k < mesh.triangle_count(); ++k) {
        const Distance<double, N> d = signed_distance(body, mesh.triangle(k));
        if (want_k < 0 || d.distance < want.distance) want = d, want_k = static_cast<std::int64_t>(k);
      }
      const MeshDistance<double, N> got = signed_distance(body, mesh);
      ASSERT_EQ(got.triangle, want_k) << m << " " << q;
      ASSERT_EQ(got.distance.distance, want.distance) << m << " " << q;
      ASSERT_EQ(got.distance.point_a, want.point_a) << m << " " << q;
      const Relation r = classify(body, mesh).relation;
      ASSERT_EQ(got.distance.status, r == Relation::separated  ? DistanceStatus::separated
                                     : r == Relation::touching ? DistanceStatus::touching
                                                               : DistanceStatus::overlapping);
      const MeshDistance<double, N> plain = distance(body, mesh);
      ASSERT_EQ(plain.distance.distance, got.distance.status == DistanceStatus::overlapping ? 0.0 : got.distance.distance);
      tally[std::string(to_string(got.distance.status))]++;
    }
  }
  for (const char* outcome : {"separated", "overlapping"}) EXPECT_GT(tally[outcome], 0) << outcome;
  const MeshDistance<double, N> none = signed_distance(Ellipsoid<double, N>(), TriangleMesh<double, N>());
  EXPECT_EQ(none.triangle, -1);
  EXPECT_EQ(none.distance.distance, inf);
  EXPECT_EQ(none.distance.status, DistanceStatus::separated);
}

TEST(TriangleMesh, DistanceMatchesEveryTriangle2D) { distance_matches_every_triangle<2>(); }
TEST(TriangleMesh, DistanceMatchesEveryTriangle3D) { distance_matches_every_triangle<3>(); }

// Found by the queries fuzz target: a float circle whose box edge lies exactly on the
// triangle's box edge (y = 0); its float axes are unit only to float's rounding, so a box
// from them fell short by an ulp and the walk dropped the triangle.
TEST(TriangleMesh, FloatBodyOnTheEdgeOfATrianglesBox) {
  Mat2<float> axes;
  axes << -0x1.aa2266p-2f, -0x1.d18f6ep-1f, 0x1.d18f6ep-1f, -0x1.aa2266p-2f;
  const auto a = Ellipsoid<float, 2>::from_axes(Vec2<float>(0, -8), axes, Vec2<float>(8, 8));
  const std::vector<float> v{10, 0, 10.5f, 1, 14, 0};
  const auto mesh = make_triangle_mesh<float, 2>(v, std::vector<std::int64_t>{0, 1, 2});
  const float never = std::numeric_limits<float>::infinity();
  const auto alone = first_contact(a, Vec2<float>(4, 0), mesh.triangle(0), Vec2<float>(0, 0), never);
  const auto walked = first_contact(a, Vec2<float>(4, 0), mesh, Vec2<float>(0, 0), never);
  EXPECT_EQ(alone.status, ContactStatus::hit);
  EXPECT_EQ(walked.contact.status, ContactStatus::hit);
  EXPECT_EQ(walked.contact.time, alone.time);
  EXPECT_EQ(walked.triangle, 0);
}

// An n x n grid of unit squares at height z(x) over [0, n]^2, two triangles each.
template <class Height>
TriangleMesh<double, 3> terrain(int n, Height&& z) {
  std::vector<double> v;
  std::vector<std::int64_t> t;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) v.insert(v.end(), {double(i), double(j), z(double(i), double(j))});
  const auto at = [&](int i, int j) { return std::int64_t(i) * (n + 1) + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) t.insert(t.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
  return make_triangle_mesh<double, 3>(v, t);
}

TEST(TriangleMesh, FallsOntoAndSlidesAcrossATiledFloor) {
  const auto floor = terrain(20, [](double, double) { return 0.0; });
  EXPECT_EQ(floor.triangle_count(), 800u);
  const auto ball = make_ball<double, 3>(V3(5.5, 5.25, 3), 1);
  const auto fall = first_contact(ball, V3(0, 0, -2), floor, V3(0, 0, 0), inf);
  EXPECT_EQ(fall.contact.status, ContactStatus::hit);
  EXPECT_NEAR(fall.contact.time, 1.0, 1e-15);
  EXPECT_NEAR((fall.contact.point - V3(5.5, 5.25, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((fall.contact.normal - V3(0, 0, -1)).norm(), 0.0, 1e-15);
  // Square (5, 5): triangles 2 (5 * 20 + 5) and + 1; (5.5, 5.25) lies in the first.
  EXPECT_EQ(fall.triangle, 2 * (5 * 20 + 5));
  EXPECT_EQ(classify(ball.translated(V3(0, 0, -2)), floor).relation, Relation::touching);
  EXPECT_EQ(classify(ball.translated(V3(0, 0, -2.5)), floor).relation, Relation::overlapping);
  // Down and across 12 squares diagonally: lands, then slides over the seams to the end.
  const auto s = collide_and_slide(ball, V3(12, 9, -4), floor);
  EXPECT_EQ(s.status, SlideStatus::slid);
  EXPECT_NEAR(s.body.center()[2], 1.0, 1e-12);
  EXPECT_NEAR(s.body.center()[0], 5.5 + 12, 1e-9);
  EXPECT_NEAR(s.body.center()[1], 5.25 + 9, 1e-9);
  EXPECT_EQ(s.contacts, 1);  // the landing; the seams are slid across
}

// A floor y = 0 over x in [-10, 10] as `pieces` collinear segments (triangles (a, b, b)).
TriangleMesh<double, 2> split_floor(int pieces) {
  std::vector<double> v;
  std::vector<std::int64_t> t;
  for (int i = 0; i <= pieces; ++i) v.insert(v.end(), {-10 + 20.0 * i / pieces, 0.0});
  for (int i = 0; i < pieces; ++i) t.insert(t.end(), {i, i + 1, i + 1});
  return make_triangle_mesh<double, 2>(v, t);
}

// A needle ellipse (radii 0.5 and 5e-4, turned by 0.8) 0.7 above a floor, moved by (7, -1):
// it lands at t = 0.7 and slides the rest of the way, ending at x = -3.3 + 7 = 3.7. Split into
// 8 collinear segments, the floor stopped it at x = 2.848, its tip on the seam x = 2.5: the
// body rests within the tangency band, a little below the next segment's end vertex, which it
// then touches off its tip, where the band tilts the tangent plane by 1e-3 (the square root
// of the band over the tip's curvature); the slide took the tilted plane and the floor for a
// corner. A touch that would not take the body deeper than half the band into the obstacle is
// a graze (slide.hpp): the split floor slides as the whole one.
TEST(TriangleMesh, FloorOfCollinearPiecesIsNoCorner2D) {
  const double rho = std::hypot(0.5 * std::sin(0.8), 5e-4 * std::cos(0.8));
  const auto needle = make_ellipse<double>(V2(-3.3, 0.7 + rho), 0.8, V2(0.5, 5e-4));
  for (const int pieces : {1, 2, 8, 40}) {
    const auto s = collide_and_slide(needle, V2(7, -1), split_floor(pieces));
    EXPECT_EQ(s.status, SlideStatus::slid) << pieces;
    EXPECT_EQ(s.contacts, 1) << pieces;
    EXPECT_NEAR(s.body.center()[0], 3.7, 1e-12) << pieces;
    EXPECT_NEAR(s.body.center()[1], rho, 1e-12) << pieces;
  }
}

// The same in 3D: a needle ellipsoid (radii 0.5, 0.2 and 5e-4, turned by 0.8 about y) lands
// on a floor of unit squares and slides across their seams as on the floor's half-space.
// Before, the 20 x 20 floor took a seam's edge, within the band, for a wall: 2 contacts and
// the end 3.5e-9 higher.
TEST(TriangleMesh, FloorOfCoplanarPiecesIsNoCorner3D) {
  const double rho = std::hypot(0.5 * std::sin(0.8), 5e-4 * std::cos(0.8));
  const Mat3<double> axes = Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const auto needle = Ellipsoid<double, 3>::from_axes(V3(3.3, 5.25, 0.7 + rho), axes, V3(0.5, 0.2, 5e-4));
  const std::vector<HalfSpace<double, 3>> plane{make_half_space<double, 3>(V3(0, 0, 0), V3(0, 0, 1))};
  const auto want = collide_and_slide(needle, V3(7, 1, -1), std::span<const HalfSpace<double, 3>>(plane));
  EXPECT_NEAR((want.body.center() - V3(10.3, 6.25, rho)).norm(), 0.0, 1e-14);
  for (const int n : {12, 20}) {
    const auto s = collide_and_slide(needle, V3(7, 1, -1), terrain(n, [](double, double) { return 0.0; }));
    EXPECT_EQ(s.status, SlideStatus::slid) << n;
    EXPECT_EQ(s.contacts, 1) << n;
    EXPECT_NEAR((s.body.center() - want.body.center()).norm(), 0.0, 1e-12) << n;
  }
}

// A step at x = 4 of height h: a riser (two triangles) and the upper floor.
TriangleMesh<double, 3> step(double h) {
  const std::vector<double> v{0, -5, 0, 4, -5, 0, 4, 5, 0, 0, 5, 0,    // lower floor
                              4, -5, h, 9, -5, h, 9, 5, h, 4, 5, h,    // upper floor
                              4, -5, 0, 4, 5, 0, 4, 5, h, 4, -5, h};  // riser
  const std::vector<std::int64_t> t{0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 8, 9, 10, 8, 10, 11};
  return make_triangle_mesh<double, 3>(v, t);
}

TEST(TriangleMesh, LowStepsAreClimbedHighStepsAreWalls) {
  const auto ball = make_ball<double, 3>(V3(1, 0, 1), 1);
  // 0.3 below the center of a unit ball: its round side rides up the step's edge (along the
  // tangent plane there, which lifts it above the upper floor: no gravity here).
  const auto low = collide_and_slide(ball, V3(6, 0, -0.01), step(0.3));
  EXPECT_EQ(low.status, SlideStatus::slid);
  EXPECT_GT(low.body.center()[0], 4.0);
  EXPECT_GE(low.body.center()[2], 1.3);
  EXPECT_EQ(low.last_contact, 3);  // the upper floor's edge (also the riser's: the lower index)
  EXPECT_NE(classify(low.body, step(0.3)).relation, Relation::overlapping);
  // 1.5: a wall; the body stops against it at x = 3, sliding along it sideways to y = 2.
  const auto high = collide_and_slide(ball, V3(6, 2, 0), step(1.5));
  EXPECT_EQ(high.status, SlideStatus::slid);
  EXPECT_NEAR(high.body.center()[0], 3.0, 1e-12);
  EXPECT_NEAR(high.body.center()[1], 2.0, 1e-12);
  EXPECT_NEAR(high.body.center()[2], 1.0, 1e-12);
  EXPECT_EQ(high.last_contact, 5);  // the riser's triangle above its diagonal, where it was hit
  EXPECT_EQ(classify(high.body, step(1.5)).relation, Relation::touching);
}

// Random soups around a body, random long displacements: never inside, never farther than
// asked.
template <int N>
void slides_through_soups() {
  using namespace scenarios::detail;
  Rng rng(17);
  std::map<std::string, int> tally;
  for (int i = 0; i < ellipsect::testing::cases(100); ++i) {
    const auto mesh = soup<N>(rng, N == 2 ? 30 : 300, log_uniform(rng, 0.3, 3));
    const auto body = Ellipsoid<double, N>::from_axes(Vec<double, N>::Zero(), rotation<N>(rng), radii<N>(rng, 0.5, 10));
    const Vec<double, N> d = unit_vector<N>(rng) * log_uniform(rng, 0.1, 20);
    const auto s = collide_and_slide(body, d, mesh);
    tally[std::string(to_string(s.status))]++;
    if (s.status == SlideStatus::overlapping_at_start) continue;
    ASSERT_NE(s.status, SlideStatus::invalid_input);
    const Relation r = classify(s.body, mesh).relation;
    ASSERT_TRUE(r == Relation::separated || r == Relation::touching) << "case " << i;
    ASSERT_LE(s.moved.norm(), d.norm() * (1 + 1e-12)) << "case " << i;
    ASSERT_LE((s.body.center() - s.moved).norm(), 1e-12 * (1 + d.norm())) << "case " << i;
  }
  std::printf("%dD:", N);
  for (const auto& [outcome, count] : tally) std::printf(" %s=%d", outcome.c_str(), count);
  std::printf("\n");
  if (!ellipsect::testing::full_case_counts()) return;
  EXPECT_GT(tally["moved"], 0);
  EXPECT_GT(tally["slid"], 0);
}

TEST(TriangleMesh, SlidesThroughSoups2D) { slides_through_soups<2>(); }
TEST(TriangleMesh, SlidesThroughSoups3D) { slides_through_soups<3>(); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
