// Ellipses and ellipsoids against capsules (stadiums in 2D): relation, overlap, signed
// distance, first contact under constant velocities.
//
// Math. The capsule { x : dist(x, [p0, p1]) <= R } is the segment grown by a ball of radius
// R, so its support function is the segment's plus R |n|, and with the support gap of
// distance.hpp (c the body's center, rho its support radius)
//     L = max over unit n of G(n),   G(n) = min_k n . (p_k - c) - rho(n) - R,
// the signed distance of the body and the capsule is L: the segment's (triangle.hpp's
// "Distance", a degenerate triangle) less R. The capsule is not carried to a capsule by the
// body's unit-ball frame (its ball becomes an ellipsoid), so the reduced-frame method of the
// other shapes does not apply; everything here is that maximum, over the stationary
// directions of G on each stratum of the sphere (src/detail/polytope_distance.hpp):
//   relation      g = L / rho(n*), n* the maximizer: the body scaled about its center by
//                 1 + g touches the capsule to first order, compared with Options::tolerance
//                 as the relative gaps of the other shapes: separated g > tolerance,
//                 touching |g| <= tolerance;
//                 a_contains_b  the capsule inside the body: both end balls are (the capsule is
//                               their convex hull), max_k (signed distance of p_k to the
//                               body's boundary) <= -R;
//                 b_contains_a  the body inside the capsule: its support function below the
//                               capsule's, max over n of (min_k n . (p_k - c) + rho(n)) <= R;
//                               both maxima over every stationary direction of the strata
//                               (also where the segment lies off the body: a needle through
//                               the capsule's surface);
//                 (both with the tolerance band counted as inside), overlapping otherwise.
//                 Before any of that, the body's center against the segment: farther than
//                 largest radius + R by 1e-9 of the lengths is separated, nearer than smallest
//                 radius + R by as much overlaps (overlap() answers there; classify goes on
//                 to tell containment).
//   first_contact With the capsule moving relative to the body at w, the gap
//                 L(t) = max_n (G(n) + t n . w) is convex in t (a maximum of affine
//                 functions), with slope n*(t) . w: Newton from t = 0 climbs monotonically to
//                 its first root (Eberly's h(t)), at most Options::max_contact_iterations steps.
//                 Stops when L(t) falls to 1e-14 of the pair's size (a hit), the slope is >= 0
//                 (the gap never closes: no contact), or the step passes t_max.
// Every query runs on the pair moved by minus the body's center (the segment's points less
// it rounded once), so that the segment is rounded to ulps of the pair's extent, not of its
// coordinates, and classify, signed_distance and first_contact's start decide on the same
// numbers.
// Accuracy (tests/property/capsule_property_test.cpp, against the 50-digit search of the
// sphere of tests/reference/support_gap_reference.hpp; random, aspect ratios to 1e4, near
// tangency, containment both ways and needles across the surface, balls (p0 = p1), long
// capsules, scale 1e-6 and 1e6; moved 1e3 to 1e6 sizes from the origin,
// tests/property/shape_translation_property_test.cpp), with
// scale = largest radius + R + largest |p_k - c|: the distance within 1e-12 scale; the
// relation exact outside the tangency band widened by 1e-12 scale / rho(n*); contact times
// where the reference's gap at the returned time is within 1e-12 scale of 0 and is positive
// just before it (the first root). A graze (the gap's minimum at 0, a double root) is a hit
// at a time accurate to about 1e-7 relative only: the gap is quadratic in time there.
#pragma once

#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <array>

namespace ellipsect {

template <class T, int N>
class Capsule {
public:
  // The unit ball at the origin as a capsule of zero length.
  constexpr Capsule() noexcept : points_{}, radius_(1) {}
  // p0, p1 finite ("p0[i]", "p1[i]"; equal points make a ball), radius finite and > 0
  // ("radius").
  static Capsule from_segment(const Vec<T, N>& p0, const Vec<T, N>& p1, T radius);
  // End point k in 0..1.
  Eigen::Map<const Vec<T, N>> point(int k) const noexcept { return Eigen::Map<const Vec<T, N>>(points_[k].data()); }
  T radius() const noexcept { return radius_; }
  // The capsule moved by offset; throws InputError "offset[i]" for a non-finite offset[i],
  // "offset" where a moved end point leaves the range of T.
  Capsule translated(const Vec<T, N>& offset) const;

private:
  std::array<std::array<T, N>, 2> points_;
  T radius_;
};
static_assert(detail::has_plain_layout<Capsule<float, 2>, float[4], float> &&
              detail::has_plain_layout<Capsule<double, 3>, double[6], double>);

template <class T, int N>
Capsule<T, N> make_capsule(const Vec<T, N>& p0, const Vec<T, N>& p1, T radius) {
  return Capsule<T, N>::from_segment(p0, p1, radius);
}

// separated, touching, overlapping, a_contains_b (the capsule inside the body) or
// b_contains_a (the body inside the capsule).
template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a, const Capsule<T, N>& b, const Options& options = {}) noexcept;

// classify(a, b) != separated.
template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const Capsule<T, N>& b, const Options& options = {}) noexcept;

// As for a triangle (triangle.hpp): the separation distance, or minus the penetration depth,
// with the body's point, the capsule's (point_a + distance * normal) and the body's outward
// normal; status classify's (overlapping for containment).
template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const Capsule<T, N>& b, const Options& options = {}) noexcept;

template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Capsule<T, N>& b, const Options& options = {}) noexcept;

// ---- Gradient (gradient.hpp's parameters for the body) -----------------------------------
//
// signed_distance(a, b) and the derivatives of its distance d: by the body as for two bodies
// (distance.hpp), and by the capsule's end points and radius, from the segment's point
// s = (1 - l) p0 + l p1 nearest to y + R n (y the capsule's point where it touches the body
// moved by -d n, n the returned normal):
//     dd/d p0 = (1 - l) n,   dd/d p1 = l n,   dd/d radius = -1.
// Differentiable where the maximizing n is unique (distance.hpp) and the capsule has a length:
// with p0 = p1 (a ball) d is the least of the distances to the two end balls, and l = 1/2 gives
// an element of its generalized gradient (the one-sided derivatives differ). Accuracy as for
// boxes (box.hpp).
template <class T, int N>
struct CapsuleGradient {
  Vec<T, N> p0, p1;
  T radius;
};
static_assert(detail::has_plain_layout<CapsuleGradient<float, 2>, float[2], float[2], float> &&
              detail::has_plain_layout<CapsuleGradient<double, 3>, double[3], double[3], double>);

template <class T, int N>
DistanceGradient<T, N, CapsuleGradient<T, N>> signed_distance_gradient(const Ellipsoid<T, N>& a,
                                                                       const Capsule<T, N>& b,
                                                                       const Options& options = {}) noexcept;

// The body moves as center + t * velocity_a, the capsule as its points + t * velocity_b;
// statuses as for two bodies (contact.hpp), did_not_converge when Options::max_contact_iterations
// Newton steps end short of the contact (the time reached is a lower bound; point and normal
// NaN); iterations the Newton steps.
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const Capsule<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

// The body in rigid motion (contact.hpp: turning about its center at a constant angular
// velocity) against the capsule moving at velocity_b, by conservative advancement
// (contact.hpp, "Rigid motion against shapes"); a zero angular velocity gives exactly the
// answer above.
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Capsule<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

}  // namespace ellipsect
