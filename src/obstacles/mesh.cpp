#include <ellipsect/mesh.hpp>

#include "detail/contact_start.hpp"
#include "detail/instantiate.hpp"
#include "detail/mesh_walk.hpp"
#include "detail/polytope_distance.hpp"
#include "detail/math.hpp"
#include "detail/obstacle_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace ellipsect {
namespace {

constexpr std::size_t leaf_size = 4;

template <class T, int N>
using Node = typename TriangleMesh<T, N>::Node;

// Builds the nodes over order[begin, end) depth first (a node's left child follows it).
template <class T, int N>
void build(std::vector<Node<T, N>>& nodes, std::vector<std::uint32_t>& order, std::size_t begin, std::size_t end,
           const std::vector<std::array<T, N>>& lo, const std::vector<std::array<T, N>>& hi) {
  const std::size_t at = nodes.size();
  nodes.emplace_back();
  Node<T, N> node;
  node.lo.fill(std::numeric_limits<T>::infinity());
  node.hi.fill(-std::numeric_limits<T>::infinity());
  std::array<T, N> c_lo, c_hi;  // bounds of the centroids (as lo + hi)
  c_lo.fill(std::numeric_limits<T>::infinity());
  c_hi.fill(-std::numeric_limits<T>::infinity());
  for (std::size_t j = begin; j < end; ++j)
    for (int i = 0; i < N; ++i) {
      const std::uint32_t k = order[j];
      node.lo[i] = std::min(node.lo[i], lo[k][i]);
      node.hi[i] = std::max(node.hi[i], hi[k][i]);
      c_lo[i] = std::min(c_lo[i], lo[k][i] / 2 + hi[k][i] / 2);
      c_hi[i] = std::max(c_hi[i], lo[k][i] / 2 + hi[k][i] / 2);
    }
  if (end - begin <= leaf_size) {
    node.first = static_cast<std::uint32_t>(begin);
    node.count = static_cast<std::uint32_t>(end - begin);
    nodes[at] = node;
    return;
  }
  int axis = 0;
  for (int i = 1; i < N; ++i)
    if (c_hi[i] - c_lo[i] > c_hi[axis] - c_lo[axis]) axis = i;
  const std::size_t mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(mid),
                   order.begin() + static_cast<std::ptrdiff_t>(end), [&](std::uint32_t x, std::uint32_t y) {
                     const T cx = lo[x][axis] / 2 + hi[x][axis] / 2, cy = lo[y][axis] / 2 + hi[y][axis] / 2;
                     return cx < cy || (cx == cy && x < y);
                   });
  build<T, N>(nodes, order, begin, mid, lo, hi);
  node.first = static_cast<std::uint32_t>(nodes.size());
  node.count = 0;
  build<T, N>(nodes, order, mid, end, lo, hi);
  nodes[at] = node;
}

// The worse of two mesh relations: overlapping (or containment) before touching before
// separated, the lower triangle index among equals.
int rank(Relation r) noexcept {
  return r == Relation::separated ? 0 : r == Relation::touching ? 1 : 2;
}

}  // namespace

template <class T, int N>
TriangleMesh<T, N> TriangleMesh<T, N>::from_arrays(std::span<const T> vertices,
                                                   std::span<const std::int64_t> triangles) {
  constexpr std::size_t limit = std::numeric_limits<std::int32_t>::max();
  if (vertices.size() % N != 0)
    throw InputError("vertices", "length " + std::to_string(vertices.size()) + " is not a multiple of " + std::to_string(N));
  if (triangles.size() % 3 != 0)
    throw InputError("triangles", "length " + std::to_string(triangles.size()) + " is not a multiple of 3");
  if (vertices.size() / N > limit || triangles.size() / 3 > limit)
    throw InputError(vertices.size() / N > limit ? "vertices" : "triangles", "more than 2^31 - 1 entries");
  const std::size_t nv = vertices.size() / N, nt = triangles.size() / 3;
  for (std::size_t v = 0; v < nv; ++v)
    for (int i = 0; i < N; ++i)
      if (!isfinite(vertices[v * N + i]))
        throw InputError("vertices[" + std::to_string(v) + "][" + std::to_string(i) + "]", "must be finite");
  for (std::size_t k = 0; k < nt; ++k)
    for (int j = 0; j < 3; ++j) {
      const std::int64_t index = triangles[k * 3 + j];
      if (index < 0 || static_cast<std::size_t>(index) >= nv)
        throw InputError("triangles[" + std::to_string(k) + "][" + std::to_string(j) + "]",
                         "vertex index " + std::to_string(index) + " is not in [0, " + std::to_string(nv) + ")");
    }
  TriangleMesh mesh;
  mesh.vertices_.assign(vertices.begin(), vertices.end());
  mesh.triangles_.reserve(nt);
  std::vector<std::array<T, N>> lo(nt), hi(nt);
  for (std::size_t k = 0; k < nt; ++k) {
    std::array<Vec<T, N>, 3> v;
    for (int j = 0; j < 3; ++j)
      v[j] = Eigen::Map<const Vec<T, N>>(vertices.data() + static_cast<std::size_t>(triangles[k * 3 + j]) * N);
    mesh.triangles_.push_back(make_triangle<T, N>(v[0], v[1], v[2]));
    for (int i = 0; i < N; ++i) {
      lo[k][i] = std::min({v[0][i], v[1][i], v[2][i]});
      hi[k][i] = std::max({v[0][i], v[1][i], v[2][i]});
    }
  }
  if (nt == 0) return mesh;
  mesh.order_.resize(nt);
  std::iota(mesh.order_.begin(), mesh.order_.end(), std::uint32_t(0));
  mesh.nodes_.reserve(2 * (nt / leaf_size + 1));
  build<T, N>(mesh.nodes_, mesh.order_, 0, nt, lo, hi);
  return mesh;
}

template <class T, int N>
Triangle<T, N> TriangleMesh<T, N>::triangle(std::size_t k) const {
  if (k >= triangles_.size())
    throw InputError("triangle", std::to_string(k) + " is not in [0, " + std::to_string(triangles_.size()) + ")");
  return triangles_[k];
}

template <class T, int N>
MeshRelation classify(const Ellipsoid<T, N>& a, const TriangleMesh<T, N>& b, const Options& options) noexcept {
  MeshRelation out;
  const std::size_t count = b.triangle_count();
  if (count == 0) return out;
  using W = detail::Work<T>;
  std::size_t contained = 0;
  detail::for_each_near<T, N>(b, a.center().template cast<W>(), detail::half_extents(a, options.tolerance),
                              [&](std::uint32_t k) {
    Relation r = classify(a, b.triangle(k), options);
    if (r == Relation::a_contains_b) {
      ++contained;
      r = Relation::overlapping;
    }
    if (rank(r) > rank(out.relation) || (rank(r) == rank(out.relation) && r != Relation::separated && k < out.triangle))
      out = {r, k};
  });
  if (contained == count) return {Relation::a_contains_b, 0};
  return out;
}

template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const TriangleMesh<T, N>& b, const Options& options) noexcept {
  return classify(a, b, options).relation != Relation::separated;
}

template <class T, int N>
MeshContact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const TriangleMesh<T, N>& b,
                                const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  if (!detail::valid_motion<T, N>(velocity_a, velocity_b, t_max)) return {detail::unanswered_contact<T, N>(), -1};
  using W = detail::Work<T>;
  const Vec<W, N> d = velocity_a.template cast<W>() - velocity_b.template cast<W>();
  // A triangle whose closed form failed its check (triangle.hpp: did_not_converge) leaves the
  // answer open from its time on: reported unless a hit comes first.
  return detail::mesh_contact<T, N>(a, b, options, d, detail::half_extents(a, options.tolerance), t_max,
                                    d == Vec<W, N>::Zero(), [&](std::uint32_t k, T t_end) {
    return first_contact(a, velocity_a, b.triangle(k), velocity_b, t_end, options);
  });
}

template <class T, int N>
MeshDistance<T, N> signed_distance(const Ellipsoid<T, N>& a, const TriangleMesh<T, N>& b, const Options& options) noexcept {
  MeshDistance<T, N> out;
  out.distance.status = DistanceStatus::separated;
  out.distance.distance = std::numeric_limits<T>::infinity();
  out.distance.point_a = out.distance.point_b = out.distance.normal = detail::nan_vec<T, N>();
  if (b.triangle_count() == 0) return out;
  using W = detail::Work<T>;
  detail::for_each_nearest<T, N>(b, a.center().template cast<W>(), detail::half_extents(a, options.tolerance),
                                 [&](std::uint32_t k) {
    const Distance<T, N> d = signed_distance(a, b.triangle(k), options);
    if (out.triangle < 0 || d.distance < out.distance.distance ||
        (d.distance == out.distance.distance && k < out.triangle)) {
      out.distance = d;
      out.triangle = k;
    }
    return W(out.distance.distance);
  });
  // The status is the mesh's relation (classify); the fields those of the triangle found.
  out.distance.status = detail::distance_status(classify(a, b, options).relation);
  return out;
}

template <class T, int N>
MeshDistance<T, N> distance(const Ellipsoid<T, N>& a, const TriangleMesh<T, N>& b, const Options& options) noexcept {
  MeshDistance<T, N> out = signed_distance(a, b, options);
  out.distance = detail::unsigned_distance(out.distance);
  return out;
}

// Under rigid motion (detail/obstacle_motion.hpp): each candidate triangle by its own
// advancement.
template <class T, int N>
MeshContact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a,
                                const TriangleMesh<T, N>& b, const VecArg<T, N>& velocity_b, T t_max,
                                const Options& options) noexcept {
  using detail::rigid::R;
  if (!detail::obstacle::valid_rigid<T, N>(motion_a, velocity_b, t_max))
    return {detail::unanswered_contact<T, N>(), -1};
  if (detail::rigid::magnitude<N>(motion_a.angular_velocity) == R(0) && motion_a.growth == T(0))
    return first_contact(a, motion_a.velocity, b, velocity_b, t_max, options);
  // The candidates: triangles whose boxes the body's bounding ball (radius R at the window's
  // end, grown by the tangency band and 1e-9) meets along its center's path relative to the
  // mesh; each by its own advancement.
  using W = detail::Work<T>;
  const W grown = motion_a.growth == T(0) ? W(1) : 1 + W(motion_a.growth) * W(t_max);
  const W reach = W(a.radii().maxCoeff()) * grown * (1 + 2 * W(double(options.tolerance)) + W(1e-9)) *
                  (sizeof(T) < sizeof(double) ? W(1 + 1e-6) : W(1));
  return detail::mesh_contact<T, N>(a, b, options, (motion_a.velocity - velocity_b).template cast<W>(),
                                    Vec<W, N>::Constant(reach), t_max, false, [&](std::uint32_t k, T t_end) {
    return first_contact(a, motion_a, b.triangle(k), velocity_b, t_end, options);
  });
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                      \
  template MeshContact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&,                       \
                                                 const TriangleMesh<T, N>&, const VecArg<T, N>&, T,                     \
                                                 const Options&) noexcept;                                              \
  template class TriangleMesh<T, N>;                                                                                     \
  template MeshRelation classify<T, N>(const Ellipsoid<T, N>&, const TriangleMesh<T, N>&, const Options&) noexcept;    \
  template bool overlap<T, N>(const Ellipsoid<T, N>&, const TriangleMesh<T, N>&, const Options&) noexcept;             \
  template MeshContact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const VecArg<T, N>&, const TriangleMesh<T, N>&, \
                                                 const VecArg<T, N>&, T, const Options&) noexcept;          \
  template MeshDistance<T, N> signed_distance<T, N>(const Ellipsoid<T, N>&, const TriangleMesh<T, N>&,                  \
                                                    const Options&) noexcept;                                            \
  template MeshDistance<T, N> distance<T, N>(const Ellipsoid<T, N>&, const TriangleMesh<T, N>&, const Options&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
