// signed_distance_gradient of a body and a shape (half_space.hpp, box.hpp, capsule.hpp,
// triangle.hpp) against 50-digit central differences of the value by a route of its own:
// the half-space's gap n . (c - p) - rho(n) in closed form; for the polytopes (a box's corners,
// a triangle's vertices, a capsule's segment less its radius) the support gap's maximum on the
// stratum that holds it, the directions orthogonal to the edges between the vertices that
// attain the minimum at the library's normal: there the gap is one vertex's, n . y - rho(n)
// (smooth), maximized by Newton on that sphere in Real. The stratum is checked where it is
// found: its maximum equals the library's distance, and no other vertex lies lower there.
// Every parameter of the body and of the shape moves in Real by 1e-15 of the pair's scale
// (turns by 1e-15 rad), so the differences see no rounding of the moved shapes.
//
// Claims under test (the headers'): each component within its unit (gradient_common.hpp's
// Comparison: per length for centers, points, radii and extents; times the pair's scale for
// turns) of 1e-12 for half-spaces, and of 1e-9 for the polytopes and capsules; the translation
// invariance (the body's center derivative minus the shape's translation derivatives is 0) on
// every case, degenerate triangles and balls (capsules of zero length) included, where the
// derivatives are an element of the generalized gradient.
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/triangle.hpp>

#include "scenarios/box.hpp"
#include "scenarios/half_space.hpp"
#include "scenarios/triangle.hpp"
#include "tests/property/common.hpp"
#include "tests/property/gradient_common.hpp"
#include "tests/reference/distance_reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace ellipsect::testing {
namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace gradient;
using ref::Real;
template <int N>
using RMat = ref::RMat<N>;

// The unit z maximizing z . w - sqrt(z^T S z), by Newton on the sphere from z.
template <int M>
RVec<M> sphere_maximizer(const RVec<M>& w, const RMat<M>& S, RVec<M> z) {
  z /= sqrt(z.dot(z));
  if constexpr (M > 1) {
    for (int step = 0; step < 40; ++step) {
      const Eigen::Matrix<Real, M, M - 1> q = ref::detail::tangent_basis<Real, M>(z);
      const RVec<M> sz = S * z;
      const Real rho = sqrt(z.dot(sz));
      const RVec<M> g = w - sz / rho;
      const RMat<M> h = -(S / rho - sz * sz.transpose() / (rho * rho * rho));
      const Eigen::Matrix<Real, M - 1, M - 1> hess =
          q.transpose() * h * q - z.dot(g) * Eigen::Matrix<Real, M - 1, M - 1>::Identity();
      const Eigen::Matrix<Real, M - 1, 1> t = -hess.inverse() * (q.transpose() * g);
      z += q * t;
      z /= sqrt(z.dot(z));
      if (sqrt(t.dot(t)) < Real("1e-45")) break;
    }
  }
  return z;
}

// The stratum's maximum: over unit n orthogonal to y_k - y_j (k, j active) of
// n . y_j - sqrt(n^T P n), from n0; *normal gets the maximizer.
template <int N>
Real stratum_maximum(const RMat<N>& P, const std::vector<RVec<N>>& y, const std::vector<int>& active,
                     const RVec<N>& n0, RVec<N>* normal) {
  // An orthonormal basis of the edges' span, then of its complement, by Gram-Schmidt.
  std::vector<RVec<N>> span, free;
  const auto add = [&](RVec<N> v, std::vector<RVec<N>>& to, const Real& floor) {
    for (const auto& e : span) v -= e.dot(v) * e;
    for (const auto& e : to) v -= e.dot(v) * e;
    const Real len = sqrt(v.dot(v));
    if (len > floor) to.push_back(v / len);
  };
  Real size = 0;
  for (const auto& v : y) size = std::max(size, Real(sqrt(v.dot(v))));
  for (int k : active) add(RVec<N>(y[k] - y[active[0]]), span, Real("1e-30") * size);
  for (int i = 0; i < N; ++i) add(RVec<N>::Unit(i), free, Real("1e-3"));
  const auto solve = [&]<int M>() {
    Eigen::Matrix<Real, N, M> b;
    for (int i = 0; i < M; ++i) b.col(i) = free[i];
    *normal = b * sphere_maximizer<M>(b.transpose() * y[active[0]], b.transpose() * P * b, b.transpose() * n0);
    return normal->dot(y[active[0]]) - sqrt(normal->dot(P * *normal));
  };
  if (free.size() == 1) return solve.template operator()<1>();
  if (free.size() == 2) return solve.template operator()<2>();
  return solve.template operator()<N>();
}

// A shape as parameters in Real: value(body, parameters) is the signed distance; kinds are
// Comparison's (0 a position, 1 a turn, 2 a length), library the library's derivatives.
template <int N>
struct Model {
  std::vector<Real> params;
  std::vector<int> kinds;
  std::vector<double> library;
  std::function<Real(const RBody<N>&, const std::vector<Real>&)> value;

  void add(const Real& p, int kind, double derivative) {
    params.push_back(p);
    kinds.push_back(kind);
    library.push_back(derivative);
  }
  // A turn (world rotation vector) at 0, one parameter per component.
  void add_turns(const RotationVector<double, N>& derivative) {
    for (int j = 0; j < turns<N>; ++j) add(0, 1, angular_component<N>(derivative, j));
  }
};

// The polytope's vertices less the body's center.
template <int N>
std::vector<RVec<N>> relative(const std::vector<RVec<N>>& v, const RBody<N>& body) {
  std::vector<RVec<N>> y;
  for (const auto& x : v) y.push_back(x - body.c);
  return y;
}

// The support gap's maximum of the body and the polytope of `vertices(params)` on the stratum
// that holds it near the library's normal n: among the vertices within 1e-9 scale of the least
// n . y there (all of them, each pair, each one), the stratum whose maximum is largest where
// no vertex lies below the stratum's own at its maximizer (a maximum near where strata meet
// may lie on either, 1e-8 rad apart: its derivatives differ by as much); false where that
// maximum is more than 1e-11 scale from the library's distance.
template <int N>
bool polytope_model(const RBody<N>& a, const Distance<double, N>& got, Real grow, const Real& scale,
                    std::function<std::vector<RVec<N>>(const std::vector<Real>&)> vertices, Model<N>& m) {
  const RVec<N> n0 = ref::to_real<N>(Vec<double, N>(got.normal));
  const std::vector<RVec<N>> y = relative<N>(vertices(m.params), a);
  Real low = n0.dot(y[0]);
  for (const auto& v : y) low = std::min(low, Real(n0.dot(v)));
  std::vector<int> near;
  for (int k = 0; k < static_cast<int>(y.size()); ++k)
    if (n0.dot(y[k]) - low <= Real("1e-9") * scale) near.push_back(k);
  std::vector<std::vector<int>> candidates{near};
  if (near.size() > 1)
    for (std::size_t i = 0; i < near.size(); ++i) {
      candidates.push_back({near[i]});
      for (std::size_t j = i + 1; j < near.size() && near.size() > 2; ++j) candidates.push_back({near[i], near[j]});
    }
  std::vector<int> active;
  Real base = 0;
  for (const auto& set : candidates) {
    RVec<N> n;
    const Real value = stratum_maximum<N>(a.P, y, set, n0, &n) - grow;
    bool valid = true;
    for (const auto& v : y) valid = valid && n.dot(v) >= n.dot(y[set[0]]) - Real("1e-25") * scale;
    if (valid && (active.empty() || value > base)) {
      active = set;
      base = value;
    }
  }
  if (active.empty() || abs(base - got.distance) > Real("1e-11") * scale) return false;
  m.value = [=](const RBody<N>& body, const std::vector<Real>& p) {
    RVec<N> unused;
    return stratum_maximum<N>(body.P, relative<N>(vertices(p), body), active, n0, &unused) - grow;
  };
  return true;
}

// Central differences over every parameter of the body and the shape; the worst error
// relative to its unit. Lengths move by 1e-15 of the body's largest radius, not of the pair's
// scale: a shape 1e12 radii across would move them by 1e-3 radii, where the differences'
// truncation (the gap's curvature is of order 1 / radius) reaches 1e-6.
template <int N>
double compare(const RBody<N>& a, const BodyGradient<double, N>& ga, const Model<N>& m, const Real& scale,
               std::string& shown) {
  Comparison cmp;
  cmp.scale = scale;
  const Real step = Real("1e-15") * std::min(scale, a.rmax);
  for (int k = 0; k < params<N>; ++k) {
    const Real h = kind_of<N>(k) == 1 ? Real("1e-15") : step;
    cmp.add(kind_of<N>(k), component<N>(ga, k),
            (m.value(moved<N>(a, k, h), m.params) - m.value(moved<N>(a, k, -h), m.params)) / (2 * h));
  }
  for (std::size_t j = 0; j < m.params.size(); ++j) {
    const Real h = m.kinds[j] == 1 ? Real("1e-15") : step;
    std::vector<Real> plus = m.params, minus = m.params;
    plus[j] += h;
    minus[j] -= h;
    cmp.add(m.kinds[j], m.library[j], (m.value(a, plus) - m.value(a, minus)) / (2 * h));
  }
  shown = cmp.show();
  return cmp.worst();
}

template <int N>
Vec<double, N> center_sum(const BodyGradient<double, N>& a, const Vec<double, N>& shape) {
  return a.center + shape;
}

// The axes turned by the turn parameters params[first..] (one nonzero at a time).
template <int N>
RMat<N> turned(RMat<N> axes, const std::vector<Real>& p, std::size_t first) {
  for (int j = 0; j < turns<N>; ++j)
    if (p[first + j] != 0) axes = world_turn<N>(j, p[first + j]) * axes;
  return axes;
}

template <int N>
RMat<N> to_real_mat(const Mat<double, N>& m) {
  RMat<N> r;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) r(i, j) = m(i, j);
  return r;
}

std::string scientific(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%.2e", x);
  return s;
}

// Bodies and shapes moved 1e6 sizes from the origin on every other case.
template <int N>
Vec<double, N> far_offset(int i, double size) {
  return Vec<double, N>::Constant(i % 2 ? 1e6 * size : 0.0);
}

constexpr double half_space_tolerance = 1e-12;
// The polytopes' and capsules': the 1e-9 (the normal polished on its stratum).
constexpr double polytope_tolerance = 1e-9;

template <int N>
void half_spaces() {
  Tally tally;
  double worst = 0;
  const int kinds = static_cast<int>(scenarios::planes.size());
  for (int i = 0; i < cases(110); ++i) {
    const auto c = scenarios::make_plane_case<N>(scenarios::planes[i % kinds], 300 + i);
    const double size = c.a.radii().maxCoeff();
    const auto a = c.a.translated(far_offset<N>(i / kinds, size));
    const auto b = c.b.translated(far_offset<N>(i / kinds, size));
    const auto g = signed_distance_gradient(a, b);
    ASSERT_LE((center_sum<N>(g.a, g.b.point)).norm(), 1e-15) << describe(c);
    const RBody<N> ra = ref::detail::make_rbody<N>(to_ref(a));
    const RVec<N> normal = ref::to_real<N>(Vec<double, N>(b.normal()));
    Model<N> m;
    for (int k = 0; k < N; ++k) m.add(Real(b.point()[k]), 0, g.b.point[k]);
    m.add_turns(g.b.normal);
    m.value = [&](const RBody<N>& body, const std::vector<Real>& p) {
      RVec<N> point, n = normal;
      for (int k = 0; k < N; ++k) point[k] = p[k];
      for (int j = 0; j < turns<N>; ++j)
        if (p[N + j] != 0) n = world_turn<N>(j, p[N + j]) * n;
      return n.dot(body.c - point) - sqrt(n.dot(body.P * n));
    };
    std::string shown;
    const double e = compare<N>(ra, g.a, m, ra.rmax, shown);
    worst = std::max(worst, e);
    EXPECT_LE(e, half_space_tolerance) << describe(c) << "\n" << shown;
    tally.add(scenarios::name(c.kind), to_string(g.value.status));
  }
  tally.print("half-space signed_distance_gradient " + std::to_string(N) + "D, worst relative error " + scientific(worst));
}

template <int N>
void boxes() {
  Tally tally;
  double worst = 0;
  int unresolved = 0, total = 0;
  for (int i = 0; i < cases(96); ++i) {
    const int kind = i % scenarios::box_kinds, seed = i / scenarios::box_kinds;
    const auto [a0, b0] = scenarios::make_box_pair<N>(kind, seed);
    const double size = a0.radii().maxCoeff() + b0.half_extents().norm();
    const auto a = a0.translated(far_offset<N>(seed, size));
    const auto b = b0.translated(far_offset<N>(seed, size));
    const std::string what = "box kind " + std::to_string(kind) + " seed " + std::to_string(seed);
    const auto g = signed_distance_gradient(a, b);
    ASSERT_LE((center_sum<N>(g.a, g.b.center)).norm(), 1e-14) << what;
    ++total;
    const RBody<N> ra = ref::detail::make_rbody<N>(to_ref(a));
    const RMat<N> axes = to_real_mat<N>(b.axes());
    Model<N> m;
    for (int k = 0; k < N; ++k) m.add(Real(b.center()[k]), 0, g.b.center[k]);
    m.add_turns(g.b.orientation);
    for (int k = 0; k < N; ++k) m.add(Real(b.half_extents()[k]), 2, g.b.half_extents[k]);
    const auto corners = [axes](const std::vector<Real>& p) {
      const RMat<N> turned_axes = turned<N>(axes, p, N);
      std::vector<RVec<N>> out;
      for (int k = 0; k < (1 << N); ++k) {
        RVec<N> x;
        for (int i2 = 0; i2 < N; ++i2) x[i2] = p[i2];
        for (int j = 0; j < N; ++j) x += ((k >> j) & 1 ? 1 : -1) * p[N + turns<N> + j] * turned_axes.col(j);
        out.push_back(x);
      }
      return out;
    };
    const Real scale = Real(a.radii().maxCoeff()) + Real(b.half_extents().norm());
    if (!polytope_model<N>(ra, g.value, 0, scale, corners, m)) {
      ++unresolved;
      tally.add(std::to_string(kind), "stratum unresolved");
      continue;
    }
    std::string shown;
    const double e = compare<N>(ra, g.a, m, scale, shown);
    worst = std::max(worst, e);
    EXPECT_LE(e, polytope_tolerance) << what << "\n" << shown;
    tally.add("kind " + std::to_string(kind), to_string(g.value.status));
  }
  tally.print("box signed_distance_gradient " + std::to_string(N) + "D, worst relative error " + scientific(worst));
  EXPECT_LE(unresolved * 10, total);
}

template <int N>
void triangles_and_capsules() {
  Tally tally;
  double worst_triangle = 0, worst_capsule = 0;
  int unresolved = 0, total = 0;
  const int kinds = static_cast<int>(scenarios::triangle_kinds.size());
  for (int i = 0; i < cases(120); ++i) {
    const auto c = scenarios::make_triangle_case<N>(scenarios::triangle_kinds[i % kinds], 500 + i);
    const bool degenerate = c.kind == scenarios::TriangleKind::needle;
    double size = c.a.radii().maxCoeff();
    for (int k = 0; k < 3; ++k) size = std::max(size, c.a.radii().maxCoeff() + (c.b.vertex(k) - c.a.center()).norm());
    const Vec<double, N> offset = far_offset<N>(i / kinds, size);
    const auto a = c.a.translated(offset);
    const RBody<N> ra = ref::detail::make_rbody<N>(to_ref(a));
    const Real scale = size;
    // The triangle.
    {
      const auto b = c.b.translated(offset);
      const auto g = signed_distance_gradient(a, b);
      ASSERT_LE((center_sum<N>(g.a, Vec<double, N>(g.b.vertices[0] + g.b.vertices[1] + g.b.vertices[2]))).norm(),
                1e-14)
          << describe(c);
      ++total;
      Model<N> m;
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < N; ++j) m.add(Real(b.vertex(k)[j]), 0, g.b.vertices[k][j]);
      const auto vertices = [](const std::vector<Real>& p) {
        std::vector<RVec<N>> out(3);
        for (int k = 0; k < 3; ++k)
          for (int j = 0; j < N; ++j) out[k][j] = p[k * N + j];
        return out;
      };
      if (degenerate) {
        tally.add(scenarios::name(c.kind), "degenerate: translation only");
      } else if (!polytope_model<N>(ra, g.value, 0, scale, vertices, m)) {
        ++unresolved;
        tally.add(scenarios::name(c.kind), "stratum unresolved");
      } else {
        std::string shown;
        const double e = compare<N>(ra, g.a, m, scale, shown);
        worst_triangle = std::max(worst_triangle, e);
        EXPECT_LE(e, polytope_tolerance) << describe(c) << "\n" << shown;
        tally.add(scenarios::name(c.kind), to_string(g.value.status));
      }
    }
    // A capsule on the segment of the first two vertices (one point for every fourth case:
    // a ball), pushed out by its radius along the segment's normal to the body, so its gap is
    // the segment's.
    {
      const bool ball = i % 4 == 3;
      const Vec<double, N> p0 = c.b.vertex(0), p1 = ball ? p0 : Vec<double, N>(c.b.vertex(1));
      const double radius = (0.05 + 0.5 * (i % 5) / 4.0) * c.a.radii().maxCoeff();
      const Vec<double, N> out = signed_distance(c.a, make_triangle<double, N>(p0, p1, p1)).normal;
      const auto b = make_capsule<double, N>(p0 + radius * out, p1 + radius * out, radius).translated(offset);
      const auto g = signed_distance_gradient(a, b);
      ASSERT_LE((center_sum<N>(g.a, Vec<double, N>(g.b.p0 + g.b.p1))).norm(), 1e-14) << describe(c);
      ASSERT_EQ(g.b.radius, -1.0);
      if (ball) {
        EXPECT_EQ(g.b.p0, g.b.p1) << describe(c);  // l = 1/2
        tally.add("capsule", "ball: translation only");
        continue;
      }
      ++total;
      Model<N> m;
      for (int k = 0; k < 2; ++k)
        for (int j = 0; j < N; ++j) m.add(Real(b.point(k)[j]), 0, (k == 0 ? g.b.p0 : g.b.p1)[j]);
      m.add(Real(b.radius()), 2, g.b.radius);
      const auto ends = [](const std::vector<Real>& p) {
        std::vector<RVec<N>> out(2);
        for (int k = 0; k < 2; ++k)
          for (int j = 0; j < N; ++j) out[k][j] = p[k * N + j];
        return out;
      };
      const Real capsule_scale = scale + Real(radius);
      if (!polytope_model<N>(ra, g.value, Real(b.radius()), capsule_scale, ends, m)) {
        ++unresolved;
        tally.add("capsule", "stratum unresolved");
        continue;
      }
      // The radius enters as -R: the model's value takes it from the parameters.
      const auto segment = m.value;
      m.value = [segment, base = Real(b.radius())](const RBody<N>& body, const std::vector<Real>& p) {
        return segment(body, p) + base - p.back();
      };
      std::string shown;
      const double e = compare<N>(ra, g.a, m, capsule_scale, shown);
      worst_capsule = std::max(worst_capsule, e);
      EXPECT_LE(e, polytope_tolerance) << "capsule from " << describe(c) << "\n" << shown;
      tally.add("capsule", to_string(g.value.status));
    }
  }
  tally.print("triangle and capsule signed_distance_gradient " + std::to_string(N) + "D, worst relative error " +
              scientific(worst_triangle) + " and " + scientific(worst_capsule));
  EXPECT_LE(unresolved * 10, total);
}

TEST(ShapeGradientProperty, HalfSpaces2D) { half_spaces<2>(); }
TEST(ShapeGradientProperty, HalfSpaces3D) { half_spaces<3>(); }
TEST(ShapeGradientProperty, Boxes2D) { boxes<2>(); }
TEST(ShapeGradientProperty, Boxes3D) { boxes<3>(); }
TEST(ShapeGradientProperty, TrianglesAndCapsules2D) { triangles_and_capsules<2>(); }
TEST(ShapeGradientProperty, TrianglesAndCapsules3D) { triangles_and_capsules<3>(); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
}  // namespace ellipsect::testing
