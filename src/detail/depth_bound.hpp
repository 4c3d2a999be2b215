// A lower bound on the penetration depth that certifies a descent's minimum as the global one
// (docs/distance.md, "Penetration").
//
// The depth of two overlapping bodies is min over unit n of phi(n) = |B_1 n| + |B_2 n| - n . r
// (distance_gap.hpp): the depth of the point r in the Minkowski sum M of the centered bodies,
// whose support function is |B_1 n| + |B_2 n|. For any orthogonal Q the ellipsoid
// E = { C u : |u| <= 1 } with C^T = B_1 + Q B_2 has support |B_1 n + Q B_2 n|, at most that
// of M for every n, so E lies in M and the depth of r in E is at most the depth in M. E is
// one ellipsoid: its semi-axes and axes are the singular values and left singular vectors of
// C (one-sided Jacobi, reduce.hpp), and the depth of r in it is its closest boundary point
// from inside (the secular equation, secular.hpp), which is global.
//
// The bound equals phi(n) at a direction n where Q takes B_2 n to the direction of B_1 n.
// What is left of Q (a rotation or reflection of the directions orthogonal to B_1 n) is
// chosen so that, as n moves away, the unit vectors B_i n / |B_i n| turn alike (orthogonal
// Procrustes on their derivatives along the tangent plane): then |B_1 n + Q B_2 n| falls
// below |B_1 n| + |B_2 n| only slowly away from n, and at a global minimum of phi the bound
// usually reaches it (for two balls E = M exactly). Where the bound falls short (another
// minimum nearly as deep, or an E too thin near n), it certifies nothing, and the caller
// searches further.
#pragma once

#include "distance_gap.hpp"
#include "reduce.hpp"
#include "secular.hpp"

#include <limits>

namespace ellipsect::detail {

// The depth of r in E for the Q fitted at `at` (a direction with B_1 n, B_2 n != 0), or
// -infinity where r is not inside E (or where rounding left nothing finite).
template <class R, int N>
R depth_lower_bound(const GapBodies<R, N>& g, const GapAt<R, N>& at) noexcept {
  const Vec<R, N> a = at.w1 * at.inv1, b = at.w2 * at.inv2;  // B_1 n, B_2 n as unit vectors
  const TangentBasis<R, N> ta = tangent_basis<R, N>(a), tb = tangent_basis<R, N>(b);
  // The derivatives of the unit vectors along the tangent basis of n, in the planes
  // orthogonal to them: X for B_2 n (in tb), Y for B_1 n (in ta).
  TangentMat<R, N> x = tb.transpose() * g.b2 * at.q, y = ta.transpose() * g.b1 * at.q;
  x *= at.inv2;
  y *= at.inv1;
  TangentMat<R, N> turn;  // orthogonal, as close to taking x to y as can be
  if constexpr (N == 2) {
    turn(0, 0) = x(0, 0) * y(0, 0) >= R(0) ? R(1) : R(-1);
  } else {
    const TangentMat<R, N> m = y * x.transpose();  // maximize trace(turn^T m)
    const R rc = m(0, 0) + m(1, 1), rs = m(1, 0) - m(0, 1), fc = m(0, 0) - m(1, 1), fs = m(1, 0) + m(0, 1);
    const R rotation = rc * rc + rs * rs, reflection = fc * fc + fs * fs;
    if (rotation >= reflection) {
      const R h = sqrt(rotation), c = h > R(0) ? rc / h : R(1), s = h > R(0) ? rs / h : R(0);
      turn << c, -s, s, c;
    } else {
      const R h = sqrt(reflection), c = fc / h, s = fs / h;
      turn << c, s, s, -c;
    }
  }
  // Q = [a ta] diag(1, turn) [b tb]^T: Q b = a.
  const Mat<R, N> q = a * b.transpose() + ta * turn * tb.transpose();
  const Mat<R, N> c = (g.b1 + q * g.b2).transpose();
  Vec<R, N> sigma;
  Mat<R, N> u;
  left_singular<R, N>(c, sigma, u);
  const Vec<R, N> k = -(u.transpose() * g.r);  // E's center seen from r, in E's axes
  const R none = -std::numeric_limits<R>::infinity();
  if (!(sigma.minCoeff() > R(0)) || !(level_at_origin<R, N>(sigma, k) <= R(0))) return none;
  const R depth = closest_from_inside<R, N>(sigma, k).norm;
  return isfinite(depth) ? depth : none;
}

}  // namespace ellipsect::detail
