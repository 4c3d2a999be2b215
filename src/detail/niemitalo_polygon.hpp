// The per-level coefficients of Niemitalo's polygon bisection (docs/niemitalo.md).
//
// The ellipse is the image A z of the unit circle |z| = 1 under a linear map A (for an
// axis-aligned ellipse A = diag(w, h); in general the columns of A are two conjugate
// semi-diameters). Level t has 4 * 2^t vertices A z_k, z_k equally spaced. For two
// neighbours c0, c2 of level t - 1 (parameter angle pi / 2^t apart):
//
//   c1 = inner(t) (c0 + c2),  inner(t) = 1 / (2 cos(pi / 2^(t+1)))      the new vertex,
//                                                                        on the ellipse;
//   V  = outer(t - 1) (c0 + c2),  outer(t) = 1 / (2 cos^2(pi / 2^(t+2))) the corner where
//                                 the tangents at c0 and c2 meet (outer(0) = 1: V = c0 + c2).
//
// Both are linear in the vertices, so they hold for any A (midpoints and tangents are
// affine notions). The tables are computed once, in long double, and rounded to T; the
// iteration itself then needs only multiplications and additions.
//
// The band of level n (h = pi / 2^(n+2), half the angle between neighbours): in the
// circle's frame the inscribed polygon reaches in to cos h, the triangles out to 1 / cos h,
// the circle cover's disks (center cos h, radius sin h) out to cos h + sin h <= 1 + sin h;
// a linear map stretches these by at most the major radius:
//   below(n) = 1 - cos h = 2 sin^2(h / 2),  above(n) = 1 / cos h - 1 = below(n) / cos h,
//   cover_above(n) = sin h.
#pragma once

#include <array>
#include <cmath>
#include "math.hpp"

namespace ellipsect::detail {

// Largest level with a table entry; the public cap (niemitalo_max_level) equals it.
inline constexpr int niemitalo_levels = 30;

template <class T>
struct NiemitaloCoefficients {
  std::array<T, niemitalo_levels + 1> inner{};  // inner[0] is unused (no level -1)
  std::array<T, niemitalo_levels + 1> outer{};
  std::array<T, niemitalo_levels + 1> below{};        // the band at level n, per unit of major radius
  std::array<T, niemitalo_levels + 1> above{};
  std::array<T, niemitalo_levels + 1> cover_above{};
};

template <class T>
const NiemitaloCoefficients<T>& niemitalo_coefficients() noexcept {
  static const NiemitaloCoefficients<T> table = [] {
    NiemitaloCoefficients<T> k;
    const long double pi = 3.141592653589793238462643383279502884L;
    for (int t = 0; t <= niemitalo_levels; ++t) {
      const long double half = pi / ldexp(1.0L, t + 2);  // half the angle between level-t neighbours
      k.outer[t] = static_cast<T>(0.5L / (cos(half) * cos(half)));
      if (t > 0) k.inner[t] = static_cast<T>(0.5L / cos(2 * half));
      const long double s = sin(half / 2);
      k.below[t] = static_cast<T>(2 * s * s);
      k.above[t] = static_cast<T>(2 * s * s / cos(half));
      k.cover_above[t] = static_cast<T>(sin(half));
    }
    return k;
  }();
  return table;
}

}  // namespace ellipsect::detail
