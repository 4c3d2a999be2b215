#include <ellipsect/triangle.hpp>

#include "detail/axes.hpp"
#include "detail/compensated.hpp"
#include "detail/contact_start.hpp"
#include "detail/gradient.hpp"
#include "detail/instantiate.hpp"
#include "detail/polytope_distance.hpp"
#include "detail/reduce.hpp"
#include "detail/scale.hpp"
#include "detail/math.hpp"
#include "detail/obstacle_motion.hpp"
#include "detail/validate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

namespace ellipsect {
namespace {

using detail::CompensatedDot;
using detail::Double;

// The computations below are written once over S = F (plain) and S = Double<F> (double
// length), F = double or the wide type.
template <class S>
struct Base {
  using type = S;
};
template <class F>
struct Base<Double<F>> {
  using type = F;
};
template <class S>
using BaseOf = typename Base<S>::type;

template <class S>
S lit(double x) noexcept {
  return S{BaseOf<S>(x)};
}
template <class F>
F value(F x) noexcept {
  return x;
}
template <class F>
F value(Double<F> x) noexcept {
  return x.hi + x.lo;
}

template <class S, int N>
using Point = std::array<S, N>;
template <class S, int N>
using Vertices = std::array<Point<S, N>, 3>;

template <class S, int N>
S dot(const Point<S, N>& a, const Point<S, N>& b) noexcept {
  S s = a[0] * b[0];
  for (int i = 1; i < N; ++i) s = s + a[i] * b[i];
  return s;
}

template <class S, int N>
Point<S, N> minus(const Point<S, N>& a, const Point<S, N>& b) noexcept {
  Point<S, N> d;
  for (int i = 0; i < N; ++i) d[i] = a[i] - b[i];
  return d;
}

// a + s b
template <class S, int N>
Point<S, N> plus_times(const Point<S, N>& a, S s, const Point<S, N>& b) noexcept {
  Point<S, N> d;
  for (int i = 0; i < N; ++i) d[i] = a[i] + s * b[i];
  return d;
}

// The ball frame: diag(r)^-1 A^T (x - y), x - y split exactly and the products compensated
// for S = Double<F>.
template <class S, class F, int N>
Point<S, N> to_ball(const Mat<F, N>& axes, const Vec<F, N>& r, const Vec<F, N>& x, const Vec<F, N>& y) noexcept {
  Point<S, N> u;
  if constexpr (std::is_same_v<S, F>) {
    Vec<F, N> e;
    for (int i = 0; i < N; ++i) e[i] = x[i] - y[i];
    const Vec<F, N> m = axes.transpose() * e;
    for (int k = 0; k < N; ++k) u[k] = m[k] / r[k];
  } else {
    std::array<Double<F>, N> e;
    for (int i = 0; i < N; ++i) e[i] = detail::two_sum(x[i], -y[i]);
    for (int k = 0; k < N; ++k) {
      CompensatedDot<F> d;
      for (int i = 0; i < N; ++i) {
        d.add(axes(i, k), e[i].hi);
        d.add(axes(i, k), e[i].lo);
      }
      u[k] = d.value() / Double<F>{r[k], 0};
    }
  }
  return u;
}

// The unit roundoff of S: eps for F, eps^2 for Double<F>.
template <class S>
BaseOf<S> rounding() noexcept {
  const BaseOf<S> eps = std::numeric_limits<BaseOf<S>>::epsilon();
  return std::is_same_v<S, BaseOf<S>> ? eps : eps * eps;
}

// The face of the triangle u: the edges f1 = u1 - u0 and f2 = u2 - u0, the normal n = f1 x f2
// (in 2D the scalar f1 x f2) and nn = |n|^2 = |f1|^2 |f2|^2 sin^2 of the angle at u0.
// `resolved` where sin^2 exceeds the unit roundoff of S: below, n's rounding (of order
// rounding |f1| |f2|) leaves its direction unknown, the triangle is numerically a segment or
// a point, and its edges and vertices, within |f| sin of every point of it, stand for it
// (collinear and coincident vertices give nn = 0). Barycentric coordinates are taken from
// cross products (conditioned as 1 / sin), not from the Gram matrix of the edges (1 / sin^2).
template <class S, int N>
struct Face {
  Point<S, N> f1, f2;
  std::conditional_t<N == 3, Point<S, N>, S> n;
  S nn;
  bool resolved;
};

template <class S, int N>
Face<S, N> face_of(const Vertices<S, N>& u) noexcept {
  Face<S, N> face;
  face.f1 = minus<S, N>(u[1], u[0]);
  face.f2 = minus<S, N>(u[2], u[0]);
  const Point<S, N>&f1 = face.f1, &f2 = face.f2;
  if constexpr (N == 3) {
    face.n = {f1[1] * f2[2] - f1[2] * f2[1], f1[2] * f2[0] - f1[0] * f2[2], f1[0] * f2[1] - f1[1] * f2[0]};
    face.nn = dot<S, N>(face.n, face.n);
  } else {
    face.n = f1[0] * f2[1] - f1[1] * f2[0];
    face.nn = face.n * face.n;
  }
  face.resolved = face.nn > dot<S, N>(f1, f1) * dot<S, N>(f2, f2) * S{rounding<S>()};
  return face;
}

// The barycentric weights of the point x of the face's plane (2D: of any point), for a
// resolved face: the areas of the sub-triangles over the whole, as cross products.
template <class S, int N>
std::array<S, 3> face_weights(const Face<S, N>& face, const Point<S, N>& u0, const Point<S, N>& x) noexcept {
  const Point<S, N> y = minus<S, N>(x, u0);
  const auto area = [&](const Point<S, N>& a, const Point<S, N>& b) {
    if constexpr (N == 3) {
      return dot<S, N>({a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}, face.n);
    } else {
      return (a[0] * b[1] - a[1] * b[0]) * face.n;
    }
  };
  const S s = area(y, face.f2) / face.nn, t = area(face.f1, y) / face.nn;
  return {lit<S>(1) - s - t, s, t};
}

template <class S>
bool inside(const std::array<S, 3>& weights) noexcept {
  const S zero{};
  return weights[1] >= zero && weights[2] >= zero && weights[0] >= zero;
}

// Barycentric weights (>= 0, summing to 1) of the point of the triangle u nearest the origin,
// as the nearest of seven candidates: the vertices, the feet on the three edges, the foot on
// the face (where it is resolved, above). However they are rounded, they are weights of a
// point of the triangle; the bracket below makes any error harmless.
template <class S, int N>
std::array<S, 3> nearest_weights(const Vertices<S, N>& u, const Face<S, N>& face) noexcept {
  const S zero{}, one = lit<S>(1);
  std::array<S, 3> best{one, zero, zero};
  S best_q = dot<S, N>(u[0], u[0]);
  const auto consider = [&](const std::array<S, 3>& weights, const Point<S, N>& x) {
    const S q = dot<S, N>(x, x);
    if (q < best_q) {
      best_q = q;
      best = weights;
    }
  };
  for (int k = 1; k < 3; ++k) {
    std::array<S, 3> weights{zero, zero, zero};
    weights[k] = one;
    consider(weights, u[k]);
  }
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const Point<S, N> f = minus<S, N>(u[j], u[i]);
    const S ff = dot<S, N>(f, f);
    if (!(ff > zero)) continue;
    const S s = -dot<S, N>(u[i], f) / ff;
    if (!(s > zero && s < one)) continue;
    std::array<S, 3> weights{zero, zero, zero};
    weights[i] = one - s;
    weights[j] = s;
    consider(weights, plus_times<S, N>(u[i], s, f));
  }
  if (face.resolved) {
    // The plane's point nearest the origin: (u0 . n / |n|^2) n in 3D, the origin in 2D.
    Point<S, N> x{};
    if constexpr (N == 3) x = plus_times<S, N>(x, dot<S, N>(u[0], face.n) / face.nn, face.n);
    const std::array<S, 3> weights = face_weights<S, N>(face, u[0], x);
    if (inside(weights))
      consider(weights, plus_times<S, N>(plus_times<S, N>(u[0], weights[1], face.f1), weights[2], face.f2));
  }
  const S sum = best[0] + best[1] + best[2];
  for (S& w : best) w = w / sum;
  return best;
}

// The relation's numbers, as gaps from 1 with their error bounds included: the relative gap
// g = d - 1 in [gap_lo, gap_hi], the containment gap D - 1 in [contain_lo, contain_hi]; the
// nearest point of the triangle in the ball frame.
template <class F, int N>
struct Bracket {
  F gap_lo, gap_hi, contain_lo, contain_hi;
  Vec<F, N> nearest;
};

// hi = |x| for x the weighted vertices; lo = min_k w . u_k for a unit w, since every point y of
// the triangle has |y| >= w . y >= that minimum (w along x, below). `slack` bounds the rounding of u and of
// these evaluations.
template <class F, class S, int N>
Bracket<F, N> bracket(const Vertices<S, N>& u, F slack) noexcept {
  const Face<S, N> face = face_of<S, N>(u);
  const std::array<S, 3> weights = nearest_weights<S, N>(u, face);
  Point<S, N> x;
  for (int i = 0; i < N; ++i) x[i] = weights[0] * u[0][i] + weights[1] * u[1][i] + weights[2] * u[2][i];
  using std::sqrt;
  const S zero{}, one = lit<S>(1), n = sqrt(dot<S, N>(x, x));
  Bracket<F, N> b;
  b.gap_hi = value(n - one) + slack;
  // The lower bound's direction: x itself at a vertex; on an edge x made exactly normal to it,
  // on the face (3D) the face's normal towards it: the vertices far along the feature would
  // otherwise turn the rounding of x's direction into an error times their distance.
  Point<S, N> w = x;
  int first = -1, second = -1, count = 0;
  for (int k = 0; k < 3; ++k)
    if (weights[k] > zero) (count++ == 0 ? first : second) = k;
  if (count == 2) {
    const Point<S, N> f = minus<S, N>(u[second], u[first]);
    const S ff = dot<S, N>(f, f);
    if (ff > zero) w = plus_times<S, N>(x, -dot<S, N>(x, f) / ff, f);
  } else if constexpr (N == 3) {
    if (count == 3) {  // a resolved face
      Point<S, N> normal = face.n;
      if (dot<S, N>(normal, u[0]) < zero)
        for (S& c : normal) c = -c;
      w = normal;
    }
  }
  const S wn = sqrt(dot<S, N>(w, w));
  if (wn > zero && n > zero) {
    S m = dot<S, N>(w, u[0]);
    for (int k = 1; k < 3; ++k) m = std::min(m, dot<S, N>(w, u[k]));
    b.gap_lo = value(m / wn - one) - slack;
  } else {
    b.gap_lo = F(-1) - slack;
  }
  S far = dot<S, N>(u[0], u[0]);
  for (int k = 1; k < 3; ++k) far = std::max(far, dot<S, N>(u[k], u[k]));
  const S far_norm = sqrt(far);
  b.contain_lo = value(far_norm - one) - slack;
  b.contain_hi = value(far_norm - one) + slack;
  for (int i = 0; i < N; ++i) b.nearest[i] = value(x[i]);
  return b;
}

// The relation a bracket decides, or nullopt-like `undecided`.
enum class Decision { separated, touching, overlapping, a_contains_b, undecided };

template <class F, int N>
Decision decide(const Bracket<F, N>& b, F band) noexcept {
  if (b.gap_lo > band) return Decision::separated;
  if (b.gap_lo >= -band && b.gap_hi <= band) return Decision::touching;
  if (b.gap_hi < -band) {
    if (b.contain_hi <= band) return Decision::a_contains_b;
    if (b.contain_lo > band) return Decision::overlapping;
  }
  return Decision::undecided;
}

// The midpoints of a bracket that the double-length pass could not narrow to one side.
template <class F, int N>
Decision decide_by_midpoint(const Bracket<F, N>& b, F band) noexcept {
  const F gap = (b.gap_lo + b.gap_hi) / 2, contain = (b.contain_lo + b.contain_hi) / 2;
  if (gap > band) return Decision::separated;
  if (gap >= -band) return Decision::touching;
  return contain <= band ? Decision::a_contains_b : Decision::overlapping;
}

// One pair in the working type F: the body's frame, the triangle's vertices in the ball frame
// in both precisions as needed, and the decided relation.
template <class F, int N>
struct Pair {
  Mat<F, N> axes;
  Vec<F, N> center, radii;
  std::array<Vec<F, N>, 3> vertices;
  Vertices<F, N> u;
  Vertices<Double<F>, N> u2;
  bool double_length = false;  // u2 computed and used
  F size;                      // max |u_k| + 1
  Bracket<F, N> bracket;
  Decision relation;
};

// The bracket of the triangle v (world coordinates) in the tier S (F plain, Double<F> double
// length), its ball-frame vertices in u and max |u_k| + 1 in size. The slack bounds the
// rounding: of u (from max |v_k - c| / r_min, times sqrt N) and of the bracket's sums.
template <class S, class F, int N>
Bracket<F, N> bracket_of(const Pair<F, N>& p, const std::array<Vec<F, N>, 3>& v, Vertices<S, N>& u, F& size) noexcept {
  F extent = 0;
  size = 1;
  for (int k = 0; k < 3; ++k) {
    u[k] = to_ball<S, F, N>(p.axes, p.radii, v[k], p.center);
    extent = std::max(extent, detail::max_abs(Vec<F, N>(v[k] - p.center)) / p.radii.minCoeff());
    size = std::max(size, sqrt(value(dot<S, N>(u[k], u[k]))) + 1);
  }
  extent *= sqrt(F(N));
  const F eps = std::numeric_limits<F>::epsilon();
  const F slack = std::is_same_v<S, F> ? 2 * eps * (F((N + 2) * N) * extent + F(4 * (N + 4)) * size)
                                       : 2 * eps * eps * (F(8 * N * N) * extent + F(64 * (N + 4)) * size);
  return bracket<F, S, N>(u, slack);
}

// The body's axis-aligned half-extents sqrt(sum_k (A_ik r_k)^2), grown by the band and 1e-9.
template <class F, int N>
Vec<F, N> box_half_extents(const Pair<F, N>& p, F band) noexcept {
  Vec<F, N> h;
  for (int i = 0; i < N; ++i) h[i] = p.axes.row(i).cwiseProduct(p.radii.transpose()).norm() * (1 + 2 * band + F(1e-9));
  return h;
}

// Whether the triangle's bounding box misses the body's (grown by the band): then they are
// separated, whatever the triangle's size (a certificate that needs no cancellation).
template <class F, int N>
bool boxes_apart(const Pair<F, N>& p, F band) noexcept {
  const Vec<F, N> h = box_half_extents(p, band);
  for (int i = 0; i < N; ++i) {
    const F lo = std::min({p.vertices[0][i], p.vertices[1][i], p.vertices[2][i]});
    const F hi = std::max({p.vertices[0][i], p.vertices[1][i], p.vertices[2][i]});
    if (lo > p.center[i] + h[i] || hi < p.center[i] - h[i]) return true;
  }
  return false;
}

template <class F, class T, int N>
Pair<F, N> pair_in(const Ellipsoid<T, N>& a, const Triangle<T, N>& b, const Options& options) noexcept {
  Pair<F, N> p;
  p.axes = detail::work_axes<F>(a);
  p.center = a.center().template cast<F>();
  p.radii = a.radii().template cast<F>();
  for (int k = 0; k < 3; ++k) p.vertices[k] = b.vertex(k).template cast<F>();
  const F band = F(double(options.tolerance));
  p.bracket = bracket_of<F, F, N>(p, p.vertices, p.u, p.size);
  p.relation = decide(p.bracket, band);
  if (p.relation != Decision::undecided) return p;
  if (boxes_apart(p, band)) {
    p.relation = Decision::separated;
    p.bracket.gap_lo = p.bracket.gap_hi = std::numeric_limits<F>::infinity();
    return p;
  }
  // Double length near a band edge.
  F size;
  p.bracket = bracket_of<Double<F>, F, N>(p, p.vertices, p.u2, size);
  p.double_length = true;
  p.relation = decide(p.bracket, band);
  if (p.relation == Decision::undecided) p.relation = decide_by_midpoint(p.bracket, band);
  return p;
}

// Calls then(pair) with the pair in the working type, or in the wide type beyond the
// representable range (detail/scale.hpp). The pair's arithmetic is in the body's unit-ball
// frame, scale-free, so it runs on the bodies as given in the rescaled range too.
template <class T, int N, class Then>
auto with_pair(const Ellipsoid<T, N>& a, const Triangle<T, N>& b, const Options& options, Then&& then) noexcept {
  T coordinate = detail::max_abs(a.center());
  for (int k = 0; k < 3; ++k) coordinate = std::max(coordinate, detail::max_abs(b.vertex(k)));
  const detail::Scale scale = detail::scale_of<T>(a.radii().maxCoeff(), a.radii().minCoeff(), coordinate);
  return detail::in_type<detail::Work<T>>(scale, [&]<class F>(int) { return then(pair_in<F>(a, b, options)); });
}

Relation relation_of(Decision d) noexcept {
  switch (d) {
    case Decision::separated: return Relation::separated;
    case Decision::touching: return Relation::touching;
    case Decision::a_contains_b: return Relation::a_contains_b;
    default: return Relation::overlapping;
  }
}

// The world point c + A diag(r) x of the ball-frame point x, moved by `shift`, and the body's
// outward unit normal there, A diag(r)^-1 x normalized.
template <class T, class F, int N>
void world_contact(const Pair<F, N>& p, const Vec<F, N>& x, const Vec<F, N>& shift, Contact<T, N>& out) noexcept {
  out.point = (p.center + shift + p.axes * p.radii.cwiseProduct(x)).template cast<T>();
  out.normal = detail::unit_vector<F, N>(p.axes * x.cwiseQuotient(p.radii)).template cast<T>();
}

// The entering root of |p + t q|^2 = 1 from |p| > 1 (c = |p|^2 - 1 > 0, b = p . q, a = |q|^2):
// t = c / (-b + sqrt(b^2 - a c)), or a negative value where there is none.
template <class S>
S entering_root(S a, S b, S c) noexcept {
  const S zero{};
  if (!(b < zero)) return -lit<S>(1);
  const S disc = b * b - a * c;
  if (disc < zero) return -lit<S>(1);
  using std::sqrt;
  return c / (sqrt(disc) - b);
}

// The first time t > 0 at which the ball touches the triangle u moving at w (d(0) > 1), with
// the ball-frame contact point; time < 0 where there is none.
template <class S, int N>
struct Hit {
  S time;
  Point<S, N> point;
};

template <class S, int N>
Hit<S, N> earliest_hit(const Vertices<S, N>& u, const Point<S, N>& w) noexcept {
  const S zero{}, one = lit<S>(1);
  Hit<S, N> best{-one, {}};
  const auto consider = [&](S t, const Point<S, N>& x) {
    if (t >= zero && (best.time < zero || t < best.time)) best = {t, x};
  };
  const S ww = dot<S, N>(w, w);
  for (int k = 0; k < 3; ++k) {
    const S t = entering_root(ww, dot<S, N>(u[k], w), dot<S, N>(u[k], u[k]) - one);
    if (t >= zero) consider(t, plus_times<S, N>(u[k], t, w));
  }
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const Point<S, N> f = minus<S, N>(u[j], u[i]);
    const S ff = dot<S, N>(f, f);
    if (!(ff > zero)) continue;
    // The components of u_i and w across the edge's line.
    const Point<S, N> p = plus_times<S, N>(u[i], -dot<S, N>(u[i], f) / ff, f);
    const Point<S, N> q = plus_times<S, N>(w, -dot<S, N>(w, f) / ff, f);
    const S c = dot<S, N>(p, p) - one;
    if (!(c > zero)) continue;  // the line already meets the ball: d(t) convex, no entry on it
    const S t = entering_root(dot<S, N>(q, q), dot<S, N>(p, q), c);
    if (!(t >= zero)) continue;
    const Point<S, N> y = plus_times<S, N>(u[i], t, w);
    const S s = -dot<S, N>(y, f) / ff;
    if (s >= zero && s <= one) consider(t, plus_times<S, N>(y, s, f));
  }
  if constexpr (N == 3) {
    // The face's plane (where resolved: a numerically collinear triangle's plane is any
    // plane through its line, and its edges stand for it) enters the ball from the side of
    // sign(d0), at |d0 + t dw| = rn.
    const Face<S, N> face = face_of<S, N>(u);
    using std::sqrt;
    const S rn = sqrt(face.nn), d0 = dot<S, N>(u[0], face.n), dw = dot<S, N>(w, face.n);
    const bool above = d0 > rn && dw < zero, below = -d0 > rn && dw > zero;
    if (face.resolved && (above || below)) {
      const S t = above ? (d0 - rn) / -dw : (-d0 - rn) / dw;
      const S side = above ? one : -one;
      Point<S, N> x;
      for (int i = 0; i < N; ++i) x[i] = side * face.n[i] / rn;
      // x - t w in the triangle at rest.
      if (inside(face_weights<S, N>(face, u[0], plus_times<S, N>(x, -t, w)))) consider(t, x);
    }
  }
  return best;
}

}  // namespace

template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a, const Triangle<T, N>& b, const Options& options) noexcept {
  return with_pair(a, b, options, [](const auto& p) { return relation_of(p.relation); });
}

template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const Triangle<T, N>& b, const Options& options) noexcept {
  return classify(a, b, options) != Relation::separated;
}

// The velocities are rescaled by 2^-v (v the exponent of the largest speed beyond 2^+-500, or
// 0) before their difference is taken; the time comes back times 2^-v.
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const Triangle<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  Contact<T, N> out = detail::unanswered_contact<T, N>();
  if (!detail::valid_motion<T, N>(velocity_a, velocity_b, t_max)) return out;
  return with_pair(a, b, options, [&](const auto& p) {
    using F = typename std::decay_t<decltype(p.center)>::Scalar;
    if (p.relation != Decision::separated) {
      out.time = T(0);
      if (p.relation != Decision::touching) {
        out.status = ContactStatus::overlapping_at_start;
        return out;
      }
      out.status = ContactStatus::touching_at_start;
      world_contact<T, F, N>(p, p.bracket.nearest, Vec<F, N>::Zero(), out);
      return out;
    }
    out.status = ContactStatus::no_contact_in_window;
    const T speed = std::max(detail::max_abs(velocity_a), detail::max_abs(velocity_b));
    if (!(speed > T(0))) return out;
    const int v = detail::speed_exponent(speed);
    Vec<F, N> va, vb;
    for (int i = 0; i < N; ++i) {
      va[i] = ldexp(F(velocity_a[i]), -v);
      vb[i] = ldexp(F(velocity_b[i]), -v);
    }
    // The body's box swept relative to the triangle's box over [0, t_max] (times here in units
    // of 2^v): where they never meet, no contact, whatever the triangle's size.
    {
      const Vec<F, N> h = box_half_extents(p, F(double(options.tolerance))), d = va - vb;
      F entry = 0, exit = ldexp(F(t_max), v);
      for (int i = 0; i < N; ++i) {
        const F lo = std::min({p.vertices[0][i], p.vertices[1][i], p.vertices[2][i]}) - h[i] - p.center[i];
        const F hi = std::max({p.vertices[0][i], p.vertices[1][i], p.vertices[2][i]}) + h[i] - p.center[i];
        if (d[i] == F(0)) {
          if (lo > F(0) || hi < F(0)) return out;
          continue;
        }
        const F t1 = lo / d[i], t2 = hi / d[i];
        entry = std::max(entry, std::min(t1, t2));
        exit = std::min(exit, std::max(t1, t2));
      }
      if (entry > exit) return out;
    }
    F time = -1;
    Vec<F, N> x;
    const auto solve = [&](const auto& u, auto zero) {
      using S = decltype(zero);
      const Hit<S, N> hit = earliest_hit<S, N>(u, to_ball<S, F, N>(p.axes, p.radii, vb, va));
      const F t = value(hit.time);
      if (!(t >= F(0)) || (time >= F(0) && t >= time)) return;
      time = t;
      for (int i = 0; i < N; ++i) x[i] = value(hit.point[i]);
    };
    // A thin triangle's plane (3D) is known to the rounding over the sine of its angle.
    bool thin = false;
    if constexpr (N == 3) {
      const Face<F, N> face = face_of<F, N>(p.u);
      thin = face.nn * 256 < dot<F, N>(face.f1, face.f1) * dot<F, N>(face.f2, face.f2);
    }
    if (p.double_length || p.bracket.gap_lo < F(0.25) || p.size > F(1024) || thin) {
      // The entering roots cancel in |u|^2 - 1 as the gap closes, and across a triangle far
      // larger than the body in its frame; a thin triangle's face (the sine of its angle
      // below 1/16) puts the rounding over that sine into its contact: within a gap of 1/4,
      // beyond 1024 radii or for a thin triangle, double length.
      Vertices<Double<F>, N> u2 = p.u2;
      if (!p.double_length)
        for (int k = 0; k < 3; ++k) u2[k] = to_ball<Double<F>, F, N>(p.axes, p.radii, p.vertices[k], p.center);
      solve(u2, Double<F>{});
    } else {
      solve(p.u, F(0));
    }
    if (!(time >= F(0))) return out;
    time = std::max(ldexp(time, -v), F(std::numeric_limits<T>::denorm_min()));
    if (!(isfinite(T(time)) && T(time) <= t_max)) return out;
    out.time = T(time);
    // The contact point lies on the unit sphere of the ball frame; one that does not (only
    // for triangles far beyond the stated range, whose roots lose every digit) is no answer.
    const F length = x.norm();
    if (!(abs(length - 1) <= F(1e-6))) {
      out.status = ContactStatus::did_not_converge;
      return out;
    }
    out.status = ContactStatus::hit;
    Vec<F, N> shift;
    for (int i = 0; i < N; ++i) shift[i] = time * F(velocity_a[i]);
    world_contact<T, F, N>(p, x / length, shift, out);
    return out;
  });
}

// The triangle as a polytope (detail/polytope_distance.hpp): its vertices, three edges and, in
// 3D, one face.
template <class T, int N>
struct detail::PolytopeTraits<Triangle<T, N>> {
  static std::array<Vec<T, N>, 3> vertices(const Triangle<T, N>& t) noexcept { return {t.vertex(0), t.vertex(1), t.vertex(2)}; }
  static constexpr std::array<std::array<int, 2>, 3> edges{{{0, 1}, {1, 2}, {2, 0}}};
  static constexpr auto faces = [] {
    std::array<std::array<int, 3>, N == 3 ? 1 : 0> f{};
    if constexpr (N == 3) f[0] = {0, 1, 2};
    return f;
  }();
};

template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const Triangle<T, N>& b, const Options& options) noexcept {
  return detail::polytope_signed_distance<T, N>(a, b, options, [&] { return classify(a, b, options); });
}

template <class T, int N>
DistanceGradient<T, N, TriangleGradient<T, N>> signed_distance_gradient(const Ellipsoid<T, N>& a,
                                                                        const Triangle<T, N>& b,
                                                                        const Options& options) noexcept {
  // The barycentric weights of the touching point y = p + d n (less a's center): the vertices
  // less y, whose point nearest the origin is y's nearest.
  const auto weights = [&](const auto& n, const auto& p, auto d) {
    using R = decltype(d);
    const Vec<R, N> y = p + d * n;
    Vertices<R, N> u;
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < N; ++i) u[k][i] = (R(b.vertex(k)[i]) - R(a.center()[i])) - y[i];
    return nearest_weights<R, N>(u, face_of<R, N>(u));
  };
  // The face's normal toward the body's side, and the edge of a touching point on an edge or
  // nearly (polish_normal keeps n where the maximum is not inside that edge's stratum).
  const auto stratum = [&](const auto& n, const auto& p, auto d, auto& out) {
    if constexpr (N == 3) {
      using R = decltype(d);
      const Vec<R, 3> v0 = b.vertex(0).template cast<R>();
      Vec<R, 3> face = (b.vertex(1).template cast<R>() - v0).cross(b.vertex(2).template cast<R>() - v0);
      if (face.norm() > R(0)) {
        face.normalize();
        out.faces[out.face_count++] = face.dot(n) < 0 ? Vec<R, 3>(-face) : face;
      }
      const auto w = weights(n, p, d);
      for (int k = 0; k < 3; ++k)
        if (w[k] <= 1e-9 && w[(k + 1) % 3] > 0 && w[(k + 2) % 3] > 0) {
          detail::set_edge<R>(out, a, Vec<T, 3>(b.vertex((k + 1) % 3)), Vec<T, 3>(b.vertex((k + 2) % 3)));
          out.sides[out.side_count++] = b.vertex(k).template cast<R>() - b.vertex((k + 1) % 3).template cast<R>();
        }
    }
  };
  return detail::shape_distance_gradient<T, N, TriangleGradient<T, N>>(
      a, signed_distance(a, b, options), stratum, [&](const auto& n, const auto& p, auto d) {
        const auto w = weights(n, p, d);
        TriangleGradient<T, N> out;
        for (int k = 0; k < 3; ++k) out.vertices[k] = (w[k] * n).template cast<T>();
        return out;
      });
}

template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Triangle<T, N>& b, const Options& options) noexcept {
  return detail::unsigned_distance(signed_distance(a, b, options));
}

// ---- Rigid motion (detail/obstacle_motion.hpp) --------------------------------------------

namespace detail::obstacle {
template <class T, int N>
struct ObstacleTraits<Triangle<T, N>> : PolytopeObstacle<T, N, Triangle<T, N>> {
  static std::optional<Vec<R, N>> inner_point(const Triangle<T, N>& t) noexcept {
    return (t.vertex(0).template cast<R>() + t.vertex(1).template cast<R>() + t.vertex(2).template cast<R>()) / 3;
  }
};
}  // namespace detail::obstacle

ELLIPSECT_RIGID_OBSTACLE_CONTACT(Triangle)

// ---- The factories -----------------------------------------------------------------------

template <class T, int N>
Triangle<T, N> Triangle<T, N>::from_vertices(const Vec<T, N>& v0, const Vec<T, N>& v1, const Vec<T, N>& v2) {
  detail::require_finite(v0, "vertices[0]");
  detail::require_finite(v1, "vertices[1]");
  detail::require_finite(v2, "vertices[2]");
  Triangle t;
  Eigen::Map<Vec<T, N>>(t.vertices_[0].data()) = v0;
  Eigen::Map<Vec<T, N>>(t.vertices_[1].data()) = v1;
  Eigen::Map<Vec<T, N>>(t.vertices_[2].data()) = v2;
  return t;
}

template <class T, int N>
Triangle<T, N> Triangle<T, N>::translated(const Vec<T, N>& offset) const {
  Triangle t = *this;
  for (int k = 0; k < 3; ++k)
    Eigen::Map<Vec<T, N>>(t.vertices_[k].data()) = detail::moved<T, N>(vertex(k), offset, "a vertex");
  return t;
}

#define ELLIPSECT_INSTANTIATE(T, N) ELLIPSECT_INSTANTIATE_OBSTACLE(Triangle, TriangleGradient, T, N)
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
