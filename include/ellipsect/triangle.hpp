// Ellipses and ellipsoids against triangles: relation, overlap, first contact under constant
// velocities (the swept test of a character controller).
//
// Math. A triangle is the convex hull of its three vertices: a filled triangle in 2D and 3D;
// collinear or coincident vertices give the segment or point they span, with the same
// queries (degenerate triangles are answered, not rejected). In the body's unit-ball frame
// u = diag(r)^-1 A^T (x - c) (the quadric as stored: A is orthonormal to 4 N eps) the body is
// the unit ball and the triangle the triangle T' of the mapped vertices u_k. With
//     d = min over T' of |u|      (the body scaled about its center by d just touches it)
//     D = max_k |u_k|             (scaled by D it just contains it)
// the relative gap of options.hpp is g = d - 1, and
//     separated     g > tolerance
//     touching      |g| <= tolerance
//     a_contains_b  D <= 1 + tolerance (the triangle inside the body, touching from inside
//                   included), otherwise overlapping.
// Under constant velocities the triangle moves in the ball frame at w = diag(r)^-1 A^T
// (v_b - v_a), and d(t) is convex in t (the distance from a point to a moving convex set):
// contact is the first root of d(t) = 1, the earliest entering root among the vertices
// (|u_k + t w| = 1), the edges' lines (valid where the foot lies on the edge) and, in 3D, the
// face's plane (valid where the touching point lies in the triangle): the swept sphere
// against a triangle of Fauerby's and Nettle's character controllers, solved in closed form.
//
// Method and guarantee: the nearest point x of T' to the origin is the nearest of seven
// candidates (vertices, edges, face) as barycentric weights (the face's from cross products,
// and only where the face is resolved: the sine of its angle above the square root of the
// working precision's unit roundoff, below which the triangle is numerically its segment or
// point and its edges, within sine times U of every point of it, stand for it); then a certified bracket
// lo <= d <= hi: hi = |x| (a convex combination of the vertices: a point of T'), lo =
// min_k (x / |x|) . u_k (the plane through x normal to x supports T'), each widened by the
// rounding-error bound of its evaluation. A bracket that decides the relation is the answer;
// otherwise the pair is computed again in double length (vertices less center split exactly,
// compensated dot products: errors of order 1e-32 U, U the triangle's extent in the ball
// frame), and a bracket that still straddles a band edge is decided by its midpoint; a
// triangle whose bounding box misses the body's is separated without further arithmetic. So
// the relation is exact outside the tangency band widened by about 1e-30 U: by 1e-14 (the
// tests' margin) for triangles to 1e15 radii across and more (tested to 1e12 on random
// cases, at 1e20 on a floor), whatever the aspect ratio, and for needles, segments and
// points (collinear or coincident vertices, or within rounding of that: widened there by
// about 2e-16 U, the sine of a face too thin for double length); a triangle apart from the
// body's box always exactly. Contact times are computed in double length where the gap is
// below 1/4, U above 1024 (the entering roots cancel there) or the sine of the triangle's
// angle below 1/16 (its face's plane is known to the rounding over that sine), with errors
// of order 1e-32 U^2 relative; a body whose box, swept relative to the
// triangle's over the window, never meets it has no contact, exactly. (Not met: a triangle
// more than about 1e8 radii across, in the body's frame, that the body's box does sweep
// through can get a contact time with less than the stated accuracy.) Pairs beyond the native range (shapes.hpp, "Range") run in long double. float
// bodies and triangles are computed in double, the axes orthonormalized.
//
// Accuracy (tests/property/triangle_property_test.cpp, against a 50-digit reference that
// minimizes (x - c)^T M (x - c) over the triangle in world coordinates, M = A diag(r)^-2 A^T,
// face, edges and vertices by their Lagrange conditions, and finds contact times by bisection
// on that static test; random, aspect ratios to 1e4, near tangency at faces, edges and
// vertices (relative gaps 1e-13 to 1e-3, outside and inside), containment, triangles 1e3 to
// 1e12 radii across, needles, segments and points, scale 1e-6 and 1e6, grazing, zero relative
// velocity; and each of these made collinear, nearly collinear (a vertex 1 to 4 ulps off the
// segment), a point or nearly a point in world coordinates):
//   relation      exact outside the tangency band widened by 1e-14;
//   contact time  where the reference finds a contact (its least gap in the window more than
//                 1e-9 below 0: not a graze), a hit at a time where the reference's relative
//                 gap is within 1e-12 of 0 and, where the approach is not grazing, within
//                 1e-13 relative of the reference's time; no hit where its least gap stays
//                 more than 1e-9 above 0;
//   point         within 1e-12 (size + |point|) of the reference's contact point;
//   normal        within 1e-12 of the body's outward unit normal there.
// Status: did_not_converge (with the computed time, NaN point and normal) where the closed
// form's contact point fails its check of lying on the body (|x| = 1 in the ball frame to
// 1e-6): seen only for triangles far beyond the range above (1e238 radii across); iterations
// is 0.
//
// Distance. signed_distance is the maximum over unit n of the support gap G(n) = min_k n .
// (v_k - c) - sqrt(n^T A diag(r^2) A^T n) (distance.hpp), found as the best of a finite set
// of candidate directions that contains the maximizer: the stationary points of G on each
// stratum of the sphere where one vertex, two (n orthogonal to an edge) or, in 3D, three (the
// face's normals) attain the minimum, from the secular equation of the point (vertex) or of
// the edge's point in the body's shadow along the edge (src/detail/polytope_distance.hpp);
// where the largest roots' directions already separate (G > 0) they alone are tried, every
// stratum's function being concave there. Each root by Newton within its bracket (at most 100
// steps, bisection where a step leaves it; the extreme roots on 1 - q^(-1/2), q the secular
// sum, nearly linear there). The status is classify's, which is asked only where |G| <=
// (tolerance + 1e-9) R + 1e-12 max_k |v_k - c| (R the largest radius) or where the vertices
// lie beyond 1e12 smallest radii from the center (classify's stated range): elsewhere the
// relative gap is beyond the tolerance on the same side (the body scaled by d about its center
// moves its boundary by at most |d - 1| R). Accuracy (tests/property/
// polytope_distance_property_test.cpp, against a 50-digit search of the sphere stratum by
// stratum; the triangle scenarios above and boxes: random, around the body, inside it, thin
// to aspect 1e4, near tangency at faces, edges and corners, and those features far), with scale = largest radius + largest |vertex - center|: the distance
// within 1e-12 scale, the support gap at the returned normal within 1e-12 scale of the
// maximum; point_a on the body to 1e-12 relative, the normal its outward normal there.
#pragma once

#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <array>

namespace ellipsect {

template <class T, int N>
class Triangle {
public:
  // The default triangle: the origin and the first two unit vectors.
  constexpr Triangle() noexcept : vertices_{} {
    vertices_[1][0] = T(1);
    vertices_[2][1] = T(1);
  }

  // Every coordinate finite ("vertices[k][i]"); any three points, degenerate ones included.
  static Triangle from_vertices(const Vec<T, N>& v0, const Vec<T, N>& v1, const Vec<T, N>& v2);

  // Vertex k in 0..2.
  Eigen::Map<const Vec<T, N>> vertex(int k) const noexcept { return Eigen::Map<const Vec<T, N>>(vertices_[k].data()); }

  // The triangle moved by offset; throws InputError "offset[i]" for a non-finite offset[i],
  // "offset" where a moved vertex leaves the range of T.
  Triangle translated(const Vec<T, N>& offset) const;

private:
  std::array<std::array<T, N>, 3> vertices_;
};
static_assert(detail::has_plain_layout<Triangle<float, 2>, float[6]> &&
              detail::has_plain_layout<Triangle<double, 3>, double[9]>);

template <class T, int N>
Triangle<T, N> make_triangle(const Vec<T, N>& v0, const Vec<T, N>& v1, const Vec<T, N>& v2) {
  return Triangle<T, N>::from_vertices(v0, v1, v2);
}

// separated, touching, overlapping, or a_contains_b (the triangle inside the body).
template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a, const Triangle<T, N>& b, const Options& options = {}) noexcept;

// classify(a, b) != separated.
template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const Triangle<T, N>& b, const Options& options = {}) noexcept;

// Signed distance (distance.hpp's Distance): the separation distance when apart, minus the
// penetration depth (the length of the shortest translation that separates them) when they
// overlap; point_a on the body, point_b = point_a + distance * normal on the triangle's
// supporting plane (on the triangle when apart), normal the body's outward unit normal at
// point_a. Status classify's (overlapping for a_contains_b); iterations the number of
// directions evaluated. Method and accuracy: see "Distance" above.
template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const Triangle<T, N>& b, const Options& options = {}) noexcept;

// As signed_distance(), but overlapping pairs get distance 0 and NaN points and normal.
template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Triangle<T, N>& b, const Options& options = {}) noexcept;

// ---- Gradient (gradient.hpp's parameters for the body) -----------------------------------
//
// signed_distance(a, b) and the derivatives of its distance d: by the body as for two bodies
// (distance.hpp), and by the vertices, from the barycentric weights w of the triangle's point
// y where it touches the body moved by -d n (n the returned normal; the point of the triangle
// nearest to point_b):
//     dd/d v_k = w_k n.
// Differentiable where the maximizing n is unique (distance.hpp) and the triangle is not
// degenerate; for collinear or coincident vertices the weights of y are not unique (one-sided
// derivatives differ), and the fields are those of the nearest of its vertices, edges and face
// (triangle.cpp's seven candidates), an element of the generalized gradient. Accuracy as for
// boxes (box.hpp).
template <class T, int N>
struct TriangleGradient {
  std::array<Vec<T, N>, 3> vertices;
};
static_assert(detail::has_plain_layout<TriangleGradient<float, 2>, float[6]> &&
              detail::has_plain_layout<TriangleGradient<double, 3>, double[9]>);

template <class T, int N>
DistanceGradient<T, N, TriangleGradient<T, N>> signed_distance_gradient(const Ellipsoid<T, N>& a,
                                                                        const Triangle<T, N>& b,
                                                                        const Options& options = {}) noexcept;

// The body moves as center + t * velocity_a, the triangle as vertices + t * velocity_b;
// contact is searched in [0, t_max]. Statuses as for two bodies: invalid_input for a
// non-finite velocity or a NaN or negative t_max; overlapping_at_start (overlap or
// containment at t = 0); touching_at_start (the point is the body's point nearest the
// triangle); hit at the first time in (0, t_max] at which the body touches the triangle,
// with that point and the body's outward unit normal there (from a towards b); otherwise
// no_contact_in_window.
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const Triangle<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

// The body in rigid motion (contact.hpp: turning about its center at a constant angular
// velocity) against the triangle moving at velocity_b, by conservative advancement
// (contact.hpp, "Rigid motion against shapes"); a zero angular velocity gives exactly the
// answer above.
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Triangle<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

}  // namespace ellipsect
