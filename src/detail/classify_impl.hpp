// Classification in the reduced frame: S is the unit ball at the origin, O the
// axis-aligned ellipsoid (center k, semi-axes e).
//
//   origin outside O:  gap = |closest point of O| - 1 decides separated / touching;
//                      a deeper pair is O-inside-S when O's farthest point has norm <= 1.
//   origin inside O:   S is inside O when O's boundary is at least 1 away from the origin,
//                      O is inside S when its farthest point is within 1; both: equal.
//
// Every comparison with 1 allows the relative band `tol` (Options::tolerance): scaling S
// about its center by (1 + gap) makes it touch O, and the Perram-Wertheim factor mu of
// the pair satisfies |mu - 1| <= |gap|, so the band bounds mu too.
#pragma once

#include <ellipsect/classify.hpp>

#include "reduce.hpp"
#include "secular.hpp"
#include "math.hpp"

#include <limits>

namespace ellipsect::detail {

enum class ReducedRelation { separated, touching, overlapping, s_contains_o, o_contains_s, equal };

// The relation a nonzero code of classify's certificates stands for (certificates-inl.hpp:
// -1 separated, +1 overlapping, +2 a contains b, +3 b contains a).
inline Relation certified_relation(double code) noexcept {
  return code < 0 ? Relation::separated
         : code == 1 ? Relation::overlapping
         : code == 2 ? Relation::a_contains_b
                     : Relation::b_contains_a;
}

// Bit-identical data: the same set, so `equal` without reduction. Reducing a body onto
// itself would see its axes' rounding (orthonormal to ~eps, ~1e-7 for float data) times
// its aspect ratio, which leaves the tangency band from aspect ~1e4 (double) or at once
// (float).
template <class T, int N>
bool identical(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b) noexcept {
  return a.center() == b.center() && a.radii() == b.radii() && a.axes() == b.axes();
}

// The reduction with O's center settled (detail::settled): moving O by at most eps e_max
// changes every reduced distance by no more than e's own rounding (reduced_rounding allows
// 32 times that).
template <class R, int N, class T>
Reduced<R, N> reduce_settled(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o) noexcept {
  Reduced<R, N> r = reduce<R>(s, o);
  r.k = settled<R, N>(r.e, r.k);
  return r;
}

// Whether S and O share a point, decided by classify_reduced's own comparisons (S's center
// inside O, then the gap against the band's outer edge) only where each lies beyond
// `rounding` of its threshold: +1 they do, -1 they do not, 0 undecided (the caller then
// takes classify's decision, so overlap == (classify != separated)).
template <class R, int N>
int overlap_reduced(const Vec<R, N>& e, const Vec<R, N>& k, R tol, R rounding) noexcept {
  const R q0 = level_at_origin(e, k);
  if (!(abs(q0) > rounding)) return 0;
  if (q0 < R(0)) return 1;
  const R gap = closest_from_outside(e, k).norm - R(1);
  if (!(abs(gap - tol) > rounding)) return 0;
  return gap <= tol ? 1 : -1;
}

// `margin` receives the smallest distance of a compared quantity from its threshold: a
// caller whose rounding error may exceed it re-decides in a wider type.
template <class R, int N>
ReducedRelation classify_reduced(const Vec<R, N>& e, const Vec<R, N>& k, R tol, R& margin) noexcept {
  margin = std::numeric_limits<R>::infinity();
  auto le = [&](R x, R threshold) {
    margin = std::min(margin, abs(x - threshold));
    return x <= threshold;
  };
  auto ge = [&](R x, R threshold) {
    margin = std::min(margin, abs(x - threshold));
    return x >= threshold;
  };
  const R q0 = level_at_origin(e, k);
  margin = abs(q0);
  if (q0 > R(0)) {
    const R d = closest_from_outside(e, k).norm;
    if (!le(d, R(1) + tol)) return ReducedRelation::separated;
    if (!le(d, R(1) - tol)) return ReducedRelation::touching;
    return le(farthest(e, k).norm, R(1) + tol) ? ReducedRelation::s_contains_o : ReducedRelation::overlapping;
  }
  const bool s_in_o = ge(closest_from_inside(e, k).norm, R(1) - tol);
  const bool o_in_s = le(farthest(e, k).norm, R(1) + tol);
  if (s_in_o && o_in_s) return ReducedRelation::equal;
  if (s_in_o) return ReducedRelation::o_contains_s;
  if (o_in_s) return ReducedRelation::s_contains_o;
  return ReducedRelation::overlapping;
}

// Rounding of reduced-frame distances: the SVD and the frame change carry about `ulps`
// ulps relative to |k|, O's largest semi-axis and the centers' offset in S units (k =
// to_z (c_o - c_s), the offset rounded once: the pair's place in the world does not count).
inline constexpr int reduced_frame_ulps = 32;

template <class R, int N, class T>
R reduced_rounding(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, const Vec<R, N>& e, const Vec<R, N>& k) noexcept {
  const R offset = Vec<R, N>(o.center().template cast<R>() - s.center().template cast<R>()).norm();
  return R(reduced_frame_ulps) * std::numeric_limits<R>::epsilon() *
         (k.norm() + e.maxCoeff() + offset / R(s.radii().minCoeff()));
}

}  // namespace ellipsect::detail
