// Ellipses and ellipsoids against triangle meshes: relation and swept first contact, each
// with the triangle that decides it, over a bounding-volume hierarchy.
//
// A mesh is a set of triangles (triangle.hpp) sharing vertices: a surface, not a solid; a
// body overlaps it when it overlaps one of its triangles (a body wholly inside a closed
// mesh's volume is separated from it). Its triangles may be degenerate, may intersect each
// other and need not be connected or consistently oriented.
//
// Hierarchy. Built once, at construction: an axis-aligned box tree over the triangles, split
// top-down at the median of the triangles' centroids along the longest axis of their
// bounds, at most 4 triangles per leaf (O(F log F) time, 2F / 4 nodes). It is written here
// rather than taken from a library: Debian's candidates (FCL's and Coal's BVHModel, CGAL's
// AABB_tree) answer their own queries and would need the ellipsoid's box test and swept
// test written against their interfaces anyway, and bring large dependencies into a
// library that otherwise needs only Eigen and Highway. A query visits the nodes whose
// boxes, grown by the body's axis-aligned half-extents, meet the body's box (classify) or
// the segment its center sweeps relative to the mesh (first_contact; nearest entry first,
// pruned by the earliest contact found so far); the boxes are grown by 1e-9 of their size
// so that rounding never prunes a triangle that the exact test would touch. The answers
// are those of the triangles' own queries (triangle.hpp), with their accuracy.
#pragma once

#include <ellipsect/triangle.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace ellipsect {

template <class T, int N>
class TriangleMesh {
public:
  TriangleMesh() = default;  // no triangles

  // vertices: N coordinates per vertex, row after row; triangles: three vertex indices per
  // triangle. Throws InputError naming "vertices" or "triangles" (a length that is not a
  // multiple of N or 3, more than 2^31 - 1 entries), "vertices[i][j]" (not finite) or
  // "triangles[k][j]" (an index outside the vertices).
  static TriangleMesh from_arrays(std::span<const T> vertices, std::span<const std::int64_t> triangles);

  std::size_t vertex_count() const noexcept { return vertices_.size() / N; }
  // The vertices as given: N coordinates per vertex, row after row.
  std::span<const T> vertices() const noexcept { return vertices_; }
  std::size_t triangle_count() const noexcept { return triangles_.size(); }
  // Triangle k (InputError "triangle" when k is out of range).
  Triangle<T, N> triangle(std::size_t k) const;

  // The hierarchy, for the queries: node boxes and leaves' ranges in `order`.
  struct Node {
    std::array<T, N> lo, hi;
    std::uint32_t first;  // leaf: first index into order; inner: the right child (the left is next)
    std::uint32_t count;  // leaf: number of triangles (> 0); inner: 0
  };
  std::span<const Node> nodes() const noexcept { return nodes_; }
  std::span<const std::uint32_t> order() const noexcept { return order_; }

private:
  std::vector<T> vertices_;
  std::vector<Triangle<T, N>> triangles_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;
};

template <class T, int N>
TriangleMesh<T, N> make_triangle_mesh(std::span<const T> vertices, std::span<const std::int64_t> triangles) {
  return TriangleMesh<T, N>::from_arrays(vertices, triangles);
}

// The body against the whole mesh: overlapping when it overlaps or contains some triangle
// (a_contains_b when it contains all of them), else touching when it touches some, else
// separated. `triangle` is the lowest index of a triangle with that relation (-1 when
// separated).
struct MeshRelation {
  Relation relation = Relation::separated;
  std::int64_t triangle = -1;
};
static_assert(detail::has_plain_layout<MeshRelation, Relation, std::int64_t>);

template <class T, int N>
MeshRelation classify(const Ellipsoid<T, N>& a, const TriangleMesh<T, N>& b, const Options& options = {}) noexcept;

template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const TriangleMesh<T, N>& b, const Options& options = {}) noexcept;

// first_contact of the body against every triangle, the mesh moving as a whole with
// velocity_b: the start relation as classify's (overlapping_at_start, touching_at_start with
// that triangle's point and normal), else the earliest hit over the triangles (ties: the
// lowest index) with its triangle; -1 with no_contact_in_window and invalid_input;
// did_not_converge with its triangle where a triangle's closed form failed its check
// (triangle.hpp) no later than the earliest hit.
template <class T, int N>
struct MeshContact {
  Contact<T, N> contact;
  std::int64_t triangle = -1;
};
static_assert(detail::has_plain_layout<MeshContact<float, 2>, Contact<float, 2>, std::int64_t> &&
              detail::has_plain_layout<MeshContact<double, 3>, Contact<double, 3>, std::int64_t>);

template <class T, int N>
MeshContact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const TriangleMesh<T, N>& b,
                                const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

// The body in rigid motion (contact.hpp: turning about its center at a constant angular
// velocity) against the mesh moving at velocity_b: the start relation as above, else the
// earliest hit over the triangles whose boxes the body's bounding ball (radius R) meets along
// its center's path, each by conservative advancement (contact.hpp, "Rigid motion against
// shapes"); ties, triangle and did_not_converge as above. A zero angular velocity gives
// exactly the answer above.
template <class T, int N>
MeshContact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const TriangleMesh<T, N>& b,
                                const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

// The signed distance of the body and the mesh: the least over the triangles of their signed
// distance (triangle.hpp), with its triangle (ties: the lowest index). Apart, the distance to
// the mesh; overlapping, minus the largest penetration depth into one triangle (a mesh is a
// set of triangles, not a solid: no depth through it as a whole is defined). The status is
// classify's for the whole mesh. No triangles: separated, distance +infinity, NaN points and
// normal, triangle -1. Triangles are visited nearest box first; those whose boxes lie
// farther than the best so far are skipped.
template <class T, int N>
struct MeshDistance {
  Distance<T, N> distance;
  std::int64_t triangle = -1;
};
static_assert(detail::has_plain_layout<MeshDistance<float, 2>, Distance<float, 2>, std::int64_t> &&
              detail::has_plain_layout<MeshDistance<double, 3>, Distance<double, 3>, std::int64_t>);

template <class T, int N>
MeshDistance<T, N> signed_distance(const Ellipsoid<T, N>& a, const TriangleMesh<T, N>& b,
                                   const Options& options = {}) noexcept;

// As signed_distance(), with distance 0 and NaN points and normal where the body overlaps the
// mesh.
template <class T, int N>
MeshDistance<T, N> distance(const Ellipsoid<T, N>& a, const TriangleMesh<T, N>& b, const Options& options = {}) noexcept;

}  // namespace ellipsect
