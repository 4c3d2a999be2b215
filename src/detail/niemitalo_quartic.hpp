// A careful closed form for the closest point of an ellipse to an outside point.
//
// Ellipse x^2 / a^2 + y^2 / b^2 = 1 (a >= b), point (c, d) with c, d >= 0 outside it.
// The Lagrange condition gives the closest point (a^2 c / (a^2 + t), b^2 d / (b^2 + t))
// with t > -b^2 the unique root of (a c / (a^2 + t))^2 + (b d / (b^2 + t))^2 = 1, i.e. the
// largest real root of a quartic. With t = a^2 tau, beta = b^2 / a^2, C = c / a,
// D = b d / a^2, and sigma = tau + (1 + beta) / 2, delta = (1 - beta) / 2:
//
//   (sigma^2 - delta^2)^2 = C^2 (sigma - delta)^2 + D^2 (sigma + delta)^2.
//
// Ferrari: add 2 y (sigma^2 - delta^2) + y^2 to both sides; the right side,
// (S + 2y) sigma^2 - 2 delta (C^2 - D^2) sigma + S delta^2 - 2 y delta^2 + y^2 with
// S = C^2 + D^2, is a perfect square (w sigma - z)^2 when
//
//   2 y^3 + (S - 4 delta^2) y^2 + 4 delta^2 C^2 D^2 = 0        (no linear term),
//
// w = sqrt(S + 2y), z = delta (C^2 - D^2) / w. Then sigma^2 - delta^2 + y = +-(w sigma - z):
// two quadratics whose largest real root is sigma. We take the largest real root y of
// the resolvent (trigonometric form for three real roots, Cardano otherwise, two Newton
// steps), so w is as far from 0 as possible, and solve each quadratic in its
// cancellation-free form.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include "math.hpp"

namespace ellipsect::detail {

// Largest real root of y^3 + a2 y^2 + a0 = 0.
template <class R>
R resolvent_largest_root(R a2, R a0) noexcept {
  const R shift = a2 / 3;
  const R p = -a2 * shift;                         // x^3 + p x + q = 0, y = x - a2 / 3
  const R q = 2 * shift * shift * shift + a0;
  const R disc = q * q / 4 + p * p * p / 27;
  R x;
  if (p == R(0)) {
    x = cbrt(-q);
  } else if (disc <= R(0)) {                       // three real roots
    const R m = sqrt(-p / 3);
    const R cos3 = std::clamp(-q / (2 * m * m * m), R(-1), R(1));
    x = 2 * m * cos(acos(cos3) / 3);
  } else {                                         // one real root
    const R big = -copysign(cbrt(abs(q) / 2 + sqrt(disc)), q);
    x = big != R(0) ? big - p / (3 * big) : R(0);
  }
  R y = x - shift;
  for (int i = 0; i < 2; ++i) {  // Newton from the closed form, against its rounding
    const R g = (y + a2) * y * y + a0;
    const R dg = (3 * y + 2 * a2) * y;
    if (dg == R(0)) break;
    y -= g / dg;
  }
  return y;
}

// tau = t / a^2 for the closest point, from beta = (b / a)^2 in (0, 1], C = c / a >= 0,
// D = b d / a^2 >= 0 (the point outside: C^2 + (D / beta)^2 > 1).
template <class R>
R secular_quartic_root(R beta, R C, R D) noexcept {
  const R delta = (1 - beta) / 2;
  const R C2 = C * C, D2 = D * D, S = C2 + D2;
  const R d2 = delta * delta;
  const R y = resolvent_largest_root<R>((S - 4 * d2) / 2, 2 * d2 * C2 * D2);
  const R w2 = std::max(S + 2 * y, R(0));
  const R w = sqrt(w2);
  const R cross = delta * (C2 - D2);
  // z^2 = y^2 - 2 delta^2 y + S delta^2; from the division while w is not small.
  const R z = w2 >= S / 4 ? cross / w : copysign(sqrt(std::max(y * y - 2 * d2 * y + S * d2, R(0))), cross);
  const R k1 = y - d2 + z;  // sigma^2 - w sigma + k1 = 0
  const R k2 = y - d2 - z;  // sigma^2 + w sigma + k2 = 0
  const R disc1 = w2 - 4 * k1, disc2 = w2 - 4 * k2;
  R sigma = -std::numeric_limits<R>::infinity();
  if (disc1 >= R(0)) sigma = (w + sqrt(disc1)) / 2;
  if (disc2 >= R(0)) {
    const R den = w + sqrt(disc2);
    sigma = std::max(sigma, den > R(0) ? -2 * k2 / den : R(0));
  }
  if (!(sigma > -std::numeric_limits<R>::infinity()))  // rounding made both slightly negative
    sigma = disc1 >= disc2 ? w / 2 : -w / 2;
  return sigma - (1 - delta);
}

}  // namespace ellipsect::detail
