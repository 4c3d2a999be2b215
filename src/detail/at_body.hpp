// A body and a shape moved by minus the body's center: the body at the origin (exactly),
// the shape's points at their differences from that center, rounded once. Points the shape
// computes from those (a box's corners, a capsule's segment moved along its motion) are then
// rounded to ulps of the pair's extent rather than of its coordinates (1e6 sizes from the
// origin, gaps were 1e-10 of the size off), and every query of the pair sees the same
// rounded pair (classify and first_contact's start agree). Left in place where a difference
// overflows; points of the moved pair plus `shift` are the world's.
#pragma once

#include <ellipsect/shapes.hpp>

namespace ellipsect::detail {

template <class T, int N, class Shape>
struct AtBody {
  Ellipsoid<T, N> a;
  Shape b;
  Vec<T, N> shift = Vec<T, N>::Zero();

  // `points`: the shape's stored points, whose differences from the body's center must be finite.
  template <class... Points>
  AtBody(const Ellipsoid<T, N>& a_world, const Shape& b_world, const Points&... points) noexcept
      : a(a_world), b(b_world) {
    const Vec<T, N> c = a_world.center();
    if (c.isZero(0) || !(Vec<T, N>(points - c).allFinite() && ...)) return;
    a = a_world.translated(-c);  // no throw: the moved points are finite
    b = b_world.translated(-c);
    shift = c;
  }
};

}  // namespace ellipsect::detail
