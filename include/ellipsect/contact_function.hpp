// The Perram-Wertheim contact function and the distance of closest approach along a
// direction: the quantities molecular-dynamics and granular codes use directly.
//
// Math. With M_A, M_B the quadric matrices (x^T M x <= 1 about the centers) and
// r = center(b) - center(a),
//
//     F(A, B) = max over lambda in [0, 1] of  F(lambda) = lambda (1 - lambda) r^T C(lambda)^-1 r,
//     C(lambda) = (1 - lambda) M_A^-1 + lambda M_B^-1
//
// (J. W. Perram and M. S. Wertheim, J. Comput. Phys. 58, 1985). F < 1: the bodies overlap,
// F = 1: they touch, F > 1: they are apart; sqrt(F) is the factor by which both bodies,
// scaled about their own centers, just touch. F(lambda) is strictly concave for r != 0, and F
// is homogeneous of degree 2 in r, so the distance of closest approach along a unit
// direction u (X. Zheng and P. Palffy-Muhoray, Phys. Rev. E 75, 2007), the center distance
// sigma at which b translated to center(a) + sigma u touches a from outside, is
// sigma = 1 / sqrt(F(A, B with r = u)).
//
// Method: the pair is reduced to a unit ball and an axis-aligned ellipsoid (semi-axes e,
// docs/method.md section 1; F is invariant under that affine map), where C is diagonal:
// F(lambda) = lambda (1 - lambda) sum_i k_i^2 / (1 - lambda + lambda e_i^2) with the weights on
// the two bodies carried separately. Its maximizer is the root of the decreasing
// F'(lambda), found by Newton safeguarded by a bracket (bisection when a step leaves it),
// from the maximizer for two balls, at most Options::max_contact_function_iterations steps. Pairs whose
// aspect ratios multiply beyond 1e12 are solved in the world frame instead: there e spreads
// over that product, and its rounding relative to the largest reached the thinnest (two
// needles of aspect ratio 1e8: F off by 28%); C(lambda) is applied through the QR
// factorization of the bodies' stacked factors diag(r) A^T (row-sorted, column-pivoted
// Householder), which keeps every radius whatever their spread.
//
// Accuracy (tested against a 50-digit reference reached by golden-section maximization of
// F(lambda) in the world frame and, for sigma, by root finding on an overlap test that does
// not use F; tests/property/contact_function_property_test.cpp), on random pairs, aspect
// ratios to 1e4, near tangency (F within 1e-12 of 1), containment, equal and concentric
// bodies, scales 1e-6 and 1e6, bodies 1e4 sizes apart, and needles and discs of aspect
// ratio 1e4 to 1e8 touching or placed at random; A below is the larger aspect ratio of the
// two bodies:
//   F        relative error <= 1e-12 + 2 eps A (eps = 2^-52: 1e-12 for round bodies, 5e-12 at
//            A = 1e4, 4e-8 at 1e8, the largest accepted), the error that the axes' own
//            rounding (orthonormal to about eps, which moves a thin extent by eps times the
//            body's length) makes; largest seen 2e-13 on the random categories, and on the
//            needles and discs 1.3e-12 at A = 1e4, 2.5e-11 at 1e6, 6.3e-9 at 1e8;
//   lambda   error <= 1e-10 * min(lambda, 1 - lambda) + 1e-12 for A <= 1e4 (largest seen
//            1e-11 relative); beyond, where F is flat in lambda, 1e-12 A min(lambda, 1 - lambda)
//            + 1e-12 (largest seen 1.3e-7 relative at A = 1e6, 3.3e-6 at 1e7, 2.2e-5 at 1e8);
//   sigma    relative error <= 1e-12 + 2 eps A (largest seen 8e-15 on the random categories,
//            1.1e-12 on the needles and discs); it equals L - t, t the first contact time (first_contact) of
//            b moving with velocity -u from center(a) + L u, to first_contact's accuracy;
//   point    on a's boundary and on b's (at center(a) + sigma u) within 1e-12 (sigma + radii);
//   normal   a's outward and b's inward normal at `point`, within 1e-12 (sigma + radii) / rho
//            rad, rho the smallest radius of curvature (r_min^2 / r_max) of the two bodies.
// Consequently sign(F - 1) agrees with classify (separated; the overlapping relations) wherever
// |sqrt(F) - 1| > 2 * Options::tolerance + 1e-12, and a pair classify calls touching has F
// within that band of 1. Swapping a and b gives the same F bit for bit and lambda ->
// 1 - lambda (the other weight, computed on its own, so a weight below eps keeps its
// digits); closest_approach(b, a, -u) gives the same sigma bit for bit. Scaling both bodies
// by 2^k leaves F, lambda and the normal unchanged and multiplies sigma and the point by
// exactly 2^k, at any scale (docs/method.md, section 7). float bodies are computed in double
// and the results rounded (tested to 1e-5 relative against the float bodies' reference).
// Cost: about 0.2 us in 2D and 0.5 us in 3D per query; pairs solved in the world frame
// (aspect ratios multiplying beyond 1e12) about 2.6 us in 2D and 5 us in 3D, 10 to 19
// Newton and bisection steps of a QR each (bench/RESULTS.md).
#pragma once

#include <ellipsect/gradient.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <string_view>

namespace ellipsect {

enum class ContactFunctionStatus {
  ok,                // converged: the values carry the stated accuracy
  concentric,        // perram_wertheim only: the centers are equal, F = 0 for every lambda;
                     // f = f_upper = 0 and lambda is NaN (no maximizer)
  did_not_converge,  // Options::max_contact_function_iterations steps without converging (not seen on the
                     // tested pairs with the default cap of 64: on 2000 pairs of each
                     // scenario category at most 25 steps, 5.8 (2D) and 6.5 (3D) on average;
                     // needles of aspect ratio 1e8, 10 to 19); the values are the last
                     // iterate's, with certified bounds
};

std::string_view to_string(ContactFunctionStatus s) noexcept;

template <class T>
struct ContactFunction {
  ContactFunctionStatus status = ContactFunctionStatus::did_not_converge;
  // F(A, B) = mu^2 (>= 0; +inf only where mu^2 exceeds the largest T). did_not_converge: F at
  // the last iterate less its rounding, a lower bound of F(A, B).
  T f;
  // An upper bound of F(A, B): equal to f when ok and concentric; did_not_converge: the
  // tangent of the concave F(lambda) at the last iterate evaluated across the bracket, plus
  // its rounding, so f <= F(A, B) <= f_upper.
  T f_upper;
  // The maximizing lambda in (0, 1), the weight of b's matrix in C (did_not_converge: the last
  // iterate; concentric: NaN).
  T lambda;
  // Newton and bisection steps taken.
  int iterations = 0;
};
static_assert(detail::has_plain_layout<ContactFunction<float>, ContactFunctionStatus, float, float, float, int> &&
              detail::has_plain_layout<ContactFunction<double>, ContactFunctionStatus, double, double, double, int>);

template <class T, int N>
struct ClosestApproach {
  ContactFunctionStatus status = ContactFunctionStatus::did_not_converge;  // ok or did_not_converge
  // sigma: b translated to center(a) + sigma * u (u the unit direction) touches a from
  // outside; did_not_converge: an upper bound (from the lower bound of F).
  T distance;
  // A lower bound of sigma: equal to distance when ok.
  T distance_lower;
  // World frame, b at center(a) + distance * u: the contact point (on both boundaries) and
  // the unit normal there, outward from a (towards b). did_not_converge: those of the last
  // iterate (approximate).
  Vec<T, N> point;
  Vec<T, N> normal;
  // The maximizing lambda of F(A, B with r = u).
  T lambda;
  int iterations = 0;
};
static_assert(detail::has_plain_layout<ClosestApproach<float, 2>, ContactFunctionStatus, float, float, float[2],
                                       float[2], float, int> &&
              detail::has_plain_layout<ClosestApproach<double, 3>, ContactFunctionStatus, double, double, double[3],
                                       double[3], double, int>);

// F(A, B) and its maximizer.
template <class T, int N>
ContactFunction<T> perram_wertheim(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                   const Options& options = {}) noexcept;

// ---- Gradient (gradient.hpp's parameters) ---------------------------------------------
//
// perram_wertheim(a, b) and the derivatives of F. By the envelope theorem at the maximizer
// lambda, with y = C(lambda)^-1 r and w_a = 1 - lambda, w_b = lambda the weights of the bodies'
// matrices (M_X^-1 = A_X diag(r_X^2) A_X^T):
//     dF/d center(b) = 2 lambda (1 - lambda) y = -dF/d center(a),
//     dF/d radii(X)_i = -2 lambda (1 - lambda) w_X r_X,i (A_X^T y)_i^2,
//     dF/d phi_X = -2 lambda (1 - lambda) w_X (M_X^-1 y) x y,
// with y from the reduced frame of the solve (y = to_z^T of its diagonal solution), so it
// keeps the solve's relative accuracy at any aspect ratio it supports. F is differentiable
// everywhere (F(lambda) is strictly concave for r != 0, so its maximizer is unique; at
// concentric bodies F vanishes to second order in r: the gradient is 0, status concentric).
// did_not_converge: the gradient fields are NaN.
// Accuracy (tests/property/gradient_property_test.cpp, against 50-digit central differences of
// F by golden-section search in the world frame): each component within 1e-12 of its unit,
// the largest derivative by a center or a radius (times the pair's largest radius for the
// orientations), on the cases of signed_distance_gradient; measured up to 1.1e-13.
template <class T, int N>
struct ContactFunctionGradient {
  ContactFunction<T> value;  // perram_wertheim(a, b)
  BodyGradient<T, N> a, b;   // of value.f
};
static_assert(detail::has_plain_layout<ContactFunctionGradient<float, 2>, ContactFunction<float>, BodyGradient<float, 2>,
                                        BodyGradient<float, 2>> &&
              detail::has_plain_layout<ContactFunctionGradient<double, 3>, ContactFunction<double>,
                                        BodyGradient<double, 3>, BodyGradient<double, 3>>);

template <class T, int N>
ContactFunctionGradient<T, N> perram_wertheim_gradient(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                                       const Options& options = {}) noexcept;

// The distance of closest approach of b to a along `direction` (any nonzero finite length; it
// is normalized). b keeps its orientation and shape; only its center moves, along the ray from
// a's center. Throws InputError("direction") for a zero or non-finite direction.
template <class T, int N>
ClosestApproach<T, N> closest_approach(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                       const VecArg<T, N>& direction, const Options& options = {});

// closest_approach(a, b, direction) and the derivatives of its sigma. Implicit differentiation
// of the touching of a and b placed at center(a) + sigma u (u = direction / |direction|): with n
// the returned normal, the signed distance g there changes by n . u per unit of sigma and by
// -d rho_a(n) - d rho_b(n) with the bodies' radii and orientations (distance.hpp), so
//     d sigma / d radii(X)_i = r_i (A_X^T n)_i^2 / (rho_X(n) (n . u)),
//     d sigma / d phi_X = (p_X x n) / (n . u)   (p_X X's support point along n less its center),
//     d sigma / d direction = -sigma (n - (n . u) u) / ((n . u) |direction|),
// and 0 by the centers (b is placed relative to a). n . u > 0 for every pair (b's center lies
// beyond the contact plane), so sigma is differentiable everywhere. did_not_converge: NaN.
// Accuracy (tests/property/gradient_property_test.cpp, against 50-digit central differences of
// 1 / sqrt(F) by golden-section search in the world frame, on the cases of
// perram_wertheim_gradient with random directions): each component within 1e-11 of its unit
// (the largest derivative by a radius, times the pair's largest radius for the orientations;
// the largest by the direction, at least sigma / |direction|, for the direction's), 1e6 sizes
// from the origin on every other case: the normal's error (above) moves the support points;
// measured up to 1.1e-12 (aspect ratio 1e3).
template <class T, int N>
struct ClosestApproachGradient {
  ClosestApproach<T, N> value;  // closest_approach(a, b, direction)
  BodyGradient<T, N> a, b;      // of value.distance
  Vec<T, N> direction;          // of value.distance
};
static_assert(detail::has_plain_layout<ClosestApproachGradient<float, 2>, ClosestApproach<float, 2>,
                                       BodyGradient<float, 2>, BodyGradient<float, 2>, float[2]> &&
              detail::has_plain_layout<ClosestApproachGradient<double, 3>, ClosestApproach<double, 3>,
                                       BodyGradient<double, 3>, BodyGradient<double, 3>, double[3]>);

// Throws InputError("direction") as closest_approach.
template <class T, int N>
ClosestApproachGradient<T, N> closest_approach_gradient(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                                        const VecArg<T, N>& direction, const Options& options = {});

}  // namespace ellipsect
