// 50-digit reference for a body against a half-space { x : n . (x - p) <= 0 } (header templates,
// never includes the library).
//
// Route, different from the library's (compensated double arithmetic on |diag(r) A^T n| and
// (s^2 - rho^2) / (s + rho), the contact time in closed form):
//   * the body is the one the library answers for: { c + A diag(r) u : |u| <= 1 } with the
//     axes A exactly as stored (not re-orthonormalized as in reference.hpp: a near-tangent
//     gap of 1e-12 would otherwise change with their last bits), P = A diag(r)^2 A^T and
//     M = P^-1 in Real; the normal is normalized in Real, and the support radius is
//     rho = sqrt(n^T P n);
//   * the lowest point y = c - P n / rho is verified against the Lagrange conditions of
//     min n . x on (x - c)^T M (x - c) = 1: on the quadric and with M (y - c) parallel to
//     -n, to 1e-30 (a violation throws);
//   * the gaps are L = n . (c - p) - rho and U = -n . (c - p) - rho, directly in Real;
//   * the first contact time is found by bisection in time on the sign of L(t), evaluated
//     afresh at each t from the moved center and plane point (no use of linearity).
#pragma once

#include "tests/reference/reference.hpp"

#include <Eigen/LU>

#include <stdexcept>
#include <string>

namespace ellipsect::reference {

template <int N>
struct HalfSpaceGaps {
  Real lower, upper, rho;
  RVec<N> lowest;  // the body's point deepest along -n
  RVec<N> normal;  // n / |n|
};

template <int N>
HalfSpaceGaps<N> half_space_gaps(const Body<N>& body, const DVec<N>& point, const DVec<N>& normal) {
  RMat<N> L;
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < N; ++k) L(i, k) = Real(body.axes(i, k)) * Real(body.radii(k));
  const RMat<N> P = L * L.transpose();
  const RMat<N> M = P.inverse();
  const RVec<N> center = to_real<N>(body.center);
  RVec<N> n = to_real<N>(normal);
  n /= sqrt(detail::dot<N>(n, n));
  HalfSpaceGaps<N> g;
  g.normal = n;
  const RVec<N> pn = detail::matvec<N>(P, n);
  g.rho = sqrt(detail::dot<N>(n, pn));
  const RVec<N> y = -pn / g.rho;
  g.lowest = center + y;
  const RVec<N> my = detail::matvec<N>(M, y);
  const Real on_quadric = abs(detail::dot<N>(y, my) - 1);
  const Real parallel = sqrt(detail::dot<N>(my, my)) - (-detail::dot<N>(my, n));  // |My| - (My . -n)
  if (on_quadric > Real(1e-30) || parallel > Real(1e-30) * sqrt(detail::dot<N>(my, my)))
    throw std::logic_error("half_space_gaps: the lowest point fails its Lagrange conditions (" +
                           on_quadric.str(3) + ", " + parallel.str(3) + ")");
  const Real s = detail::dot<N>(n, RVec<N>(center - to_real<N>(point)));
  g.lower = s - g.rho;
  g.upper = -s - g.rho;
  return g;
}

// The first time in [0, t_max] at which the body moving with velocity_a touches the
// half-space moving with velocity_b: 0 when they already meet (L(0) <= 0), +infinity when
// they do not meet in the window; to 1e-45 relative.
template <int N>
Real half_space_contact_time(const Body<N>& body, const DVec<N>& point, const DVec<N>& normal,
                             const DVec<N>& velocity_a, const DVec<N>& velocity_b, double t_max) {
  const RVec<N> va = to_real<N>(velocity_a), vb = to_real<N>(velocity_b);
  const HalfSpaceGaps<N> g0 = half_space_gaps<N>(body, point, normal);
  auto lower_at = [&](const Real& t) {
    // The moved center less the moved plane point, c - p + t (va - vb), in Real.
    const RVec<N> offset = RVec<N>(to_real<N>(body.center) - to_real<N>(point)) + t * RVec<N>(va - vb);
    return detail::dot<N>(g0.normal, offset) - g0.rho;
  };
  if (lower_at(Real(0)) <= 0) return Real(0);
  Real hi = Real(t_max);
  if (!std::isfinite(t_max)) {
    hi = Real(1);
    for (int k = 0; k < 4000 && lower_at(hi) > 0; ++k) hi *= 2;
  }
  if (lower_at(hi) > 0) return detail::infinity();
  Real lo = 0;
  for (int k = 0; k < 20000 && hi - lo > Real(1e-47) * hi; ++k) {
    const Real mid = (lo + hi) / 2;
    (lower_at(mid) > 0 ? lo : hi) = mid;
  }
  return hi;
}

// The functions the tests and benchmarks call, for N = 2 and 3: compiled once, in
// half_space_reference.cpp (the library ellipsect_reference), not in every program that includes
// this header.
#define ELLIPSECT_HALF_SPACE_REFERENCE_FUNCTIONS(extern_, N) \
  extern_ template HalfSpaceGaps<N> half_space_gaps<N>(const Body<N>&, const DVec<N>&, const DVec<N>&); \
  extern_ template Real half_space_contact_time<N>(const Body<N>&, const DVec<N>&, const DVec<N>&, const DVec<N>&, \
                                                   const DVec<N>&, double);
ELLIPSECT_HALF_SPACE_REFERENCE_FUNCTIONS(extern, 2)
ELLIPSECT_HALF_SPACE_REFERENCE_FUNCTIONS(extern, 3)

}  // namespace ellipsect::reference
