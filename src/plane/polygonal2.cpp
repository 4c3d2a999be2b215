// Niemitalo's polygon bisection (docs/niemitalo.md). Differences from the document's code:
//
// * Out of levels is `undecided`, with the certified band of the signed gap, never `false`.
// * The document's bisection shortcuts (a center on the inner side of a new chord counts
//   as a collision; a sub-triangle is chosen by projections onto the tangent at the new
//   vertex) are exact in the folded frame of an axis-aligned ellipse (bisect_folded, with
//   touching counted as meeting), but not on the conjugate semi-diameters that the
//   document's non-parallel ellipse-ellipse test bisects, where they report collisions
//   between separated ellipses (tests/unit/polygonal2_test.cpp has one). There ellipsect
//   finds the stretched ellipse's own axes (principal_frame: three square roots, two divisions)
//   and runs the folded test in them.
// * Everything runs in T (the document mixes float into the double non-parallel test,
//   which overflows for scenes of size 1e6), on inputs scaled by a power of two.
// * The non-parallel stretch omits the document's final rotation back (an isometry, so
//   the circle stays a circle): A = diag(h_b, w_b) Q_b^T instead of Q_b diag(h_b, w_b) Q_b^T.
#include <ellipsect/polygonal2.hpp>

#include "detail/instantiate.hpp"
#include "detail/niemitalo_polygon.hpp"
#include "detail/scale.hpp"
#include "detail/shape_access.hpp"
#include "detail/show.hpp"
#include "detail/math.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace ellipsect {

std::string_view to_string(Verdict v) noexcept {
  switch (v) {
    case Verdict::collision: return "collision";
    case Verdict::no_collision: return "no_collision";
    case Verdict::undecided: return "undecided";
    case Verdict::invalid_input: return "invalid_input";
  }
  return "unknown";
}

std::string_view to_string(Side s) noexcept {
  switch (s) {
    case Side::left: return "left";
    case Side::on_line: return "on_line";
    case Side::right: return "right";
  }
  return "unknown";
}

namespace {

using detail::unit_scale;

// Points of the test's frame (plain scalars: this is the inner loop).
template <class T>
struct Pt {
  T x, y;
  friend Pt operator+(Pt a, Pt b) noexcept { return {a.x + b.x, a.y + b.y}; }
  friend Pt operator-(Pt a, Pt b) noexcept { return {a.x - b.x, a.y - b.y}; }
  friend Pt operator-(Pt a) noexcept { return {-a.x, -a.y}; }
  friend Pt operator*(T k, Pt a) noexcept { return {k * a.x, k * a.y}; }
};

template <class T>
T dot(Pt<T> u, Pt<T> v) noexcept {
  return u.x * v.x + u.y * v.y;
}

template <class T>
T cross(Pt<T> u, Pt<T> v) noexcept {
  return u.x * v.y - u.y * v.x;
}

// The query disk in the frame of the test: center p, squared radius rr.
template <class T>
struct Disk {
  Pt<T> p;
  T rr;
};

// What a test found, before the band is attached.
struct Outcome {
  Verdict verdict;
  int level;       // deepest level examined
  int iterations;  // bisections performed
};

// The document's segment test. Moving a to the origin and multiplying by conj(b - a)
// puts the segment on [0, |b - a|^2] of the x axis and the center at (proj, cross); the
// radius becomes r |b - a|. `side` > 0: the center is left of a -> b.
template <class T>
bool meets_segment(const Disk<T>& d, Pt<T> a, Pt<T> b, T& side) noexcept {
  const Pt<T> e = b - a, q = d.p - a;
  const T len2 = dot(e, e);
  side = cross(e, q);
  if (side * side > d.rr * len2) return false;  // farther from the line than r
  const Pt<T> qb = d.p - b;
  if (dot(q, q) <= d.rr || dot(qb, qb) <= d.rr) return true;
  const T proj = dot(e, q);
  return len2 > T(0) && proj >= T(0) && proj <= len2;
}

template <class T>
bool meets_segment(const Disk<T>& d, Pt<T> a, Pt<T> b) noexcept {
  T side;
  return meets_segment(d, a, b, side);
}

// p in the closed counter-clockwise triangle (a, b, c).
template <class T>
bool inside(Pt<T> p, Pt<T> a, Pt<T> b, Pt<T> c) noexcept {
  return cross(b - a, p - a) >= T(0) && cross(c - b, p - b) >= T(0) && cross(a - c, p - c) >= T(0);
}

// The disk meets the chord from c1 to c1 + e, given that it misses both ends, or its
// center is within the chord's extent on the side `inner` (+1: left of e, -1: right).
template <class T>
bool meets_chord_or_inside(const Disk<T>& d, Pt<T> u, Pt<T> e, T inner) noexcept {
  const T proj = dot(u, e), len2 = dot(e, e);
  if (proj < T(0) || proj > len2) return false;
  const T side = inner * cross(e, u);
  return side >= T(0) || side * side <= d.rr * len2;
}

// The bisection of quadrant_test: the arc (c0, c2) of an axis-aligned ellipse in the first
// quadrant, where both coordinates are monotonic along the arc, and the disk's center p in
// that quadrant. The disk meets the live triangle (c0, V, c2) and misses the polygon of
// level t - 1. There the document's iteration is exact (docs/niemitalo.md, "The folded
// bisection"):
// * p within a new chord's extent and on its inner side lies in the polygon (whose part in
//   the quadrant is closed under decreasing either coordinate); with c1 tested, this and
//   the two chords cover the triangle (c0, c1, c2), whose angle at c1 is obtuse.
// * Otherwise, with t3 = c3 - c1 along the tangent at c1: a disk wholly beyond that
//   tangent misses both sub-triangles; else p projecting into [c1, c3] means the disk
//   meets (c0, c3, c1), beyond c3 it does iff p projects onto the tangent at c0 on c0's
//   side of c3 (or contains c3); the same with c4 and c2 on the other side.
template <class T>
[[gnu::always_inline]] inline Outcome bisect_folded(const Disk<T>& d, Pt<T> c0, Pt<T> c2, int max_level) noexcept {
  const auto& k = detail::niemitalo_coefficients<T>();
  for (int t = 1; t <= max_level; ++t) {
    const Pt<T> c1 = k.inner[t] * (c0 + c2);
    const Pt<T> u = d.p - c1;
    if (dot(u, u) <= d.rr || meets_chord_or_inside(d, u, c2 - c1, T(1)) || meets_chord_or_inside(d, u, c0 - c1, T(-1)))
      return {Verdict::collision, t, t};
    const Pt<T> c3 = k.outer[t] * (c0 + c1);
    const Pt<T> c4 = (c1 - c3) + c1;
    const Pt<T> p3 = d.p - c3, p4 = d.p - c4, t3 = c3 - c1;
    const T side = cross(t3, u), len2 = dot(t3, t3), proj = dot(u, t3);
    if (dot(p3, p3) <= d.rr)
      c2 = c1;
    else if (dot(p4, p4) <= d.rr)
      c0 = c1;
    else if (side > T(0) && side * side > d.rr * len2)
      return {Verdict::no_collision, t, t};
    else if (proj > T(0) && (proj <= len2 || dot(p3, c0 - c3) >= T(0)))
      c2 = c1;
    else if (proj <= T(0) && (-proj <= len2 || dot(p4, c2 - c4) >= T(0)))
      c0 = c1;
    else
      return {Verdict::no_collision, t, t};
  }
  return {Verdict::undecided, max_level, max_level};
}

// Axis-aligned ellipse (w, h) with the center folded into the first quadrant (the ellipse
// is symmetric about both axes, so its point nearest to the center stays there): level 0
// is the edge (w, 0) -> (0, h) of the inscribed rhombus and the box [0, w] x [0, h].
template <class T>
bool level_zero_collides(const Disk<T>& d, T w, T h) noexcept {
  T side;
  return meets_segment(d, {w, 0}, {0, h}, side) || side >= T(0);  // an edge, or the center inside
}

// An ellipse within eps_T of the scene's size (the scaled scene's is in [1, 2)) lies inside
// the rounding allowance rho of its center (rho >= 32 eps_T there), and its squared sizes
// would underflow (a float ellipse of radius 3e-23 at 1.4 from a unit circle read as a
// collision): it is tested as its center, exactly, at level 0.
template <class T>
bool point_like(T w, T h) noexcept {
  return std::max(w, h) <= std::numeric_limits<T>::epsilon();
}

template <class T>
Outcome point_test(const Disk<T>& d) noexcept {
  return {dot(d.p, d.p) <= d.rr ? Verdict::collision : Verdict::no_collision, 0, 0};
}

template <class T>
[[gnu::always_inline]] inline Outcome quadrant_test(const Disk<T>& d, T w, T h, int max_level) noexcept {
  // A disk that misses the box [0, w] x [0, h] misses the rhombus inside it (most pairs
  // apart: decided before the edge test); missing the rhombus, the disk meets the enclosing
  // triangle iff it meets the box.
  const T dx = std::max(d.p.x - w, T(0)), dy = std::max(d.p.y - h, T(0));
  if (dx * dx + dy * dy > d.rr) return {Verdict::no_collision, 0, 0};
  if (level_zero_collides(d, w, h)) return {Verdict::collision, 0, 0};
  return bisect_folded(d, {w, 0}, {0, h}, max_level);
}

// The folded frame of the ellipse with conjugate semi-diameters u, v: its semi-axes w >= h
// and the disk's center p turned into its axes and folded. The shape matrix u u^T + v v^T =
// [[a, b], [b, c]] has eigenvalues m +- g (m = (a + c) / 2, g = |((a - c) / 2, b)|); the
// larger, w^2, has the eigenvector (w^2 - c, b) when a >= c, else (b, w^2 - a), both free
// of cancellation; h = |cross(u, v)| / w (w h is the area's factor), whose rounding is
// eps |u| |v| / w <= eps w absolute. A circle (g = 0) keeps the x axis.
template <class T>
struct Folded {
  Disk<T> d;
  T w, h;
};

template <class T>
Folded<T> principal_frame(const Disk<T>& d, Pt<T> u, Pt<T> v) noexcept {
  const T a = u.x * u.x + v.x * v.x, b = u.x * u.y + v.x * v.y, c = u.y * u.y + v.y * v.y;
  const T half_gap = T(0.5) * (a - c);
  const T g = sqrt(half_gap * half_gap + b * b);
  const T w2 = T(0.5) * (a + c) + g;
  Pt<T> e = a >= c ? Pt<T>{w2 - c, b} : Pt<T>{b, w2 - a};
  const T len = sqrt(dot(e, e));
  e = len > T(0) ? (T(1) / len) * e : Pt<T>{T(1), T(0)};
  const T w = sqrt(w2);
  return {{{abs(dot(e, d.p)), abs(cross(e, d.p))}, d.rr}, w, abs(cross(u, v)) / w};
}

// The disk around the arc (c0, c2) of level t: center the chord's midpoint m, radius^2 the
// larger distance^2 from m to the enclosing triangle's vertices. It meets the query disk
// when |p - m| <= r + rho, i.e. (with g = |p - m|^2 - r^2 - rho^2) g <= 0 or g^2 <= 4 r^2 rho^2.
template <class T>
bool meets_cover(const Disk<T>& d, Pt<T> c0, Pt<T> c2, int t) noexcept {
  const Pt<T> sum = c0 + c2, chord = c2 - c0;
  const Pt<T> m = T(0.5) * sum;
  const Pt<T> to_corner = detail::niemitalo_coefficients<T>().outer[t] * sum - m;
  const Pt<T> pm = d.p - m;
  const T rho2 = std::max(T(0.25) * dot(chord, chord), dot(to_corner, to_corner));
  const T g = dot(pm, pm) - d.rr - rho2;
  return g <= T(0) || g * g <= T(4) * d.rr * rho2;
}

template <class T>
Outcome cover_test(const Disk<T>& d, T w, T h, int max_level) noexcept {
  if (level_zero_collides(d, w, h)) return {Verdict::collision, 0, 0};
  struct Node {
    Pt<T> c0, c2;
    int level;  // the arc joins neighbours of level - 1
  };
  // Depth first: each pop pushes at most two children, one of which is popped next, so
  // the stack holds at most one waiting sibling per level.
  std::array<Node, detail::niemitalo_levels + 2> stack;
  int size = 0;
  if (meets_cover(d, {w, 0}, {0, h}, 0)) stack[size++] = {{w, 0}, {0, h}, 1};
  const auto& k = detail::niemitalo_coefficients<T>();
  int deepest = 0, bisections = 0;
  bool undecided = false;
  while (size > 0) {
    const Node n = stack[--size];
    if (n.level > max_level) {
      undecided = true;
      continue;
    }
    deepest = std::max(deepest, n.level);
    ++bisections;
    const Pt<T> c1 = k.inner[n.level] * (n.c0 + n.c2);
    if (meets_segment(d, n.c0, c1) || meets_segment(d, c1, n.c2) || inside(d.p, n.c0, c1, n.c2))
      return {Verdict::collision, deepest, bisections};
    if (meets_cover(d, c1, n.c2, n.level)) stack[size++] = {c1, n.c2, n.level + 1};
    if (meets_cover(d, n.c0, c1, n.level)) stack[size++] = {n.c0, c1, n.level + 1};
  }
  return {undecided ? Verdict::undecided : Verdict::no_collision, deepest, bisections};
}

bool valid_level(int max_level) noexcept { return max_level >= 0 && max_level <= niemitalo_max_level; }

// The result in world units: `major` is the major radius of the ellipse whose polygons were
// built, `scaled_size` = s (|offset_x| + |offset_y| + major + R) (see polygonal2.hpp, "The
// band") in the frame scaled by the power of two s, where it cannot overflow (the world
// sum overflowed for a float ellipse of radius 3.7e38: rho = inf).
template <class T>
PolygonalOverlap<T> with_band(const Outcome& o, T major, T scaled_size, T s, bool cover) noexcept {
  constexpr T inf = std::numeric_limits<T>::infinity();
  const T rho = T(16 * (o.level + 2)) * std::numeric_limits<T>::epsilon() * scaled_size / s;
  if (o.verdict == Verdict::collision) return {o.verdict, o.level, o.iterations, -inf, rho};
  if (o.verdict == Verdict::no_collision) return {o.verdict, o.level, o.iterations, -rho, inf};
  const auto& k = detail::niemitalo_coefficients<T>();
  return {o.verdict, o.level, o.iterations, -k.below[o.level] * major - rho,
          (cover ? k.cover_above[o.level] : k.above[o.level]) * major + rho};
}

template <class T>
T band_size(const Vec2<T>& offset, T major, T other) noexcept {
  return abs(offset.x()) + abs(offset.y()) + major + other;
}

// Half the largest of |offset| (componentwise), `major` and `other`, taken on halves (the
// offset of two finite points may overflow). The scene's scale s = unit_scale(half) / 2, an
// exact power of two, brings that largest into [1, 2): every quantity of the test, squared,
// then stays in range (only parts far below rounding underflow).
template <class T>
T scene_half_size(const Vec2<T>& from, const Vec2<T>& to, T major, T other) noexcept {
  const T half = T(0.5);
  return std::max({abs(half * to.x() - half * from.x()), abs(half * to.y() - half * from.y()),
                   half * major, half * other});
}

// s (to - from) for the scene's scale s: the difference first (exact where it is subnormal,
// rounded once otherwise), on halves where it overflows (a point is then beyond 2^1022 and
// halving loses nothing above that difference's rounding). Scaling each point first
// overflowed for a tiny scene far from the origin (s = 2^1021 at x = -8).
template <class T>
Vec2<T> scaled_offset(const Vec2<T>& from, const Vec2<T>& to, T s) noexcept {
  const Vec2<T> d = to - from;
  if (d.allFinite()) [[likely]]
    return s * d;
  return (T(2) * s) * (T(0.5) * to - T(0.5) * from);
}

// A scene whose half size is below the smallest normal T cannot be brought into [1, 2) by
// one finite power of two (two subnormal circles of radius 3e-316 at the same center read as
// no_collision). Such a scene runs moved to `origin` (its offsets are exact differences at
// that size) and scaled by 2^tiny_shift, exactly; the band is scaled back.
template <class T>
constexpr int tiny_shift = std::numeric_limits<T>::max_exponent - 1;

template <class T>
Ellipse2<T> blown_up(const Ellipse2<T>& e, const VecArg<T, 2>& origin) noexcept {
  return detail::ShapeAccess::unchecked<T, 2>(detail::times_pow2(Vec2<T>(e.center() - origin), tiny_shift<T>),
                                              e.axes(), detail::times_pow2(e.radii(), tiny_shift<T>));
}

template <class T>
Circle<T> blown_up(const Circle<T>& c, const VecArg<T, 2>& origin) noexcept {
  return make_circle<T>(detail::times_pow2(Vec2<T>(c.center() - origin), tiny_shift<T>),
                        ldexp(c.radius(), tiny_shift<T>));
}

template <class T>
PolygonalOverlap<T> shrunk_back(PolygonalOverlap<T> r) noexcept {
  r.gap_lo = ldexp(r.gap_lo, -tiny_shift<T>);
  r.gap_hi = ldexp(r.gap_hi, -tiny_shift<T>);
  return r;
}

// The disk (center at `offset` from the ellipse's, radius r, both in the scene scaled by s,
// where the offset does not overflow) with its center in the ellipse's axes, folded into
// the first quadrant.
template <class T>
Disk<T> folded_disk(const Ellipse2<T>& e, const Vec2<T>& offset, T r) noexcept {
  const Mat2<T>& q = e.axes();
  const T dx = offset.x(), dy = offset.y();
  return {{abs(q(0, 0) * dx + q(1, 0) * dy), abs(q(0, 1) * dx + q(1, 1) * dy)}, r * r};
}

template <class T>
bool same_direction(const Vec2<T>& u, const Vec2<T>& v) noexcept {
  return u == v || u == Vec2<T>(-v);
}

// b - a and c - a in the given units, so their rounding is relative to themselves; where
// one overflows (coordinates beyond 2^1022) all three points are halved first (half = 1/2),
// which is exact but for parts far below that rounding.
template <class T>
struct Offsets {
  Vec2<T> e, q;
  T half;
};

template <class T>
Offsets<T> offsets(const Vec2<T>& a, const Vec2<T>& b, const Vec2<T>& c) noexcept {
  const Offsets<T> given{b - a, c - a, T(1)};
  if (given.e.allFinite() && given.q.allFinite()) return given;
  return {T(0.5) * b - T(0.5) * a, T(0.5) * c - T(0.5) * a, T(0.5)};
}

// Whether the closed segment [a, b] meets the closed disk of the given radius about c, from
// their offsets (a at the origin) and two exact powers of two: one brings the largest of
// |c - a| (componentwise) and the radius into [1, 2), the other e = b - a. Every comparison
// is homogeneous in e, so a segment far shorter than the circle leaves no product of e with
// itself subnormal (one common scale did: |e|^2 kept 12 bits for a segment 2^-530 of the
// radius, too few to see a gap of 1e-4). e at the circle's scale may underflow or
// overflow; it only decides where the foot of the perpendicular lies, which matters then
// at a resolution far below the rounding.
template <class T>
bool segment_meets_disk(const Offsets<T>& o, T radius) noexcept {
  const Vec2<T>& e = o.e;
  const T scaled_radius = o.half * radius;
  const T sq = unit_scale(std::max(o.q.cwiseAbs().maxCoeff(), scaled_radius));
  const T r = sq * scaled_radius;
  const T rr = r * r;
  const Pt<T> p{sq * o.q.x(), sq * o.q.y()}, end{sq * e.x(), sq * e.y()};
  const Pt<T> pb = p - end;
  if (dot(p, p) <= rr || dot(pb, pb) <= rr) return true;  // an end in the disk
  if (e.x() == T(0) && e.y() == T(0)) return false;
  const T se = unit_scale(e.cwiseAbs().maxCoeff());
  const Pt<T> u{se * e.x(), se * e.y()};
  const T side = cross(u, p);
  if (side * side > rr * dot(u, u)) return false;  // the line farther than the radius
  const T proj = dot(u, p);
  return proj >= T(0) && proj <= dot(u, end);
}

// The sign of cross(b - a, c - a), each offset scaled by its own exact power of two into
// [1, 2) (a common scale underflowed the product when one was far shorter).
template <class T>
T side_of(const Offsets<T>& o) noexcept {
  const T se = unit_scale(o.e.cwiseAbs().maxCoeff()), sq = unit_scale(o.q.cwiseAbs().maxCoeff());
  return cross(Pt<T>{se * o.e.x(), se * o.e.y()}, Pt<T>{sq * o.q.x(), sq * o.q.y()});
}

}  // namespace

template <class T>
Circle<T> make_circle(const VecArg<T, 2>& center, T radius) {
  for (int i = 0; i < 2; ++i)
    if (!isfinite(center[i]))
      throw InputError("center[" + std::to_string(i) + "]", "must be finite (got " + detail::show(center[i]) + ")");
  if (!isfinite(radius) || radius < T(0))
    throw InputError("radius", "must be finite and >= 0 (got " + detail::show(radius) + ")");
  return Circle<T>(center, radius);
}

template <class T>
Ellipse2<T> Circle<T>::ellipse() const {
  if (!(radius_ > T(0))) throw InputError("radius", "must be > 0 for an Ellipse2 (got 0: a point)");
  return make_ball<T, 2>(center_, radius_);
}

template <class T>
SegmentCircle segment_circle(const VecArg<T, 2>& a, const VecArg<T, 2>& b, const Circle<T>& circle) noexcept {
  if (!a.allFinite() || !b.allFinite()) return {Verdict::invalid_input, Side::on_line};
  const Offsets<T> o = offsets<T>(a, b, circle.center());
  const bool hit = segment_meets_disk(o, circle.radius());
  // The side at the scale of the segment and the center alone: in the frame above a radius
  // far larger than both (2^824 against 1) made their cross product underflow to 0.
  const T side = side_of(o);
  return {hit ? Verdict::collision : Verdict::no_collision,
          side > T(0) ? Side::left : side < T(0) ? Side::right : Side::on_line};
}

// The folded ellipse-circle tests (quadrant_test, cover_test) in world units.
template <bool cover, class T>
PolygonalOverlap<T> folded_overlap(const Ellipse2<T>& ellipse, const Circle<T>& circle, int max_level) noexcept {
  if (!valid_level(max_level)) return {};
  const T major = ellipse.radii().maxCoeff();
  const T half = scene_half_size<T>(ellipse.center(), circle.center(), major, circle.radius());
  if (half < std::numeric_limits<T>::min()) [[unlikely]]
    return shrunk_back(folded_overlap<cover>(blown_up(ellipse, ellipse.center()), blown_up(circle, ellipse.center()),
                                             max_level));
  const T s = T(0.5) * unit_scale(half);
  const Vec2<T> offset = scaled_offset<T>(ellipse.center(), circle.center(), s);
  const T r = s * circle.radius();
  const Disk<T> d = folded_disk(ellipse, offset, r);
  const T w = s * ellipse.radii()[0], h = s * ellipse.radii()[1];
  const Outcome o = point_like(w, h) ? point_test(d)
                    : cover         ? cover_test(d, w, h, max_level)
                                    : quadrant_test(d, w, h, max_level);
  return with_band(o, major, band_size<T>(offset, s * major, r), s, cover);
}

template <class T>
PolygonalOverlap<T> polygonal_overlap(const Ellipse2<T>& ellipse, const Circle<T>& circle, int max_level) noexcept {
  return folded_overlap<false>(ellipse, circle, max_level);
}

template <class T>
PolygonalOverlap<T> polygonal_overlap(const Ellipse2<T>& a, const Ellipse2<T>& b, int max_level) noexcept {
  if (!valid_level(max_level)) return {};
  const T major = a.radii().maxCoeff(), major_b = b.radii().maxCoeff();
  const T half = scene_half_size<T>(a.center(), b.center(), std::max(major, major_b), T(0));
  if (half < std::numeric_limits<T>::min()) [[unlikely]]
    return shrunk_back(polygonal_overlap(blown_up(a, a.center()), blown_up(b, a.center()), max_level));
  // Two exact powers of two: sb brings b's major radius into [1, 2) (the stretch factors),
  // s the largest of the offset and the radii (positions). Stretched positions are then
  // products of two numbers below 2 (the stretched frame is linear: scaled by sb s).
  const T sb = unit_scale(major_b);
  const T s = T(0.5) * unit_scale(half);
  const Mat2<T>& qa = a.axes();
  const Mat2<T>& qb = b.axes();
  const Vec2<T> ra = s * a.radii(), rb = sb * b.radii(), rbs = s * b.radii();
  const Vec2<T> offset = scaled_offset<T>(a.center(), b.center(), s);
  const bool same = same_direction<T>(qa.col(0), qb.col(0)) && same_direction<T>(qa.col(1), qb.col(1));
  const bool swapped = same_direction<T>(qa.col(0), qb.col(1)) && same_direction<T>(qa.col(1), qb.col(0));
  Outcome o;
  if (same || swapped) {
    // Parallel axes (the document's route): in a's axes, multiply x by b's extent along y
    // and y by b's extent along x; b becomes the circle of radius w_b h_b.
    const T wb = same ? rb[0] : rb[1], hb = same ? rb[1] : rb[0];
    const Vec2<T> local = (qa.transpose() * offset).cwiseAbs();
    const T r = wb * (same ? rbs[1] : rbs[0]);
    const Disk<T> d{{local.x() * hb, local.y() * wb}, r * r};
    o = point_like(ra[0], ra[1]) ? point_test(d) : quadrant_test(d, ra[0] * hb, ra[1] * wb, max_level);
  } else {
    // Rotation-stretch: A = diag(h_b, w_b) Q_b^T makes b the circle of radius w_b h_b; a's
    // semi-axes become two conjugate semi-diameters u, v, and the folded test runs in the
    // axes of the ellipse they span.
    const Vec2<T> stretch(rb[1], rb[0]);
    const Mat2<T> to_b = qb.transpose();
    const Vec2<T> p = stretch.cwiseProduct(to_b * offset);
    const Vec2<T> u = stretch.cwiseProduct(to_b * (ra[0] * qa.col(0)));
    const Vec2<T> v = stretch.cwiseProduct(to_b * (ra[1] * qa.col(1)));
    const T r = rb[0] * rbs[1];
    const Disk<T> d{{p.x(), p.y()}, r * r};
    // Level 0 without the axes where it can: the disk holds a's center; a is point-like
    // (judged on its radii in the scene, before the stretch) and its center outside; or
    // the disk misses the circle through the corners of a's bounding box in its axes
    // (squared radius w^2 + h^2 = |u|^2 + |v|^2), which the box test would find too.
    const T d2 = dot(d.p, d.p), corner2 = u.squaredNorm() + v.squaredNorm(), excess = d2 - d.rr - corner2;
    if (d2 <= d.rr)
      o = {Verdict::collision, 0, 0};
    else if (point_like(ra[0], ra[1]) || (excess > T(0) && excess * excess > T(4) * d.rr * corner2))
      o = {Verdict::no_collision, 0, 0};
    else {
      const Folded<T> f = principal_frame<T>(d, {u.x(), u.y()}, {v.x(), v.y()});
      o = quadrant_test(f.d, f.w, f.h, max_level);
    }
  }
  // The band is a's (the polygons are a's, mapped by an invertible linear map).
  return with_band(o, major, band_size<T>(offset, s * major, s * major_b), s, false);
}

template <class T>
PolygonalOverlap<T> circle_cover_overlap(const Ellipse2<T>& ellipse, const Circle<T>& circle, int max_level) noexcept {
  return folded_overlap<true>(ellipse, circle, max_level);
}

template <class T>
T niemitalo_error_bound(T major_radius, int level) noexcept {
  return T(std::exp2(0.303 - 2.0 * level)) * major_radius;
}

template <class T>
T niemitalo_error_bound(const Ellipse2<T>& ellipse, int level) noexcept {
  return niemitalo_error_bound(ellipse.radii().maxCoeff(), level);
}

template <class T>
NiemitaloPolygons<T> niemitalo_polygons(const Ellipse2<T>& ellipse, int level) {
  if (level < 0 || level > niemitalo_polygons_max_level)
    throw InputError("level", "must be in [0, " + std::to_string(niemitalo_polygons_max_level) + "] (got " +
                                  std::to_string(level) + ")");
  const auto& k = detail::niemitalo_coefficients<T>();
  const Vec2<T> u = ellipse.radii()[0] * ellipse.axes().col(0), v = ellipse.radii()[1] * ellipse.axes().col(1);
  std::vector<Vec2<T>> rim{u, v, -u, -v};  // relative to the center
  for (int t = 1; t <= level; ++t) {
    std::vector<Vec2<T>> next;
    next.reserve(2 * rim.size());
    for (std::size_t i = 0; i < rim.size(); ++i) {
      next.push_back(rim[i]);
      next.push_back(k.inner[t] * (rim[i] + rim[(i + 1) % rim.size()]));
    }
    rim = std::move(next);
  }
  NiemitaloPolygons<T> p;
  p.inscribed.reserve(rim.size());
  p.circumscribed.reserve(rim.size());
  for (std::size_t i = 0; i < rim.size(); ++i) {
    p.inscribed.push_back(ellipse.center() + rim[i]);
    p.circumscribed.push_back(ellipse.center() + k.outer[level] * (rim[i] + rim[(i + 1) % rim.size()]));
  }
  return p;
}

#define ELLIPSECT_INSTANTIATE(T)                                                                                     \
  template class Circle<T>;                                                                                         \
  template Circle<T> make_circle<T>(const VecArg<T, 2>&, T);                                                            \
  template SegmentCircle segment_circle<T>(const VecArg<T, 2>&, const VecArg<T, 2>&, const Circle<T>&) noexcept;            \
  template PolygonalOverlap<T> polygonal_overlap<T>(const Ellipse2<T>&, const Circle<T>&, int) noexcept;            \
  template PolygonalOverlap<T> polygonal_overlap<T>(const Ellipse2<T>&, const Ellipse2<T>&, int) noexcept;          \
  template PolygonalOverlap<T> circle_cover_overlap<T>(const Ellipse2<T>&, const Circle<T>&, int) noexcept;         \
  template T niemitalo_error_bound<T>(T, int) noexcept;                                                             \
  template T niemitalo_error_bound<T>(const Ellipse2<T>&, int) noexcept;                                          \
  template NiemitaloPolygons<T> niemitalo_polygons<T>(const Ellipse2<T>&, int);
ELLIPSECT_FOR_EACH_TYPE(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
