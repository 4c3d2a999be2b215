// The Perram-Wertheim contact function and the distance of closest approach
// (contact_function.hpp), in the reduced frame of docs/method.md section 1.
//
// There the sphere body S is the unit ball (S's matrix M_S^-1 = I) and the other body O has
// M_O^-1 = diag(e^2), so C = u I + v diag(e^2) is diagonal, with u the weight of S and v that
// of O (u + v = 1). For O's center at k relative to S's, and D_i = u + v e_i^2:
//   F   = u v sum_i k_i^2 / D_i,
//   F'  = qs - qo,   qs = u^2 sum_i k_i^2 / D_i^2,   qo = v^2 sum_i e_i^2 k_i^2 / D_i^2,
//   F'' = -2 sum_i e_i^2 k_i^2 / D_i^3 < 0                      (derivatives in v),
// where qs and qo are the quadrics of S and O at the Perram-Wertheim point z = u k / D
// (componentwise, relative to S's center), equal to F at the maximizer. F is homogeneous of
// degree 2 in k, so the solve runs on the unit direction of the centers and F is scaled
// by |r|^2 afterwards (no underflow of k^2 for centers 1e-200 apart).
#include <ellipsect/contact_function.hpp>

#include "detail/classify_impl.hpp"
#include "detail/gradient.hpp"
#include "detail/instantiate.hpp"
#include "detail/scale.hpp"

#include <cmath>
#include <limits>

namespace ellipsect {

std::string_view to_string(ContactFunctionStatus s) noexcept {
  switch (s) {
    case ContactFunctionStatus::ok: return "ok";
    case ContactFunctionStatus::concentric: return "concentric";
    case ContactFunctionStatus::did_not_converge: return "did_not_converge";
  }
  return "unknown";
}

namespace {

// The maximum of F over the weights in the reduced frame, with bounds.
template <class R>
struct Maximum {
  R f, f_upper;  // F at the last iterate and an upper bound of max F (before rounding margins)
  R u, v;        // the weights of S and O there
  int iterations = 0;
  bool converged = false;
};

template <class R>
struct Terms {
  R f, fp, fpp, rounding;  // F, F', F'' and the rounding of F'
};

template <class R, int N>
Terms<R> terms(const Vec<R, N>& e2, const Vec<R, N>& k2, R u, R v) noexcept {
  R s = 0, qs = 0, qo = 0, c = 0;
  for (int i = 0; i < N; ++i) {
    const R inv = R(1) / (u + v * e2[i]);
    const R t = k2[i] * inv;
    s += t;
    qs += t * inv;
    qo += t * inv * e2[i];
    c += t * inv * inv * e2[i];
  }
  qs *= u * u;
  qo *= v * v;
  return {u * v * s, qs - qo, R(-2) * c, R(8) * std::numeric_limits<R>::epsilon() * (qs + qo)};
}

// Newton on F' from the maximizer for two balls, v = rho_S / (rho_S + rho_O) with the support
// radii rho_S = |k|, rho_O = |e k|; a step that leaves the bracket of the root is replaced by
// bisection. Converged when F' vanishes to its rounding or the step is below the weights'
// rounding.
template <class R, int N>
Maximum<R> maximize(const Vec<R, N>& e, const Vec<R, N>& k, int max_iterations) noexcept {
  constexpr R eps = std::numeric_limits<R>::epsilon();
  const Vec<R, N> e2 = e.cwiseAbs2(), k2 = k.cwiseAbs2();
  const R rho_s = k.norm(), rho_o = e.cwiseProduct(k).norm();
  Maximum<R> m;
  m.u = rho_o / (rho_s + rho_o);
  m.v = rho_s / (rho_s + rho_o);
  R u_lo = 1, v_lo = 0, u_hi = 0, v_hi = 1;  // F' > 0 at v_lo, < 0 at v_hi
  for (;;) {
    const Terms<R> t = terms<R, N>(e2, k2, m.u, m.v);
    m.f = t.f;
    ++m.iterations;
    if (t.fp > 0) {
      u_lo = m.u;
      v_lo = m.v;
    } else {
      u_hi = m.u;
      v_hi = m.v;
    }
    if (std::abs(t.fp) <= t.rounding) {
      m.converged = true;
      break;
    }
    if (m.iterations >= max_iterations) {
      // Concavity: max F <= F + F' (v* - v) with v* in the bracket.
      m.f_upper = t.f + (t.fp > 0 ? t.fp * (v_hi - m.v) : t.fp * (v_lo - m.v));
      return m;
    }
    // The Newton step, judged on the smaller weight (the other may not change at all).
    const R step = t.fp / t.fpp;
    R u = m.u + step, v = m.v - step;
    if (!(v <= u ? v > v_lo && v < v_hi : u > u_hi && u < u_lo)) {
      u = (u_lo + u_hi) / 2;
      v = (v_lo + v_hi) / 2;
    }
    const bool small = (v <= u ? std::abs(v - m.v) : std::abs(u - m.u)) <= R(4) * eps * std::min(u, v);
    m.u = u;
    m.v = v;
    if (small) {
      m.converged = true;
      break;
    }
  }
  m.f_upper = m.f;
  return m;
}

// The reduction and the maximum for the world direction `dir` of O's center from S's (unit).
template <class R, int N>
struct Solved {
  detail::Reduced<R, N> red;
  Vec<R, N> k;  // the direction in the reduced frame
  Maximum<R> max;
  R rounding;  // relative rounding of F from the reduction: the map's condition is S's aspect
};

template <class R, class T, int N>
Solved<R, N> solve(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, const Vec<R, N>& dir,
                   const Options& options) noexcept {
  Solved<R, N> out{detail::reduce<R>(s, o), {}, {}, {}};
  out.k = out.red.to_z * dir;
  out.max = maximize<R, N>(out.red.e, out.k, options.max_iterations);
  const R aspect = R(s.radii().maxCoeff()) / R(s.radii().minCoeff());
  out.rounding = R(4 * detail::reduced_frame_ulps) * std::numeric_limits<R>::epsilon() * aspect;
  return out;
}

// x rounded to T towards -inf (+inf when `up`).
template <class T, class R>
T directed(R x, bool up) noexcept {
  T y = T(x);
  if (up ? R(y) < x : R(y) > x) y = std::nextafter(y, up ? std::numeric_limits<T>::infinity() : -std::numeric_limits<T>::infinity());
  return y;
}

// perram_wertheim's value from the solve, for r = center(o) - center(s) of length `norm`.
template <class T, class R, int N>
ContactFunction<T> value_of(const Solved<R, N>& sol, bool a_is_s, R norm) noexcept {
  ContactFunction<T> out;
  const Maximum<R>& m = sol.max;
  const R f = norm * (norm * m.f);
  out.iterations = m.iterations;
  out.lambda = T(a_is_s ? m.v : m.u);
  if (m.converged) {
    out.status = ContactFunctionStatus::ok;
    out.f = out.f_upper = T(f);
  } else {
    out.status = ContactFunctionStatus::did_not_converge;
    out.f = directed<T>(f * (R(1) - sol.rounding), false);
    out.f_upper = directed<T>(norm * (norm * m.f_upper) * (R(1) + sol.rounding), true);
  }
  return out;
}

// The pair in query order (detail::order_pair): the sphere body s, the other body o, and
// r = center(o) - center(s) as a unit direction and its length.
template <class R, class T, int N>
ContactFunction<T> contact_function(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, bool a_is_s,
                                    const Vec<R, N>& direction, R norm, const Options& options) noexcept {
  return value_of<T>(solve<R>(s, o, direction, options), a_is_s, norm);
}

// F and its gradient (contact_function.hpp) for the pair scaled by 2^-e. In the Z frame, per
// unit of |r|, y = k / D; in the world frame y = to_z^T (k / D), M_S^-1 y = to_world (k / D)
// and M_O^-1 y = to_world (e^2 k / D).
template <class R, class T, int N>
ContactFunctionGradient<T, N> contact_function_gradient(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o,
                                                        bool a_is_s, const Vec<R, N>& direction, R norm, int e,
                                                        const Options& options) noexcept {
  const Solved<R, N> sol = solve<R>(s, o, direction, options);
  const BodyGradient<T, N> unknown = detail::constant_gradient<T, N>(std::numeric_limits<T>::quiet_NaN());
  ContactFunctionGradient<T, N> out{value_of<T>(sol, a_is_s, norm), unknown, unknown};
  const Maximum<R>& m = sol.max;
  if (!m.converged) return out;
  Vec<R, N> z, ez;
  for (int i = 0; i < N; ++i) {
    z[i] = sol.k[i] / (m.u + m.v * sol.red.e[i] * sol.red.e[i]);
    ez[i] = sol.red.e[i] * sol.red.e[i] * z[i];
  }
  const Vec<R, N> y = sol.red.to_z.transpose() * z;
  const R uv2 = R(2) * m.u * m.v * norm;  // 2 lambda (1 - lambda) |r|
  // The body X with weight w and M_X^-1 y = my: d/d radii and d/d phi, in the scaled frame.
  auto body = [&](const Ellipsoid<T, N>& x, R w, const Vec<R, N>& my, const Vec<R, N>& center) {
    const Vec<R, N> q = detail::work_axes<R>(x).transpose() * y;
    BodyGradient<R, N> g;
    g.center = center;
    g.radii = -(uv2 * norm * w) * x.radii().template cast<R>().cwiseProduct(q.cwiseAbs2());
    g.orientation = detail::times<R, N>(detail::turn_rate<R, N>(my, y), -uv2 * norm * w);
    return g;
  };
  BodyGradient<R, N> gs = body(s, m.u, Vec<R, N>(sol.red.to_world * z), Vec<R, N>(-uv2 * y));
  BodyGradient<R, N> go = body(o, m.v, Vec<R, N>(sol.red.to_world * ez), Vec<R, N>(uv2 * y));
  // Lengths of the pair scaled by 2^-e: the derivatives by a length scale by 2^-e.
  for (BodyGradient<R, N>* g : {&gs, &go}) {
    g->center = detail::times_pow2(g->center, -e);
    g->radii = detail::times_pow2(g->radii, -e);
  }
  out.a = detail::gradient_in<T>(a_is_s ? gs : go, R(1));
  out.b = detail::gradient_in<T>(a_is_s ? go : gs, R(1));
  return out;
}

// The same with b moving from a's center along the unit direction u.
template <class R, class T, int N>
ClosestApproach<T, N> approach(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, bool a_is_s, const Vec<R, N>& u,
                               const Options& options) noexcept {
  ClosestApproach<T, N> out;
  // O's center relative to S's, per unit of sigma.
  const Solved<R, N> sol = solve<R>(s, o, a_is_s ? u : Vec<R, N>(-u), options);
  const Maximum<R>& m = sol.max;
  out.iterations = m.iterations;
  out.lambda = T(a_is_s ? m.v : m.u);
  const R sigma = R(1) / std::sqrt(m.f);
  // The contact point z = u k / D on S's boundary (normalized: |z| = 1 at the maximizer).
  Vec<R, N> z;
  for (int i = 0; i < N; ++i) z[i] = sol.k[i] / (m.u + m.v * sol.red.e[i] * sol.red.e[i]);
  z = detail::unit_vector<R, N>(z);
  const Vec<R, N> center_s = a_is_s ? Vec<R, N>(s.center().template cast<R>())
                                    : Vec<R, N>(o.center().template cast<R>() + sigma * u);
  out.point = (center_s + sol.red.to_world * z).template cast<T>();
  const Vec<R, N> n = detail::unit_vector<R, N>(sol.red.normal_map * z);
  out.normal = (a_is_s ? n : Vec<R, N>(-n)).template cast<T>();
  if (m.converged) {
    out.status = ContactFunctionStatus::ok;
    out.distance = out.distance_lower = T(sigma);
  } else {
    out.status = ContactFunctionStatus::did_not_converge;
    out.distance = directed<T>(R(1) / std::sqrt(m.f * (R(1) - sol.rounding)), true);
    out.distance_lower = directed<T>(R(1) / std::sqrt(m.f_upper * (R(1) + sol.rounding)), false);
  }
  return out;
}

// F is dimensionless: pairs outside the native range (detail/scale.hpp) run rescaled by a
// power of two, or in long double. The sphere body is chosen before rescaling (rescaling
// can merge bodies that differ only below the smallest subnormal; swap symmetry needs the
// order they had). `finish(s, o, a_is_s, direction, norm, e)` solves the pair in query order,
// scaled by 2^-e, with r = norm * direction in the working type of direction.
template <class T, int N, class Finish>
auto at_scale(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, Finish finish) noexcept {
  using R = detail::Work<T>;
  using W = detail::Wide<R>;
  const auto [s, o, a_is_s] = detail::order_pair(a, b);
  auto difference = [](const auto& x, const auto& y, auto type) {
    using S = decltype(type);
    return Vec<S, N>(y.center().template cast<S>() - x.center().template cast<S>());
  };
  const detail::Scale scale = detail::scale_of(a, b);
  if (scale.range == detail::Range::wide) {
    const Vec<W, N> r = difference(s, o, W());
    return finish(s, o, a_is_s, detail::unit_vector<W, N>(r), detail::stable_norm<W, N>(r), 0);
  }
  if (scale.range == detail::Range::native) {
    const Vec<R, N> r = difference(s, o, R());
    return finish(s, o, a_is_s, detail::unit_vector<R, N>(r), detail::stable_norm<R, N>(r), 0);
  }
  // Rescaled: the same arithmetic as at the native scale (answers equal bit for bit), unless
  // the rescaled centers are too close to keep the direction's digits (r subnormal or zero);
  // then r comes from the given centers in long double.
  const int e = scale.exponent;
  const Ellipsoid<T, N> s2 = detail::scaled(s, -e), o2 = detail::scaled(o, -e);
  Vec<R, N> r = difference(s2, o2, R());
  R norm = detail::stable_norm<R, N>(r);
  if (!(norm >= std::numeric_limits<R>::min())) {
    const Vec<W, N> wide = difference(s, o, W());
    r = detail::unit_vector<W, N>(wide).template cast<R>();
    norm = R(std::ldexp(detail::stable_norm<W, N>(wide), -e));
  }
  return finish(s2, o2, a_is_s, detail::unit_vector<R, N>(r), norm, e);
}

template <class T>
ContactFunction<T> concentric() noexcept {
  ContactFunction<T> out;
  out.status = ContactFunctionStatus::concentric;
  out.f = out.f_upper = T(0);
  out.lambda = std::numeric_limits<T>::quiet_NaN();
  return out;
}

}  // namespace

template <class T, int N>
ContactFunction<T> perram_wertheim(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options) noexcept {
  if (a.center() == b.center()) return concentric<T>();
  return at_scale(a, b, [&](const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, bool a_is_s, const auto& direction,
                            auto norm, int) { return contact_function(s, o, a_is_s, direction, norm, options); });
}

template <class T, int N>
ContactFunctionGradient<T, N> perram_wertheim_gradient(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                                       const Options& options) noexcept {
  if (a.center() == b.center()) {
    // F vanishes to second order in r: every derivative is 0.
    return {concentric<T>(), detail::constant_gradient<T, N>(T(0)), detail::constant_gradient<T, N>(T(0))};
  }
  return at_scale(a, b, [&](const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, bool a_is_s, const auto& direction,
                            auto norm, int e) {
    return contact_function_gradient(s, o, a_is_s, direction, norm, e, options);
  });
}

template <class T, int N>
ClosestApproach<T, N> closest_approach(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                       const VecArg<T, N>& direction, const Options& options) {
  using R = detail::Work<T>;
  using W = detail::Wide<R>;
  if (!direction.allFinite()) throw InputError("direction", "must be finite");
  if (direction.isZero(0)) throw InputError("direction", "must be nonzero");
  const auto [s, o, a_is_s] = detail::order_pair(a, b);
  const detail::Scale scale = detail::scale_of(a, b);
  if (scale.range == detail::Range::wide)
    return approach<W>(s, o, a_is_s, detail::unit_vector<W, N>(direction.template cast<W>()), options);
  const Vec<R, N> u = detail::unit_vector<R, N>(direction.template cast<R>());
  if (scale.range == detail::Range::native) return approach<R>(s, o, a_is_s, u, options);
  const int e = scale.exponent;
  ClosestApproach<T, N> out = approach<R>(detail::scaled(s, -e), detail::scaled(o, -e), a_is_s, u, options);
  out.distance = std::ldexp(out.distance, e);
  out.distance_lower = std::ldexp(out.distance_lower, e);
  out.point = detail::times_pow2(out.point, e);
  return out;
}

template <class T, int N>
ClosestApproachGradient<T, N> closest_approach_gradient(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                                        const VecArg<T, N>& direction, const Options& options) {
  using R = detail::Work<T>;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const BodyGradient<T, N> unknown = detail::constant_gradient<T, N>(nan);
  ClosestApproachGradient<T, N> out{closest_approach(a, b, direction, options), unknown, unknown,
                                    Vec<T, N>::Constant(nan)};
  if (out.value.status != ContactFunctionStatus::ok) return out;
  const Vec<R, N> n = out.value.normal.template cast<R>();
  const Vec<R, N> d = direction.template cast<R>();
  const Vec<R, N> u = detail::unit_vector<R, N>(d);
  const R along = n.dot(u);
  if (!(along > R(0))) return out;
  // sigma grows with either support radius along n, at 1 / (n . u).
  out.a = detail::gradient_in<T>(detail::support_radius_gradient<R>(a, n), R(1) / along);
  out.b = detail::gradient_in<T>(detail::support_radius_gradient<R>(b, n), R(1) / along);
  const R largest = d.cwiseAbs().maxCoeff(), length = largest * (d / largest).norm();  // |d|, without overflow
  out.direction = (Vec<R, N>(n - along * u) * (-R(out.value.distance) / (along * length))).template cast<T>();
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                   \
  template ClosestApproachGradient<T, N> closest_approach_gradient<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&, \
                                                                         const VecArg<T, N>&, const Options&);        \
  template ContactFunction<T> perram_wertheim<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&,                   \
                                                    const Options&) noexcept;                                         \
  template ContactFunctionGradient<T, N> perram_wertheim_gradient<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&, \
                                                                        const Options&) noexcept;                     \
  template ClosestApproach<T, N> closest_approach<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&,               \
                                                        const VecArg<T, N>&, const Options&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
