// The convex hull's exact test behind inscribed_ellipsoid's unbounded status
// (src/geometry/hull.cpp, beside hull_half_spaces).
#pragma once

#include <ellipsect/shapes.hpp>

#include <span>

namespace ellipsect::detail {

// Whether the origin lies strictly inside the convex hull of the points, exactly (the signs
// of orientation determinants); false for points of no area (2D) or volume (3D).
template <class T, int N>
bool surrounds_origin(std::span<const Vec<T, N>> points);

}  // namespace ellipsect::detail
