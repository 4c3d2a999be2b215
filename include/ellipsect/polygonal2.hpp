// Niemitalo's division-free 2D tests (O. Niemitalo, "Ellipse-circle and ellipse-ellipse
// collision detection"; derivations and measurements in docs/niemitalo.md).
//
// segment_circle: translate so the segment starts at the origin, multiply by the
//   conjugate of the segment's end (complex numbers), compare squared quantities.
//
// polygonal_overlap: the ellipse is sandwiched between an inscribed polygon (vertices on
//   the ellipse) and a circumscribed one; their edges form triangles that enclose the
//   ellipse's rim. Level 0 is the quadrilateral of two conjugate semi-diameters and its
//   enclosing parallelogram. A circle that meets the inscribed polygon collides; one that
//   meets no triangle does not; otherwise the one triangle it meets (there is never more
//   than one) is bisected: a new vertex on the ellipse, two smaller triangles. Each
//   iteration doubles the number of sides; after n iterations the polygon has 2^(n+2).
//   For two ellipses, b is first stretched into a circle (parallel axes: the document's
//   coordinate scaling; otherwise a rotation-stretch matrix, still division-free).
//
// circle_cover_overlap: the document's circle variant, for an ellipse and a circle: each
//   arc between neighbouring vertices is enclosed by a disk (center the chord's
//   midpoint, radius^2 the larger of chord^2 / 4 and the squared distance to the
//   triangle's outer corner) instead of a triangle; neighbouring disks overlap, so a
//   query may follow more than one arc (depth first, at most 2^(n+1) - 1 arcs).
//
// Arithmetic. Only +, -, * and comparisons on T run per query: no division, no square
// root, no trigonometry. The per-level coefficients (1 / (2 cos(pi / 2^(t+1))), ...) are
// tabulated once; inputs are scaled by an exact power of two (an exponent shift) so that
// squared quantities stay in range; float runs in float.
//
// Contract. Every result is collision, no_collision, undecided (max_iterations used up:
// never a guess) or invalid_input (a non-finite circle, a negative radius, or
// max_iterations outside [0, niemitalo_max_iterations]). In exact arithmetic collision and
// no_collision are always right, and undecided happens only when the bodies' signed gap g
// (distance apart, or minus the penetration depth) in the frame where the test runs (for
// two ellipses: after stretching b into a circle) is within the polygon's error:
//   |g| <= niemitalo_error_bound(s_max, n),  s_max the ellipse's major radius there.
// With R the circle's radius and s_min the ellipse's minor radius in that frame, the
// pair's Perram-Wertheim factor mu (scale both bodies by mu about their centers and they
// touch) then satisfies |mu - 1| <= |g| / (R + s_min); in world terms
//   ellipse-circle:   |mu - 1| <= bound(1, n) * major / (radius + minor),
//   two ellipses:     |mu - 1| <= bound(1, n) * r_a,max r_b,max / (r_b0 r_b1 + r_a,min r_b,min).
// The circle cover's band is wider on the outside: -bound <= g <= s_max sin(pi / 2^(n+2)).
//
// Accuracy (tested against the 50-digit reference, tests/property/niemitalo_property_test.cpp,
// on the scenario categories with aspect ratios to 1e4, near tangency, containment and
// scenes scaled by 1e-6 and 1e6, n = 0 .. 20): every undecided answer lies inside the band
// above, and a decided answer is wrong only within rounding of tangency,
// |mu - 1| <= 16 (n + 2) eps_T * (size of the test's frame) / (R + s_min). Measured: no
// wrong answer in double; in float up to |mu - 1| = 1.1e-5 (aspect ratio 1e4) and 2.9e-6
// (near tangent), where float rounding rather than the polygon limits the answer (n >= 8).
// Scaling a scene by a power of two gives the same verdict and iteration count, bit for bit.
#pragma once

#include <ellipsect/shapes.hpp>

#include <string_view>

namespace ellipsect {

enum class Verdict {
  collision,     // the closed bodies share a point
  no_collision,  // they do not
  undecided,     // max_iterations reached with the circle still inside the polygon's band
  invalid_input, // see each function
};

std::string_view to_string(Verdict v) noexcept;

// Largest accepted max_iterations (beyond about 26 the double coefficients are exactly
// 1/2 and the polygon stops improving).
inline constexpr int niemitalo_max_iterations = 30;

// Side of the directed line from a to b on which a point lies (left: counter-clockwise).
enum class Side { left, on_line, right };

std::string_view to_string(Side s) noexcept;

struct SegmentCircle {
  Verdict verdict;  // collision when the closed segment and the closed disk share a point
  Side side;        // side of the line a -> b on which the circle's center lies
};

// Closed segment [a, b] against the closed disk |x - center| <= radius; a == b is a point.
// invalid_input (side on_line) when an input is not finite or radius < 0.
template <class T>
SegmentCircle segment_circle(const Vec2<T>& a, const Vec2<T>& b, const Vec2<T>& center, T radius) noexcept;

struct PolygonalOverlap {
  Verdict verdict;
  // Bisections performed: 0 when the level-0 polygons decided; max_iterations when
  // undecided; for circle_cover_overlap the deepest level visited.
  int iterations;
};

// Ellipse against the disk |x - center| <= radius (radius >= 0).
template <class T>
PolygonalOverlap polygonal_overlap(const Ellipse2<T>& ellipse, const VecArg<T, 2>& center, T radius,
                                   int max_iterations = 10) noexcept;

// Two ellipses; b is stretched into a circle. Axes that are exactly parallel (equal
// columns up to sign and order) take the document's cheaper scaling route.
template <class T>
PolygonalOverlap polygonal_overlap(const Ellipse2<T>& a, const Ellipse2<T>& b, int max_iterations = 10) noexcept;

// The circle-cover variant, ellipse against a disk.
template <class T>
PolygonalOverlap circle_cover_overlap(const Ellipse2<T>& ellipse, const VecArg<T, 2>& center, T radius,
                                      int max_iterations = 10) noexcept;

// The document's bound: after n iterations every point of the inscribed and circumscribed
// polygons lies within 2^(0.303 - 2n) * major_radius of the ellipse. (Tested; the exact
// worst case is (1 / cos(pi / 2^(n+2)) - 1) * major_radius, about a quarter of it.)
template <class T>
T niemitalo_error_bound(T major_radius, int iterations) noexcept;

}  // namespace ellipsect
