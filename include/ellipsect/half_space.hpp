// Ellipses and ellipsoids against half-spaces (half-planes in 2D): relation, overlap,
// distance and signed distance with witness points, first contact under constant velocities.
//
// Math. The half-space H = { x : n . (x - p) <= 0 } has the unit outward normal n and the
// point p on its boundary plane. For a body E with center c, axes A and radii r, the support
// radius along n is rho = |diag(r) A^T n|, and n . (x - p) takes exactly the values
// [s - rho, s + rho] on E, s = n . (c - p). So
//     lower gap   L = s - rho     E lies above the plane when L > 0 (L is then the distance,
//                                 and -L the penetration depth when L < 0);
//     upper gap   U = -s - rho    E lies inside H when U >= 0.
// E's point nearest H (deepest in H) is its lowest point c - A diag(r)^2 A^T n / rho, and
// that point moved by -L n lies on the plane. Under constant velocities L changes linearly,
// L(t) = L(0) - t sigma with the closing speed sigma = -n . (v_E - v_H): contact at L(0) / sigma.
//
// Tolerance model (options.hpp): the relative gap of E is L / rho (E scaled about its center
// by 1 + L / rho touches the plane); |L| <= tolerance * rho is touching, U >= -tolerance * rho
// is containment (touching from inside included).
//
// Method: closed form, exact for the body as stored (the image of the unit ball under its
// stored axes and radii) and the half-space as stored. s and A^T n come from compensated dot
// products (error-free products and sums, c - p split exactly), and L and U from
// (s^2 - rho^2) / (s + rho) in double length where s - rho cancels: both keep their relative
// accuracy however small they are, and however far p lies from c along the plane. Pairs
// outside the native range run rescaled by a power of two or in long double (shapes.hpp,
// "Range"). float bodies and half-spaces are computed in double (the axes orthonormalized)
// and the results rounded (tested to 1e-6 * scale).
//
// Accuracy (tests/property/half_space_property_test.cpp, against a 50-digit reference: the
// support radius from the inverse quadric, the lowest point checked against its Lagrange
// conditions, the contact time by bisection on the gap at each time; random, aspect ratios
// to 1e4, near tangency, containment, tangency from inside, grazing motion, zero closing
// speed, scale 1e-6 and 1e6, far apart, plane points 1e15 away along the plane), with
// scale = largest radius + |distance|:
//   relation        exact outside the tangency band widened by 1e-14 of rho;
//   distance        absolute error <= 1e-14 * scale;
//   point_a, point_b, contact point   within 1e-14 * (scale + |point|) of the exact points;
//   normal          exactly -n (from the body towards the half-space);
//   contact time    relative error <= 1e-14 (time and t_max are compared exactly as computed).
// Status: no iteration (iterations is 0); did_not_converge only from first_contact, for a hit
// whose point lies beyond the range of T (the body has moved out of it by then: bodies of
// radius 1e200 closing at 1e-70 with a speed of 1e100 along the plane, hit at 2e270): the hit's
// time, point and normal NaN.
#pragma once

#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <array>

namespace ellipsect {

template <class T, int N>
class HalfSpace {
public:
  // The default half-space: x_N <= 0 (point 0, normal the last coordinate axis).
  constexpr HalfSpace() noexcept : point_{}, normal_{} { normal_[N - 1] = T(1); }

  // point: finite ("point[i]"); normal: finite ("normal[i]") and not zero ("normal"); the
  // stored normal is normal / |normal| (also where |normal|^2 would under- or overflow).
  static HalfSpace from_point_normal(const Vec<T, N>& point, const Vec<T, N>& normal);

  Eigen::Map<const Vec<T, N>> point() const noexcept { return Eigen::Map<const Vec<T, N>>(point_.data()); }
  Eigen::Map<const Vec<T, N>> normal() const noexcept { return Eigen::Map<const Vec<T, N>>(normal_.data()); }

  // The half-space moved by offset (the same normal); throws InputError "offset[i]" for a
  // non-finite offset[i], "offset" where the moved point leaves the range of T.
  HalfSpace translated(const Vec<T, N>& offset) const;

private:
  std::array<T, N> point_, normal_;
};
static_assert(detail::has_plain_layout<HalfSpace<float, 2>, float[2], float[2]> &&
              detail::has_plain_layout<HalfSpace<double, 3>, double[3], double[3]>);

template <class T, int N>
HalfSpace<T, N> make_half_space(const Vec<T, N>& point, const Vec<T, N>& normal) {
  return HalfSpace<T, N>::from_point_normal(point, normal);
}

// separated, touching, overlapping, or b_contains_a (the body inside the half-space).
template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b, const Options& options = {}) noexcept;

// classify(a, b) != separated.
template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b, const Options& options = {}) noexcept;

// As distance() of two bodies: status separated, touching or overlapping (classify's, with
// containment as overlapping); distance L (0 when overlapping, with NaN points and normal);
// point_a the body's lowest point, point_b = point_a + distance * normal on the plane,
// normal = -n.
template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b, const Options& options = {}) noexcept;

// As distance(), and for overlapping bodies the signed distance L = -(penetration depth),
// with the same points and normal: moving the body by -distance * n (or the half-space by
// distance * n) makes them touch.
template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b,
                               const Options& options = {}) noexcept;

// ---- Gradient (gradient.hpp's parameters for the body) -----------------------------------
//
// signed_distance(a, b) and the derivatives of its distance L = n_H . (c - p) - rho(n_H), n_H
// the half-space's normal: by the body as for two bodies (distance.hpp), and by the half-space's
// point p and its normal turned about p (a world rotation vector, as a body's orientation):
//     dL/dp = -n_H,   dL/dphi = (x - p) x n,
// n = -n_H the returned normal, x the body's lowest point (any point on the line x + s n_H).
// Differentiable everywhere. Where the plane's point lies beyond 1024 radii of the body's
// center, the turn's lever x - p is formed with c - p split exactly and compensated products,
// so a plane point far along the plane costs no digits. Accuracy
// (tests/property/shape_gradient_property_test.cpp, against 50-digit central differences of L
// in closed form, on the cases of signed_distance's test, 1e6 sizes from the origin on every
// other one): each component within 1e-12 of its unit (as for two bodies); measured up to 2.3e-14.
template <class T, int N>
struct HalfSpaceGradient {
  Vec<T, N> point;
  RotationVector<T, N> normal;  // the plane turned about its point
};
static_assert(detail::has_plain_layout<HalfSpaceGradient<float, 2>, float[2], float> &&
              detail::has_plain_layout<HalfSpaceGradient<double, 3>, double[3], double[3]>);

template <class T, int N>
DistanceGradient<T, N, HalfSpaceGradient<T, N>> signed_distance_gradient(const Ellipsoid<T, N>& a,
                                                                         const HalfSpace<T, N>& b,
                                                                         const Options& options = {}) noexcept;

// The body moves as center + t * velocity_a, the half-space as point + t * velocity_b
// (a moving plane; its normal does not turn); contact is searched in [0, t_max]. Statuses as
// for two bodies: invalid_input for a non-finite velocity or a NaN or negative t_max;
// overlapping_at_start for an overlap or containment at t = 0; touching_at_start; hit at
// time L(0) / sigma in (0, t_max] with the body's lowest point then and the normal -n;
// otherwise no_contact_in_window (also for sigma <= 0: receding or sliding along the plane);
// did_not_converge for a hit whose point lies beyond the range of T (above).
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const HalfSpace<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

// The body in rigid motion (contact.hpp: turning about its center at a constant angular
// velocity) against the half-space moving at velocity_b, by conservative advancement
// (contact.hpp, "Rigid motion against shapes"); a zero angular velocity gives exactly the
// answer above.
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const HalfSpace<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

}  // namespace ellipsect
