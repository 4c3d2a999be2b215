// The certificates of overlap and classify computed in float, for Pairs<float, N> (float
// columns): twice the lanes of the double filter per instruction and half its memory
// traffic. Written for a Highway vector of floats (batch_kernels.cpp).
//
// Unlike the double filter (certificates-inl.hpp), which repeats the scalar code bit for
// bit, this one proves its answers with explicit bounds on every rounding, so it may decide
// fewer pairs than the double filter but never a pair the exact path would answer otherwise:
// a decided pair's true contact scale mu (and, for classify, both containment factors) is
// certified outside [1 - 2 tol - 1e-6, 1 + 2 tol + 1e-6], where the scalar functions answer
// exactly (classify.hpp), so the answer is theirs. Open pairs take the scalar functions.
//
// The errors covered, with u = 2^-24 float's unit roundoff: the columns S = A diag(r^2) A^T
// computed in double (at most 1e-14 rmax^2 per entry) and rounded to float (u |S_ij|);
// r = c_b - c_a rounded (u |r_i|; the centers are exact); every float operation after
// that (the standard bound gamma_n sum |x_i y_i| for a sum of n products), with a factor 2
// or more of slack on each constant.
//   Separation: for any vector y and any weights l, m > 0,
//     mu^2 >= F(l, m) / (l + m),  F(l, m) = l m r^T C^-1 r >= l m (2 y.r - y^T C y),
//   C = m Sa + l Sb, since y^T C y - 2 y.r is smallest at y = C^-1 r. The float solve of
//   C y = r only chooses y: its error weakens the bound, never its validity.
//   A common point: x = c_a + m Sa y has a's quadric m^2 y^T Sa y, and x - c_b =
//   -l Sb y + e with e = C y - r, so sqrt of b's quadric is at most
//   l sqrt(y^T Sb y) + |e| / rmin_b.
//   Neither body inside the other (classify): a point z of a shrunk about c_a by
//   k_in = 1 - 2 tol - 1e-6 that lies outside b scaled about c_b by k_out = 1 + 2 tol +
//   1e-6 shows that b scaled by k_out does not hold a, nor b a scaled by k_in: both of
//   classify's containment tests, whichever body its reduction makes the unit ball
//   (detail/classify_impl.hpp), fail beyond the band. z is the point of a's inscribed
//   ball away from c_b, |r| + k_in rmin_a from c_b (outside when that exceeds k_out
//   rmax_b), or a's support point away from b, pulled in by its own quadric's upper bound
//   (with M's rounding, at most 1e-14 / rmin^2 per entry in double, and u |M_ij|), with
//   b's quadric bounded below likewise.
//   Containment (classify): b lies in a shrunk by k_in about c_a when sqrt(qa(c_b)) +
//   sqrt(tr(Ma Sb)) <= k_in (certificates-inl.hpp), here with both terms bounded above.
// Radii must lie in [2^-30, 2^30] (so that no square underflows); other pairs stay open.
// A NaN or infinity anywhere fails every comparison: the pair stays open.
#if defined(ELLIPSECT_CERTIFICATES_FLOAT_INL_) == defined(HWY_TARGET_TOGGLE)
#ifdef ELLIPSECT_CERTIFICATES_FLOAT_INL_
#undef ELLIPSECT_CERTIFICATES_FLOAT_INL_
#else
#define ELLIPSECT_CERTIFICATES_FLOAT_INL_
#endif

#include "certificates-inl.hpp"
#include "math.hpp"

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace ellipsect::detail::HWY_NAMESPACE {

// Thresholds from the tolerance, rounded outwards to float, with 64 u of slack for the
// last few operations of each comparison.
struct FloatBand {
  float apart2;  // |r|^2 > apart2 (rmax_a + rmax_b)^2: separated
  float inner2;  // |r|^2 < inner2 (rmin_a + rmin_b)^2: a common point
  float pass2;   // F / (l + m) >= pass2: separated
  float deep;    // both quadrics' square roots at most deep: a common point
  float reach;   // a point of a shrunk by deep (about c_a) beyond reach times b (about
                 // c_b): a is not inside b
};

inline FloatBand float_band(double tol) {
  constexpr double slack = 64 * 0x1p-24;
  const double out = 1 + 2 * tol + 1e-6, in = 1 - 2 * tol - 1e-6;
  auto up = [](double x) {
    const float f = float(x);
    return double(f) >= x ? f : nextafter(f, std::numeric_limits<float>::infinity());
  };
  auto down = [](double x) {
    if (!(x > 0)) return -1.0f;  // a tolerance this wide: the comparison never passes
    const float f = float(x);
    return double(f) <= x ? f : nextafter(f, 0.0f);
  };
  return {up(out * out * (1 + slack)), down(in * in * (1 - slack)), up(out * out * (1 + slack)),
          down(in * (1 - slack)), up(out * (1 + slack))};
}

// |M| w_abs: what the rounding of M w is measured against (w_abs = |w|).
template <class V, int N>
HWY_INLINE void abs_times(const V (&m)[N][N], const V* w_abs, V* out) {
  for (int i = 0; i < N; ++i) {
    out[i] = Abs(m[i][0]) * w_abs[0];
    for (int j = 1; j < N; ++j) out[i] = out[i] + Abs(m[i][j]) * w_abs[j];
  }
}

// |w|^T |M| |w|: what the rounding of w^T M w is measured against.
template <class V, int N>
HWY_INLINE V abs_level(const V (&m)[N][N], const V* w_abs) {
  V row[N];
  abs_times<V, N>(m, w_abs, row);
  return dot<V, N>(w_abs, row);
}

// Codes as certify's in certificates-inl.hpp: -1 separated, +1 a common point (overlap) or
// overlapping with neither body inside the other (classify, `containment`), +2 a contains b,
// +3 b contains a (classify), 0 open.
template <class V, int N, bool containment, int rounds = newton_steps>
HWY_INLINE V float_code(const BodyLanes<V, N>& a, const BodyLanes<V, N>& b, const FloatBand& band) {
  constexpr double u = 0x1p-24;
  const V one = Splat<V>(1), zero = Splat<V>(0), minus_one = zero - one;
  const V k_sum = Splat<V>(16 * u), k_vec = Splat<V>(16 * u), double_s = Splat<V>(1e-14);
  V r[N], r_abs[N];
  for (int i = 0; i < N; ++i) {
    r[i] = b.c[i] - a.c[i];
    r_abs[i] = Abs(r[i]);
  }
  const auto gate = And(Ge(Min(a.rmin, b.rmin), Splat<V>(0x1p-30)), Le(Max(a.rmax, b.rmax), Splat<V>(0x1p30)));
  const V d2 = dot<V, N>(r, r), sum_max = a.rmax + b.rmax, sum_min = a.rmin + b.rmin, dist = Sqrt(d2);
  auto separated = And(gate, Gt(d2, Splat<V>(band.apart2) * (sum_max * sum_max)));
  auto shared = AndNot(separated, And(gate, Lt(d2, Splat<V>(band.inner2) * (sum_min * sum_min))));
  const V reach = Splat<V>(band.reach), deep = Splat<V>(band.deep);
  const auto a_ball_out = Gt(dist + deep * a.rmin, reach * b.rmax);
  const auto b_ball_out = Gt(dist + deep * b.rmin, reach * a.rmax);
  auto proper = And(a_ball_out, b_ball_out);
  auto decided = [&] { return containment ? Or(separated, And(shared, proper)) : Or(separated, shared); };
  auto code = [&] {
    const auto yes = containment ? And(shared, proper) : shared;
    return IfThenElse(separated, minus_one, IfThenElse(yes, one, zero));
  };
  if (all_lanes<V>(decided())) return code();

  const auto& sa = a.s;
  const auto& sb = b.s;
  V ga[N], gb[N];
  times<V, N>(sa, r, ga);
  times<V, N>(sb, r, gb);
  const V rho_a = Sqrt(dot<V, N>(r, ga)), rho_b = Sqrt(dot<V, N>(r, gb)), rho = rho_a + rho_b;
  const auto closed = And(Le(a.rmax, Splat<V>(closed_form_aspect) * a.rmin),
                          Le(b.rmax, Splat<V>(closed_form_aspect) * b.rmin));
  const Solver solver = all_lanes<V>(closed)        ? Solver::closed_form
                        : all_lanes<V>(Not(closed)) ? Solver::ldlt
                                                    : Solver::mixed;
  const V pass2 = Splat<V>(band.pass2);
  const V ra2 = a.rmax * a.rmax, rb2 = b.rmax * b.rmax;
  // The bounds at the iterate q: separated and common-point masks.
  auto judge = [&](const PerramWertheim<V, N>& q) {
    V y_abs[N], ha[N], hb[N], y1 = zero;
    for (int i = 0; i < N; ++i) {
      y_abs[i] = Abs(q.y[i]);
      y1 = y1 + y_abs[i];
    }
    abs_times<V, N>(sa, y_abs, ha);
    abs_times<V, N>(sb, y_abs, hb);
    const V pa = dot<V, N>(y_abs, ha), pb = dot<V, N>(y_abs, hb), q_abs = dot<V, N>(y_abs, r_abs);
    // y^T S y of the exact S is within k_sum P + 1e-14 rmax^2 |y|_1^2 of the float one.
    const V s_a = double_s * ra2 * (y1 * y1), s_b = double_s * rb2 * (y1 * y1);
    const V yr = dot<V, N>(q.y, r);
    const V g = (yr + yr) - (q.m * q.a + q.l * q.b);
    const V g_err = k_sum * ((q_abs + q_abs) + (q.m * pa + q.l * pb)) + (q.m * s_a + q.l * s_b);
    const auto apart = And(gate, Ge(q.l * q.m * (g - g_err), pass2 * (q.l + q.m)));
    V e2 = zero;
    const V s_e = double_s * (q.m * ra2 + q.l * rb2) * y1;
    for (int i = 0; i < N; ++i) {
      const V e = Abs((q.m * q.sy_a[i] + q.l * q.sy_b[i]) - r[i]) + k_vec * ((q.m * ha[i] + q.l * hb[i]) + r_abs[i]) +
                  s_e;
      e2 = e2 + e * e;
    }
    const V root_a = Sqrt(q.a + k_sum * pa + s_a), root_b = Sqrt(q.b + k_sum * pb + s_b);
    const auto common = And(gate, And(Le(q.m * root_a, deep), Le(q.l * root_b + Sqrt(e2) / b.rmin, deep)));
    return std::pair(apart, common);
  };
  auto p = perram_wertheim<V, N>(sa, sb, r, rho_a / rho, rho_b / rho, solver, closed);
  for (int it = 0;; ++it) {
    const auto [apart, common] = judge(p);
    separated = Or(separated, apart);
    shared = AndNot(separated, Or(shared, common));
    if (it == rounds || all_lanes<V>(Or(separated, shared))) break;
    V l, m;
    p.newton(l, m);
    p = perram_wertheim<V, N>(sa, sb, r, l, m, solver, closed);
  }
  if constexpr (containment) {
    if (!all_lanes<V>(decided())) {
      V wa[N], wb[N], minus_r[N];
      for (int i = 0; i < N; ++i) {
        wa[i] = zero - ga[i] / rho_a;
        wb[i] = gb[i] / rho_b;
        minus_r[i] = zero - r[i];
      }
      // `own`'s support point w (from its center) pulled in until it surely lies in own
      // shrunk by deep, beyond `reach` times other's quadric scale from other's center (at
      // `base`, own's center less other's): own is not inside other.
      auto sticks_out = [&](const BodyLanes<V, N>& own, const V* w, const BodyLanes<V, N>& other, const V* base) {
        V z[N], q[N], w_abs[N], q_abs[N], w1 = zero, q1 = zero, dq = zero;
        for (int i = 0; i < N; ++i) {
          w_abs[i] = Abs(w[i]);
          w1 = w1 + w_abs[i];
        }
        const V own_up = (level<V, N>(own, w) + k_sum * abs_level<V, N>(own.m, w_abs) +
                          double_s * (w1 * w1) / (own.rmin * own.rmin)) * Splat<V>(1 + 8 * u);
        const V pull = deep / Sqrt(own_up);
        for (int i = 0; i < N; ++i) {
          z[i] = w[i] * pull;
          q[i] = z[i] + base[i];
          q_abs[i] = Abs(q[i]);
          q1 = q1 + q_abs[i];
          dq = dq + (Abs(z[i]) + Abs(base[i]));
        }
        const V other_low = level<V, N>(other, q) - k_sum * abs_level<V, N>(other.m, q_abs) -
                            double_s * (q1 * q1) / (other.rmin * other.rmin);
        return Gt(Sqrt(Max(other_low, zero)) - Splat<V>(2 * u) * dq / other.rmin, reach);
      };
      proper = And(Or(a_ball_out, sticks_out(a, wa, b, minus_r)), Or(b_ball_out, sticks_out(b, wb, a, r)));
    }
    // `inner` inside `outer` shrunk by deep about its center (certificates-inl.hpp's test,
    // with bounds): the upper bounds of qa(c_b) and tr(Ma Sb), M's double rounding at most
    // 1e-14 / rmin^2 per entry and S's 1e-14 rmax^2.
    V r1 = zero;
    for (int i = 0; i < N; ++i) r1 = r1 + r_abs[i];
    auto holds = [&](const BodyLanes<V, N>& outer, const BodyLanes<V, N>& inner) {
      const V outer_min2 = outer.rmin * outer.rmin;
      const V level_up =
          level<V, N>(outer, r) + k_sum * abs_level<V, N>(outer.m, r_abs) + double_s * (r1 * r1) / outer_min2;
      V trace_abs = zero;
      for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) trace_abs = trace_abs + Abs(outer.m[i][j]) * Abs(inner.s[i][j]);
      const V trace_up = trace_product<V, N>(outer.m, inner.s) + k_sum * trace_abs +
                         Splat<V>(2e-14 * N * N) * (inner.rmax * inner.rmax) / outer_min2;
      return And(gate, Le(Sqrt(level_up) + Sqrt(trace_up), deep));
    };
    return relation_code<V>(separated, And(shared, proper), holds(a, b), holds(b, a));
  }
  return code();
}

}  // namespace ellipsect::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
