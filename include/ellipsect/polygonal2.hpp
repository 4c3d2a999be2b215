// Niemitalo's polygonal 2D tests (O. Niemitalo, "Ellipse-circle and ellipse-ellipse
// collision detection"; derivations and measurements in docs/niemitalo.md).
//
// segment_circle: translate so the segment starts at the origin, multiply by the
//   conjugate of the segment's end (complex numbers), compare squared quantities.
//
// polygonal_overlap: the ellipse is sandwiched between an inscribed polygon (vertices on
//   the ellipse) and a circumscribed one; their edges form triangles that enclose the
//   ellipse's rim. Level 0 is the rhombus of the semi-axes and its enclosing rectangle.
//   A circle that meets the inscribed polygon collides; one that
//   meets no triangle does not; otherwise the one triangle it meets (there is never more
//   than one) is bisected: a new vertex on the ellipse, two smaller triangles. Each
//   level doubles the number of sides; at level n the polygon has 2^(n+2).
//   For two ellipses, b is first stretched into a circle (parallel axes: the document's
//   coordinate scaling; otherwise a rotation-stretch matrix, after which the stretched
//   ellipse's own axes are found: two square roots for its semi-axes and its direction,
//   and two divisions).
//
// circle_cover_overlap: the document's circle variant, for an ellipse and a circle: each
//   arc between neighbouring vertices is enclosed by a disk (center the chord's
//   midpoint, radius^2 the larger of chord^2 / 4 and the squared distance to the
//   triangle's outer corner) instead of a triangle; neighbouring disks overlap, so a
//   query may follow more than one arc (depth first, at most 2^(n+1) - 1 bisections).
//
// Arithmetic. Only +, -, * and comparisons on T run per level: no division, no square
// root, no trigonometry (once per query, the non-parallel ellipse-ellipse test finds the
// stretched ellipse's axes as above). The per-level coefficients (1 / (2 cos(pi / 2^(t+1))), ...) are
// tabulated once; inputs are scaled by an exact power of two (an exponent shift) so that
// squared and fourth-power quantities stay in range; float runs in float.
//
// Levels and iterations (one meaning everywhere). Level t of the sandwich has 2^(t+2)
// sides; `max_level` caps the level. `level` in a result is the deepest level examined
// (undecided => level == max_level); `iterations` is the number of bisections performed
// (new vertices computed): equal to `level` for polygonal_overlap, which follows one
// triangle, and up to 2^(max_level+1) - 1 for circle_cover_overlap, which may follow several.
//
// The band. Every result carries [gap_lo, gap_hi], a certified range of the signed gap g
// between the closed bodies in world units (distance apart, or minus the penetration
// depth: the signed distance of distance.hpp): collision [-inf, rho], no_collision
// [-rho, +inf], undecided the polygon's band at level n = max_level,
//   -(1 - cos h) major - rho  <=  g  <=  (1 / cos h - 1) major + rho,      h = pi / 2^(n+2)
// (the circle cover: sin h major + rho on the right), with `major` the major radius of the
// ellipse (for two ellipses: of a, the one not stretched; incidence is affine-invariant, so
// the stretch does not enter) and rho the rounding allowance
//   rho = 16 (n + 2) eps_T (|dx| + |dy| + major + R),  (dx, dy) the offset between the
//   centers, R the circle's radius (for two ellipses, b's major radius), n = level
//   (measured: g never needed more than 0.3% of rho, in float; nothing in double).
// In exact arithmetic rho = 0 and collision / no_collision are always right. For
// polygonal_overlap both sides of the undecided band are within
// niemitalo_error_bound(major, n) + rho of 0.
//
// Contract. Every result is collision, no_collision, undecided (max_level used up: never a
// guess) or invalid_input (max_level outside [0, niemitalo_max_level]; band NaN). Circles
// are validated once, by make_circle. An ellipse whose major radius is at most eps_T of
// the scene's size (the largest of the offset's coordinates, the radii) lies within rho of
// its center, and polygonal_overlap and circle_cover_overlap test it as that point (level 0).
//
// Accuracy (tested against the 50-digit reference, tests/property/niemitalo_property_test.cpp,
// on the scenario categories with aspect ratios to 1e4, near tangency, containment and
// scenes scaled by 1e-6 and 1e6, n = 0 .. 20, double and float): the reference's signed
// distance lies in [gap_lo, gap_hi] for every answer. A decided answer is therefore wrong
// only within rho of tangency. Measured: no wrong answer in double; in float wrong answers
// only for gaps below float resolution (near tangent, aspect ratio 1e4), where float
// rounding rather than the polygon limits the answer (n >= 8). In terms of the pair's
// Perram-Wertheim factor mu, an undecided answer means
//   ellipse-circle:   |mu - 1| <= bound(1, n) * major / (radius + minor),
//   two ellipses:     |mu - 1| <= bound(1, n) * r_a,max r_b,max / (r_b0 r_b1 + r_a,min r_b,min).
// Scaling a scene by a power of two gives the same verdict, level and iteration count, bit
// for bit, and the band scaled by it.
//
// segment_circle: the verdict is exact (that of the closed sets given) when every sum and
// product of the test is exact in T, e.g. for integer multiples of one power of two 2^m
// with |coordinates|, radius <= 2^(m+11) in double, 2^(m+4) in float. Otherwise it is
// exact except within
//   |dist(center, segment) - radius| <= 8 eps_T (|b - a| + |center - a| + radius),
// and `side` is exact except for a center within 2 eps_T |center - a| of the line. Any
// finite inputs are valid (no overflow or underflow: the segment, and the circle about a,
// are each rescaled by an exact power of two).
#pragma once

#include <ellipsect/shapes.hpp>

#include <limits>
#include <string_view>
#include <vector>

namespace ellipsect {

enum class Verdict {
  collision,     // the closed bodies share a point
  no_collision,  // they do not
  undecided,     // max_level reached with the circle still inside the polygon's band
  invalid_input, // see each function
};

std::string_view to_string(Verdict v) noexcept;

// Largest accepted max_level (beyond about 26 the double coefficients are exactly 1/2 and
// the polygon stops improving).
inline constexpr int niemitalo_max_level = 30;

template <class T>
class Circle;

// The closed disk |x - center| <= radius; radius 0 is a point. Throws InputError naming
// "center[i]" (not finite) or "radius" (not finite, or negative).
template <class T>
Circle<T> make_circle(const VecArg<T, 2>& center, T radius);

// The circle of every Niemitalo test (segment_circle, polygonal_overlap,
// circle_cover_overlap): a validated value, like Ellipse2.
template <class T>
class Circle {
public:
  using Scalar = T;

  const Vec2<T>& center() const noexcept { return center_; }
  T radius() const noexcept { return radius_; }

  // The same disk as an Ellipse2 (make_ball), for the exact queries (classify, overlap,
  // distance, contact, ...). Throws InputError("radius") for radius 0: an Ellipse2 has
  // positive radii.
  Ellipse2<T> ellipse() const;

private:
  Circle(const Vec2<T>& center, T radius) noexcept : center_(center), radius_(radius) {}
  friend Circle make_circle<T>(const VecArg<T, 2>&, T);

  Vec2<T> center_;
  T radius_;
};

static_assert(detail::has_plain_layout<Circle<float>, float[2], float> &&
              detail::has_plain_layout<Circle<double>, double[2], double>);

// Side of the directed line from a to b on which a point lies (left: counter-clockwise).
enum class Side { left, on_line, right };

std::string_view to_string(Side s) noexcept;

struct SegmentCircle {
  Verdict verdict;  // collision when the closed segment and the closed disk share a point
  Side side;        // side of the line a -> b on which the circle's center lies
};

// Closed segment [a, b] against the closed disk; a == b is a point. invalid_input (side
// on_line) when a or b is not finite. Exactness: see the top of this file.
template <class T>
SegmentCircle segment_circle(const VecArg<T, 2>& a, const VecArg<T, 2>& b, const Circle<T>& circle) noexcept;

template <class T>
struct PolygonalOverlap {
  Verdict verdict = Verdict::invalid_input;
  int level = 0;       // deepest level examined (0: the level-0 polygons decided); max_level when undecided
  int iterations = 0;  // bisections performed (== level for polygonal_overlap)
  T gap_lo = std::numeric_limits<T>::quiet_NaN();  // the signed gap g, world units: gap_lo <= g <= gap_hi
  T gap_hi = std::numeric_limits<T>::quiet_NaN();  // (+-inf on the open side of a decided answer)
};

static_assert(detail::has_plain_layout<PolygonalOverlap<float>, Verdict, int, int, float, float> &&
              detail::has_plain_layout<PolygonalOverlap<double>, Verdict, int, int, double, double>);

// Ellipse against a circle.
template <class T>
PolygonalOverlap<T> polygonal_overlap(const Ellipse2<T>& ellipse, const Circle<T>& circle, int max_level = 10) noexcept;

// Two ellipses; b is stretched into a circle. Axes that are exactly parallel (equal
// columns up to sign and order) take the document's cheaper scaling route. The band's
// `major` is a's.
template <class T>
PolygonalOverlap<T> polygonal_overlap(const Ellipse2<T>& a, const Ellipse2<T>& b, int max_level = 10) noexcept;

// The circle-cover variant, ellipse against a circle.
template <class T>
PolygonalOverlap<T> circle_cover_overlap(const Ellipse2<T>& ellipse, const Circle<T>& circle,
                                         int max_level = 10) noexcept;

// The document's bound: after n levels every point of the inscribed and circumscribed
// polygons lies within 2^(0.303 - 2n) * major_radius of the ellipse (the exact worst case,
// (1 / cos(pi / 2^(n+2)) - 1) * major_radius, is about a quarter of it). Hence an
// undecided answer's band lies within +-(bound + rho) (see the top of this file).
template <class T>
T niemitalo_error_bound(T major_radius, int level) noexcept;

// The same for the ellipse of polygonal_overlap / circle_cover_overlap (for two ellipses:
// a, the first argument), in world units.
template <class T>
T niemitalo_error_bound(const Ellipse2<T>& ellipse, int level) noexcept;

// The sandwich of one level, for drawing and inspection: the polygons that
// polygonal_overlap builds for this ellipse (for two ellipses with parallel axes: a's, which
// the stretch maps to the test's frame; with other axes the test builds the polygons of the
// stretched ellipse's own axes, which are a's polygons of the same level at another
// starting parameter, with the same bounds), computed with the same coefficients, world
// frame. The tests bisect only the triangles the circle meets; these are all of them.
template <class T>
struct NiemitaloPolygons {
  // 2^(level+2) vertices on the ellipse (to rounding), in the order of the parametrization
  // center + axes diag(radii) (cos t, sin t), t increasing from 0.
  std::vector<Vec2<T>> inscribed;
  // As many corners: circumscribed[i] is where the tangents at inscribed[i] and
  // inscribed[i + 1] (cyclically) meet, the outer corner of the triangle over that arc.
  std::vector<Vec2<T>> circumscribed;
};

// Largest level niemitalo_polygons accepts (2^18 vertices per polygon).
inline constexpr int niemitalo_polygons_max_level = 16;

// Throws InputError("level") outside [0, niemitalo_polygons_max_level].
template <class T>
NiemitaloPolygons<T> niemitalo_polygons(const Ellipse2<T>& ellipse, int level);

}  // namespace ellipsect
