// Separation distance, closest points and penetration depth of two bodies.
//
// Math. With r = center(b) - center(a) and rho_X(n) = sqrt(n^T M_X^-1 n) the support radius
// of body X about its center in the unit direction n, the support gap
//
//     g(n) = n . r - rho_a(n) - rho_b(n)
//
// is the width of the slab between the tangent plane of a with outward normal n and the
// tangent plane of b with outward normal -n. Its maximum over unit n is the signed
// distance of the two convex bodies: the separation distance when they are apart, and
// minus the penetration depth (the length of the smallest translation that separates
// them) when they overlap. At the maximizing n the witness points are the support points
//     point_a = center(a) + M_a^-1 n / rho_a(n),   point_b = center(b) - M_b^-1 n / rho_b(n),
// and point_b - point_a = distance * normal with normal = n, in both cases.
//
// Method (docs/distance.md): trust-region Newton on the sphere of directions. The status
// is classify's (certified far from touching by the Perram-Wertheim test or by a converged
// gap above the tangency band, otherwise decided in classify's reduced frame; at
// Options::tolerance = 0 classify's exact relation: touching only for bodies that touch
// exactly). Separated
// and touching bodies need one descent, started in {g > 0}: g is concave and positively
// homogeneous, so its maximum on that cone is unique. Penetration depth is not a convex
// problem (g can have several local maxima): the first descent's answer stands where the
// depth inside an ellipsoid within the bodies' Minkowski sum, fitted at that answer, proves
// it global (docs/distance.md); otherwise overlapping bodies also start from the best
// directions sampled on both bodies' Gauss maps, and the deepest descent wins.
//
// A trust-region step rejected because it crossed a kink of g (the support radius of a thin
// body turns sharply where n is orthogonal to its long axes) is cut at the kink.
//
// Accuracy (tested against a 50-digit reference, tests/property/distance_property_test.cpp,
// on random and adversarial pairs: aspect ratios to 1e4, near tangency, deep overlap,
// containment and internal tangency, equal bodies, scale 1e-6 and 1e6, bodies 1e4 sizes
// apart; the distance and status also at aspect ratios 1e6 to 1e8), with
// scale = largest radius of a + largest radius of b + |distance|:
//   distance     absolute error <= 1e-12 * scale (separated, touching and overlapping;
//                aspect ratios to 1e8);
//   point_a/_b   within 1e-12 * scale of the boundary of a / b, and of the support points
//                of `normal`; within 1e-10 * scale of the exact witness points where the
//                optimum is unique; plus the rounding of their coordinates (eps |point|),
//                at any distance from the origin (tested to 1e6 sizes,
//                tests/property/translation_property_test.cpp);
//   normal       parallel to the outward normal of a at point_a and to the inward normal
//                of b at point_b, to 1e-12 * scale / (smallest radius of curvature) rad.
// The status equals classify's (separated, touching, overlapping for all other relations).
// Swapping two distinct bodies gives the same distance, swapped points and the negated
// normal, bit for bit. Scaling both bodies by 2^k (|k| <= 1000 tested) multiplies the distance
// and the points by exactly 2^k, the status and normal unchanged (docs/method.md, section 7),
// except where a nonzero axis entry, or a nonzero center coordinate relative to the bodies'
// size, is below about 2^-300 (1e-90): products of those underflow differently at another
// scale, and the last bits of the results can change.
// float bodies are computed in double and the results rounded (tested to 1e-6 *
// scale).
#pragma once

#include <ellipsect/gradient.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <string_view>

namespace ellipsect {

enum class DistanceStatus {
  separated,         // gap larger than the tangency band: distance >= +0 (see Distance)
  touching,          // within Options::tolerance of touching (the band of classify)
  overlapping,       // interiors intersect (includes containment and equal bodies)
  did_not_converge,  // Options::max_distance_iterations evaluations in a descent without converging
                     // (not seen on the tested pairs with the default cap). The fields are
                     // finite and certified: see Distance.
};

std::string_view to_string(DistanceStatus s) noexcept;

template <class T, int N>
struct Distance {
  DistanceStatus status = DistanceStatus::did_not_converge;
  // Signed distance: the separation distance when separated (>= +0: a gap below the stated
  // accuracy may round to 0), minus the penetration depth when overlapping (<= 0;
  // distance() reports 0 there), within the rounding of 0 when touching (either sign).
  T distance;
  // Witness points, world frame: on the boundary of a and of b; point_b - point_a =
  // distance * normal (but see did_not_converge below). NaN for distance() on overlapping
  // bodies.
  Vec<T, N> point_a;
  Vec<T, N> point_b;
  // Unit normal, world frame: outward from a at point_a, pointing from a towards b when
  // separated. Translating b by -distance * normal (a pure push along the normal, of
  // length equal to the depth when overlapping) makes the bodies touch. NaN where the points are.
  Vec<T, N> normal;
  // did_not_converge: the fields hold the best iterate n, and are bounds, not estimates:
  // normal = n (unit), point_a and point_b the support points of a along n and of b along
  // -n (on the boundaries), and distance = g(n) less a bound on its rounding, rounded down:
  // at most the true signed distance. When the bodies are apart |point_b - point_a| is at
  // least the true distance (to the rounding of the points), so it lies between the two.
  // point_b - point_a = distance * normal does not hold then.
  //
  // Evaluations of the support gap on the direction (Newton and cut steps), summed over
  // all starts.
  int iterations = 0;
};
static_assert(
    detail::has_plain_layout<Distance<float, 2>, DistanceStatus, float, float[2], float[2], float[2], int> &&
    detail::has_plain_layout<Distance<double, 3>, DistanceStatus, double, double[3], double[3], double[3], int>);

// Separation distance and closest points. Overlapping bodies: status overlapping,
// distance 0, points and normal NaN (no penetration is computed; see signed_distance).
template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options = {}) noexcept;

// Signed distance: as distance() for separated and touching bodies; for overlapping ones
// the penetration depth as a negative distance, with its witness points and normal.
template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                               const Options& options = {}) noexcept;

// The same, started from `hint`, a direction from a towards b (the normal of an earlier
// answer for a nearby pair: a simulation's last step, an advancement's last distance). The
// answer meets the same claims as without it; only the cost changes: a hint near the answer
// settles a separated pair, or a penetration that the depth bound proves global
// (docs/distance.md), by its descent alone, without the cold start; any other hint (zero,
// not finite, far off, or a pair within the band) costs that descent more.
template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options,
                        const VecArg<T, N>& hint) noexcept;
template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options,
                               const VecArg<T, N>& hint) noexcept;

// ---- Gradient (gradient.hpp's parameters) ---------------------------------------------
//
// signed_distance(a, b) and the derivatives of its distance d. By the envelope theorem, with
// n the returned normal (the maximizer of the support gap g) and rho_X, p_X = M_X^-1 n / rho_X(n)
// body X's support radius and support point less its center along n:
//     dd/d center(b) = n,   dd/d center(a) = -n,
//     dd/d radii(X)_i = -r_i (A_X^T n)_i^2 / rho_X(n),   dd/d phi_X = -p_X x n
// (A_X the axes: float bodies' as every query computes with them, detail/axes.hpp), formed
// from the solve's normal, at about 1% of its cost. d is differentiable wherever the maximizer
// of g is unique, across touching included: separated and touching bodies always (g is concave
// on the cone g > 0), overlapping ones except where several directions give the same depth
// (concentric bodies, symmetric deep overlaps). There the fields are the gradient at the
// returned n: an element of Clarke's generalized gradient (d is a maximum of functions smooth
// in the parameters), not a derivative. distance() is this d where the bodies are apart and 0
// where they overlap (its gradient there is 0; at touching the one-sided derivatives differ).
// did_not_converge: the gradient fields are NaN.
// Accuracy (tests/property/gradient_property_test.cpp, against 50-digit central differences of
// the support gap's maximum in the world frame, on random pairs, aspect ratios to 1e4, near
// tangency, overlap, scale 1e-6 and 1e6, far from the origin): each component within 1e-12
// of its unit, the largest derivative by a center or a radius (times the pair's largest radius
// for the orientations); measured up to 8e-14.
//
// G: the gradient by b's parameters, a body's here; against a shape, the shape's (half_space.hpp,
// box.hpp, capsule.hpp, triangle.hpp).
template <class T, int N, class G = BodyGradient<T, N>>
struct DistanceGradient {
  Distance<T, N> value;  // signed_distance(a, b)
  BodyGradient<T, N> a;  // of value.distance
  G b;                   // of value.distance
};
static_assert(detail::has_plain_layout<DistanceGradient<float, 2>, Distance<float, 2>, BodyGradient<float, 2>,
                                        BodyGradient<float, 2>> &&
              detail::has_plain_layout<DistanceGradient<double, 3>, Distance<double, 3>, BodyGradient<double, 3>,
                                        BodyGradient<double, 3>>);

template <class T, int N>
DistanceGradient<T, N> signed_distance_gradient(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                                const Options& options = {}) noexcept;

}  // namespace ellipsect
