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
#include "math.hpp"

namespace ellipsect::detail {

// |v| without the underflow or overflow of its squares: v.norm() where the squared norm is
// a normal number (bit for bit), else the norm of v scaled by a power of two.
template <class R, int N>
R stable_norm(const Vec<R, N>& v) noexcept {
  const R s = v.squaredNorm();
  if (s >= std::numeric_limits<R>::min() && s <= std::numeric_limits<R>::max()) return sqrt(s);
  const R m = v.cwiseAbs().maxCoeff();
  if (!(m > R(0)) || !isfinite(m)) return m;
  const int e = ilogb(m);
  Vec<R, N> w;
  for (int i = 0; i < N; ++i) w[i] = ldexp(v[i], -e);
  return ldexp(w.norm(), e);
}

template <class R>
struct SecularRoot {
  R x;        // the root
  bool hard;  // x = 0 with the degenerate group absent from S; s_rest = S(0) <= 1
  R s_rest;
};

// Newton steps before the bisection fallback; Newton from the left converges
// quadratically, so in practice it stops after a handful.
inline constexpr int secular_newton_steps = 32;

// `guess` (ignored unless inside the bracket) warm-starts Newton; from the right of the
// root the first step lands left of it, after which convergence is monotone again.
template <class R, int N>
SecularRoot<R> solve_secular(const Vec<R, N>& c_in, const Vec<R, N>& g, R guess = R(-1)) noexcept {
  using std::abs;
  using std::sqrt;
  const Vec<R, N> c = c_in.cwiseAbs();
  const R eps = std::numeric_limits<R>::epsilon();

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
  R hi = std::max(lo, stable_norm(c) - g.minCoeff());

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

  R x = guess > lo && guess < hi ? guess : lo;
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

// Query results in the reduced frame: the boundary point P of the ellipsoid, the same
// point relative to the ellipsoid's center (offset = P - k, computed without the
// cancellation of P - k when the origin is far away), and |P|.
template <class R, int N>
struct BranchPoint {
  Vec<R, N> point;
  Vec<R, N> offset;
  R norm;
  R root;  // the secular root x, to warm-start a nearby solve
};

// The branch's point from its root x: with den_i = g_i + x,
//   P_i = k_i * num / den_i  and  P_i - k_i = k_i * off / den_i,
// where (num, off) = (u, -e_i^2) for the closest point (u = x outside, x - e_min^2
// inside) and (x + e_max^2, e_i^2) for the farthest. In the hard case the terms with
// den_i = 0 are replaced by the boundary completion along the group's first axis.
// k * (n / den), or (k / den) * n where n / den overflows (den subnormal; k is then as
// small, as den = g_i + x >= |c_i| = e_i |k_i| on the branch).
template <class R>
R scaled_ratio(R k, R n, R den) noexcept {
  const R q = n / den;
  return isfinite(q) ? k * q : k / den * n;
}

template <class R, int N, class Num, class Off>
BranchPoint<R, N> branch_point(const Vec<R, N>& e, const Vec<R, N>& k, const Vec<R, N>& g, const SecularRoot<R>& root,
                               Num num, Off off) noexcept {
  BranchPoint<R, N> b;
  bool completed = false;
  for (int i = 0; i < N; ++i) {
    const R den = g[i] + root.x;
    if (den == R(0)) {  // hard case: k_i = 0 here
      b.offset[i] = completed ? R(0) : e[i] * sqrt(std::max(R(0), R(1) - root.s_rest));
      b.point[i] = b.offset[i];
      completed = true;
    } else {
      b.point[i] = scaled_ratio(k[i], num(i), den);
      b.offset[i] = scaled_ratio(k[i], off(i), den);
    }
  }
  b.norm = stable_norm(b.point);
  b.root = root.x;
  return b;
}

// Closest boundary point to the origin when the origin is outside (q(0) > 0).
template <class R, int N>
BranchPoint<R, N> closest_from_outside(const Vec<R, N>& e, const Vec<R, N>& k, R guess = R(-1)) noexcept {
  const Vec<R, N> g = e.cwiseProduct(e);
  const SecularRoot<R> root = solve_secular<R, N>(e.cwiseProduct(k), g, guess);
  return branch_point<R, N>(e, k, g, root, [&](int) { return root.x; }, [&](int i) { return -g[i]; });
}

// Closest boundary point to the origin when the origin is inside or on (q(0) <= 0).
template <class R, int N>
BranchPoint<R, N> closest_from_inside(const Vec<R, N>& e, const Vec<R, N>& k) noexcept {
  const R em = e.minCoeff();
  Vec<R, N> g;
  for (int i = 0; i < N; ++i) g[i] = (e[i] - em) * (e[i] + em);
  const SecularRoot<R> root = solve_secular<R, N>(e.cwiseProduct(k), g);
  const R u = root.x - em * em;  // <= 0
  return branch_point<R, N>(e, k, g, root, [&](int) { return u; }, [&](int i) { return -e[i] * e[i]; });
}

// Farthest boundary point from the origin (any position of the origin).
template <class R, int N>
BranchPoint<R, N> farthest(const Vec<R, N>& e, const Vec<R, N>& k) noexcept {
  const R eM = e.maxCoeff();
  Vec<R, N> g;
  for (int i = 0; i < N; ++i) g[i] = (eM - e[i]) * (eM + e[i]);
  const SecularRoot<R> root = solve_secular<R, N>(e.cwiseProduct(k), g);
  const R v = root.x + eM * eM;
  return branch_point<R, N>(e, k, g, root, [&](int) { return v; }, [&](int i) { return e[i] * e[i]; });
}

// k with its components of at most eps * e_max set to zero: the query point moved by at most
// eps e_max. Components that small (a center 1e-16 or a subnormal off the query point)
// underflow c_i = e_i k_i and the secular root, and k_i num / (g_i + x) overflows (a 1e-320
// offset made the farthest point infinite).
template <class R, int N>
Vec<R, N> settled(const Vec<R, N>& e, Vec<R, N> k) noexcept {
  const R floor = std::numeric_limits<R>::epsilon() * e.maxCoeff();
  for (int i = 0; i < N; ++i)
    if (abs(k[i]) <= floor) k[i] = R(0);
  return k;
}

// q(0) = sum (k_i / e_i)^2 - 1: positive when the origin is outside the ellipsoid.
template <class R, int N>
R level_at_origin(const Vec<R, N>& e, const Vec<R, N>& k) noexcept {
  return k.cwiseQuotient(e).squaredNorm() - R(1);
}

}  // namespace ellipsect::detail
