// Signed distance within a margin: what an engine's contact generation asks of every pair its
// broad phase passes (a contact wherever two shapes come closer than a margin), answered
// without the distance's descent for the pairs that are farther apart.
#pragma once

#include <ellipsect/classify.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <cmath>
#include <limits>
#include <optional>

namespace ellipsect {

// signed_distance(a, b, options) where it may be at most `margin`; nullopt where the distance is
// proved larger than margin. b is a body or any shape with overlap(a, b) and
// signed_distance(a, b) (half_space.hpp, triangle.hpp, box.hpp, capsule.hpp).
//
// The proof: a scaled about its center by s = 1 + margin / (its smallest radius) holds a grown
// by a ball of radius margin, because its support along every unit direction n grows by
// (s - 1) rho(n) >= margin (rho(n) = |diag(r) A^T n| >= the smallest radius). s is padded by 8
// ulps against its own rounding. When that body does not overlap b (the exact overlap test,
// several times cheaper than the distance), the distance exceeds margin. A margin <= 0 tests a
// itself. Where the scaled radii would overflow the filter is skipped.
template <class T, int N, class Shape>
std::optional<Distance<T, N>> signed_distance_within(const Ellipsoid<T, N>& a, const Shape& b, T margin,
                                                     const Options& options = {}) {
  const T grow = margin > 0 ? (1 + margin / a.radii().minCoeff()) * (1 + 8 * std::numeric_limits<T>::epsilon()) : T(1);
  if (std::isfinite(grow * a.radii().maxCoeff())) {
    const bool may_touch = grow == 1 ? overlap(a, b, options)
                                     : overlap(Ellipsoid<T, N>::from_axes(a.center(), a.axes(), grow * a.radii()), b, options);
    if (!may_touch) return std::nullopt;
  }
  return signed_distance(a, b, options);
}

}  // namespace ellipsect
