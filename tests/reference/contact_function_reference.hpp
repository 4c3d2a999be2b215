// Independent high-precision REFERENCE for the Perram-Wertheim contact function and the
// distance of closest approach (header templates; builds on reference.hpp, N = 2 or 3).
//
// Routes, in `Real` (about 50 digits), chosen to differ from the library's (reduced frame,
// Newton on F') and from reference.hpp's pw() (Newton on F'):
//
//   * F(A, B) = max over lambda in [0, 1] of lambda (1 - lambda) r^T C(lambda)^-1 r,
//     C = (1 - lambda) Ma^-1 + lambda Mb^-1, by golden-section search on the defining formula
//     in the WORLD frame (C factored by LDL^T at each point). F is strictly concave, so the
//     search keeps the maximizer bracketed; it stops at a bracket of 1e-32. It compares
//     values of F, which is flat at its maximum, so lambda is good to about the square root
//     of Real's precision (measured: 4e-26) and F to rounding.
//   * the distance of closest approach sigma along a unit direction u: b's center at
//     ca + t u, and h(t) = -1 while ca lies in b, else (min over b's boundary of sqrt(q_a)) - 1,
//     the gauge of a at b's nearest point (reference.hpp's extrema of a quadratic on the sphere:
//     Jacobi eigenvectors and a secular equation, no F). The overlap test h(t) <= 0 holds
//     exactly on [0, sigma], and h is convex (the gauge distance from a's center to a
//     translating convex set), so its root sigma is found by the Illinois variant of regula
//     falsi, from [0, (largest radius of a + of b) * 1.01].
#pragma once

#include "reference.hpp"

#include <cmath>

namespace ellipsect::reference {

template <int N> struct ContactFunctionRef {
  Real f;       // F(A, B) (0 when the centers coincide)
  Real lambda;  // its maximizer, to about 1e-25
};

// The same for bodies in Real (their P and centers).
template <int N> ContactFunctionRef<N> contact_function(const detail::RBody<N>& ra, const detail::RBody<N>& rb) {
  const RVec<N> r = rb.c - ra.c;
  auto F = [&](const Real& l) {
    RMat<N> C;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) C(i, j) = (1 - l) * ra.P(i, j) + l * rb.P(i, j);
    detail::Ldlt<N> ldlt;
    ldlt.compute(C);
    return l * (1 - l) * detail::dot<N>(r, ldlt.solve(r));
  };
  if (detail::is_zero<N>(r)) return {Real(0), Real(0.5)};
  static const Real g = (sqrt(Real(5)) - 1) / 2, stop("1e-32");
  Real lo = 0, hi = 1;
  Real x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  Real f1 = F(x1), f2 = F(x2);
  while (hi - lo > stop) {
    if (f1 < f2) {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = F(x2);
    } else {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = F(x1);
    }
  }
  const Real l = (lo + hi) / 2;
  return {F(l), l};
}

template <int N> ContactFunctionRef<N> contact_function(const Body<N>& a, const Body<N>& b) {
  return contact_function<N>(detail::make_rbody<N>(a, "a"), detail::make_rbody<N>(b, "b"));
}

// sigma for the direction u (any nonzero length; normalized in Real).
template <int N> Real closest_approach(const Body<N>& a, const Body<N>& b, const DVec<N>& u) {
  const detail::RBody<N> ra = detail::make_rbody<N>(a, "a"), rb = detail::make_rbody<N>(b, "b");
  RVec<N> dir = to_real<N>(u);
  dir /= sqrt(detail::dot<N>(dir, dir));
  auto h = [&](const Real& t) {
    detail::RBody<N> bt = rb;
    bt.c = ra.c + dir * t;
    const RVec<N> d = ra.c - bt.c;
    if (detail::dot<N>(d, detail::matvec<N>(bt.M, d)) <= 1) return Real(-1);
    return detail::metric_range_impl<N>(ra, bt).min - 1;
  };
  Real lo = 0, hi = (ra.rmax + rb.rmax) * Real(1.01);
  Real f_lo = -1, f_hi = h(hi);
  int side = 0;
  static const Real stop("1e-45");
  for (int it = 0; it < 400 && hi - lo > stop * hi; ++it) {
    const Real t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    const Real ft = h(t);
    if (ft > 0) {
      hi = t;
      f_hi = ft;
      if (side == 1) f_lo /= 2;
      side = 1;
    } else if (ft < 0) {
      lo = t;
      f_lo = ft;
      if (side == -1) f_hi /= 2;
      side = -1;
    } else {
      return t;
    }
    if (abs(ft) < stop) return t;
  }
  return (lo + hi) / 2;
}

// The functions the tests and benchmarks call, for N = 2 and 3: compiled once, in
// contact_function_reference.cpp (the library ellipsect_reference), not in every program that includes
// this header.
#define ELLIPSECT_CONTACT_FUNCTION_REFERENCE_FUNCTIONS(extern_, N) \
  extern_ template ContactFunctionRef<N> contact_function<N>(const Body<N>&, const Body<N>&); \
  extern_ template ContactFunctionRef<N> contact_function<N>(const detail::RBody<N>&, const detail::RBody<N>&); \
  extern_ template Real closest_approach<N>(const Body<N>&, const Body<N>&, const DVec<N>&);
ELLIPSECT_CONTACT_FUNCTION_REFERENCE_FUNCTIONS(extern, 2)
ELLIPSECT_CONTACT_FUNCTION_REFERENCE_FUNCTIONS(extern, 3)

}  // namespace ellipsect::reference
