// Ellipses and ellipsoids against oriented boxes (rectangles in 2D): relation, overlap, first
// contact under constant velocities.
//
// Math. The box { center + axes u : |u_i| <= half_extents_i } is solid. It is the union of
// two filled triangles in 2D; in 3D its boundary is twelve triangles and a body meets the
// solid box exactly when it meets one of them or its center lies inside. So every answer
// comes from the triangle queries (triangle.hpp), exact outside the tangency band:
//     a_contains_b  every triangle inside the body (the box is their convex hull);
//     b_contains_a  the body overlaps the box and lies in each of its 2N faces' half-spaces
//                   (half_space.hpp, touching from inside included);
//     overlapping   some triangle overlapping or inside the body, or (3D) the body's center
//                   inside the box;
//     touching      otherwise some triangle touching; separated otherwise.
// Most pairs are settled before the triangles, in the box's frame: separated where a slab of
// the box, or the plane through its point nearest the body's center, keeps the body off by
// more than the tangency band; overlapping where that center is inside the box, or that
// point inside the body shrunk by the band (the same relation, only cheaper).
// first_contact: the start relation as classify's; a separated body first meets the box on
// its boundary, so the hit is the earliest of the triangles' (closed form, triangle.hpp),
// with their accuracy; in 3D it skips the faces that cannot hold the first contact (those
// facing away from the relative velocity, or whose plane the body lies inside of at the
// start), except on a box thinner than 64 ulps of its corners' magnitude, whose computed
// corners need not bound a box: there every triangle is tested. Every query runs on the pair
// moved by minus the body's center (the box's center then the difference of the centers,
// rounded once), so the box answered for is the convex hull of its corners as computed there
// (that center +- half extents along the axes, rounded to T): within a few ulps of the
// distance between the centers plus the half extents of the stored box, whatever the
// coordinates' magnitude (tests/property/shape_translation_property_test.cpp).
#pragma once

#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>
#include <ellipsect/triangle.hpp>

#include <array>

namespace ellipsect {

template <class T, int N>
class Box {
public:
  // The cube [-1, 1]^N.
  Box() noexcept : frame_(make_ball<T, N>(Vec<T, N>::Zero(), T(1))) {}

  // center: finite ("center[i]"); axes: orthonormal columns ("axes"); half_extents: finite,
  // > 0 and within a ratio of 1e8 ("half_extents[i]", "half_extents"): the checks and
  // messages of Ellipsoid::from_axes.
  static Box from_axes(const Vec<T, N>& center, const Mat<T, N>& axes, const Vec<T, N>& half_extents);

  auto center() const noexcept { return frame_.center(); }
  auto axes() const noexcept { return frame_.axes(); }
  auto half_extents() const noexcept { return frame_.radii(); }

  // Corner k (bit i of k set: +half_extents_i along axis i), k in [0, 2^N).
  Vec<T, N> corner(int k) const noexcept;

  // The box's triangles: two covering the rectangle in 2D, twelve covering the boundary in 3D.
  std::array<Triangle<T, N>, N == 2 ? 2 : 12> triangles() const noexcept;

  // The box moved by offset; throws InputError "offset[i]" for a non-finite offset[i],
  // "offset" where the moved center leaves the range of T.
  Box translated(const Vec<T, N>& offset) const;

private:
  explicit Box(const Ellipsoid<T, N>& frame) noexcept : frame_(frame) {}
  Ellipsoid<T, N> frame_;  // center, axes and half extents, stored as a body's
};
static_assert(detail::has_plain_layout<Box<double, 3>, Ellipsoid<double, 3>>);

template <class T, int N>
Box<T, N> make_box(const Vec<T, N>& center, const Mat<T, N>& axes, const Vec<T, N>& half_extents) {
  return Box<T, N>::from_axes(center, axes, half_extents);
}

template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options = {}) noexcept;

template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options = {}) noexcept;

// Signed distance and distance as for a triangle (triangle.hpp), the solid box the polytope
// of its 2^N corners: minus the penetration depth for a body inside the box or containing it.
// The first pass (largest roots) tries only the features that can hold the nearest point: those
// within the body's slabs along the box's axes widened by an upper bound on the distance, and
// on the body's side along an axis where the body's slab lies beyond the box's.
template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options = {}) noexcept;

template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options = {}) noexcept;

// ---- Gradient (gradient.hpp's parameters for the body) -----------------------------------
//
// signed_distance(a, b) and the derivatives of its distance d: by the body as for two bodies
// (distance.hpp), and by the box's center, orientation (a world rotation vector about its
// center, as a body's) and half extents e, from the box's point y where it touches the body
// moved by -d n (n the returned normal; y = point_b where the points are exact), u = A^T (y -
// center) its coordinates along the box's axes a_i:
//     dd/d center = n,   dd/d phi = (y - center) x n,   dd/d e_i = (u_i / e_i) (a_i . n)
// (-|a_i . n| where y lies on a face across axis i, 0 along an axis the normal is orthogonal to).
// Differentiable where the maximizing n is unique (distance.hpp: always when apart; deep
// overlaps with several deepest directions are not); there the fields are the gradient at the
// returned n, an element of the generalized gradient. In 3D the returned normal is first
// polished on its stratum: on an edge (a triangle's, a box's, a capsule's segment) by Newton
// on the circle of directions orthogonal to it, the edge's line taken relative to the body's
// center in double length; at a face, the face's own normal (the solve's normal carries its
// rounding, of first order in the derivatives though of second order in the distance).
// Accuracy (tests/property/shape_gradient_property_test.cpp, against 50-digit central
// differences of the support gap's maximum on the stratum of the box's features that attain it
// (near where strata meet, the one with the larger maximum), on the cases of signed_distance's
// test, 1e6 sizes from the origin on every other one; triangles to 1e12 radii across): each
// component within 1e-9 of its unit (the largest derivative by a center or a length, times
// the pair's scale for the orientations); measured up to 2.6e-10 (boxes, a corner at aspect
// ratio 1e4), 1.4e-13 (triangles), 4e-14 (capsules).
template <class T, int N>
struct BoxGradient {
  Vec<T, N> center;
  RotationVector<T, N> orientation;
  Vec<T, N> half_extents;
};
static_assert(detail::has_plain_layout<BoxGradient<float, 2>, float[2], float, float[2]> &&
              detail::has_plain_layout<BoxGradient<double, 3>, double[3], double[3], double[3]>);

template <class T, int N>
DistanceGradient<T, N, BoxGradient<T, N>> signed_distance_gradient(const Ellipsoid<T, N>& a, const Box<T, N>& b,
                                                                   const Options& options = {}) noexcept;

// Statuses as for two bodies (contact.hpp); the box moves as center + t * velocity_b.
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const Box<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

// The body in rigid motion (contact.hpp: turning about its center at a constant angular
// velocity) against the box moving at velocity_b, by conservative advancement
// (contact.hpp, "Rigid motion against shapes"); a zero angular velocity gives exactly the
// answer above.
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Box<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

}  // namespace ellipsect
