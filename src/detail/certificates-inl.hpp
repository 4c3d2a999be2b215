// Certificates that decide most pairs without the exact solve, written once for a lane
// type V: double (one pair: classify.cpp, contact.cpp) or a Highway vector of doubles
// (several pairs per instruction: batch_kernels.cpp). Both run the same IEEE operations in
// the same order (the SIMD file is built with -ffp-contract=off), so a lane of the vector
// code returns exactly what the scalar code returns for that pair: the batch functions
// equal the scalar ones bit for bit.
//
// Each certificate answers only outside the tangency band, by a margin well above its
// rounding; pairs it leaves open (code 0) take the exact path.
//   circumscribed balls apart (1e-9 margin)   -> separated
//   inscribed balls meet (1e-9 margin)        -> a common point
//   (one pair's overlap) the bodies' reaches along the centre line sum to at least
//   |r| / (1 - margin)^1/2                    -> a common point
//   the support planes normal to r apart: |r|^2 > (1 + margin) (rho_a + rho_b), rho the
//   support radii times |r| (rho_a^2 = r^T Sa r)  -> separated (margin as F's, below)
//   Perram-Wertheim F(l) = l (1 - l) r^T C^-1 r, C = (1 - l) Sa + l Sb (S = A diag(radii^2)
//   A^T, r = c_b - c_a): max_l F = mu^2, mu the scale at which the bodies touch. Any l
//   bounds mu^2 from below, and x(l) = c_a + (1 - l) Sa C^-1 r has quadrics qa, qb:
//     F >= 1 + margin                         -> separated
//     qa, qb <= 1 - margin                    -> a common interior point
//   evaluated at the two-ball maximizer l = rho_a / (rho_a + rho_b) (rho: support radii
//   along r), then at Newton iterates while a lane is open. cond(C) <= (largest aspect
//   ratio)^2; C is solved in closed form up to aspect 100 (rounding ~ eps cond(C)^2 <=
//   1e8 eps) and by L D L^T beyond (~ eps cond(C) <= 1e8 eps), plus eps |r| / r_min from
//   the centers' offset (rounded once; where the pair lies does not count). F is used for
//   aspect ratios up to 1e4, with margin = 1e-6 + 1024 eps (1e8 + |r| / r_min), about
//   2.4e-5.
//   a's support point away from b, c_a - Sa r / rho_a, has b's quadric >= 1.02 and b's away
//   from a has a's quadric >= 1.02            -> neither body inside the other
//   sqrt(qa(c_b)) + sqrt(tr(Ma Sb)) <= 1 - margin  -> a contains b (and the same for b)
//   the centers' closest approach over [0, t_max] exceeds the circumscribed radii
//                                             -> no contact in the window
// A certified answer is therefore the one the exact path gives (the property tests check
// both against the 50-digit reference).
//
// Highway's per-target include guard: the file is compiled once per SIMD target. nvcc
// (batch_gpu.cu) compiles it once, without Highway, for V = double on the GPU: one pair per
// thread, the operations of the scalar code (built with --fmad=false; division and square
// root correctly rounded, nvcc's default).
#if defined(ELLIPSECT_CERTIFICATES_INL_) == defined(HWY_TARGET_TOGGLE)
#ifdef ELLIPSECT_CERTIFICATES_INL_
#undef ELLIPSECT_CERTIFICATES_INL_
#else
#define ELLIPSECT_CERTIFICATES_INL_
#endif

#include <ellipsect/shapes.hpp>

#include "axes.hpp"
#include "math.hpp"

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#ifdef __CUDACC__
#define ELLIPSECT_LANE __host__ __device__ inline
#define ELLIPSECT_LANE_NAMESPACE cuda
#else
#include <hwy/highway.h>
#define ELLIPSECT_LANE HWY_INLINE
#define ELLIPSECT_LANE_NAMESPACE HWY_NAMESPACE
HWY_BEFORE_NAMESPACE();
#endif
namespace ellipsect::detail::ELLIPSECT_LANE_NAMESPACE {

// Scalar twins of the Highway operations, so one template serves both. Max and Min follow
// the x86 instructions (the second operand when unordered).
ELLIPSECT_LANE double Sqrt(double x) { return sqrt(x); }
ELLIPSECT_LANE double Max(double a, double b) { return a > b ? a : b; }
ELLIPSECT_LANE double Min(double a, double b) { return a < b ? a : b; }
ELLIPSECT_LANE bool Lt(double a, double b) { return a < b; }
ELLIPSECT_LANE bool Le(double a, double b) { return a <= b; }
ELLIPSECT_LANE bool Gt(double a, double b) { return a > b; }
ELLIPSECT_LANE bool Ge(double a, double b) { return a >= b; }
ELLIPSECT_LANE bool IsFinite(double x) { return isfinite(x); }
ELLIPSECT_LANE double Abs(double x) { return abs(x); }
ELLIPSECT_LANE bool And(bool a, bool b) { return a && b; }
ELLIPSECT_LANE bool Or(bool a, bool b) { return a || b; }
ELLIPSECT_LANE bool AndNot(bool not_a, bool b) { return !not_a && b; }
ELLIPSECT_LANE bool Not(bool a) { return !a; }
ELLIPSECT_LANE double IfThenElse(bool m, double yes, double no) { return m ? yes : no; }

template <class V>
ELLIPSECT_LANE V Splat(double x) {
  if constexpr (std::is_same_v<V, double>) {
    return x;
  } else {
#ifndef __CUDACC__
    return hwy::HWY_NAMESPACE::Set(hwy::HWY_NAMESPACE::DFromV<V>(), x);
#endif
  }
}

// The smallest normal number of V's lanes (double or float).
template <class V>
ELLIPSECT_LANE V tiny_normal() {
  if constexpr (std::is_same_v<V, double>) {
    return std::numeric_limits<double>::min();
  } else {
#ifndef __CUDACC__
    using Lane = hwy::HWY_NAMESPACE::TFromV<V>;
    return hwy::HWY_NAMESPACE::Set(hwy::HWY_NAMESPACE::DFromV<V>(), std::numeric_limits<Lane>::min());
#endif
  }
}

template <class V, class M>
ELLIPSECT_LANE bool all_lanes(M m) {
  if constexpr (std::is_same_v<V, double>) {
    return m;
  } else {
#ifndef __CUDACC__
    return hwy::HWY_NAMESPACE::AllTrue(hwy::HWY_NAMESPACE::DFromV<V>(), m);
#endif
  }
}

template <class V, int N>
ELLIPSECT_LANE V dot(const V* x, const V* y) {
  V s = x[0] * y[0];
  for (int i = 1; i < N; ++i) s = s + x[i] * y[i];
  return s;
}

template <class V, int N>
ELLIPSECT_LANE V largest(const V* r) {
  V m = r[0];
  for (int i = 1; i < N; ++i) m = Max(m, r[i]);
  return m;
}

template <class V, int N>
ELLIPSECT_LANE V smallest(const V* r) {
  V m = r[0];
  for (int i = 1; i < N; ++i) m = Min(m, r[i]);
  return m;
}

template <class V, int N>
ELLIPSECT_LANE void times(const V (&s)[N][N], const V* w, V* g) {
  for (int i = 0; i < N; ++i) g[i] = dot<V, N>(s[i], w);
}

// One body per lane, in the form the certificates use: center, S = A diag(r^2) A^T (the
// inverse of the quadric matrix), the quadric matrix M = A diag(r^-2) A^T (classify
// only), largest and smallest radius. Pairs stores these per body, so the batch filter
// reads the values the scalar functions compute here.
template <class V, int N>
struct BodyLanes {
  V c[N];
  V s[N][N];
  V m[N][N];
  V rmax, rmin;
};

// What lanes_of fills: the ball tests need the center and the radii only, overlap and
// first_contact S, classify also M.
enum class Fill { balls, shape, quadric };

template <class T, int N>
BodyLanes<double, N> lanes_of(const Ellipsoid<T, N>& e, Fill fill) noexcept {
  BodyLanes<double, N> b;
  double w[N][N], r[N];
  for (int k = 0; k < N; ++k) r[k] = double(e.radii()[k]);
  for (int i = 0; i < N; ++i) b.c[i] = double(e.center()[i]);
  b.rmax = largest<double, N>(r);
  b.rmin = smallest<double, N>(r);
  if (fill == Fill::balls) return b;
  const Mat<double, N> axes = work_axes<double>(e);
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < N; ++k) w[i][k] = axes(i, k) * r[k];
  for (int i = 0; i < N; ++i)
    for (int j = i; j < N; ++j) b.s[i][j] = b.s[j][i] = dot<double, N>(w[i], w[j]);
  if (fill == Fill::quadric) {
    for (int i = 0; i < N; ++i)
      for (int k = 0; k < N; ++k) w[i][k] = axes(i, k) / r[k];
    for (int i = 0; i < N; ++i)
      for (int j = i; j < N; ++j) b.m[i][j] = b.m[j][i] = dot<double, N>(w[i], w[j]);
  }
  return b;
}

// tr(M S) for symmetric M and S.
template <class V, int N>
ELLIPSECT_LANE V trace_product(const V (&m)[N][N], const V (&s)[N][N]) {
  V diagonal = m[0][0] * s[0][0], off = Splat<V>(0);
  for (int i = 1; i < N; ++i) diagonal = diagonal + m[i][i] * s[i][i];
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j) off = off + m[i][j] * s[i][j];
  return diagonal + (off + off);
}

// The body's quadric at offset w from its center, w^T M w.
template <class V, int N>
ELLIPSECT_LANE V level(const BodyLanes<V, N>& b, const V* w) {
  V mw[N];
  times<V, N>(b.m, w, mw);
  return dot<V, N>(w, mw);
}

// How C is solved in a vector: in closed form (adjugate over determinant, for aspect ratios
// up to 100), by L D L^T (beyond), or both with a per-lane choice when a vector mixes them.
// The two have relative rounding of a few eps cond(C)^2 and eps cond(C); with
// cond(C) <= (largest aspect)^2 both stay under 1e8 eps.
enum class Solver { closed_form, ldlt, mixed };
inline constexpr double closed_form_aspect = 100;

// The Perram-Wertheim function at l: C = m Sa + l Sb with m = 1 - l, y = C^-1 r,
// A = y^T Sa y, B = y^T Sb y, F = l m r^T y, and the quadrics of the point x(l) = c_a + m Sa y
// = c_b - l Sb y: qa = m^2 A, qb = l^2 B. F' = qa - qb, so at the maximizer qa = qb = F = mu^2.
// The weights l and m are carried separately (each from its own formula, updated by the same
// Newton step with opposite signs), never as 1 - l: swapping the bodies then swaps l and m
// bit for bit and negates r and y exactly, so every certificate is exactly swap-symmetric,
// and a weight far below eps (balls 1e100 apart in size) keeps its digits instead of making
// 1 - l round to 1. F is homogeneous of degree 1 in (l, m) and x(l) solves C y = r for any
// weights, so l + m = 1 up to rounding costs F a relative eps and the point nothing.
template <class V, int N>
struct PerramWertheim {
  using Mask = decltype(Lt(std::declval<V>(), std::declval<V>()));
  Solver solver;
  Mask closed;    // lanes solved in closed form (Solver::mixed)
  V l, m, f, qa, qb;
  Mask factored;  // det or every pivot of D positive and normal: the values are meaningful
  V adj[N][N], inv_det, low[N][N], inv[N], y[N], a, b, sy_a[N], sy_b[N];  // y = C^-1 r

  // The determinant and the pivots must be normal numbers: a subnormal one has lost digits
  // and its reciprocal may overflow (3D balls 1e107 apart in size have det(C) ~ 1e-313, and
  // an infinite F would certify separation).
  ELLIPSECT_LANE void factor(const V (&sa)[N][N], const V (&sb)[N][N]) {
    const V one = Splat<V>(1), zero = Splat<V>(0), tiny = tiny_normal<V>();
    V c[N][N];
    for (int i = 0; i < N; ++i)
      for (int j = 0; j <= i; ++j) c[i][j] = c[j][i] = m * sa[i][j] + l * sb[i][j];
    auto closed_ok = And(Gt(l, zero), Gt(m, zero)), ldlt_ok = closed_ok;
    if (solver != Solver::ldlt) {
      if constexpr (N == 2) {
        adj[0][0] = c[1][1];
        adj[1][1] = c[0][0];
        adj[0][1] = adj[1][0] = zero - c[0][1];
      } else {
        static_assert(N == 3, "closed form for 2 and 3 dimensions");
        adj[0][0] = c[1][1] * c[2][2] - c[1][2] * c[1][2];
        adj[1][1] = c[0][0] * c[2][2] - c[0][2] * c[0][2];
        adj[2][2] = c[0][0] * c[1][1] - c[0][1] * c[0][1];
        adj[0][1] = adj[1][0] = c[0][2] * c[1][2] - c[0][1] * c[2][2];
        adj[0][2] = adj[2][0] = c[0][1] * c[1][2] - c[0][2] * c[1][1];
        adj[1][2] = adj[2][1] = c[0][1] * c[0][2] - c[0][0] * c[1][2];
      }
      const V det = dot<V, N>(c[0], adj[0]);
      inv_det = one / det;
      closed_ok = And(closed_ok, Ge(det, tiny));
    }
    if (solver != Solver::closed_form) {
      V dg[N];
      for (int j = 0; j < N; ++j) {
        V s = c[j][j];
        for (int k = 0; k < j; ++k) s = s - low[j][k] * low[j][k] * dg[k];
        dg[j] = s;
        inv[j] = one / s;
        ldlt_ok = And(ldlt_ok, Ge(s, tiny));
        for (int i = j + 1; i < N; ++i) {
          V t = c[i][j];
          for (int k = 0; k < j; ++k) t = t - low[i][k] * low[j][k] * dg[k];
          low[i][j] = t * inv[j];
        }
      }
    }
    factored = solver == Solver::closed_form ? closed_ok
               : solver == Solver::ldlt      ? ldlt_ok
                                             : Or(And(closed, closed_ok), AndNot(closed, ldlt_ok));
  }

  // x = C^-1 rhs.
  ELLIPSECT_LANE void solve(const V* rhs, V* x) const {
    V xc[N];
    if (solver != Solver::ldlt)
      for (int i = 0; i < N; ++i) xc[i] = dot<V, N>(adj[i], rhs) * inv_det;
    if (solver == Solver::closed_form) {
      for (int i = 0; i < N; ++i) x[i] = xc[i];
      return;
    }
    for (int i = 0; i < N; ++i) {
      V s = rhs[i];
      for (int k = 0; k < i; ++k) s = s - low[i][k] * x[k];
      x[i] = s;
    }
    for (int i = 0; i < N; ++i) x[i] = x[i] * inv[i];
    for (int i = N - 1; i >= 0; --i)
      for (int k = i + 1; k < N; ++k) x[i] = x[i] - low[k][i] * x[k];
    if (solver == Solver::mixed)
      for (int i = 0; i < N; ++i) x[i] = IfThenElse(closed, xc[i], x[i]);
  }

  // The Newton iterate: l - F'/F'' and m + F'/F'' (F'' from z = C^-1 (Sb - Sa) y:
  // A' = -2 (Sa y).z, B' = -2 (Sb y).z), or (l, m) where it leaves (0, 1) or F'' >= 0.
  ELLIPSECT_LANE void newton(V& l_next, V& m_next) const {
    const V zero = Splat<V>(0), two = Splat<V>(2);
    V d[N], z[N];
    for (int i = 0; i < N; ++i) d[i] = sy_b[i] - sy_a[i];
    solve(d, z);
    const V curvature = zero - two * (m * a + l * b) - two * (m * m * dot<V, N>(sy_a, z) - l * l * dot<V, N>(sy_b, z));
    const V step = (qa - qb) / curvature;
    const V next_l = l - step, next_m = m + step;
    const auto take = And(Lt(curvature, zero), And(Gt(next_l, zero), Gt(next_m, zero)));
    l_next = IfThenElse(take, next_l, l);
    m_next = IfThenElse(take, next_m, m);
  }
};

template <class V, int N, class Mask>
ELLIPSECT_LANE PerramWertheim<V, N> perram_wertheim(const V (&sa)[N][N], const V (&sb)[N][N], const V* r, V l, V m,
                                                Solver solver, Mask closed) {
  PerramWertheim<V, N> p;
  p.solver = solver;
  p.closed = closed;
  p.l = l;
  p.m = m;
  p.factor(sa, sb);
  p.solve(r, p.y);
  times<V, N>(sa, p.y, p.sy_a);
  times<V, N>(sb, p.y, p.sy_b);
  p.a = dot<V, N>(p.y, p.sy_a);
  p.b = dot<V, N>(p.y, p.sy_b);
  p.f = l * m * dot<V, N>(r, p.y);
  p.qa = m * m * p.a;
  p.qb = l * l * p.b;
  return p;
}

// Circumscribed-ball reach of the pair, with the band and the 1e-9 rounding margin.
template <class V, int N>
ELLIPSECT_LANE V outer_reach(const BodyLanes<V, N>& a, const BodyLanes<V, N>& b, V tol) {
  return (a.rmax + b.rmax) * (Splat<V>(1) + Splat<V>(2) * tol + Splat<V>(1e-9));
}

// The circumscribed balls are apart; the inscribed balls meet (both with a 1e-9 margin).
template <class V, int N>
ELLIPSECT_LANE auto ball_tests(const BodyLanes<V, N>& a, const BodyLanes<V, N>& b, V tol) {
  V r[N];
  for (int i = 0; i < N; ++i) r[i] = b.c[i] - a.c[i];
  const V d2 = dot<V, N>(r, r);
  const V outer = outer_reach<V, N>(a, b, tol);
  const V inner = (a.rmin + b.rmin) * Splat<V>(1 - 1e-9);
  return std::pair(Gt(d2, outer * outer), Lt(d2, inner * inner));
}

// F is used for aspect ratios up to 1e4, so cond(C) <= 1e8; its margin is 1e-6 above
// 1024 times the rounding estimate eps (cond(C) + |r| / r_min) of F and the quadrics, r the
// centers' offset.
template <class V, int N>
ELLIPSECT_LANE auto aspect_gate(const BodyLanes<V, N>& a, const BodyLanes<V, N>& b) {
  const V aspect = Splat<V>(1e4);
  return And(Le(a.rmax, aspect * a.rmin), Le(b.rmax, aspect * b.rmin));
}

template <class V, int N>
ELLIPSECT_LANE V certificate_margin(const BodyLanes<V, N>& a, const BodyLanes<V, N>& b, const V* r) {
  V offset = Splat<V>(0);
  for (int i = 0; i < N; ++i) offset = offset + Abs(r[i]);
  offset = offset / Min(a.rmin, b.rmin);
  constexpr double ulp_scale = 1024 * std::numeric_limits<double>::epsilon();
  return Splat<V>(1e-6 + ulp_scale * 1e8) + Splat<V>(ulp_scale) * offset;
}

// classify's code from its certified masks, first that holds: -1 separated, +1 overlapping
// with neither body inside the other, +2 a contains b, +3 b contains a, else 0.
template <class V, class M>
ELLIPSECT_LANE V relation_code(M separated, M proper, M b_in_a, M a_in_b) {
  const V one = Splat<V>(1), two = one + one;
  return IfThenElse(separated, Splat<V>(0) - one,
                    IfThenElse(proper, one, IfThenElse(b_in_a, two, IfThenElse(a_in_b, two + one, Splat<V>(0)))));
}

// Newton steps on the Perram-Wertheim parameter (quadratic convergence: three leave
// 0.25% of random pairs open).
inline constexpr int newton_steps = 3;

// Codes: -1 separated, +1 decided otherwise (overlap: a common point; classify: relation
// overlapping, neither body inside the other), classify also +2 a contains b, +3 b contains
// a (with the margin), 0 undecided. `rounds`: Newton rounds at
// most; a lane's code does not depend on the other lanes, nor on whether the rounds are
// run at once or after a first call with none (the rounds start from the same iterate).
template <class V, int N, bool containment, int rounds = newton_steps>
ELLIPSECT_LANE V certify(const BodyLanes<V, N>& a, const BodyLanes<V, N>& b, V tol) {
  const V one = Splat<V>(1), zero = Splat<V>(0), minus_one = zero - one;
  V r[N];
  for (int i = 0; i < N; ++i) r[i] = b.c[i] - a.c[i];
  const auto [apart, inside] = ball_tests<V, N>(a, b, tol);
  if constexpr (containment) {
    if (all_lanes<V>(apart)) return minus_one;
  } else {
    if (all_lanes<V>(Or(apart, inside))) return IfThenElse(apart, minus_one, one);
  }
  const auto aspect_ok = aspect_gate<V, N>(a, b);
  auto gate = aspect_ok;
  const V margin = certificate_margin<V, N>(a, b, r);

  const auto& sa = a.s;
  const auto& sb = b.s;
  V ga[N], gb[N];
  times<V, N>(sa, r, ga);
  times<V, N>(sb, r, gb);
  const V rho_a = Sqrt(dot<V, N>(r, ga)), rho_b = Sqrt(dot<V, N>(r, gb));
  // F at the two-ball l, then at Newton iterates towards its maximizer while some lane is
  // open: every l bounds mu from below and gives a candidate common point.
  const V closed_aspect = Splat<V>(closed_form_aspect);
  const auto closed = And(Le(a.rmax, closed_aspect * a.rmin), Le(b.rmax, closed_aspect * b.rmin));
  const Solver solver = all_lanes<V>(closed)            ? Solver::closed_form
                        : all_lanes<V>(Not(closed)) ? Solver::ldlt
                                                        : Solver::mixed;
  const V rho = rho_a + rho_b, pass = one + margin, deep = one - margin;
  // The plane normal to r between the support planes: |r| >= (rho_a + rho_b) / |r| (1 +
  // margin) makes mu >= 1 + margin, before C is solved (F at the two-ball l is at least
  // (|r|^2 / rho)^2 by Cauchy-Schwarz, so F would decide these lanes too).
  const auto slab = And(gate, Gt(dot<V, N>(r, r), rho * pass));  // strict: concentric bodies have r = rho = 0
  if constexpr (containment) {
    if (all_lanes<V>(Or(apart, slab))) return minus_one;
  } else {
    if (all_lanes<V>(Or(Or(apart, slab), inside))) return IfThenElse(Or(apart, slab), minus_one, one);
  }
  auto p = perram_wertheim<V, N>(sa, sb, r, rho_a / rho, rho_b / rho, solver, closed);
  gate = And(gate, p.factored);
  auto certain = [&](const PerramWertheim<V, N>& q) { return And(gate, q.factored); };
  auto separated = Or(Or(apart, slab), And(certain(p), Ge(p.f, pass)));
  auto shared = AndNot(separated, Or(inside, And(certain(p), And(Le(p.qa, deep), Le(p.qb, deep)))));
  for (int it = 1; it <= rounds && !all_lanes<V>(Or(separated, shared)); ++it) {
    V l, m;
    p.newton(l, m);
    p = perram_wertheim<V, N>(sa, sb, r, l, m, solver, closed);
    separated = Or(separated, And(certain(p), Ge(p.f, pass)));
    shared = AndNot(separated, Or(shared, And(certain(p), And(Le(p.qa, deep), Le(p.qb, deep)))));
  }
  if constexpr (!containment) {
    return IfThenElse(separated, minus_one, IfThenElse(shared, one, zero));
  } else {
    V wa[N], wb[N];  // a's support point away from b, relative to c_b; b's away from a, relative to c_a
    for (int i = 0; i < N; ++i) {
      wa[i] = zero - r[i] - ga[i] / rho_a;
      wb[i] = r[i] + gb[i] / rho_b;
    }
    const V out = Splat<V>(1.02);
    const auto proper = And(And(shared, gate), And(Ge(level<V, N>(b, wa), out), Ge(level<V, N>(a, wb), out)));
    // b inside a shrunk by 1 - margin about c_a: over b, |x - c_a|_a <= |c_b - c_a|_a +
    // |Ma^1/2 Lb| (b = c_b + Lb (unit ball), Lb Lb^T = Sb), and |Ma^1/2 Lb|^2 = lambda_max(Ma Sb)
    // <= tr(Ma Sb); likewise a inside b.
    const auto b_in_a = And(aspect_ok, Le(Sqrt(level<V, N>(a, r)) + Sqrt(trace_product<V, N>(a.m, b.s)), deep));
    const auto a_in_b = And(aspect_ok, Le(Sqrt(level<V, N>(b, r)) + Sqrt(trace_product<V, N>(b.m, a.s)), deep));
    return relation_code<V>(separated, proper, b_in_a, a_in_b);
  }
}

template <class V, int N, int rounds = newton_steps>
ELLIPSECT_LANE V overlap_code(const BodyLanes<V, N>& a, const BodyLanes<V, N>& b, V tol) {
  return certify<V, N, false, rounds>(a, b, tol);
}

template <class V, int N, int rounds = newton_steps>
ELLIPSECT_LANE V classify_code(const BodyLanes<V, N>& a, const BodyLanes<V, N>& b, V tol) {
  return certify<V, N, true, rounds>(a, b, tol);
}

// +1 when the velocities and t_max are valid and the circumscribed balls stay apart over
// [0, t_max] (first_contact: no contact in the window), else 0.
template <class V, int N>
ELLIPSECT_LANE V swept_code(const BodyLanes<V, N>& a, const V* va, const BodyLanes<V, N>& b, const V* vb, V t_max,
                        V tol) {
  const V one = Splat<V>(1), zero = Splat<V>(0);
  V c0[N], v[N];
  auto valid = Ge(t_max, zero);
  for (int i = 0; i < N; ++i) {
    c0[i] = b.c[i] - a.c[i];
    v[i] = vb[i] - va[i];
    valid = And(valid, And(IsFinite(va[i]), IsFinite(vb[i])));
  }
  V speed = Abs(v[0]);
  for (int i = 1; i < N; ++i) speed = Max(speed, Abs(v[i]));
  const V vv = dot<V, N>(v, v);
  const auto moving = Gt(speed, zero);
  // |v|^2 underflows for relative speeds below about 1e-154 (bodies at ordinary speeds
  // closing very slowly: time rescaling follows the speeds, not their difference), and the
  // closest approach would be taken at t = 0: such pairs take the exact path.
  valid = And(valid, Or(Not(moving), Ge(vv, Splat<V>(std::numeric_limits<double>::min()))));
  V t = IfThenElse(moving, (zero - dot<V, N>(c0, v)) / IfThenElse(moving, vv, one), zero);
  valid = And(valid, IsFinite(t));
  t = Min(Max(t, zero), t_max);
  V p[N];
  for (int i = 0; i < N; ++i) p[i] = c0[i] + t * v[i];
  const V reach = outer_reach<V, N>(a, b, tol);
  return IfThenElse(And(valid, Gt(dot<V, N>(p, p), reach * reach)), one, zero);
}

// One pair: classify's code (`containment`) or overlap's, with the balls tested before S
// and M are formed (the same decisions as certify's, which tests them first too).
// The centre line (overlap of one pair, before S is formed: the batch columns hold no axes,
// so the batch filter leaves such pairs to overlap, which runs this). a reaches t_a |r|
// from c_a along r = c_b - c_a, t_a = (r^T Ma r)^-1/2 = |diag(radii)^-1 A^T r|^-1 (a sum of
// squares: relative rounding a few eps times the aspect ratio), and b reaches t_b |r| back;
// (t_a + t_b)^2 (1 - margin) >= 1 puts a point of the segment at both quadrics <= 1 - margin.
template <class T, int N>
bool centre_line_meets(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const BodyLanes<double, N>& la,
                       const BodyLanes<double, N>& lb) noexcept {
  double r[N];
  for (int i = 0; i < N; ++i) r[i] = lb.c[i] - la.c[i];
  auto reach = [&r](const Ellipsoid<T, N>& e) {
    const Mat<double, N> axes = work_axes<double>(e);
    double q = 0;
    for (int k = 0; k < N; ++k) {
      double p = axes(0, k) * r[0];
      for (int i = 1; i < N; ++i) p = p + axes(i, k) * r[i];
      p = p / double(e.radii()[k]);
      q = q + p * p;
    }
    return 1 / sqrt(q);  // concentric: infinite
  };
  const double t = reach(a) + reach(b);
  return aspect_gate<double, N>(la, lb) && t * t * (1 - certificate_margin<double, N>(la, lb, r)) >= 1;
}

template <bool containment, class T, int N>
double certificate_code(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, double tol) noexcept {
  const auto balls_a = lanes_of(a, Fill::balls), balls_b = lanes_of(b, Fill::balls);
  const auto [apart, inside] = ball_tests<double, N>(balls_a, balls_b, tol);
  if (apart) return -1;
  if constexpr (!containment) {
    if (inside || centre_line_meets(a, b, balls_a, balls_b)) return 1;
  }
  const Fill fill = containment ? Fill::quadric : Fill::shape;
  return certify<double, N, containment>(lanes_of(a, fill), lanes_of(b, fill), tol);
}

}  // namespace ellipsect::detail::ELLIPSECT_LANE_NAMESPACE
#ifndef __CUDACC__
HWY_AFTER_NAMESPACE();
#endif

#endif  // per-target include guard
