// Walks of a mesh's box hierarchy (mesh.hpp): the triangles whose boxes, grown by a body's
// half-extents, meet a box or a swept segment; and first contact over them. Conservative: boxes are grown by 1e-9 of
// their size, so rounding never drops a triangle the exact tests would reach.
#pragma once

#include <ellipsect/mesh.hpp>

#include "contact_start.hpp"
#include "reduce.hpp"
#include "math.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace ellipsect::detail {

// The walks compute in Work<T> (reduce.hpp: double for float): float boxes and bodies are
// widened there, where the margins below are far above the rounding.

// The body's axis-aligned half-extents, sqrt(sum_k (A_ik r_k)^2), grown by 1e-9 and by the
// tangency band (options.hpp), so that a touching triangle's box is reached; and by 1e-6 for
// float bodies (their axes are orthonormal only to float's rounding).
template <class T, int N>
Vec<Work<T>, N> half_extents(const Ellipsoid<T, N>& a, double tolerance) noexcept {
  using W = Work<T>;
  const W grow = W(1 + 2 * tolerance + 1e-9) + (sizeof(T) < sizeof(double) ? W(1e-6) : W(0));
  Vec<W, N> h;
  for (int i = 0; i < N; ++i) {
    W s = 0;
    for (int k = 0; k < N; ++k) s = std::max(s, abs(W(a.axes()(i, k))) * W(a.radii()[k]));
    W sum = 0;
    for (int k = 0; k < N; ++k) {
      const W x = W(a.axes()(i, k)) * W(a.radii()[k]) / s;
      sum += x * x;
    }
    h[i] = s * sqrt(sum) * grow;
  }
  return h;
}

// The node's box grown by h and by 1e-9 of the box's and h's size, on axis i.
template <class T, int N>
std::pair<Work<T>, Work<T>> grown(const typename TriangleMesh<T, N>::Node& node, const Vec<Work<T>, N>& h,
                                  int i) noexcept {
  using W = Work<T>;
  const W lo = W(node.lo[i]), hi = W(node.hi[i]);
  const W margin = W(1e-9) * (abs(lo) + abs(hi) + h[i]) + std::numeric_limits<W>::denorm_min();
  return {lo - h[i] - margin, hi + h[i] + margin};
}

// Calls visit(k) for each triangle k whose box, grown by h, contains the point c.
template <class T, int N, class Visit>
void for_each_near(const TriangleMesh<T, N>& mesh, const Vec<Work<T>, N>& c, const Vec<Work<T>, N>& h,
                   Visit&& visit) {
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

// Calls visit(k) for the triangles, nearest box first, whose boxes grown by h lie at most
// `bound` from the point c (bound: what visit returns, the least signed distance so far;
// boxes that meet the point's are always visited, as a triangle there can be deeper).
template <class T, int N, class Visit>
void for_each_nearest(const TriangleMesh<T, N>& mesh, const Vec<Work<T>, N>& c, const Vec<Work<T>, N>& h,
                      Visit&& visit) {
  using W = Work<T>;
  const auto nodes = mesh.nodes();
  if (nodes.empty()) return;
  // The distance from c to the node's grown box, -infinity where it contains c.
  const auto gap = [&](std::uint32_t at) {
    W sum = 0;
    for (int i = 0; i < N; ++i) {
      const auto [lo, hi] = grown<T, N>(nodes[at], h, i);
      const W out = std::max({lo - c[i], c[i] - hi, W(0)});
      sum += out * out;
    }
    return sum > W(0) ? sqrt(sum) : -std::numeric_limits<W>::infinity();
  };
  W bound = std::numeric_limits<W>::infinity();
  std::array<std::pair<W, std::uint32_t>, 64> stack;  // (gap, node)
  int top = 0;
  stack[top++] = {gap(0), 0};
  while (top > 0) {
    const auto [g, at] = stack[--top];
    if (g > bound) continue;
    const auto& node = nodes[at];
    if (node.count > 0) {
      for (std::uint32_t j = 0; j < node.count; ++j) bound = visit(mesh.order()[node.first + j]);
      continue;
    }
    std::array<std::pair<W, std::uint32_t>, 2> children{{{gap(at + 1), at + 1}, {gap(node.first), node.first}}};
    if (children[0].first < children[1].first) std::swap(children[0], children[1]);
    for (const auto& child : children) stack[top++] = child;  // the nearer one on top
  }
}

// The interval of t in [0, t_end] at which c + t d lies in the node's box grown by h:
// {entry, exit}, empty when entry > exit.
template <class T, int N>
std::pair<Work<T>, Work<T>> slab(const typename TriangleMesh<T, N>::Node& node, const Vec<Work<T>, N>& c,
                                 const Vec<Work<T>, N>& d, const Vec<Work<T>, N>& h, Work<T> t_end) noexcept {
  using W = Work<T>;
  W entry = 0, exit = t_end;
  for (int i = 0; i < N; ++i) {
    const auto [lo, hi] = grown<T, N>(node, h, i);
    if (d[i] == W(0)) {
      if (c[i] < lo || c[i] > hi) return {W(1), W(0)};
      continue;
    }
    W t1 = (lo - c[i]) / d[i], t2 = (hi - c[i]) / d[i];
    if (t1 > t2) std::swap(t1, t2);
    entry = std::max(entry, t1);
    exit = std::min(exit, t2);
  }
  // The quotients are rounded: widen the interval by 1e-9 of itself.
  const W slack = W(1e-9) * (abs(entry) + abs(exit));
  return {entry - slack, exit + slack};
}

// Calls visit(k) for the triangles whose grown boxes the segment c + t d, t in [0, t_end],
// meets, nearest entry first; visit returns the new t_end (the earliest contact so far), and
// subtrees entered after it are skipped. t_end may be +infinity.
template <class T, int N, class Visit>
void for_each_swept(const TriangleMesh<T, N>& mesh, const Vec<Work<T>, N>& c, const Vec<Work<T>, N>& d,
                    const Vec<Work<T>, N>& h, Work<T> t_end, Visit&& visit) {
  const auto nodes = mesh.nodes();
  if (nodes.empty()) return;
  std::array<std::pair<Work<T>, std::uint32_t>, 64> stack;  // (entry time, node)
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
    std::array<std::pair<Work<T>, std::uint32_t>, 2> children;
    int n = 0;
    for (const std::uint32_t child : {at + 1, node.first}) {
      const auto [e, x] = slab<T, N>(nodes[child], c, d, h, t_end);
      if (e <= x) children[n++] = {e, child};
    }
    if (n == 2 && children[0].first < children[1].first) std::swap(children[0], children[1]);
    for (int k = 0; k < n; ++k) stack[top++] = children[k];  // the nearer one on top
  }
}

// first_contact against a mesh from its triangles' (mesh.hpp): the start relation's triangle
// gives the start answer, answer(k, t_max); else the earliest hit, answer(k, t_end), over the
// triangles whose boxes grown by h the segment c + t d meets (ties: the lowest index), or the
// earliest did_not_converge where no hit comes before it. `still`: nothing moves relative to
// the mesh, so a separated body never meets it.
template <class T, int N, class Answer>
MeshContact<T, N> mesh_contact(const Ellipsoid<T, N>& a, const TriangleMesh<T, N>& mesh, const Options& options,
                               const Vec<Work<T>, N>& d, const Vec<Work<T>, N>& h, T t_max, bool still,
                               Answer&& answer) {
  MeshContact<T, N> out;
  const MeshRelation start = classify(a, mesh, options);
  if (start.relation != Relation::separated) {
    // The triangle's own start answer: overlapping_at_start, or touching_at_start with its
    // point and normal.
    return {answer(static_cast<std::uint32_t>(start.triangle), t_max), start.triangle};
  }
  out.contact = unanswered_contact<T, N>();
  out.contact.status = ContactStatus::no_contact_in_window;
  if (still) return out;
  MeshContact<T, N> failed{out.contact, -1};
  for_each_swept<T, N>(mesh, a.center().template cast<Work<T>>(), d, h, Work<T>(t_max), [&](std::uint32_t k, Work<T> t_end) {
    const Contact<T, N> c = answer(k, T(t_end));
    if (c.status == ContactStatus::did_not_converge && (failed.triangle < 0 || c.time < failed.contact.time))
      failed = {c, k};
    if (c.status != ContactStatus::hit) return t_end;
    if (out.triangle < 0 || c.time < out.contact.time || (c.time == out.contact.time && k < out.triangle)) {
      out.contact = c;
      out.triangle = k;
    }
    return Work<T>(out.contact.time);
  });
  if (failed.triangle >= 0 && (out.triangle < 0 || !(out.contact.time < failed.contact.time))) return failed;
  return out;
}

}  // namespace ellipsect::detail
