// 50-digit reference for the signed distance of a body and a convex polytope given by its
// vertices (header templates, never includes the library).
//
// The signed distance is the maximum over unit n of the support gap
//     G(n) = min_k n . (v_k - c) - sqrt(n^T A diag(r^2) A^T n)
// (world frame, the axes as stored). Route, different from the library's (directions from
// the stationary points of each stratum by secular roots): search, stratum by stratum. The
// maximizer lies where one vertex attains the minimum (a local maximum of that vertex's own
// gap on the sphere), or two tie (n orthogonal to their difference: a great circle in 3D, two
// normals in 2D), or, in 3D, three (the normals of their plane). Each vertex's gap is
// searched on the whole sphere from the local maxima among evenly spread directions (a 150 x
// 300 latitude-longitude grid; 4,000 angles on the circle; the best 6), each pair's great
// circle from the local maxima among 2,000 angles, by golden-section windows of +-0.5 rad
// shrinking tenfold (nested in tangent coordinates on the sphere) in long double, then
// +-1e-8 rad in Real for the directions within 1e-9 of the best; G itself, evaluated in Real
// at every direction found, picks the answer. The searches assume each smooth function has
// one maximum within a window around a good start.
#pragma once

#include "tests/reference/reference.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace ellipsect::reference {

template <int N>
struct SupportGapMaximum {
  Real gap;        // the signed distance
  RVec<N> normal;  // a maximizing unit direction
};

template <class S, int N>
struct SupportGap {
  std::vector<Eigen::Matrix<S, N, 1>> y;  // v_k - c
  Eigen::Matrix<S, N, N> sigma;           // A diag(r^2) A^T

  S operator()(Eigen::Matrix<S, N, 1> n) const {
    using std::sqrt;
    S nn = 0;
    for (int i = 0; i < N; ++i) nn += n[i] * n[i];
    n /= S(sqrt(nn));
    S low = 0;
    for (std::size_t k = 0; k < y.size(); ++k) {
      S d = 0;
      for (int i = 0; i < N; ++i) d += n[i] * y[k][i];
      if (k == 0 || d < low) low = d;
    }
    S q = 0;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) q += n[i] * sigma(i, j) * n[j];
    return low - S(sqrt(q));
  }
};

template <class S, int N>
SupportGap<S, N> support_gap_of(const Body<N>& body, const std::vector<DVec<N>>& vertices) {
  SupportGap<S, N> g;
  for (const auto& v : vertices) {
    Eigen::Matrix<S, N, 1> y;
    for (int i = 0; i < N; ++i) y[i] = S(v[i]) - S(body.center[i]);
    g.y.push_back(y);
  }
  g.sigma.setZero();
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      for (int k = 0; k < N; ++k)
        g.sigma(i, j) += S(body.axes(i, k)) * S(body.axes(j, k)) * S(body.radii[k]) * S(body.radii[k]);
  return g;
}

namespace detail {

// max of f on [lo, hi] by golden section, `steps` reductions; returns the argument.
template <class S, class F>
S golden_max(const F& f, S lo, S hi, int steps) {
  const S ratio = S(0.6180339887498948482045868343656381177203L);
  S x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  S f1 = f(x1), f2 = f(x2);
  for (int k = 0; k < steps; ++k) {
    if (f1 < f2) {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + ratio * (hi - lo);
      f2 = f(x2);
    } else {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - ratio * (hi - lo);
      f1 = f(x1);
    }
  }
  return f1 < f2 ? x2 : x1;
}

// The best direction within +-delta of n0 (tangent coordinates), by golden section (nested
// in 3D), for g a function of the direction (a SupportGap, or another).
template <class S, int N, class G>
Eigen::Matrix<S, N, 1> refine(const G& g, const Eigen::Matrix<S, N, 1>& n0, S delta, int steps) {
  using V = Eigen::Matrix<S, N, 1>;
  if constexpr (N == 2) {
    const V t(-n0[1], n0[0]);
    const S u = golden_max<S>([&](S s) { return g(V(n0 + s * t)); }, -delta, delta, steps);
    return V(n0 + u * t);
  } else {
    // A tangent basis: the coordinate axis least aligned with n0, orthogonalized.
    int i = 0;
    for (int k = 1; k < 3; ++k)
      if (abs(n0[k]) < abs(n0[i])) i = k;
    V e = V::Zero();
    e[i] = 1;
    V t1 = e - n0.dot(e) * n0;
    using std::sqrt;
    t1 /= S(sqrt(t1.dot(t1)));
    const V t2 = n0.cross(t1);
    const auto best_v = [&](S u) {
      return golden_max<S>([&](S v) { return g(V(n0 + u * t1 + v * t2)); }, -delta, delta, steps);
    };
    const S u = golden_max<S>([&](S s) { return g(V(n0 + s * t1 + best_v(s) * t2)); }, -delta, delta, steps);
    const S v = best_v(u);
    const V n = n0 + u * t1 + v * t2;
    return n / S(sqrt(n.dot(n)));
  }
}

}  // namespace detail

namespace detail {

// A direction found in long double, and how to find it again in Real.
template <int N>
struct Candidate {
  Eigen::Matrix<long double, N, 1> direction;
  std::function<RVec<N>()> polish;
};

// The local maxima of f among evenly spread directions (4,000 angles on the circle; in 3D a
// 150 x 300 grid of latitude and longitude), compared with their grid neighbours: the best
// `count`, best first.
template <int N, class F>
std::vector<DVec<N>> best_starts(const F& f, std::size_t count) {
  std::vector<std::pair<double, DVec<N>>> found;
  const double pi = 3.14159265358979323846;
  if constexpr (N == 2) {
    const int m = 4000;
    std::vector<double> v(m);
    const auto at = [&](int k) { return DVec<2>(std::cos(2 * pi * (k + 0.5) / m), std::sin(2 * pi * (k + 0.5) / m)); };
    for (int k = 0; k < m; ++k) v[k] = f(at(k));
    for (int k = 0; k < m; ++k)
      if (v[k] >= v[(k + 1) % m] && v[k] >= v[(k + m - 1) % m]) found.emplace_back(v[k], at(k));
  } else {
    const int rows = 150, cols = 300;
    const auto at = [&](int i, int j) {
      const double t = pi * (i + 0.5) / rows, p = 2 * pi * j / cols;
      return DVec<3>(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
    };
    std::vector<double> v(rows * cols);
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) v[i * cols + j] = f(at(i, j));
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) {
        bool top = true;
        for (int di = -1; di <= 1 && top; ++di)
          for (int dj = -1; dj <= 1 && top; ++dj) {
            const int r = i + di;
            if (r < 0 || r >= rows) continue;
            top = v[i * cols + j] >= v[r * cols + (j + dj + cols) % cols];
          }
        if (top) found.emplace_back(v[i * cols + j], at(i, j));
      }
  }
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<DVec<N>> starts;
  for (std::size_t k = 0; k < found.size() && k < count; ++k) starts.push_back(found[k].second);
  return starts;
}

// Local maxima of g (a smooth function of the direction, given in double, long double and
// Real) on the sphere: golden-section windows of +-0.5 rad shrinking tenfold in long double
// from the best samples, then +-1e-8 rad in Real.
template <int N, class GD, class GL, class GR>
void sphere_maxima(const GD& gd, const GL& gl, const GR& gr, std::vector<Candidate<N>>& out) {
  using L = long double;
  for (const auto& s : best_starts<N>(gd, 6)) {
    Eigen::Matrix<L, N, 1> n = s.template cast<L>();
    for (L delta = L(0.5); delta > L(1e-9); delta /= 10) n = refine<L, N>(gl, n, delta, 40);
    out.push_back({n, [n, gr] {
                     RVec<N> r;
                     for (int i = 0; i < N; ++i) r[i] = Real(n[i]);
                     r = refine<Real, N>(gr, RVec<N>(r / sqrt(r.dot(r))), Real(1e-8), 45);
                     return RVec<N>(r / sqrt(r.dot(r)));
                   }});
  }
}

// Local maxima of g on the great circle cos t p + sin t q (3D), the same way.
template <class GL, class GR>
void circle_maxima(const RVec<3>& p, const RVec<3>& q, const GL& gl, const GR& gr, std::vector<Candidate<3>>& out) {
  using L = long double;
  const Eigen::Matrix<L, 3, 1> pl = p.template cast<L>(), ql = q.template cast<L>();
  const auto at_l = [&](L t) { return gl(Eigen::Matrix<L, 3, 1>(std::cos(t) * pl + std::sin(t) * ql)); };
  const auto at_r = [gr, p, q](const Real& t) { return gr(RVec<3>(cos(t) * p + sin(t) * q)); };
  std::vector<std::pair<L, L>> samples;
  for (int k = 0; k < 2000; ++k) {
    const L t = L(2 * 3.14159265358979323846L * (k + 0.5L) / 2000);
    samples.emplace_back(at_l(t), t);
  }
  std::vector<std::pair<L, L>> peaks;  // local maxima among the samples
  const std::size_t m = samples.size();
  for (std::size_t k = 0; k < m; ++k)
    if (samples[k].first >= samples[(k + 1) % m].first && samples[k].first >= samples[(k + m - 1) % m].first)
      peaks.push_back(samples[k]);
  std::sort(peaks.begin(), peaks.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<L> starts;
  for (std::size_t k = 0; k < peaks.size() && k < 6; ++k) starts.push_back(peaks[k].second);
  for (L t : starts) {
    for (L delta = L(0.5); delta > L(1e-9); delta /= 10) t = golden_max<L>(at_l, t - delta, t + delta, 40);
    out.push_back({Eigen::Matrix<L, 3, 1>(std::cos(t) * pl + std::sin(t) * ql), [t, p, q, at_r] {
                     const Real r = golden_max<Real>(at_r, Real(t) - Real(1e-8), Real(t) + Real(1e-8), 45);
                     return RVec<3>(cos(r) * p + sin(r) * q);
                   }});
  }
}

}  // namespace detail

template <int N>
SupportGapMaximum<N> max_support_gap(const Body<N>& body, const std::vector<DVec<N>>& vertices) {
  using L = long double;
  const auto gl = support_gap_of<L, N>(body, vertices);
  const auto gr = support_gap_of<Real, N>(body, vertices);
  std::vector<detail::Candidate<N>> candidates;
  const auto exact = [](const RVec<N>& n) {
    Eigen::Matrix<L, N, 1> l;
    for (int i = 0; i < N; ++i) l[i] = n[i].template convert_to<L>();
    return detail::Candidate<N>{l, [n] { return n; }};
  };
  // Each vertex's own gap on the whole sphere.
  for (const auto& v : vertices) {
    const std::vector<DVec<N>> one{v};
    detail::sphere_maxima<N>(support_gap_of<double, N>(body, one), support_gap_of<long double, N>(body, one),
                             support_gap_of<Real, N>(body, one), candidates);
  }
  // Directions orthogonal to each pair of distinct vertices, where both tie: in 2D the two
  // normals of the segment; in 3D the great circle, searched with the first vertex's gap; and
  // in 3D the two normals of each triple of vertices not on a line.
  for (std::size_t j = 0; j < vertices.size(); ++j)
    for (std::size_t k = j + 1; k < vertices.size(); ++k) {
      const RVec<N> e = to_real<N>(vertices[k]) - to_real<N>(vertices[j]);
      if (detail::is_zero<N>(e)) continue;
      if constexpr (N == 2) {
        const RVec<2> n = RVec<2>(-e[1], e[0]) / sqrt(e.dot(e));
        candidates.push_back(exact(n));
        candidates.push_back(exact(RVec<2>(-n)));
      } else {
        const RVec<3> u = e / sqrt(e.dot(e));
        RVec<3> p = RVec<3>::Zero();
        int i = 0;
        for (int m = 1; m < 3; ++m)
          if (abs(u[m]) < abs(u[i])) i = m;
        p[i] = 1;
        p -= u.dot(p) * u;
        p /= sqrt(p.dot(p));
        const RVec<3> q = u.cross(p);
        const std::vector<DVec<N>> one{vertices[j]};
        detail::circle_maxima(p, q, support_gap_of<long double, 3>(body, one), support_gap_of<Real, 3>(body, one),
                              candidates);
        for (std::size_t l = k + 1; l < vertices.size(); ++l) {
          const RVec<3> n = e.cross(RVec<3>(to_real<3>(vertices[l]) - to_real<3>(vertices[j])));
          if (detail::is_zero<3>(n)) continue;
          candidates.push_back(exact(RVec<3>(n / sqrt(n.dot(n)))));
          candidates.push_back(exact(RVec<3>(-n / sqrt(n.dot(n)))));
        }
      }
    }
  // Polished in Real: the directions within 1e-9 (largest radius + |vertex - center|) of the
  // best in long double (a tenth of the tests' tolerance; the rest cannot win).
  L best_l = -std::numeric_limits<L>::infinity(), size = L(body.radii.maxCoeff());
  for (const auto& c : candidates) best_l = std::max(best_l, gl(c.direction));
  for (const auto& y : gl.y) size = std::max(size, L(body.radii.maxCoeff()) + y.norm());
  SupportGapMaximum<N> best{-std::numeric_limits<Real>::infinity(), RVec<N>::Zero()};
  for (const auto& c : candidates) {
    if (gl(c.direction) < best_l - L(1e-9) * size) continue;
    const RVec<N> n = c.polish();
    const Real g = gr(n);
    if (g > best.gap) best = {g, n};
  }
  return best;
}

// G(n) in Real at a given direction.
template <int N>
Real support_gap_at(const Body<N>& body, const std::vector<DVec<N>>& vertices, const DVec<N>& n) {
  return support_gap_of<Real, N>(body, vertices)(to_real<N>(n));
}

// The functions the tests and benchmarks call, for N = 2 and 3: compiled once, in
// support_gap_reference.cpp (the library ellipsect_reference), not in every program that includes
// this header.
#define ELLIPSECT_SUPPORT_GAP_REFERENCE_FUNCTIONS(extern_, N) \
  extern_ template SupportGapMaximum<N> max_support_gap<N>(const Body<N>&, const std::vector<DVec<N>>&); \
  extern_ template Real support_gap_at<N>(const Body<N>&, const std::vector<DVec<N>>&, const DVec<N>&);
ELLIPSECT_SUPPORT_GAP_REFERENCE_FUNCTIONS(extern, 2)
ELLIPSECT_SUPPORT_GAP_REFERENCE_FUNCTIONS(extern, 3)

}  // namespace ellipsect::reference
