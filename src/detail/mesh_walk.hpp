// Walks of a mesh's box hierarchy (mesh.hpp): the triangles whose boxes, grown by a body's
// half-extents, meet a box or a swept segment. Conservative: boxes are grown by 1e-9 of
// their size, so rounding never drops a triangle the exact tests would reach.
#pragma once

#include <ellipsect/mesh.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace ellipsect::detail {

// The body's axis-aligned half-extents, sqrt(sum_k (A_ik r_k)^2), grown by 1e-9 and by the
// tangency band (options.hpp), so that a touching triangle's box is reached.
template <class T, int N>
Vec<T, N> half_extents(const Ellipsoid<T, N>& a, double tolerance) noexcept {
  Vec<T, N> h;
  for (int i = 0; i < N; ++i) {
    T s = 0;
    for (int k = 0; k < N; ++k) s = std::max(s, std::abs(a.axes()(i, k)) * a.radii()[k]);
    T sum = 0;
    for (int k = 0; k < N; ++k) {
      const T x = a.axes()(i, k) * a.radii()[k] / s;
      sum += x * x;
    }
    h[i] = s * std::sqrt(sum) * T(1 + 2 * tolerance + 1e-9);
  }
  return h;
}

// The node's box grown by h and by 1e-9 of the box's and h's size, on axis i.
template <class T, int N>
std::pair<T, T> grown(const typename TriangleMesh<T, N>::Node& node, const Vec<T, N>& h, int i) noexcept {
  const T margin = T(1e-9) * (std::abs(node.lo[i]) + std::abs(node.hi[i]) + h[i]) + std::numeric_limits<T>::denorm_min();
  return {node.lo[i] - h[i] - margin, node.hi[i] + h[i] + margin};
}

// Calls visit(k) for each triangle k whose box, grown by h, contains the point c.
template <class T, int N, class Visit>
void for_each_near(const TriangleMesh<T, N>& mesh, const Vec<T, N>& c, const Vec<T, N>& h, Visit&& visit) {
  const auto nodes = mesh.nodes();
  if (nodes.empty()) return;
  std::array<std::uint32_t, 64> stack;
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const std::uint32_t at = stack[--top];
    const auto& node = nodes[at];
    bool meets = true;
    for (int i = 0; i < N && meets; ++i) {
      const auto [lo, hi] = grown<T, N>(node, h, i);
      meets = c[i] >= lo && c[i] <= hi;
    }
    if (!meets) continue;
    if (node.count > 0) {
      for (std::uint32_t j = 0; j < node.count; ++j) visit(mesh.order()[node.first + j]);
    } else {
      stack[top++] = node.first;
      stack[top++] = at + 1;
    }
  }
}

// The interval of t in [0, t_end] at which c + t d lies in the node's box grown by h:
// {entry, exit}, empty when entry > exit.
template <class T, int N>
std::pair<T, T> slab(const typename TriangleMesh<T, N>::Node& node, const Vec<T, N>& c, const Vec<T, N>& d,
                     const Vec<T, N>& h, T t_end) noexcept {
  T entry = 0, exit = t_end;
  for (int i = 0; i < N; ++i) {
    const auto [lo, hi] = grown<T, N>(node, h, i);
    if (d[i] == T(0)) {
      if (c[i] < lo || c[i] > hi) return {T(1), T(0)};
      continue;
    }
    T t1 = (lo - c[i]) / d[i], t2 = (hi - c[i]) / d[i];
    if (t1 > t2) std::swap(t1, t2);
    entry = std::max(entry, t1);
    exit = std::min(exit, t2);
  }
  // The quotients are rounded: widen the interval by 1e-9 of itself.
  const T slack = T(1e-9) * (std::abs(entry) + std::abs(exit));
  return {entry - slack, exit + slack};
}

// Calls visit(k) for the triangles whose grown boxes the segment c + t d, t in [0, t_end],
// meets, nearest entry first; visit returns the new t_end (the earliest contact so far), and
// subtrees entered after it are skipped. t_end may be +infinity.
template <class T, int N, class Visit>
void for_each_swept(const TriangleMesh<T, N>& mesh, const Vec<T, N>& c, const Vec<T, N>& d, const Vec<T, N>& h, T t_end,
                    Visit&& visit) {
  const auto nodes = mesh.nodes();
  if (nodes.empty()) return;
  std::array<std::pair<T, std::uint32_t>, 64> stack;  // (entry time, node)
  int top = 0;
  const auto [entry0, exit0] = slab<T, N>(nodes[0], c, d, h, t_end);
  if (entry0 > exit0) return;
  stack[top++] = {entry0, 0};
  while (top > 0) {
    const auto [entry, at] = stack[--top];
    if (entry > t_end) continue;
    const auto& node = nodes[at];
    if (node.count > 0) {
      for (std::uint32_t j = 0; j < node.count; ++j) t_end = visit(mesh.order()[node.first + j], t_end);
      continue;
    }
    std::array<std::pair<T, std::uint32_t>, 2> children;
    int n = 0;
    for (const std::uint32_t child : {at + 1, node.first}) {
      const auto [e, x] = slab<T, N>(nodes[child], c, d, h, t_end);
      if (e <= x) children[n++] = {e, child};
    }
    if (n == 2 && children[0].first < children[1].first) std::swap(children[0], children[1]);
    for (int k = 0; k < n; ++k) stack[top++] = children[k];  // the nearer one on top
  }
}

}  // namespace ellipsect::detail
