// Boundary intersection points and overlap area of two ellipses (docs/distance.md).
//
// Reduced frame (detail/reduce.hpp): S is the unit circle, O = { k + diag(e) u : |u| = 1 }.
// With u = (cos t, sin t), w(t) = k + diag(e) u and h(t) = |w(t)|:
//
// * Critical points of h are the feet of the normals from the origin to O: u_i =
//   -c_i / (e_i^2 + s), c_i = e_i k_i, for the roots s of the secular equation
//   sum c_i^2 / (e_i^2 + s)^2 = 1 (detail/secular.hpp). Its outer branches give the
//   closest and the farthest point (the solver handles their hard cases). With e_lo < e_hi,
//   delta = e_hi^2 - e_lo^2 and a = -(e_lo^2 + s) in (0, delta), the middle branch is
//   S(a) = c_lo^2 / a^2 + c_hi^2 / (delta - a)^2, convex, with its minimum in closed form at
//   a* = delta |c_lo|^(2/3) / (|c_lo|^(2/3) + |c_hi|^(2/3)), where
//   S(a*) = (|c_lo|^(2/3) + |c_hi|^(2/3))^3 / delta^2 (the evolute, an astroid); when it is
//   below 1 there is one root on each side of a*, each solved in its distance from the
//   nearer pole (a, or delta - a), which is tiny for nearly concentric pairs. When c_lo or
//   c_hi vanishes the middle points are the mirror image of the hard-case point across O's
//   axis and a vertex. Components of k below eps * e_max are zero (detail::settled).
// * Between consecutive critical points h is monotone: a transverse crossing wherever the
//   ends lie beyond the band on opposite sides of 1, a tangent point at each critical
//   point within the band. These are the comparisons classify makes (same functions, same
//   numbers), so the two agree; near a band edge both re-decide in the wider type.
// * Area: the crossings split the intersection's boundary into arcs of O inside S and
//   arcs of S inside O; the area is the polygon of the crossings plus the segment between
//   each arc and its chord, (e_0 e_1 / 2)(dt - sin dt) or (dtheta - sin dtheta) / 2, times
//   the determinant of the map back to the world (the product of S's radii).
#include <ellipsect/intersect2.hpp>

#include "detail/classify_impl.hpp"
#include "detail/gradient.hpp"
#include "detail/instantiate.hpp"
#include "detail/scale.hpp"
#include "detail/math.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <utility>

namespace ellipsect {

std::string_view to_string(CrossingKind k) noexcept {
  switch (k) {
    case CrossingKind::transverse: return "transverse";
    case CrossingKind::tangent: return "tangent";
  }
  return "unknown";
}

std::string_view to_string(BoundaryStatus s) noexcept {
  switch (s) {
    case BoundaryStatus::points: return "points";
    case BoundaryStatus::equal: return "equal";
  }
  return "unknown";
}

namespace {

template <class R>
constexpr R two_pi() noexcept {
  return 2 * detail::pi<R>();
}

// Insertion sort of the first n (at most 4) elements.
template <class A, class Less>
void sort_first(A& items, int n, Less less) noexcept {
  for (int i = 1; i < n; ++i)
    for (int j = i; j > 0 && less(items[j], items[j - 1]); --j) std::swap(items[j], items[j - 1]);
}

template <class R>
struct Point {
  R t;           // O's parameter angle
  Vec<R, 2> w;   // reduced-frame point k + diag(e) (cos t, sin t)
  R h;           // |w|
  CrossingKind kind = CrossingKind::tangent;
  bool entering = false;  // transverse: O's boundary goes into S as t increases
};

template <class R>
Point<R> on_o(const Vec<R, 2>& e, const Vec<R, 2>& k, const Vec<R, 2>& u) noexcept {
  const Vec<R, 2> w = k + e.cwiseProduct(u);
  return {atan2(u[1], u[0]), w, w.norm()};
}

template <class R>
Point<R> from_branch(const Vec<R, 2>& e, const detail::BranchPoint<R, 2>& b) noexcept {
  const Vec<R, 2> u = b.offset.cwiseQuotient(e);
  return {atan2(u[1], u[0]), b.point, b.norm};
}

// Root of f on [lo, hi] where f is monotone (increasing when `increasing`) and changes
// sign; f(x, value, slope). Bracketed Newton, then bisection to adjacent floats; steps
// below 2 eps (|x| + floor) end it.
template <class R, class F>
R monotone_root(F f, R lo, R hi, bool increasing, R floor) noexcept {
  const R eps = std::numeric_limits<R>::epsilon();
  R x = lo + (hi - lo) / 2;
  for (int it = 0; it < detail::secular_newton_steps; ++it) {
    R fx, dfx;
    f(x, fx, dfx);
    if (fx == R(0)) return x;
    ((fx < R(0)) == increasing ? lo : hi) = x;
    R next = x - fx / dfx;
    if (!(next > lo && next < hi)) next = lo + (hi - lo) / 2;
    if (abs(next - x) <= 2 * eps * (abs(next) + floor)) return next;
    x = next;
  }
  for (;;) {  // terminates: the bracket shrinks to adjacent floats
    const R mid = lo + (hi - lo) / 2;
    if (mid <= lo || mid >= hi) return mid;
    R fx, dfx;
    f(mid, fx, dfx);
    ((fx < R(0)) == increasing ? lo : hi) = mid;
  }
}

// Critical points of h on O's boundary (2 or 4; possibly repeated).
template <class R>
int critical_points(const Vec<R, 2>& e, const Vec<R, 2>& k, std::array<Point<R>, 4>& out) noexcept {
  const bool outside = detail::level_at_origin<R, 2>(e, k) > R(0);
  const auto closest = outside ? detail::closest_from_outside<R, 2>(e, k) : detail::closest_from_inside<R, 2>(e, k);
  const auto farthest = detail::farthest<R, 2>(e, k);
  out[0] = from_branch<R>(e, closest);
  out[1] = from_branch<R>(e, farthest);
  int m = 2;
  const int lo = e[0] <= e[1] ? 0 : 1, hi = 1 - lo;
  const R delta = (e[hi] - e[lo]) * (e[hi] + e[lo]);
  if (!(delta > R(0))) return m;
  const R c_lo = e[lo] * k[lo], c_hi = e[hi] * k[hi];
  auto add = [&](R u_lo, R u_hi) {
    Vec<R, 2> u;
    u[lo] = u_lo;
    u[hi] = u_hi;
    out[m++] = on_o<R>(e, k, u);
  };
  auto mirrored = [&](const Point<R>& p, int axis) {
    Vec<R, 2> u = (p.w - k).cwiseQuotient(e);
    u[axis] = -u[axis];
    out[m++] = on_o<R>(e, k, u);
  };
  if (c_lo != R(0) && c_hi != R(0)) {
    const R ql = cbrt(abs(c_lo)), qh = cbrt(abs(c_hi));
    const R cl = ql * ql, ch = qh * qh;  // |c|^(2/3), without the underflow of c^2
    if (!((cl + ch) * sqrt(cl + ch) < delta)) return m;  // S(a*) >= 1: no middle roots
    // The root on each side of a*, solved for the distance x of the multiplier from the nearer
    // pole (x = a on the left, delta - a on the right), where S = c_near^2 / x^2 +
    // c_far^2 / (delta - x)^2 is decreasing on [|c_near|, x*]. Near a pole x is tiny and
    // u_near = +-c_near / x keeps its digits; delta - a would cancel (a center 1e-16 off
    // left the right root's u with no correct digit, h far from the boundary).
    auto middle = [&](int near, R sign, R c_near, R c_far, R cl_near, R cl_far) {
      const R x_star = delta * cl_near / (cl_near + cl_far), x_min = abs(c_near);
      if (!(x_min < x_star)) return;
      auto s_minus_one = [&](R x, R& f, R& df) {
        const R y = delta - x, tn = c_near / x, tf = c_far / y;
        f = tn * tn + tf * tf - R(1);
        df = 2 * (tf * tf / y - tn * tn / x);
      };
      const R x = monotone_root<R>(s_minus_one, x_min, x_star, false, R(0));
      const R u_near = sign * c_near / x, u_far = -sign * c_far / (delta - x);
      near == lo ? add(u_near, u_far) : add(u_far, u_near);
    };
    middle(lo, R(1), c_lo, c_hi, cl, ch);
    middle(hi, R(-1), c_hi, c_lo, ch, cl);
  } else if (c_hi != R(0)) {  // c_lo = 0: the closest point is the hard case when |c_hi| < delta
    if (abs(c_hi) < delta) {
      mirrored(out[0], lo);
      add(R(0), c_hi > R(0) ? R(-1) : R(1));
    }
  } else if (c_lo != R(0)) {  // c_hi = 0: the farthest point is the hard case when |c_lo| < delta
    if (abs(c_lo) < delta) {
      mirrored(out[1], hi);
      add(c_lo > R(0) ? R(1) : R(-1), R(0));
    }
  } else {  // concentric: the four vertices
    mirrored(out[0], lo);
    mirrored(out[1], hi);
  }
  return m;
}

// All common points in the reduced frame, sorted by t. `doubt` is set when rounding could
// flip a comparison with the band (the caller repeats the computation in the wider type).
template <class R>
struct Common {
  detail::Reduced<R, 2> red;
  std::array<Point<R>, 4> points;
  int count = 0;
};

template <class R, class T>
Common<R> common_points(const Ellipse2<T>& s, const Ellipse2<T>& o, R tol, bool& doubt) noexcept {
  Common<R> out;
  out.red = detail::reduce_settled<R>(s, o);
  const Vec<R, 2>& e = out.red.e;
  const Vec<R, 2>& k = out.red.k;
  const R rounding = detail::reduced_rounding<R>(s, o, e, k);
  doubt = abs(detail::level_at_origin<R, 2>(e, k)) <= rounding;
  std::array<Point<R>, 4> crit;
  const int m = critical_points<R>(e, k, crit);
  const auto by_t = [](const Point<R>& x, const Point<R>& y) { return x.t < y.t; };
  sort_first(crit, m, by_t);
  for (int i = 0; i < m; ++i) {
    const R v = crit[i].h - R(1);
    doubt = doubt || abs(v - tol) <= rounding || abs(v + tol) <= rounding;
    // A tangent point (repeated critical points, e.g. a mirror image on the axis, once).
    if (abs(v) <= tol && (i == 0 || crit[i].t != crit[i - 1].t)) out.points[out.count++] = crit[i];
    const Point<R>& next = crit[(i + 1) % m];
    const R v1 = next.h - R(1);
    if (!((v < -tol && v1 > tol) || (v > tol && v1 < -tol))) continue;
    const R t1 = next.t > crit[i].t ? next.t : next.t + two_pi<R>();
    auto f = [&](R t, R& fx, R& dfx) {
      const R c = cos(t), sn = sin(t);
      const Vec<R, 2> w(k[0] + e[0] * c, k[1] + e[1] * sn);
      fx = w.squaredNorm() - R(1);
      dfx = 2 * (w[1] * e[1] * c - w[0] * e[0] * sn);
    };
    const R t = monotone_root<R>(f, crit[i].t, t1, v < R(0), R(1));
    Point<R> p = on_o<R>(e, k, Vec<R, 2>(cos(t), sin(t)));
    p.t = t;
    p.kind = CrossingKind::transverse;
    p.entering = v1 < R(0);
    out.points[out.count++] = p;
  }
  sort_first(out.points, out.count, by_t);
  return out;
}

// The computation in working precision, repeated in the wider type when in doubt, or in
// the wide type alone for a pair not representable in R (`wide`, detail/scale.hpp); `use`
// receives the result.
template <class T, class Use>
void with_common_points(const Ellipse2<T>& s, const Ellipse2<T>& o, const Options& options, bool wide,
                        Use use) noexcept {
  using R = detail::Work<T>;
  using W = detail::Wide<R>;
  bool doubt = wide;
  if (!doubt) {
    const auto c = common_points<R>(s, o, R(double(options.tolerance)), doubt);
    if (!doubt) return use(c);
  }
  use(common_points<W>(s, o, W(double(options.tolerance)), doubt));
}

// delta - sin(delta) for delta in [0, 2 pi], without cancellation for small delta.
template <class R>
R chord_gap(R d) noexcept {
  if (d >= R(1)) return d - sin(d);
  // d^3/3! - d^5/5! + ... ; nine terms reach 1/21! < eps for d < 1.
  const R d2 = d * d;
  R sum = 0;
  for (int n = 21; n >= 5; n -= 2) sum = R(1) / R(n - 1) / R(n) * (R(1) - d2 * sum);
  return d * d2 / R(6) * (R(1) - d2 * sum);
}

template <class R>
R ccw_span(R from, R to) noexcept {
  const R d = to - from;
  return d > R(0) ? d : d + two_pi<R>();
}

// Area of S inside O in the reduced frame from the transverse crossings.
template <class R>
R lens_area(const Common<R>& c) noexcept {
  std::array<const Point<R>*, 4> x;
  int m = 0;
  for (int i = 0; i < c.count; ++i)
    if (c.points[i].kind == CrossingKind::transverse) x[m++] = &c.points[i];
  R area = 0;
  for (int i = 0; i < m; ++i) {
    const Point<R>& p = *x[i];
    const Point<R>& q = *x[(i + 1) % m];
    const Vec<R, 2> dp = p.w - x[0]->w, dq = q.w - x[0]->w;
    area += (dp[0] * dq[1] - dp[1] * dq[0]) / 2;
    if (p.entering)  // O's arc from p to q lies inside S
      area += c.red.e[0] * c.red.e[1] / 2 * chord_gap(ccw_span(p.t, q.t));
    else  // S's arc from p to q lies inside O
      area += chord_gap(ccw_span(atan2(p.w[1], p.w[0]), atan2(q.w[1], q.w[0]))) / 2;
  }
  return area;
}

// Whether a query run in W (detail::at_scale) is in the wide type.
template <class W, class T>
constexpr bool in_wide = !std::is_same_v<W, detail::Work<T>>;

template <class T>
BoundaryIntersection<T> boundaries_in(const Ellipse2<T>& a, const Ellipse2<T>& b, const Options& options,
                                      bool wide) noexcept {
  BoundaryIntersection<T> out;
  const Relation relation = classify(a, b, options);
  if (relation == Relation::equal) out.status = BoundaryStatus::equal;
  if (relation == Relation::equal || relation == Relation::separated) return out;
  const auto pair = detail::order_pair(a, b);
  const Ellipse2<T>& s = pair.s;
  with_common_points<T>(s, pair.o, options, wide, [&](const auto& c) {
    using R = typename std::decay_t<decltype(c.red.e)>::Scalar;
    const Vec<R, 2> ca = a.center().template cast<R>();
    const Mat<R, 2> axes_a = detail::work_axes<R>(a);
    const Vec<R, 2> radii_a = a.radii().template cast<R>();
    // Touching bodies have disjoint interiors, so one common point; when O is small against
    // the tangency band (relative to S) several of its critical points lie in the band, and
    // the one kept is O's point nearest S's center.
    std::array<int, 4> use = {0, 1, 2, 3};
    int count = c.count;
    if (relation == Relation::touching && count > 1) {
      for (int i = 1; i < c.count; ++i)
        if (c.points[i].h < c.points[use[0]].h) use[0] = i;
      count = 1;
    }
    std::array<std::pair<R, int>, 4> order;
    std::array<Vec<R, 2>, 4> world;
    for (int i = 0; i < count; ++i) {
      world[i] = s.center().template cast<R>() + c.red.to_world * c.points[use[i]].w;
      const Vec<R, 2> u = (axes_a.transpose() * (world[i] - ca)).cwiseQuotient(radii_a);
      order[i] = {atan2(u[1], u[0]), i};
    }
    sort_first(order, count, std::less<>());
    out.count = count;
    for (int i = 0; i < count; ++i) {
      out.points[i] = world[order[i].second].template cast<T>();
      out.kinds[i] = c.points[use[order[i].second]].kind;
    }
  });
  return out;
}

}  // namespace

template <class T>
BoundaryIntersection<T> intersect_boundaries(const Ellipse2<T>& a, const Ellipse2<T>& b, const Options& options) noexcept {
  return detail::at_scale<detail::Work<T>>(detail::scale_of(a, b), [&]<class W>(auto units) {
    BoundaryIntersection<T> out = boundaries_in(units.body(a), units.body(b), options, in_wide<W, T>);
    for (int i = 0; i < out.count; ++i) units.lengths_out(out.points[i]);
    return out;
  });
}

namespace {

// pi r0 r1, in the working precision.
template <class T>
detail::Work<T> area_of(const Ellipse2<T>& e) {
  using R = detail::Work<T>;
  return std::numbers::pi_v<R> * R(e.radii()[0]) * R(e.radii()[1]);
}

// Whether q (relative to y's center) lies inside y: |diag(1 / r) A^T q| < 1.
template <class R, class T>
bool inside_of(const Ellipse2<T>& y, const Vec<R, 2>& q) noexcept {
  const Vec<R, 2> u = (detail::work_axes<R>(y).transpose() * q).cwiseQuotient(y.radii().template cast<R>());
  return u.squaredNorm() < R(1);
}

// overlap_area of a pair run as given (native, or `wide`: detail/scale.hpp); `crossings(c,
// pair)` also receives the common points of an overlapping pair (the reduced frame of pair.s
// and pair.o).
template <class T, class Crossings>
OverlapArea<T> native_overlap_area(const Ellipse2<T>& a, const Ellipse2<T>& b, const Options& options, bool wide,
                                   Crossings crossings) noexcept {
  OverlapArea<T> out{T(0), classify(a, b, options)};
  const auto pair = detail::order_pair(a, b);
  const Ellipse2<T>& s = pair.s;
  // Within the tolerance band a contained or equal body may be the larger by a hair: the
  // intersection's area is at most either's.
  const T smaller = T(std::min(area_of(a), area_of(b)));
  switch (out.relation) {
    case Relation::separated:
    case Relation::touching: break;
    case Relation::a_contains_b:
    case Relation::b_contains_a:
    case Relation::equal: out.area = smaller; break;
    case Relation::overlapping:
      with_common_points<T>(s, pair.o, options, wide, [&](const auto& c) {
        using W = typename std::decay_t<decltype(c.red.e)>::Scalar;
        int transverse = 0;
        for (int i = 0; i < c.count; ++i) transverse += c.points[i].kind == CrossingKind::transverse;
        if (transverse < 2) {
          // No crossing resolved: the boundaries lie within rounding of each other or of
          // tangency (the reduced frame settles offsets below eps of the radii to 0, so
          // bodies closer than that to equal have only tangent points). The intersection is
          // then the smaller body, to rounding, where its center lies inside the other; the
          // empty set where it lies outside.
          const bool a_smaller = area_of(a) <= area_of(b);
          const Ellipse2<T>& inner = a_smaller ? a : b;
          const Ellipse2<T>& outer = a_smaller ? b : a;
          out.area = inside_of<W>(outer, Vec<W, 2>(inner.center().template cast<W>() - outer.center().template cast<W>()))
                         ? smaller
                         : T(0);
        } else {
          out.area = T(lens_area<W>(c) * W(s.radii()[0]) * W(s.radii()[1]));
        }
        crossings(c, pair);
      });
      // The intersection lies inside both ellipses. When the smaller one lies within the
      // tangency band of the larger (radius ratios beyond about 1e12) the lens is formed
      // from crossings the band blurs (its polygon and segments cancel to rounding, of
      // either sign); bounding it keeps the area within [0, smaller].
      out.area = std::clamp(out.area, T(0), smaller);
      break;
  }
  return out;
}

// d area(x and y) / d (x's parameters) over the arcs of x's boundary inside y
// (intersect2.hpp): `rel` holds the m (2 or 4) transverse crossings relative to x's center,
// `inside(q)` whether the point q (relative to x's center) lies inside y. The arcs between
// consecutive crossings alternate in and out; the longest one's midpoint decides which.
template <class R, class T, class Inside>
BodyGradient<R, 2> arc_gradient(const Ellipse2<T>& x, const std::array<Vec<R, 2>, 4>& rel, int m,
                                Inside inside) noexcept {
  const Mat<R, 2> axes = detail::work_axes<R>(x);
  const Vec<R, 2> r = x.radii().template cast<R>();
  std::array<R, 4> phi{};
  for (int i = 0; i < m; ++i) {
    const Vec<R, 2> u = (axes.transpose() * rel[i]).cwiseQuotient(r);
    phi[i] = atan2(u[1], u[0]);
  }
  sort_first(phi, m, std::less<>());
  auto span = [&](int i) { return i + 1 < m ? phi[i + 1] - phi[i] : phi[0] + two_pi<R>() - phi[i]; };
  int longest = 0;
  for (int i = 1; i < m; ++i)
    if (span(i) > span(longest)) longest = i;
  const R middle = phi[longest] + span(longest) / 2;
  const bool longest_inside =
      inside(Vec<R, 2>(axes * r.cwiseProduct(Vec<R, 2>(cos(middle), sin(middle)))));
  BodyGradient<R, 2> g = detail::constant_gradient<R, 2>(R(0));
  Vec<R, 2> center = Vec<R, 2>::Zero();  // in x's axes
  const R handedness = axes.determinant() > R(0) ? R(1) : R(-1);
  for (int i = 0; i < m; ++i) {
    if (((i - longest + m) % 2 == 0) != longest_inside) continue;
    const R d = span(i), half = sin(d / 2), mid = phi[i] + d / 2, sum = 2 * mid;
    center += Vec<R, 2>(2 * r[1] * cos(mid) * half, 2 * r[0] * sin(mid) * half);
    g.radii[0] += r[1] * (d + cos(sum) * sin(d)) / 2;
    g.radii[1] += r[0] * (d - cos(sum) * sin(d)) / 2;
    g.orientation += handedness * (r[0] * r[0] - r[1] * r[1]) * sin(sum) * sin(d) / 2;
  }
  g.center = axes * center;
  return g;
}

// The intersection over union from the intersection's area: 1 for equal bodies (the area of
// either within the tolerance band), at most 1 (the area is at most either body's).
template <class T>
T iou_of(const OverlapArea<T>& i, const Ellipse2<T>& a, const Ellipse2<T>& b) noexcept {
  if (i.relation == Relation::equal) return T(1);
  const detail::Work<T> common = i.area;
  return T(common / (area_of(a) + area_of(b) - common));
}

// d (pi r_0 r_1) / d (the body's parameters).
template <class R, class T>
BodyGradient<R, 2> area_gradient(const Ellipse2<T>& e) noexcept {
  BodyGradient<R, 2> g = detail::constant_gradient<R, 2>(R(0));
  g.radii = std::numbers::pi_v<R> * Vec<R, 2>(R(e.radii()[1]), R(e.radii()[0]));
  return g;
}

}  // namespace

template <class T>
OverlapArea<T> overlap_area(const Ellipse2<T>& a, const Ellipse2<T>& b, const Options& options) noexcept {
  return detail::at_scale<detail::Work<T>>(detail::scale_of(a, b), [&]<class W>(auto units) {
    OverlapArea<T> out =
        native_overlap_area(units.body(a), units.body(b), options, in_wide<W, T>, [](const auto&, const auto&) {});
    units.areas_out(out.area);  // +inf beyond the largest finite T
    return out;
  });
}

namespace {

template <class T>
OverlapAreaGradient<T> area_gradient_in(const Ellipse2<T>& a, const Ellipse2<T>& b, const Options& options,
                                        bool wide) noexcept {
  using R = detail::Work<T>;
  const BodyGradient<T, 2> zero = detail::constant_gradient<T, 2>(T(0));
  OverlapAreaGradient<T> out{{}, zero, zero};
  out.value = native_overlap_area(a, b, options, wide, [&](const auto& c, const auto& pair) {
    using W = typename std::decay_t<decltype(c.red.e)>::Scalar;
    // The transverse crossings relative to each body's center.
    const Vec<W, 2> d = pair.o.center().template cast<W>() - pair.s.center().template cast<W>();
    std::array<Vec<W, 2>, 4> at_s, at_o;
    int m = 0;
    for (int i = 0; i < c.count; ++i) {
      if (c.points[i].kind != CrossingKind::transverse) continue;
      at_s[m] = c.red.to_world * c.points[i].w;
      at_o[m] = at_s[m] - d;
      ++m;
    }
    if (m < 2) {
      out.a = out.b = detail::constant_gradient<T, 2>(std::numeric_limits<T>::quiet_NaN());
      return;
    }
    const BodyGradient<W, 2> gs =
        arc_gradient<W>(pair.s, at_s, m, [&](const Vec<W, 2>& q) { return inside_of<W>(pair.o, Vec<W, 2>(q - d)); });
    const BodyGradient<W, 2> go =
        arc_gradient<W>(pair.o, at_o, m, [&](const Vec<W, 2>& q) { return inside_of<W>(pair.s, Vec<W, 2>(q + d)); });
    out.a = detail::gradient_in<T>(pair.a_is_s ? gs : go, W(1));
    out.b = detail::gradient_in<T>(pair.a_is_s ? go : gs, W(1));
  });
  switch (out.value.relation) {
    case Relation::a_contains_b: out.b = detail::gradient_in<T>(area_gradient<R>(b), R(1)); break;
    case Relation::b_contains_a: out.a = detail::gradient_in<T>(area_gradient<R>(a), R(1)); break;
    case Relation::equal: out.a = out.b = detail::constant_gradient<T, 2>(std::numeric_limits<T>::quiet_NaN()); break;
    default: break;
  }
  return out;
}

}  // namespace

template <class T>
OverlapAreaGradient<T> overlap_area_gradient(const Ellipse2<T>& a, const Ellipse2<T>& b,
                                             const Options& options) noexcept {
  return detail::at_scale<detail::Work<T>>(detail::scale_of(a, b), [&]<class W>(auto units) {
    OverlapAreaGradient<T> out = area_gradient_in(units.body(a), units.body(b), options, in_wide<W, T>);
    // The area scales as length^2: its derivatives by lengths as length, by angles as area.
    units.areas_out(out.value.area);
    for (BodyGradient<T, 2>* g : {&out.a, &out.b}) {
      units.lengths_out(g->center, g->radii);
      units.areas_out(g->orientation);
    }
    return out;
  });
}

template <class T>
T intersection_over_union(const Ellipse2<T>& a, const Ellipse2<T>& b, const Options& options) noexcept {
  return detail::at_scale<detail::Work<T>>(detail::scale_of(a, b), [&]<class W>(auto units) {
    decltype(auto) sa = units.body(a);
    decltype(auto) sb = units.body(b);
    return iou_of(overlap_area(sa, sb, options), sa, sb);
  });
}

namespace {

template <class T>
IouGradient<T> iou_gradient_in(const Ellipse2<T>& a, const Ellipse2<T>& b, const Options& options) noexcept {
  using R = detail::Work<T>;
  const OverlapAreaGradient<T> i = overlap_area_gradient(a, b, options);
  const R common = R(i.value.area), union_area = area_of(a) + area_of(b) - common;
  IouGradient<T> out{iou_of(i.value, a, b), i.value.relation, {}, {}};
  // d IoU = (d I (U + I) - I d area(X)) / U^2, for X = a, b.
  auto quotient = [&](const BodyGradient<T, 2>& di, const Ellipse2<T>& x) {
    const BodyGradient<R, 2> da = area_gradient<R>(x);
    const R k = R(1) / (union_area * union_area), grow = union_area + common;
    BodyGradient<R, 2> g;
    g.center = di.center.template cast<R>() * grow;
    g.orientation = R(di.orientation) * grow;
    g.radii = di.radii.template cast<R>() * grow - common * da.radii;
    return detail::gradient_in<T>(g, k);
  };
  out.a = quotient(i.a, a);
  out.b = quotient(i.b, b);
  return out;
}

}  // namespace

template <class T>
IouGradient<T> intersection_over_union_gradient(const Ellipse2<T>& a, const Ellipse2<T>& b,
                                                const Options& options) noexcept {
  return detail::at_scale<detail::Work<T>>(detail::scale_of(a, b), [&]<class W>(auto units) {
    IouGradient<T> out = iou_gradient_in(units.body(a), units.body(b), options);
    // Scale-free: derivatives by lengths scale as 1 / length, by angles not at all.
    for (BodyGradient<T, 2>* g : {&out.a, &out.b}) units.per_lengths_out(g->center, g->radii);
    return out;
  });
}

#define ELLIPSECT_INSTANTIATE(T)                                                                                   \
  template BoundaryIntersection<T> intersect_boundaries<T>(const Ellipse2<T>&, const Ellipse2<T>&,                  \
                                                           const Options&) noexcept;                                 \
  template OverlapArea<T> overlap_area<T>(const Ellipse2<T>&, const Ellipse2<T>&, const Options&) noexcept;          \
  template T intersection_over_union<T>(const Ellipse2<T>&, const Ellipse2<T>&, const Options&) noexcept;            \
  template OverlapAreaGradient<T> overlap_area_gradient<T>(const Ellipse2<T>&, const Ellipse2<T>&,                  \
                                                           const Options&) noexcept;                                 \
  template IouGradient<T> intersection_over_union_gradient<T>(const Ellipse2<T>&, const Ellipse2<T>&,               \
                                                              const Options&) noexcept;
ELLIPSECT_FOR_EACH_TYPE(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
