// The secular equation behind every closest/farthest point query (seed sections 4-5).
//
// For an axis-aligned ellipsoid with center k and semi-axes e (the "other" body in the
// reduced frame) and the query point at the origin, the Lagrange condition
// P = s D (P - k) gives P_i = k_i u / (e_i^2 + u) for a multiplier u; P lies on the
// boundary when  sum_i (e_i k_i / (e_i^2 + u))^2 = 1  (the seed's f(s) = 0 with u = -s).
// Each query owns one branch of that equation; shifting u so the branch starts at 0 turns
// all three into the same problem
//
//     S(x) = sum_i c_i^2 / (g_i + x)^2 = 1,   x >= 0,  g_i >= 0,  c_i = e_i k_i,
//
//   closest point from outside / inside:  x = u + e_min^2, g_i = e_i^2 - e_min^2
//     (from outside we keep x = u, g_i = e_i^2, which avoids cancellation in u)
//   farthest point:                       x = -u - e_max^2, g_i = e_max^2 - e_i^2.
//
// S is decreasing and convex for x > 0, and r(x) = S(x)^-1/2 is concave (a negative-power
// mean of the positive affine functions (g_i + x)/|c_i|). Newton on r - 1 started left of
// the root therefore never overshoots and converges monotonically; it is exact in one step
// when a single term is present (a ball). Rounding is guarded by a bracket [lo, hi], and a
// final bisection that stops when the midpoint equals an endpoint makes termination
// unconditional. When every term with g_i = 0 has c_i = 0 and the remaining S(0) <= 1 the
// root is x = 0 and the point is not determined by the formula (the classical "hard
// case"); it is completed on the boundary along the first axis of that group.
#pragma once

#include <ellipsect/shapes.hpp>

#include <cmath>
#include <limits>

namespace ellipsect::detail {

template <class R>
struct SecularRoot {
  R x;        // the root
  bool hard;  // x = 0 with the degenerate group absent from S; s_rest = S(0) <= 1
  R s_rest;
};

// Newton steps before the bisection fallback; Newton from the left converges
// quadratically, so in practice it stops after a handful.
inline constexpr int secular_newton_steps = 32;

template <class R, int N>
SecularRoot<R> solve_secular(const Vec<R, N>& c_in, const Vec<R, N>& g) noexcept {
  using std::abs;
  using std::sqrt;
  const Vec<R, N> c = c_in.cwiseAbs();
  constexpr R eps = std::numeric_limits<R>::epsilon();

  // Degenerate group: terms with g_i = 0. If all of them vanish, S(0) is finite.
  bool pole = false;
  for (int i = 0; i < N; ++i) pole = pole || (g[i] == R(0) && c[i] != R(0));
  if (!pole) {
    R s0 = 0;
    for (int i = 0; i < N; ++i)
      if (c[i] != R(0)) s0 += (c[i] / g[i]) * (c[i] / g[i]);
    if (s0 <= R(1)) return {R(0), true, s0};
  }

  // Bracket: S >= each single term, whose root is c_i - g_i; S(x) <= |c|^2 / (x + g_min)^2.
  R lo = 0;
  for (int i = 0; i < N; ++i) lo = std::max(lo, c[i] - g[i]);
  R hi = std::max(lo, c.norm() - g.minCoeff());

  auto eval = [&](R x, R& s, R& ds) {  // s = S(x), ds = sum t_i^2 / (g_i + x) = -S'(x)/2
    s = 0;
    ds = 0;
    for (int i = 0; i < N; ++i) {
      if (c[i] == R(0)) continue;
      const R den = g[i] + x;
      const R t = c[i] / den;
      s += t * t;
      ds += t * t / den;
    }
  };

  R x = lo;
  for (int it = 0; it < secular_newton_steps; ++it) {
    R s, ds;
    eval(x, s, ds);
    if (s > R(1))
      lo = x;
    else if (s < R(1))
      hi = x;
    else
      return {x, false, R(0)};
    // Newton on r(x) - 1 with r = S^-1/2:  dx = (1 - r) / r' = S (sqrt(S) - 1) / ds.
    R next = x + s * (sqrt(s) - R(1)) / ds;
    if (!(next >= lo && next <= hi)) next = lo + (hi - lo) / 2;
    if (abs(next - x) <= 2 * eps * next) return {next, false, R(0)};
    x = next;
  }
  for (;;) {  // bisection: terminates because the bracket shrinks to adjacent floats
    const R mid = lo + (hi - lo) / 2;
    if (mid <= lo || mid >= hi) return {mid, false, R(0)};
    R s, ds;
    eval(mid, s, ds);
    (s > R(1) ? lo : hi) = mid;
  }
}

// Query results in the reduced frame: the point P of the other body's boundary and |P|.
template <class R, int N>
struct BranchPoint {
  Vec<R, N> point;
  R norm;
};

template <class R, int N>
BranchPoint<R, N> make_branch_point(const Vec<R, N>& p) noexcept {
  return {p, p.norm()};
}

// Fills the hard-case point: components with g_i = 0 are zero in k (the solver checked),
// and their total offset from k has length e_group * sqrt(1 - s_rest).
template <class R, int N>
void complete_hard_case(Vec<R, N>& p, const Vec<R, N>& e, const Vec<R, N>& g, R s_rest) noexcept {
  for (int i = 0; i < N; ++i) {
    if (g[i] == R(0)) {
      p[i] = e[i] * std::sqrt(std::max(R(0), R(1) - s_rest));
      return;
    }
  }
}

// Closest boundary point to the origin when the origin is outside (q(0) > 0).
template <class R, int N>
BranchPoint<R, N> closest_from_outside(const Vec<R, N>& e, const Vec<R, N>& k) noexcept {
  const Vec<R, N> g = e.cwiseProduct(e);
  const SecularRoot<R> root = solve_secular<R, N>(e.cwiseProduct(k), g);
  const R u = root.x;
  Vec<R, N> p;
  for (int i = 0; i < N; ++i) p[i] = k[i] * (u / (g[i] + u));
  return make_branch_point(p);
}

// Closest boundary point to the origin when the origin is inside or on (q(0) <= 0).
template <class R, int N>
BranchPoint<R, N> closest_from_inside(const Vec<R, N>& e, const Vec<R, N>& k) noexcept {
  const R em = e.minCoeff();
  Vec<R, N> g;
  for (int i = 0; i < N; ++i) g[i] = (e[i] - em) * (e[i] + em);
  const SecularRoot<R> root = solve_secular<R, N>(e.cwiseProduct(k), g);
  const R u = root.x - em * em;  // <= 0
  Vec<R, N> p;
  for (int i = 0; i < N; ++i) p[i] = (g[i] + root.x == R(0)) ? R(0) : k[i] * (u / (g[i] + root.x));
  if (root.hard) complete_hard_case(p, e, g, root.s_rest);
  return make_branch_point(p);
}

// Farthest boundary point from the origin (any position of the origin).
template <class R, int N>
BranchPoint<R, N> farthest(const Vec<R, N>& e, const Vec<R, N>& k) noexcept {
  const R eM = e.maxCoeff();
  Vec<R, N> g;
  for (int i = 0; i < N; ++i) g[i] = (eM - e[i]) * (eM + e[i]);
  const SecularRoot<R> root = solve_secular<R, N>(e.cwiseProduct(k), g);
  const R v = root.x + eM * eM;  // = -u > 0
  Vec<R, N> p;
  for (int i = 0; i < N; ++i) p[i] = (g[i] + root.x == R(0)) ? R(0) : k[i] * (v / (g[i] + root.x));
  if (root.hard) complete_hard_case(p, e, g, root.s_rest);
  return make_branch_point(p);
}

// q(0) = sum (k_i / e_i)^2 - 1: positive when the origin is outside the ellipsoid.
template <class R, int N>
R level_at_origin(const Vec<R, N>& e, const Vec<R, N>& k) noexcept {
  return k.cwiseQuotient(e).squaredNorm() - R(1);
}

}  // namespace ellipsect::detail
