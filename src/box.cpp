#include <ellipsect/box.hpp>
#include <ellipsect/half_space.hpp>

#include "detail/contact_start.hpp"
#include "detail/instantiate.hpp"
#include "detail/polytope_distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace ellipsect {

template <class T, int N>
Box<T, N> Box<T, N>::from_axes(const Vec<T, N>& center, const Mat<T, N>& axes, const Vec<T, N>& half_extents) {
  try {
    return Box(Ellipsoid<T, N>::from_axes(center, axes, half_extents));
  } catch (const InputError& e) {
    // The body's checks name its radii: here they are the half extents.
    std::string field = e.field();
    if (field.starts_with("radii")) field.replace(0, 5, "half_extents");
    const std::string prefix = "ellipsect: " + e.field() + ": ";
    const std::string what = e.what();
    throw InputError(field, what.starts_with(prefix) ? what.substr(prefix.size()) : what);
  }
}

template <class T, int N>
Vec<T, N> Box<T, N>::corner(int k) const noexcept {
  Vec<T, N> x = center();
  for (int i = 0; i < N; ++i) x += ((k >> i) & 1 ? T(1) : T(-1)) * half_extents()[i] * axes().col(i);
  return x;
}

template <class T, int N>
std::array<Triangle<T, N>, N == 2 ? 2 : 12> Box<T, N>::triangles() const noexcept {
  std::array<Vec<T, N>, 1 << N> corners;  // each computed once, shared by its triangles
  for (int k = 0; k < (1 << N); ++k) corners[k] = corner(k);
  const auto tri = [&](int p, int q, int r) { return make_triangle<T, N>(corners[p], corners[q], corners[r]); };
  if constexpr (N == 2) {
    return {tri(0, 1, 3), tri(0, 3, 2)};
  } else {
    // Each face: the corners with bit i fixed, split along a diagonal.
    std::array<Triangle<T, N>, 12> out;
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      for (const int side : {0, 1}) {
        const int base = side << i;
        const int p = base, q = base | (1 << j), r = base | (1 << j) | (1 << k), s = base | (1 << k);
        out[n++] = tri(p, q, r);
        out[n++] = tri(p, r, s);
      }
    }
    return out;
  }
}

template <class T, int N>
Box<T, N> Box<T, N>::translated(const Vec<T, N>& offset) const {
  return Box(frame_.translated(offset));
}

namespace {

// The relation from the triangles' (box.hpp, "Math"), and the index of the triangle that
// decides touching or overlapping (-1 when none does: containment or the center inside).
template <class T, int N, class Triangles>
std::pair<Relation, int> relation_of(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Triangles& triangles,
                                     const Options& options) {
  int contained = 0, overlapping = -1, touching = -1;
  for (int k = 0; k < int(triangles.size()); ++k) {
    const Relation r = classify(a, triangles[std::size_t(k)], options);
    contained += r == Relation::a_contains_b;
    if ((r == Relation::overlapping || r == Relation::a_contains_b) && overlapping < 0) overlapping = k;
    if (r == Relation::touching && touching < 0) touching = k;
  }
  if (contained == int(triangles.size())) return {Relation::a_contains_b, -1};
  bool center_inside = true;
  const Vec<T, N> local = b.axes().transpose() * Vec<T, N>(a.center() - b.center());
  for (int i = 0; i < N; ++i) center_inside = center_inside && std::abs(local[i]) <= b.half_extents()[i];
  if (overlapping < 0 && !center_inside) return {touching < 0 ? Relation::separated : Relation::touching, touching};
  // The body meets the box: inside it when inside each face's half-space.
  for (int i = 0; i < N; ++i)
    for (const T side : {T(-1), T(1)}) {
      const Vec<T, N> normal = side * b.axes().col(i);
      const Vec<T, N> point = b.center() + b.half_extents()[i] * normal;
      if (classify(a, make_half_space<T, N>(point, normal), options) != Relation::b_contains_a)
        return {Relation::overlapping, overlapping};
    }
  return {Relation::b_contains_a, -1};
}

}  // namespace

template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options) noexcept {
  return relation_of(a, b, b.triangles(), options).first;
}

template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options) noexcept {
  return classify(a, b, options) != Relation::separated;
}

template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const Box<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  Contact<T, N> out = detail::unanswered_contact<T, N>();
  if (!detail::valid_motion<T, N>(velocity_a, velocity_b, t_max)) return out;
  const auto triangles = b.triangles();
  const auto [relation, triangle] = relation_of(a, b, triangles, options);
  if (relation == Relation::touching)
    return first_contact(a, velocity_a, triangles[std::size_t(triangle)], velocity_b, t_max, options);
  if (relation != Relation::separated) {
    out.status = ContactStatus::overlapping_at_start;
    out.time = T(0);
    return out;
  }
  out.status = ContactStatus::no_contact_in_window;
  for (const auto& t : triangles) {
    const Contact<T, N> c = first_contact(a, velocity_a, t, velocity_b, t_max, options);
    if (c.status == ContactStatus::hit && !(c.time >= out.time)) out = c;
  }
  return out;
}

template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options) noexcept {
  constexpr int count = 1 << N;
  std::array<Vec<T, N>, count> corners;
  for (int k = 0; k < count; ++k) corners[k] = b.corner(k);
  // Edges: corners differing in one bit; faces (3D): three corners with bit i fixed.
  std::array<std::array<int, 2>, N * count / 2> edges;
  std::array<std::array<int, 3>, 2 * N> faces;
  int e = 0;
  for (int i = 0; i < N; ++i) {
    for (int k = 0; k < count; ++k)
      if (!((k >> i) & 1)) edges[e++] = {k, k | (1 << i)};
    const int j = (i + 1) % N, l = (i + 2) % N;
    for (int side = 0; side < 2; ++side) {
      const int base = side << i;
      faces[2 * i + side] = {base, base | (1 << j), base | (1 << l)};
    }
  }
  return detail::polytope_signed_distance<T, N>(a, corners, edges,
                                                std::span<const std::array<int, 3>>(faces.data(), N == 3 ? faces.size() : 0),
                                                classify(a, b, options));
}

template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options) noexcept {
  return detail::unsigned_distance(signed_distance(a, b, options));
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                  \
  template class Box<T, N>;                                                                                         \
  template Relation classify<T, N>(const Ellipsoid<T, N>&, const Box<T, N>&, const Options&) noexcept;            \
  template bool overlap<T, N>(const Ellipsoid<T, N>&, const Box<T, N>&, const Options&) noexcept;                 \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const VecArg<T, N>&, const Box<T, N>&,       \
                                             const VecArg<T, N>&, T, const Options&) noexcept;       \
  template Distance<T, N> signed_distance<T, N>(const Ellipsoid<T, N>&, const Box<T, N>&, const Options&) noexcept; \
  template Distance<T, N> distance<T, N>(const Ellipsoid<T, N>&, const Box<T, N>&, const Options&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
