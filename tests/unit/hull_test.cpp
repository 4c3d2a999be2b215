// The convex hull's faces as half-spaces (geometry.hpp, hull_half_spaces): against a brute-force
// hull in 50 digits (every pair or triple of points whose line or plane has all others on one
// side), every point inside every half-space as stored in 50 digits, each plane through a
// vertex of its face, known hulls (a cube with points on its faces and inside, a polygon),
// collinear and coplanar points, duplicates, far from the origin, tiny and huge scales, float,
// and the largest inscribed ellipsoid of a cube's corners.
#include <ellipsect/geometry.hpp>

#include "tests/support.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using F = boost::multiprecision::cpp_bin_float_50;
template <int N>
using FV = Eigen::Matrix<F, N, 1>;
using V2 = Vec<double, 2>;
using V3 = Vec<double, 3>;

template <class T, int N>
FV<N> vec50(const auto& v) {
  FV<N> out;
  for (int i = 0; i < N; ++i) out[i] = F(double(T(v[i])));
  return out;
}

// The outward normals (unnormalized, 50 digits) of the hull's faces by brute force: lines
// through two points (N = 2) or planes through three (N = 3) with every point on one side and
// some strictly, each plane once (by its unit normal's direction).
template <class T, int N>
std::vector<FV<N>> brute_force_normals(const std::vector<Vec<T, N>>& points) {
  std::vector<FV<N>> p, normals;
  for (const auto& q : points) p.push_back(vec50<T, N>(q));
  const std::size_t n = p.size();
  // The sides of the points but those spanning the plane (whose 50-digit residues are noise).
  const auto add = [&](const FV<N>& m, const FV<N>& at, std::array<std::size_t, N> spanning) {
    if (m.squaredNorm() == 0) return;
    int above = 0, below = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (std::find(spanning.begin(), spanning.end(), i) != spanning.end()) continue;
      const F s = m.dot(p[i] - at);
      above += s > 0, below += s < 0;
    }
    if (above > 0 && below > 0) return;
    const FV<N> u = (above > 0 ? FV<N>(-m) : m) / m.norm();
    for (const auto& v : normals)
      if ((v - u).norm() < F(1e-30)) return;
    normals.push_back(u);
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if constexpr (N == 2) {
        add(FV<2>(p[j][1] - p[i][1], p[i][0] - p[j][0]), p[i], {i, j});
      } else {
        for (std::size_t k = j + 1; k < n; ++k) add((p[j] - p[i]).cross(p[k] - p[i]), p[i], {i, j, k});
      }
    }
  return normals;
}

// Every input point on or inside every half-space as stored, up to `slack` times the
// extent (the rounding of the normals); each half-space's point an input point; the normals
// those of the brute-force hull, one half-space for each.
template <class T, int N>
void expect_hull(const std::vector<Vec<T, N>>& points, const std::vector<HalfSpace<T, N>>& planes, double slack,
                 bool brute_force = true) {
  F extent = 0;
  for (const auto& a : points)
    for (const auto& b : points) extent = std::max<F>(extent, (vec50<T, N>(a) - vec50<T, N>(b)).norm());
  for (std::size_t h = 0; h < planes.size(); ++h) {
    const FV<N> n = vec50<T, N>(planes[h].normal()), at = vec50<T, N>(planes[h].point());
    F worst = -1;
    for (const auto& q : points) worst = std::max<F>(worst, n.dot(vec50<T, N>(q) - at));
    EXPECT_LE(double(worst / extent), slack) << "half-space " << h;
    EXPECT_GE(double(worst), 0.0) << "half-space " << h << ": its point is an input point";
    EXPECT_TRUE(std::any_of(points.begin(), points.end(), [&](const auto& q) { return vec50<T, N>(q) == at; }));
  }
  if (!brute_force) return;
  const std::vector<FV<N>> normals = brute_force_normals<T, N>(points);
  ASSERT_EQ(planes.size(), normals.size());
  for (const auto& u : normals) {
    const auto match = std::count_if(planes.begin(), planes.end(), [&](const HalfSpace<T, N>& h) {
      return (vec50<T, N>(h.normal()) - u).norm() < F(32 * std::numeric_limits<T>::epsilon());
    });
    EXPECT_EQ(match, 1);
  }
}

template <int N>
std::vector<Vec<double, N>> random_cloud(std::mt19937_64& rng, int n, double scale, const Vec<double, N>& offset) {
  std::normal_distribution<double> g;
  std::vector<Vec<double, N>> out;
  for (int i = 0; i < n; ++i) {
    Vec<double, N> v;
    for (int k = 0; k < N; ++k) v[k] = g(rng) * (k + 1);
    out.push_back(offset + scale * v);
  }
  return out;
}

template <int N>
void check_random() {
  std::mt19937_64 rng(48);
  for (const double scale : {1e-6, 1.0, 1e6})
    for (const double far : {0.0, 1e6})
      for (int trial = 0; trial < 6; ++trial) {
        const auto points = random_cloud<N>(rng, N == 2 ? 40 : 18, scale, Vec<double, N>::Constant(far * scale));
        expect_hull<double, N>(points, hull_half_spaces<double, N>(points), 1e-14);
      }
}

TEST(HullHalfSpaces, RandomCloudsMatchBruteForce2D) { check_random<2>(); }
TEST(HullHalfSpaces, RandomCloudsMatchBruteForce3D) { check_random<3>(); }

// A cube's corners, points on its faces' grids (many coplanar points, every face split into
// many triangles) and inside: six half-spaces with the axes' normals exactly.
TEST(HullHalfSpaces, CubeWithFacePointsGivesSixFaces) {
  std::vector<V3> points;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 4; ++j)
      for (int k = 0; k <= 4; ++k) points.push_back(V3(i, j, k) * 0.25 + V3(1e6, -2e6, 3e6));
  std::mt19937_64 rng(7);
  std::shuffle(points.begin(), points.end(), rng);
  const auto planes = hull_half_spaces<double, 3>(points);
  ASSERT_EQ(planes.size(), 6u);
  std::set<std::pair<int, int>> axes;
  for (const auto& h : planes) {
    int k = 0;
    for (int i = 0; i < 3; ++i)
      if (h.normal()[i] != 0) k = i;
    EXPECT_EQ(std::abs(h.normal()[k]), 1.0);
    EXPECT_EQ(h.normal().squaredNorm(), 1.0);
    axes.insert(std::pair<int, int>(k, h.normal()[k] > 0 ? 1 : -1));
  }
  EXPECT_EQ(axes.size(), 6u);
  expect_hull<double, 3>(points, planes, 0.0, false);
  // The largest ellipsoid inside: the ball of radius 1/2 at the cube's center.
  const auto in = inscribed_ellipsoid<double, 3>(planes);
  ASSERT_EQ(in.status, InscribedStatus::optimal);
  EXPECT_NEAR(in.body.radii().minCoeff(), 0.5, 1e-8);
  EXPECT_NEAR(in.body.radii().maxCoeff(), 0.5, 1e-8);
  EXPECT_LT((in.body.center() - V3(1e6 + 0.5, -2e6 + 0.5, 3e6 + 0.5)).norm(), 1e-8);
}

// A regular polygon's vertices, each twice, with its edges' midpoints (collinear, on the
// boundary) and its center: one half-plane per edge.
TEST(HullHalfSpaces, PolygonWithDuplicatesAndEdgePoints) {
  std::vector<V2> points{V2(0, 0)};
  const int m = 7;
  std::vector<V2> corners;
  for (int i = 0; i < m; ++i)
    corners.push_back(V2(std::cos(2 * std::numbers::pi * i / m), std::sin(2 * std::numbers::pi * i / m)));
  for (int i = 0; i < m; ++i) {
    points.push_back(corners[i]);
    points.push_back(corners[i]);
  }
  // Exact midpoints of axis-parallel edges only stay collinear in doubles: add a square's.
  const std::vector<V2> square{{-2, -2}, {2, -2}, {2, 2}, {-2, 2}, {0, -2}, {2, 0}, {0, 2}, {-2, 0}, {1, 2}};
  const auto polygon = hull_half_spaces<double, 2>(points);
  ASSERT_EQ(polygon.size(), std::size_t(m));
  expect_hull<double, 2>(points, polygon, 1e-15);
  const auto box = hull_half_spaces<double, 2>(square);
  ASSERT_EQ(box.size(), 4u);
  expect_hull<double, 2>(square, box, 0.0);
  // Counterclockwise: each normal turned left from the previous one.
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const auto a = polygon[k].normal(), b = polygon[(k + 1) % polygon.size()].normal();
    EXPECT_GT(a[0] * b[1] - a[1] * b[0], 0.0);
  }
}

// Points on a sphere: every point a vertex, 2n - 4 triangles (no four coplanar).
TEST(HullHalfSpaces, SpherePointsAreAllVertices) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  std::vector<V3> points;
  for (int i = 0; i < 200; ++i) points.push_back(V3(g(rng), g(rng), g(rng)).normalized() * 1e-6);
  const auto planes = hull_half_spaces<double, 3>(points);
  EXPECT_EQ(planes.size(), 2 * points.size() - 4);
  expect_hull<double, 3>(points, planes, 1e-14, false);
}

// Nearly coplanar: a square's corners and one point 1e-300 relative above it (the filter
// cannot decide; the rationals do): a pyramid of five faces.
TEST(HullHalfSpaces, NearlyFlatDecidedExactly) {
  const std::vector<V3> points{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1e-300}};
  const auto planes = hull_half_spaces<double, 3>(points);
  EXPECT_EQ(planes.size(), 5u);
  // One ulp off the line: a thin triangle.
  const std::vector<V2> line{V2(0, 0), V2(1, 1), V2(0.5, 0.5), V2(3, 3), V2(0.25, std::nextafter(0.25, 1.0))};
  EXPECT_EQ((hull_half_spaces<double, 2>(line).size()), 3u);
}

// Coordinates near 1e246 (face normals' cross products near 1e492, beyond double) and near
// 1e-200 (products below double's normal range): the same faces as at unit scale.
TEST(HullHalfSpaces, HugeAndTinyCoordinates) {
  std::mt19937_64 rng(17);
  const auto unit = random_cloud<3>(rng, 14, 1.0, V3::Zero());
  const std::size_t faces = hull_half_spaces<double, 3>(unit).size();
  for (const double scale : {0x1p+818, 0x1p-660}) {
    std::vector<V3> p;
    for (const auto& q : unit) p.push_back(q * scale);
    const auto planes = hull_half_spaces<double, 3>(p);
    EXPECT_EQ(planes.size(), faces) << scale;
    expect_hull<double, 3>(p, planes, 1e-14, false);
  }
}

TEST(HullHalfSpaces, FloatPoints) {
  std::mt19937_64 rng(11);
  std::vector<Vec<float, 3>> points;
  for (const auto& p : random_cloud<3>(rng, 16, 1.0, V3::Constant(100))) points.push_back(p.cast<float>());
  expect_hull<float, 3>(points, hull_half_spaces<float, 3>(points), 1e-6);
  std::vector<Vec<float, 2>> flat;
  for (const auto& p : random_cloud<2>(rng, 30, 1.0, V2::Zero())) flat.push_back(p.cast<float>());
  expect_hull<float, 2>(flat, hull_half_spaces<float, 2>(flat), 1e-6);
}

TEST(HullHalfSpaces, DegenerateAndBadInputAreNamed) {
  using ellipsect::testing::error_message;
  const auto hull3 = [](std::vector<V3> p) { return error_message([&] { (void)hull_half_spaces<double, 3>(p); }); };
  const auto hull2 = [](std::vector<V2> p) { return error_message([&] { (void)hull_half_spaces<double, 2>(p); }); };
  EXPECT_EQ(hull3({}), "ellipsect: points: must hold at least 4 points (got 0)");
  EXPECT_EQ(hull2({{0, 0}, {1, 0}}), "ellipsect: points: must hold at least 3 points (got 2)");
  EXPECT_EQ(hull3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.3, 0.2, 0}}),
            "ellipsect: points: are coplanar (or collinear, or equal): their hull has no interior");
  EXPECT_EQ(hull3({{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}}),
            "ellipsect: points: are coplanar (or collinear, or equal): their hull has no interior");
  EXPECT_EQ(hull3({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {0.5, 0.5, 0.5}}),
            "ellipsect: points: are coplanar (or collinear, or equal): their hull has no interior");
  EXPECT_EQ(hull2({{0, 0}, {1, 1}, {2, 2}, {0, 0}}),
            "ellipsect: points: are collinear (or fewer than 3 distinct): their hull has no interior");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(hull2({V2(0, 0), V2(1, 0), V2(0, nan)}), "ellipsect: row 2: points: must be finite");
  EXPECT_EQ(hull3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, HUGE_VAL}}), "ellipsect: row 3: points: must be finite");
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
