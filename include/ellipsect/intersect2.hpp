// Boundary intersection points and overlap area of two ellipses.
//
// Math. In the reduced frame of classify (the sphere body S is the unit circle, the
// other ellipse O is axis-aligned with center k and semi-axes e), O's boundary is
// w(t) = k + (e_0 cos t, e_1 sin t), and the boundaries meet where h(t) = |w(t)| = 1. The
// critical points of h (the feet of the normals from S's center to O: the closest and
// farthest points of the secular equation, plus the two of its middle branch, which exist
// when S's center lies inside the evolute of O) split the parameter circle into arcs on
// which h is monotone; each arc whose ends lie on opposite sides of 1 holds exactly one
// transverse crossing, found by bracketed Newton, and a critical point with h within the
// tangency band of 1 is a tangent point. The overlap area is the polygon of the
// transverse crossings plus one circular or elliptic segment per arc of the intersection's
// boundary, (ab / 2)(delta - sin delta) for a parameter span delta, mapped back to the
// world by the determinant of the reduction (docs/distance.md).
//
// The tangency band is classify's (Options::tolerance, relative), and both functions
// decide with the same numbers as classify: a touching pair has exactly one tangent point,
// equal ellipses are reported as such, containment has no transverse crossing.
//
// Accuracy (tested against a 50-digit reference, tests/property/intersect2_property_test.cpp:
// quartic roots for the points, tanh-sinh quadrature for the area; random and adversarial
// pairs: aspect ratios to 1e4, near tangency, containment, equal bodies, scale 1e-6 and
// 1e6, nearly concentric pairs with center offsets 0, subnormal and 1e-300 .. 1e-8), with
// scale = largest radius of a + largest radius of b:
//   points  within 1e-12 * scale of both boundaries; a transverse crossing within
//           1e-12 * scale / sin(crossing angle) of the exact one; plus the rounding of their
//           coordinates (eps |point|), at any distance from the origin (tested to 1e6
//           sizes, tests/property/translation_property_test.cpp);
//   kinds   the number of transverse crossings is exact outside the tangency band;
//   area    absolute error <= 1e-12 * the smaller ellipse's area; always within [0, the
//           smaller ellipse's area]. Where the smaller ellipse lies within the tangency
//           band of the larger's boundary (radius ratios beyond about 1e12, untested
//           otherwise) the crossings are blurred by the band and only that bound holds.
// Swapping a and b gives the same points (listed in the new a's order) and the same area,
// bit for bit. Scaling both ellipses by 2^k multiplies the points by exactly 2^k and the
// area by 4^k (+inf beyond the largest double) (docs/method.md, section 7).
// float ellipses are computed in double and the results rounded.
#pragma once

#include <ellipsect/classify.hpp>
#include <ellipsect/gradient.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <array>
#include <string_view>

namespace ellipsect {

enum class CrossingKind {
  transverse,  // the boundaries cross
  tangent,     // the boundaries touch without crossing (within the tangency band)
};

enum class BoundaryStatus {
  points,  // the boundaries share exactly the `count` points listed (possibly none)
  equal,   // the ellipses are equal within the tangency band: every point is common
};

std::string_view to_string(CrossingKind k) noexcept;
std::string_view to_string(BoundaryStatus s) noexcept;

template <class T>
struct BoundaryIntersection {
  BoundaryStatus status = BoundaryStatus::points;
  // Number of common points, 0 to 4 (0 when equal).
  int count = 0;
  // World-frame points, the first `count` valid, in counter-clockwise order of a's
  // parametrization angle (a's center + axes diag(radii) (cos t, sin t), t in (-pi, pi]).
  std::array<Vec2<T>, 4> points;
  std::array<CrossingKind, 4> kinds{};
};
static_assert(detail::has_plain_layout<BoundaryIntersection<float>, BoundaryStatus, int, float[4][2], CrossingKind[4]> &&
              detail::has_plain_layout<BoundaryIntersection<double>, BoundaryStatus, int, double[4][2], CrossingKind[4]>);

template <class T>
BoundaryIntersection<T> intersect_boundaries(const Ellipse2<T>& a, const Ellipse2<T>& b,
                                             const Options& options = {}) noexcept;

template <class T>
struct OverlapArea {
  // Area of the intersection of the two closed ellipses, in world units squared: 0 when
  // separated or touching, the smaller ellipse's area under containment and when equal (in
  // the tolerance band the contained body may be the larger by a hair; the intersection is
  // never larger than either). An overlapping pair whose boundaries cross by less than the
  // reduced frame resolves (bodies within about eps of their radii of equal, as with
  // Options::tolerance = 0) has no transverse crossing: the smaller one's area where its
  // center lies inside the other, 0 where it does not.
  T area;
  // classify(a, b), which selects the configuration.
  Relation relation;
};
static_assert(detail::has_plain_layout<OverlapArea<float>, float, Relation> &&
              detail::has_plain_layout<OverlapArea<double>, double, Relation>);

template <class T>
OverlapArea<T> overlap_area(const Ellipse2<T>& a, const Ellipse2<T>& b, const Options& options = {}) noexcept;

// Intersection over union, overlap_area / (area(a) + area(b) - overlap_area), in [0, 1]:
// 0 when separated or touching, the ratio of the areas under containment (at most 1), exactly
// 1 when equal.
// Scale-free: computed on the pair rescaled by a power of two where overlap_area rescales,
// so it is finite at every scale the factories accept. Accuracy: that of the area.
template <class T>
T intersection_over_union(const Ellipse2<T>& a, const Ellipse2<T>& b, const Options& options = {}) noexcept;

// ---- Derivatives (gradient.hpp's parameters: center, counterclockwise angle, radii) -----
//
// The intersection's area changes as its boundary moves: for a parameter theta of body X,
//     d area / d theta = integral over the arcs of X's boundary inside the other body of
//                        (d x / d theta) . nu ds
// (nu the outward normal; Reynolds' transport theorem). With X's boundary
// x(phi) = c + A diag(r) (cos phi, sin phi), nu ds = A (r_1 cos phi, r_0 sin phi) dphi, so over
// an arc [f0, f1] (span d, mid angle m):
//     d/d center = A (2 r_1 cos m sin(d/2), 2 r_0 sin m sin(d/2)),
//     d/d r_0 = r_1 (d + cos(f0 + f1) sin d) / 2,   d/d r_1 = r_0 (d - cos(f0 + f1) sin d) / 2,
//     d/d angle = det(A) (r_0^2 - r_1^2) sin(f0 + f1) sin(d) / 2,
// from the transverse crossings the area is formed from (no second solve). Containment: the
// inner body's area derivatives, pi (r_1, r_0) by its radii, 0 for the rest; separated and
// touching: 0 (the area grows as the 3/2 power of the overlap). Not differentiable where the
// boundaries coincide (equal) or where a pair classified overlapping has fewer than two
// transverse crossings (the smaller body inside the tangency band, radius ratios beyond about
// 1e12): NaN there. intersection_over_union_gradient by the quotient rule,
// d IoU = (d I (U + I) - I (d area(a) + d area(b))) / U^2 with U the union's area.
// Accuracy (tests/property/gradient_property_test.cpp, against 50-digit central differences
// of the area by Gauss-Kronrod quadrature, the bodies moved in Real): each component within
// 1e-9 of its unit (the largest derivative by a center or a radius, but at least the smaller
// ellipse's largest radius for the area and its inverse for the IoU, as the crossings are
// known to 1e-12 of the sizes; times the pair's largest radius for the angles), on random
// pairs, aspect ratios to 1e4, containment, scale 1e-6 and 1e6, far from the origin.
template <class T>
struct OverlapAreaGradient {
  OverlapArea<T> value;     // overlap_area(a, b)
  BodyGradient<T, 2> a, b;  // of value.area
};
static_assert(detail::has_plain_layout<OverlapAreaGradient<float>, OverlapArea<float>, BodyGradient<float, 2>,
                                        BodyGradient<float, 2>> &&
              detail::has_plain_layout<OverlapAreaGradient<double>, OverlapArea<double>, BodyGradient<double, 2>,
                                        BodyGradient<double, 2>>);

template <class T>
OverlapAreaGradient<T> overlap_area_gradient(const Ellipse2<T>& a, const Ellipse2<T>& b,
                                             const Options& options = {}) noexcept;

template <class T>
struct IouGradient {
  T value;                  // intersection_over_union(a, b)
  Relation relation;        // classify(a, b)
  BodyGradient<T, 2> a, b;  // of value
};
static_assert(detail::has_plain_layout<IouGradient<float>, float, Relation, BodyGradient<float, 2>,
                                        BodyGradient<float, 2>> &&
              detail::has_plain_layout<IouGradient<double>, double, Relation, BodyGradient<double, 2>,
                                        BodyGradient<double, 2>>);

template <class T>
IouGradient<T> intersection_over_union_gradient(const Ellipse2<T>& a, const Ellipse2<T>& b,
                                                const Options& options = {}) noexcept;

}  // namespace ellipsect
