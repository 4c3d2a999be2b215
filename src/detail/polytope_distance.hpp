// Signed distance of a body and a convex polytope (a triangle, a box) from the stationary
// directions of the support gap.
//
// Math. In the body's frame, y = A^T (x - c) with radii r and Sigma = diag(r^2), the signed
// distance of the body and P = conv{y_k} is the maximum over unit n of the support gap
//     G(n) = min_k n . y_k - rho(n),   rho(n) = sqrt(n^T Sigma n)
// (distance.hpp: the separation distance when apart, minus the penetration depth when
// overlapping). The sphere of directions splits into strata by the vertices attaining the
// minimum: one vertex (open regions), an edge (n orthogonal to it), a face (n its normal, 3D).
// On a stratum G is one smooth g_k(n) = n . y_k - rho(n), so the maximizer is a stationary
// point of g_k restricted to its stratum:
//   vertex    y - Sigma n / rho = lambda n: the support point x = Sigma n / rho is a
//             stationary point of |y - x| on the boundary, x_i = r_i^2 y_i / (r_i^2 + s), n
//             along x_i / r_i^2 = y_i / (r_i^2 + s), for each real root s of the secular
//             equation sum_i r_i^2 y_i^2 / (r_i^2 + s)^2 = 1: one beyond each extreme pole,
//             none or two between neighbouring poles (the sum is convex there), at most 2N;
//             and, where y_i = 0, s = -r_i^2 with x_i from the boundary (the hard case);
//   edge      the same problem one dimension down: along the edge e the body's shadow on the
//             plane orthogonal to e is the ellipse of shape B^T Sigma B (B an orthonormal
//             basis of that plane) and the edge is the point B^T y_j;
//   face      n = +- the face's normal (in 2D the edges' normals).
// Every candidate is a direction, so G there is at most the maximum, and the maximizer is a
// candidate: the best candidate is the answer, exact up to the rounding of the roots (of
// second order in G, which is stationary there) and of G's evaluation. The same candidates,
// with their opposites, give two more maxima over the sphere used for containment (reach and
// farthest, below). The hard-case
// directions are added for every axis, also where y_i != 0, so that a root too close to its
// pole to be resolved has its limit among the candidates.
#pragma once

#include <ellipsect/classify.hpp>
#include <ellipsect/distance.hpp>

#include "axes.hpp"
#include "contact_start.hpp"
#include "reduce.hpp"
#include "scale.hpp"
#include "secular.hpp"
#include "math.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>

namespace ellipsect::detail {

// Calls emit(n) with the normal direction (not normalized) at each stationary point of
// |y - x| over the boundary of {x : sum_i x_i^2 / a_i <= 1}, a_i = r_i^2 > 0; unless `all`,
// only at the largest root (the nearest point of a point outside). The point's components
// within eps of the radii are taken as 0 (secular.hpp's settled(): the point moved by at
// most that): smaller ones underflowed the terms a_i y_i^2, and a ball's hard case needs
// y_i = 0, so that a vertex 1e-312 off a ball's center gave no direction at all and the
// signed distance -infinity.
template <class F, int M, class Emit>
void stationary_normals(const Vec<F, M>& a, const Vec<F, M>& given, bool all, Emit&& emit) noexcept {
  const Vec<F, M> y = settled<F, M>(a.cwiseSqrt(), given);
  // The active poles -a_i (b_i = a_i y_i^2 > 0), equal ones merged, a ascending.
  std::array<F, M> pa{}, pb{};
  int m = 0;
  std::array<int, M> index;
  for (int i = 0; i < M; ++i) index[i] = i;
  std::sort(index.begin(), index.end(), [&](int i, int j) { return a[i] < a[j]; });
  F total = 0;
  for (const int i : index) {
    const F b = a[i] * y[i] * y[i];
    if (!(b > F(0))) continue;
    total += b;
    if (m > 0 && pa[m - 1] == a[i]) {
      pb[m - 1] += b;
    } else {
      pa[m] = a[i];
      pb[m++] = b;
    }
  }
  const auto sum = [&](F s) {
    F f = 0;
    for (int j = 0; j < m; ++j) f += pb[j] / ((pa[j] + s) * (pa[j] + s));
    return f;
  };
  const auto secular = [&](F s) { return sum(s) - 1; };
  const auto slope = [&](F s) {
    F f = 0;
    for (int j = 0; j < m; ++j) f -= 2 * pb[j] / ((pa[j] + s) * (pa[j] + s) * (pa[j] + s));
    return f;
  };
  const auto curvature = [&](F s) {
    F f = 0;
    for (int j = 0; j < m; ++j) {
      const F q = (pa[j] + s) * (pa[j] + s);
      f += 6 * pb[j] / (q * q);
    }
    return f;
  };
  // The root of f in (lo, hi), where f changes sign once (positive towards lo when
  // lo_positive), by Newton from `start` (monotone from the side where the convex secular
  // function is positive), each iterate shrinking the bracket and a step that leaves it
  // replaced by bisection; at most 100 steps, ending when a step is within the rounding of
  // the iterate.
  const auto solve = [](auto&& f, auto&& df, F lo, F hi, bool lo_positive, F x) {
    for (int it = 0; it < 100; ++it) {
      const F fx = f(x);
      if (fx == F(0)) return x;
      (((fx > F(0)) == lo_positive) ? lo : hi) = x;
      F next = x - fx / df(x);
      if (!(next > lo && next < hi)) next = lo + (hi - lo) / 2;
      if (!(abs(next - x) > 4 * std::numeric_limits<F>::epsilon() * abs(x))) return next;
      x = next;
    }
    return x;
  };
  // Beyond the extreme poles 1 - sum^(-1/2), with the secular function's roots and signs, is
  // concave and nearly linear (linear for one pole): Newton on it takes a few steps where on
  // the secular function itself it creeps away from a near pole.
  const auto flat = [&](F s) { return 1 - 1 / sqrt(sum(s)); };
  const auto flat_slope = [&](F s) {
    const F q = sum(s);
    return slope(s) / (2 * q * sqrt(q));
  };
  const auto emit_root = [&](F s) {
    Vec<F, M> n;
    for (int i = 0; i < M; ++i) n[i] = y[i] == F(0) ? F(0) : y[i] / (a[i] + s);
    emit(n);
  };
  if (m > 0) {
    const F spread = sqrt(total);
    // Beyond the extreme poles: Newton on `flat` from the end of the bracket where the
    // secular function is >= 0.
    const F right = -pa[0] + sqrt(pb[0]), left = -pa[m - 1] - sqrt(pb[m - 1]);
    emit_root(solve(flat, flat_slope, right, -pa[0] + spread, true, right));
    if (!all) return;
    emit_root(solve(flat, flat_slope, -pa[m - 1] - spread, left, false, left));
    // Between neighbouring poles it is convex: its least value (the root of the increasing
    // slope), then a root on either side of it where that value is negative.
    for (int j = 0; j + 1 < m; ++j) {
      const F lo = -pa[j + 1], hi = -pa[j];
      // The two poles' terms alone, B1 / u^2 + B2 / (L - u)^2 with u = s - lo, L = hi - lo,
      // are least at u = L c / (1 + c), c = (B1 / B2)^(1/3), where they are
      // (B1^(1/3) + B2^(1/3))^3 / L^2: at least 1 there, the function has no root here; the
      // place starts the search for its least value.
      const F c1 = cbrt(pb[j + 1]), c2 = cbrt(pb[j]);
      if ((c1 + c2) * (c1 + c2) * (c1 + c2) >= (hi - lo) * (hi - lo)) continue;
      const F low = solve(slope, curvature, lo, hi, false, lo + (hi - lo) * c1 / (c1 + c2));
      if (!(secular(low) < F(0))) continue;
      emit_root(solve(secular, slope, lo, low, true, lo + (low - lo) / 2));
      emit_root(solve(secular, slope, low, hi, false, low + (hi - low) / 2));
    }
  }
  if (!all) return;
  // The hard-case directions s = -a_i.
  for (int i = 0; i < M; ++i) {
    Vec<F, M> n;
    F rest = 1;
    bool valid = true;
    for (int j = 0; j < M; ++j) {
      if (j == i) continue;
      if (a[j] == a[i]) {
        valid = valid && y[j] == F(0);
        n[j] = 0;
        continue;
      }
      n[j] = y[j] / (a[j] - a[i]);
      rest -= a[j] * n[j] * n[j];
    }
    if (!valid || !(rest >= F(0))) continue;
    n[i] = sqrt(rest / a[i]);
    emit(n);
    n[i] = -n[i];
    emit(n);
  }
}

// The polytope: vertices, edges as vertex index pairs, faces (3D) as three of their vertices'
// indices; in 2D the edges' normals are the face directions.
// The features (bit k: vertex, edge or face k) that can hold the polytope's nearest point to
// the body where the two are apart: the caller's certificate (a box's slabs, box.cpp), every
// feature when unknown. The first pass tries only these.
struct Near {
  std::uint32_t vertices = ~std::uint32_t(0), edges = ~std::uint32_t(0), faces = ~std::uint32_t(0);
};

template <class F, int N>
struct Polytope {
  std::span<const Vec<F, N>> vertices;
  std::span<const std::array<int, 2>> edges;
  std::span<const std::array<int, 3>> faces;
  Near near;
};

template <class F, int N>
struct GapMaximum {
  Vec<F, N> normal;  // unit, body frame: where gap is reached
  F gap = -std::numeric_limits<F>::infinity();
  // max over n of min_k n . y_k + rho(n): the body lies in the polytope grown by a ball of
  // radius R exactly when reach <= R (support functions compared: h_body <= h_polytope + R).
  F reach = -std::numeric_limits<F>::infinity();
  // max over n of max_k n . y_k - rho(n) = max_k of vertex k's signed distance to the body's
  // boundary: the polytope grown by R lies in the body exactly when farthest <= -R.
  F farthest = -std::numeric_limits<F>::infinity();
  // reach and farthest are over every stationary direction (complete) where gap <= 0 or
  // the caller asks for them (below); where the body and the polytope are apart, otherwise,
  // only the largest roots' were evaluated: lower bounds.
  bool complete = false;
  int evaluations = 0;
};

// The three maxima above for the body of squared radii a. reach and farthest have the same
// stationary directions, negated (the body is symmetric about its center), so every
// candidate is evaluated with its opposite. `containment`: every stationary direction also
// where the body and the polytope are apart (a capsule's containment: the body may lie in
// the segment grown by R with the segment off the body).
template <class F, int N>
GapMaximum<F, N> max_support_gap(const Vec<F, N>& a, const Polytope<F, N>& p, bool containment = false) noexcept {
  GapMaximum<F, N> best;
  best.normal.setZero();
  const auto consider = [&](const Vec<F, N>& direction) {
    const Vec<F, N> n = unit_vector<F, N>(direction);
    if (!(n.squaredNorm() > F(0.5)) || !n.allFinite()) return;
    F low = std::numeric_limits<F>::infinity(), high = -low;
    for (const auto& y : p.vertices) {
      low = std::min(low, n.dot(y));
      high = std::max(high, n.dot(y));
    }
    const F rho = sqrt(n.cwiseAbs2().dot(a));
    best.evaluations += 2;
    if (low - rho > best.gap) {
      best.gap = low - rho;
      best.normal = n;
    }
    if (-high - rho > best.gap) {
      best.gap = -high - rho;
      best.normal = -n;
    }
    best.reach = std::max({best.reach, low + rho, rho - high});
    best.farthest = std::max({best.farthest, high - rho, -low - rho});
  };
  // Where the best largest-root direction already separates (G > 0), it is the answer: on
  // {G > 0} every stratum's function is concave, its one stationary point there the largest
  // root's, and the maximum's stratum is one of the near features'. Otherwise every
  // stationary direction of every feature is tried.
  const auto pass = [&](bool all) {
    const Near near = all ? Near{} : p.near;
    const auto tried = [](std::uint32_t mask, std::size_t k) { return (mask >> k & 1) != 0; };
    for (std::size_t k = 0; k < p.vertices.size(); ++k)
      if (tried(near.vertices, k)) stationary_normals<F, N>(a, p.vertices[k], all, consider);
    for (std::size_t edge = 0; edge < p.edges.size(); ++edge) {
      if (!tried(near.edges, edge)) continue;
      const auto [j, k] = p.edges[edge];
      const Vec<F, N> e = unit_vector<F, N>(p.vertices[k] - p.vertices[j]);
      if (!(e.squaredNorm() > F(0.5))) continue;  // coincident vertices: their vertex strata
      if constexpr (N == 2) {
        consider(Vec<F, 2>(-e[1], e[0]));
      } else {
        Mat<F, 3> frame;
        frame.col(0) = e.unitOrthogonal();
        frame.col(1) = e.cross(frame.col(0));
        const Eigen::Matrix<F, 3, 2> basis = frame.template leftCols<2>();
        const Mat<F, 2> shadow = basis.transpose() * a.asDiagonal() * basis;
        Eigen::SelfAdjointEigenSolver<Mat<F, 2>> eigen;
        eigen.computeDirect(shadow);
        const Eigen::Matrix<F, 3, 2> to_world = basis * eigen.eigenvectors();
        const Vec<F, 2> point = to_world.transpose() * p.vertices[j];
        const Vec<F, 2> squared = eigen.eigenvalues().cwiseMax(F(0));
        if (!(squared.minCoeff() > F(0))) continue;
        stationary_normals<F, 2>(squared, point, all, [&](const Vec<F, 2>& m) { consider(to_world * m); });
      }
    }
    if constexpr (N == 3)
      for (std::size_t face = 0; face < p.faces.size(); ++face) {
        const auto [i, j, k] = p.faces[face];
        if (tried(near.faces, face))
          consider((p.vertices[j] - p.vertices[i]).cross(p.vertices[k] - p.vertices[i]));
      }
  };
  pass(false);
  best.complete = containment || !(best.gap > F(0));
  if (best.complete) pass(true);
  return best;
}

// The maxima in world units: the gap (the signed distance), where it is reached (the world
// normal, the body's support point there and its support radius), reach and farthest.
template <class T, int N>
struct Support {
  Vec<T, N> normal, point;
  T gap, radius, reach, farthest;
  bool complete;  // GapMaximum's
  int evaluations;
};

// For the body and the polytope of the world-frame vertices (at most 8; edges and faces as in
// Polytope). Runs on the body scaled to a largest radius in [1, 2) whatever its range (the
// support's own normalization, exact), in the working type or in the wide type (scale.hpp).
template <class T, int N>
Support<T, N> polytope_support(const Ellipsoid<T, N>& body, std::span<const Vec<T, N>> vertices,
                               std::span<const std::array<int, 2>> edges, std::span<const std::array<int, 3>> faces,
                               Near near = {}, bool containment = false) noexcept {
  T coordinate = max_abs(body.center());
  for (const auto& v : vertices) coordinate = std::max(coordinate, max_abs(v));
  const Scale scale = scale_of<T>(body.radii().maxCoeff(), body.radii().minCoeff(), coordinate);
  return in_type<Work<T>>(scale, [&]<class F>(int) {
    const int e = ilogb(body.radii().maxCoeff());
    const Mat<F, N> axes = work_axes<F>(body);
    const Vec<F, N> center = body.center().template cast<F>();
    const Vec<F, N> a = times_pow2(body.radii().template cast<F>(), -e).cwiseAbs2();
    std::array<Vec<F, N>, 8> y;
    for (std::size_t k = 0; k < vertices.size(); ++k)
      y[k] = times_pow2(axes.transpose() * (vertices[k].template cast<F>() - center), -e);
    const GapMaximum<F, N> m =
        max_support_gap<F, N>(a, {std::span<const Vec<F, N>>(y.data(), vertices.size()), edges, faces, near}, containment);
    const F rho = sqrt(m.normal.cwiseAbs2().dot(a));
    const Vec<F, N> support = a.cwiseProduct(m.normal) / rho;
    return Support<T, N>{(axes * m.normal).template cast<T>(), (center + axes * times_pow2(support, e)).template cast<T>(),
                         T(ldexp(m.gap, e)), T(ldexp(rho, e)), T(ldexp(m.reach, e)),
                         T(ldexp(m.farthest, e)), m.complete, m.evaluations};
  });
}

// The distance status of a relation: containment counts as overlapping.
inline DistanceStatus distance_status(Relation r) noexcept {
  return r == Relation::separated  ? DistanceStatus::separated
         : r == Relation::touching ? DistanceStatus::touching
                                   : DistanceStatus::overlapping;
}

// A Distance from the support maximum less `grow` (a capsule's radius), with classify's
// relation as status (overlapping for containment); point_b = point_a + distance * normal.
template <class T, int N>
Distance<T, N> distance_of(const Support<T, N>& s, T grow, Relation relation) noexcept {
  Distance<T, N> out;
  out.iterations = s.evaluations;
  out.normal = s.normal;
  out.point_a = s.point;
  out.status = distance_status(relation);
  out.distance = s.gap - grow;
  if (out.status == DistanceStatus::separated) out.distance = std::max(out.distance, T(0));
  if (out.status == DistanceStatus::overlapping) out.distance = std::min(out.distance, T(0));
  out.point_b = out.point_a + out.distance * out.normal;
  return out;
}

// The band of a gap G between a body and a polytope (in W) outside which G alone decides
// classify's relation. Scaled by d about its center the body moves its boundary by at most
// |d - 1| R (R its largest radius), so G > tolerance R means a relative gap d - 1 >
// tolerance (separated) and G < -tolerance R one below -tolerance (overlapping or
// contained); 1e-9 R and 1e-12 of the spread (the vertices' distances from the center) are
// left for the rounding of G and of classify's relation, and 16 ulps of T of R and of the
// largest coordinate for what T's rounding leaves open (axes orthonormal to a few ulps, a
// box's four face corners coplanar to a few ulps of their magnitude: two routes may read
// such a body and polytope differently by that much).
template <class T, class W>
W status_band(const Options& options, W radius, W spread, W coordinate) noexcept {
  return (W(double(options.tolerance)) + W(1e-9)) * radius + W(1e-12) * spread +
         W(16) * W(std::numeric_limits<T>::epsilon()) * (radius + coordinate);
}

// A convex polytope's description, specialized in the shape's own file (obstacles/NAME.cpp),
// for the mechanisms that consume it: the polytope distance (below) and the rigid
// advancement's lowest point and largest coordinate (obstacle_motion.hpp, PolytopeObstacle):
//   static std::array<Vec<T, N>, K> vertices(const Shape&)   at most 8
//   static constexpr std::array<std::array<int, 2>, E> edges  vertex pairs
//   static constexpr std::array<std::array<int, 3>, F> faces  three vertices of each face (3D;
//                                                             none in 2D, where the edges are)
template <class Shape>
struct PolytopeTraits;

// The signed distance with classify's relation as status, `classify()` asked only where the
// gap leaves it in doubt (status_band).
template <class T, int N, class Classify>
Distance<T, N> polytope_signed_distance(const Ellipsoid<T, N>& body, std::span<const Vec<T, N>> vertices,
                                        std::span<const std::array<int, 2>> edges,
                                        std::span<const std::array<int, 3>> faces, const Options& options,
                                        Classify&& classify, Near near = {}) noexcept {
  const Support<T, N> s = polytope_support<T, N>(body, vertices, edges, faces, near);
  using W = std::conditional_t<(sizeof(T) < sizeof(double)), double, T>;
  W spread = 0, coordinate = W(max_abs(body.center()));
  for (const auto& v : vertices) {
    spread = std::max(spread, (v - body.center()).template cast<W>().norm());
    coordinate = std::max(coordinate, W(max_abs(v)));
  }
  const W radius = W(body.radii().maxCoeff());
  const W band = status_band<T>(options, radius, spread, coordinate);
  // Beyond 1e12 radii across, classify's relation is the one stated (triangle.hpp's range),
  // and the status follows it.
  const bool resolved = spread <= W(1e12) * W(body.radii().minCoeff()) && band < std::numeric_limits<W>::infinity();
  const Relation relation = !resolved ? classify()
                            : W(s.gap) > band                         ? Relation::separated
                            : W(s.gap) < -band                        ? Relation::overlapping
                                                                      : classify();
  return distance_of(s, T(0), relation);
}

// The same for a polytope shape, from its PolytopeTraits.
template <class T, int N, class Shape, class Classify>
Distance<T, N> polytope_signed_distance(const Ellipsoid<T, N>& body, const Shape& shape, const Options& options,
                                        Classify&& classify, Near near = {}) noexcept {
  using P = PolytopeTraits<Shape>;
  const auto vertices = P::vertices(shape);
  return polytope_signed_distance<T, N>(body, vertices, P::edges, P::faces, options, classify, near);
}

// distance() from signed_distance(): overlapping bodies get 0 and NaN points and normal.
template <class T, int N>
Distance<T, N> unsigned_distance(Distance<T, N> d) noexcept {
  if (d.status != DistanceStatus::overlapping) return d;
  d.distance = 0;
  d.point_a = d.point_b = d.normal = nan_vec<T, N>();
  return d;
}

}  // namespace ellipsect::detail
