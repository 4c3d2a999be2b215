// A body against a triangle, an oriented box and a capsule: signed distance, and the
// capsule's overlap, side by side with FCL 0.7 on the same cases.
//
// Cases (3D, 128 per shape, seeded): bodies of radii 0.1 to 1 (aspect ratios to 10), centers
// in [-2, 2]^3, any orientation; triangles with vertices in [-4, 4]^3; boxes centered in
// [-4, 4]^3 with half extents 0.1 to 2; capsules from [-4, 4]^3 of length 0 to 4 and radius
// 0.05 to 1. Answers checked against the 50-digit reference of
// tests/reference/support_gap_reference.hpp (the support gap maximized over the sphere by
// search; a capsule's is its segment's less the radius).
//   distance/ellipsect/<shape>   ellipsect::signed_distance
//   distance/fcl/<shape>         fcl::distance with FCL's default request (GJK through
//                                libccd, tolerance 1e-6); the triangle as a one-triangle
//                                fcl::BVHModel<OBBRSSd>, the box an fcl::Boxd, the capsule an
//                                fcl::Capsuled
//   overlap/ellipsect/capsule    ellipsect::overlap
//   overlap/fcl/capsule          fcl::collide, default request
//   overlap/ellipsect/box        ellipsect::overlap
//   overlap/fcl/box              fcl::collide of the fcl::Ellipsoidd and the fcl::Boxd
// distance: timed and checked on the separated cases only (FCL's distance is not a
// penetration depth); wrong: an error above 1e-6 (largest radius + |distance|); max_err: the
// largest error in those units. overlap: all cases, wrong outside a relative band of 1e-12.
//
// Swept cases: the same bodies and shapes with seeded velocities (a separate stream, seed
// 5252 + shape): the shape moving at up to 1, the body closing on it along the line of the
// centers by 0.3 to 1.6 times their distance, plus a sideways part of up to 1.5, in the
// window [0, 1]; for rigid motion the body also turns at 0.5 to 3 rad over the window about a
// random axis.
//   first_contact/ellipsect/<shape>   ellipsect::first_contact(body, v_a, shape, v_b, 1)
//   first_contact/fcl/<shape>         fcl::continuousCollide over [0, 1], default request
//                                     (CCDC_NAIVE: fcl::collide at 10 sampled times, CCDM_TRANS)
//   rigid_contact/ellipsect/<shape>   ellipsect::first_contact(body, RigidMotion, shape, v_b, 1)
//   rigid_contact/fcl_screw/<shape>   fcl::continuousCollide from the poses at 0 to those at 1
//   rigid_contact/fcl_linear/<shape>  (body_at), CCDC_NAIVE, CCDM_SCREW or CCDM_LINEAR
// Truth, in 50 digits by routes other than the library's (namespace truth below): the static
// gap of the body and a triangle is tests/reference/triangle_reference.hpp's d - 1 (d the
// scale of the body that touches it); a box is its 12 boundary triangles' (corners formed in
// Real) or overlapping where the body's center is inside; a capsule's is the Euclidean
// distance of its segment to the body, less the radius, over (largest radius + radius):
// golden section along the segment of the point-to-body distance (Newton on the secular
// equation, long double then Real) with the ends checked in Real. Translation: each
// triangle's d(t) and the capsule's gap are convex in t: golden section (100 steps) for the
// least gap in the window, bisection (110 halvings) for the first root before it; a box's
// contact is the earliest of its triangles'. Rigid motion: samples at steps max(e / W,
// 1/1000 of the window), e a lower bound on the Euclidean distance ((d - 1) times the
// smallest radius; the capsule's gap), W = |v_a - v_b| + |omega| (largest radius) the
// fastest a point of the body moves relative to the shape (no contact is stepped over while
// e / W is the larger); each local minimum of the samples below 0.1 refined by golden
// section over its two intervals; the first sign change bisected (110 halvings).
// Counters: n (cases judged: all but those whose least gap in the window is within 1e-9 of
// 0 and hits within 1e-9 of the window's end), wrong (outcome: hit, at the start, none,
// differing from the truth, or a hit's time off by more than 1e-6 relative), missed (a
// contact of the truth answered none or failed), late (a hit later than the truth's by more
// than that), max_err (largest relative time error among hits both report).
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/triangle.hpp>

#include "bench/bench_support.hpp"
#include "bench/peers.hpp"
#include "scenarios/scenarios.hpp"
#include "tests/reference/rigid_contact_reference.hpp"
#include "tests/reference/support_gap_reference.hpp"
#include "tests/reference/triangle_reference.hpp"

#include <benchmark/benchmark.h>

#ifdef ELLIPSECT_HAVE_FCL
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/continuous_collision.h>
#include <fcl/narrowphase/distance.h>
#endif

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace ellipsect;
using V = Vec3<double>;
constexpr int cases_per_shape = 128;

enum class Shape { triangle, box, capsule };
const char* name(Shape s) { return s == Shape::triangle ? "triangle" : s == Shape::box ? "box" : "capsule"; }

struct Item {
  Ellipsoid<double, 3> a;
  Triangle<double, 3> triangle;
  Box<double, 3> box;
  Capsule<double, 3> capsule;
  double distance;  // the reference's signed distance
  double scale;     // largest radius + |distance|
};

const std::vector<Item>& items(Shape shape) {
  static std::vector<Item> cache[3];
  auto& out = cache[static_cast<int>(shape)];
  if (!out.empty()) return out;
  using namespace scenarios::detail;
  Rng rng(4242 + static_cast<std::uint64_t>(shape));
  const auto point = [&](double s) { return V(uniform(rng, -s, s), uniform(rng, -s, s), uniform(rng, -s, s)); };
  for (int i = 0; i < cases_per_shape; ++i) {
    Item it{Ellipsoid<double, 3>::from_axes(point(2), rotation<3>(rng), radii<3>(rng, 1.0, 10)), {}, {}, {}, 0, 0};
    std::vector<reference::DVec<3>> vertices;
    double grow = 0;
    if (shape == Shape::triangle) {
      it.triangle = make_triangle<double, 3>(point(4), point(4), point(4));
      for (int k = 0; k < 3; ++k) vertices.push_back(it.triangle.vertex(k));
    } else if (shape == Shape::box) {
      const V h(log_uniform(rng, 0.1, 2), log_uniform(rng, 0.1, 2), log_uniform(rng, 0.1, 2));
      it.box = make_box<double, 3>(point(4), rotation<3>(rng), h);
      for (int k = 0; k < 8; ++k) vertices.push_back(it.box.corner(k));
    } else {
      const V p0 = point(4);
      it.capsule = make_capsule<double, 3>(p0, V(p0 + unit_vector<3>(rng) * uniform(rng, 0, 4)), log_uniform(rng, 0.05, 1));
      vertices = {it.capsule.point(0), it.capsule.point(1)};
      grow = it.capsule.radius();
    }
    const auto m = reference::max_support_gap<3>(reference::Body<3>{it.a.center(), it.a.axes(), it.a.radii()}, vertices);
    it.distance = reference::to_double(m.gap) - grow;
    it.scale = it.a.radii().maxCoeff() + std::abs(it.distance);
    out.push_back(it);
  }
  return out;
}

std::vector<Item> separated(Shape shape) {
  std::vector<Item> out;
  for (const auto& it : items(shape))
    if (it.distance > 1e-9 * it.scale) out.push_back(it);
  return out;
}

Distance<double, 3> ellipsect_distance(const Item& it, Shape shape) {
  return shape == Shape::triangle ? signed_distance(it.a, it.triangle)
         : shape == Shape::box    ? signed_distance(it.a, it.box)
                                  : signed_distance(it.a, it.capsule);
}

void count_errors(benchmark::State& state, const std::vector<Item>& its, const std::vector<double>& got) {
  int wrong = 0;
  double max_err = 0;
  for (std::size_t i = 0; i < its.size(); ++i) {
    const double err = std::abs(got[i] - its[i].distance) / its[i].scale;
    wrong += !(err <= 1e-6);
    max_err = std::max(max_err, err);
  }
  state.counters["wrong"] = wrong;
  state.counters["max_err"] = max_err;
  state.counters["cases"] = static_cast<double>(its.size());
}

void ellipsect_distance_bench(benchmark::State& state, Shape shape) {
  const auto its = separated(shape);
  std::vector<double> got;
  for (const auto& it : its) got.push_back(ellipsect_distance(it, shape).distance);
  bench::time_cases(state, its, [shape](const Item& it) { return ellipsect_distance(it, shape).distance; });
  count_errors(state, its, got);
}

bool wrong_overlap(const Item& it, bool got) {
  return std::abs(it.distance) > 1e-12 * it.scale && got != (it.distance <= 0);
}

bool ellipsect_overlap(const Item& it, Shape shape) {
  return shape == Shape::box ? overlap(it.a, it.box) : overlap(it.a, it.capsule);
}

void ellipsect_overlap_bench(benchmark::State& state, Shape shape) {
  const auto& its = items(shape);
  int wrong = 0;
  for (const auto& it : its) wrong += wrong_overlap(it, ellipsect_overlap(it, shape));
  bench::time_cases(state, its, [shape](const Item& it) { return ellipsect_overlap(it, shape); });
  state.counters["wrong"] = wrong;
}

// ---- Swept cases ---------------------------------------------------------------------------

constexpr double window = 1;  // t_max of every swept case

struct Sweep {
  V va, vb;  // the body's and the shape's velocities
  V omega;   // the body's angular velocity (rigid cases)
};

V shape_center(const Item& it, Shape shape) {
  return shape == Shape::triangle ? V((it.triangle.vertex(0) + it.triangle.vertex(1) + it.triangle.vertex(2)) / 3)
         : shape == Shape::box    ? V(it.box.center())
                                  : V((it.capsule.point(0) + it.capsule.point(1)) / 2);
}

const std::vector<Sweep>& sweeps(Shape shape) {
  static std::vector<Sweep> cache[3];
  auto& out = cache[static_cast<int>(shape)];
  if (!out.empty()) return out;
  using namespace scenarios::detail;
  Rng rng(5252 + static_cast<std::uint64_t>(shape));
  for (const Item& it : items(shape)) {
    const V r = shape_center(it, shape) - it.a.center();
    const V vb = unit_vector<3>(rng) * uniform(rng, 0, 1);
    const V closing = r * uniform(rng, 0.3, 1.6) + unit_vector<3>(rng) * uniform(rng, 0, 1.5);
    out.push_back({V(vb + closing), vb, V(unit_vector<3>(rng) * uniform(rng, 0.5, 3))});
  }
  return out;
}

// The truth of the swept cases, in 50 digits (see the header).
namespace truth {

namespace ref = ellipsect::reference;
using ref::Real;
using RV = ref::RVec<3>;
using RM = ref::RMat<3>;
using LV = Eigen::Matrix<long double, 3, 1>;
using LM = Eigen::Matrix<long double, 3, 3>;

// The body at time t of its motion: center c + t v, axes exp(t [omega]x) axes (Rodrigues in
// Real, rigid_contact_reference.hpp).
struct BodyAt {
  RV center;
  RM axes;
  RV radii;
};

BodyAt body_at(const Ellipsoid<double, 3>& a, const V& velocity, const V& omega, const Real& t) {
  const RM axes = a.axes().cast<Real>();
  return {RV(ref::to_real<3>(V(a.center())) + t * ref::to_real<3>(velocity)), RM(ref::detail::rotation<3>(omega, t) * axes),
          ref::to_real<3>(V(a.radii()))};
}

RM quadric(const BodyAt& b) {
  RM d = RM::Zero();
  for (int i = 0; i < 3; ++i) d(i, i) = 1 / (b.radii[i] * b.radii[i]);
  return b.axes * d * b.axes.transpose();
}

// The shape's triangles moved by `offset`: the triangle, or the box's 12 boundary triangles
// from its corners formed in Real (center +- half extents along the axes as stored).
std::vector<ref::RTriangle<3>> triangles(const Item& it, Shape shape, const RV& offset) {
  std::vector<ref::RTriangle<3>> out;
  if (shape == Shape::triangle) {
    out.push_back({});
    for (int k = 0; k < 3; ++k) out.back()[k] = ref::to_real<3>(V(it.triangle.vertex(k))) + offset;
    return out;
  }
  const RV c = ref::to_real<3>(V(it.box.center())) + offset;
  const RM axes = it.box.axes().cast<Real>();
  const RV h = ref::to_real<3>(V(it.box.half_extents()));
  const auto corner = [&](int k) {
    RV x = c;
    for (int i = 0; i < 3; ++i) x += ((k >> i) & 1 ? h[i] : Real(-h[i])) * axes.col(i);
    return x;
  };
  for (int i = 0; i < 3; ++i)
    for (int side = 0; side < 2; ++side) {
      const int j = (i + 1) % 3, k = (i + 2) % 3, base = side << i;
      const RV q00 = corner(base), q10 = corner(base | 1 << j), q11 = corner(base | 1 << j | 1 << k),
               q01 = corner(base | 1 << k);
      out.push_back({q00, q10, q11});
      out.push_back({q00, q11, q01});
    }
  return out;
}

bool inside_box(const Item& it, const RV& offset, const RV& x) {
  const RV y = x - ref::to_real<3>(V(it.box.center())) - offset;
  for (int i = 0; i < 3; ++i)
    if (!(abs(y.dot(ref::to_real<3>(V(it.box.axes().col(i))))) < Real(it.box.half_extents()[i]))) return false;
  return true;
}

// Euclidean distance from the body (its frame: axes, radii) to the point center + y; 0
// inside. Outside, the nearest point is r_i^2 q_i / (r_i^2 + l), q = axes^T y, with l > 0
// the root of sum (r_i q_i / (r_i^2 + l))^2 = 1 (convex and decreasing), and the distance is
// l |q_i / (r_i^2 + l)|: `steps` Newton steps on l from the given start.
template <class S>
S point_distance(const Eigen::Matrix<S, 3, 3>& axes, const Eigen::Matrix<S, 3, 1>& radii, const Eigen::Matrix<S, 3, 1>& y,
                 S l, int steps) {
  using std::sqrt;
  const Eigen::Matrix<S, 3, 1> q = axes.transpose() * y;
  S inside = 0;
  for (int i = 0; i < 3; ++i) inside += q[i] * q[i] / (radii[i] * radii[i]);
  if (inside <= 1) return S(0);
  for (int k = 0; k < steps; ++k) {
    S f = -1, df = 0;
    for (int i = 0; i < 3; ++i) {
      const S u = radii[i] * q[i] / (radii[i] * radii[i] + l);
      f += u * u;
      df -= 2 * u * u / (radii[i] * radii[i] + l);
    }
    l -= f / df;
  }
  S n = 0;
  for (int i = 0; i < 3; ++i) n += (q[i] / (radii[i] * radii[i] + l)) * (q[i] / (radii[i] * radii[i] + l));
  return l * S(sqrt(n));
}

// Distance of the segment [p0, p1] to the body: golden section along the segment in long
// double (the distance is convex there), then Real at the point found (Newton from the
// long double root) and at both ends.
Real segment_distance(const BodyAt& b, const RV& p0, const RV& p1) {
  using L = long double;
  const LM axes = b.axes.cast<L>();
  const LV radii = b.radii.cast<L>(), y0 = RV(p0 - b.center).cast<L>(), e = RV(p1 - p0).cast<L>();
  const auto root = [&](const LV& y) {
    // the long double secular root (0 inside), the start of the Real polish
    const LV q = axes.transpose() * y;
    L l = 0;
    for (int k = 0; k < 400; ++k) {
      L f = -1, df = 0;
      for (int i = 0; i < 3; ++i) {
        const L u = radii[i] * q[i] / (radii[i] * radii[i] + l);
        f += u * u;
        df -= 2 * u * u / (radii[i] * radii[i] + l);
      }
      if (!(f > 0) || df == 0) break;
      const L step = f / df;
      l -= step;
      if (-step <= std::numeric_limits<L>::epsilon() * l) break;
    }
    return l;
  };
  const auto dl = [&](L s) { return point_distance<L>(axes, radii, LV(y0 + s * e), root(LV(y0 + s * e)), 0); };
  const L s_best = ref::detail::golden_max<L>([&](L s) { return -dl(s); }, L(0), L(1), 70);
  Real best = ref::detail::infinity();
  for (const L s : {L(0), L(1), s_best}) {
    const RV y = p0 + Real(s) * (p1 - p0) - b.center;
    best = std::min(best, point_distance<Real>(b.axes, b.radii, y, Real(root(y.cast<L>())), 4));
  }
  return best;
}

// The static gap at one time: `value` with the sign of overlap (d - 1 for triangles and
// boxes; the capsule's Euclidean gap over largest radius + radius), `euclid` a lower bound on
// the Euclidean distance (meaningful where value > 0).
struct Gap {
  Real value, euclid;
};

Gap gap(const Item& it, Shape shape, const BodyAt& b, const RV& offset) {
  if (shape == Shape::capsule) {
    const Real g = segment_distance(b, RV(ref::to_real<3>(V(it.capsule.point(0))) + offset),
                                    RV(ref::to_real<3>(V(it.capsule.point(1))) + offset)) -
                   Real(it.capsule.radius());
    return {g / Real(it.a.radii().maxCoeff() + it.capsule.radius()), g};
  }
  const RM M = quadric(b);
  Real m = ref::detail::infinity();
  for (const auto& tri : triangles(it, shape, offset)) m = std::min(m, Real(ref::triangle_gaps<3>(M, b.center, tri).d - 1));
  if (shape == Shape::box && inside_box(it, offset, b.center)) return {-abs(m), Real(-1)};
  return {m, m * Real(it.a.radii().minCoeff())};
}

struct Crossing {
  Real time;     // first t in [0, window] with a gap <= 0; +infinity for none
  Real minimum;  // least gap found in the window (the gap at 0 when it is <= 0)
};

Real bisect(const std::function<Real(const Real&)>& f, Real lo, Real hi) {
  for (int k = 0; k < 110; ++k) {
    const Real mid = (lo + hi) / 2;
    (f(mid) > 0 ? lo : hi) = mid;
  }
  return hi;
}

// First root of a convex f on [0, window].
Crossing convex_crossing(const std::function<Real(const Real&)>& f) {
  const Real f0 = f(Real(0));
  if (f0 <= 0) return {Real(0), f0};
  Real at = ref::detail::golden_max<Real>([&](const Real& t) { return Real(-f(t)); }, Real(0), Real(window), 100);
  Real least = f(at);
  if (const Real end = f(Real(window)); end < least) least = end, at = Real(window);
  if (least > 0) return {ref::detail::infinity(), least};
  return {bisect(f, Real(0), at), least};
}

// Translation: the body at velocity va, the shape at vb.
Crossing translation(const Item& it, Shape shape, const Sweep& sw) {
  const RV va = ref::to_real<3>(sw.va), vb = ref::to_real<3>(sw.vb);
  const BodyAt b0 = body_at(it.a, sw.va, V::Zero(), Real(0));
  if (shape == Shape::capsule)
    return convex_crossing([&](const Real& t) { return gap(it, shape, body_at(it.a, sw.va, V::Zero(), t), RV(t * vb)).value; });
  const Gap g0 = gap(it, shape, b0, RV::Zero());
  if (g0.value <= 0) return {Real(0), g0.value};
  const RM M = quadric(b0);
  Crossing out{ref::detail::infinity(), g0.value};
  for (const auto& tri : triangles(it, shape, RV::Zero())) {
    const ref::MovingTriangle<3> m{M, b0.center, va, vb, tri};
    const Crossing c = convex_crossing([&](const Real& t) { return Real(m.at(t).d - 1); });
    out.time = std::min(out.time, c.time);
    out.minimum = std::min(out.minimum, c.minimum);
  }
  return out;
}

// Rigid motion of the body (va, omega), the shape at vb: sampling, refinement, bisection.
Crossing rigid(const Item& it, Shape shape, const Sweep& sw) {
  const RV vb = ref::to_real<3>(sw.vb);
  const auto g = [&](const Real& t) { return gap(it, shape, body_at(it.a, sw.va, sw.omega, t), RV(t * vb)); };
  const auto value = [&](const Real& t) { return g(t).value; };
  const double speed = (sw.va - sw.vb).norm() + sw.omega.norm() * it.a.radii().maxCoeff();
  const Real W(speed * (1 + 1e-9)), spacing = Real(window) / 1000;
  Gap cur = g(Real(0));
  if (cur.value <= 0) return {Real(0), cur.value};
  Real minimum = cur.value, t = 0, t1 = -1, v1 = 0;  // (t1, v1): the sample before t
  const auto hit = [&](const Real& lo, const Real& at) {
    const Real time = bisect(value, lo, at);
    minimum = std::min(minimum, value(std::min(Real(window), Real(at + spacing))));  // how deep it goes
    return Crossing{time, minimum};
  };
  while (t < Real(window)) {
    const Real step = W > 0 ? std::max(Real(cur.euclid / W), spacing) : Real(window);
    const Real next = std::min(Real(t + step), Real(window));
    const Gap g_next = g(next);
    minimum = std::min(minimum, g_next.value);
    if (g_next.value <= 0) return hit(t, next);
    if (t1 >= 0 && cur.value <= v1 && cur.value < g_next.value && cur.value < Real(0.1)) {
      const Real at = ref::detail::golden_max<Real>([&](const Real& s) { return Real(-value(s)); }, t1, next, 100);
      const Real v = value(at);
      minimum = std::min(minimum, v);
      if (v <= 0) return hit(t1, at);
    }
    t1 = t, v1 = cur.value;
    t = next, cur = g_next;
  }
  return {ref::detail::infinity(), minimum};
}

}  // namespace truth

// The truth of each swept case as an expected answer; `judged` false for grazes (least gap
// within 1e-9 of 0) and hits within 1e-9 of the window's end.
struct Expected {
  bench::Answer answer;
  bool judged;
};

const std::vector<Expected>& expected(Shape shape, bool rigid_motion) {
  static std::vector<Expected> cache[2][3];
  auto& out = cache[rigid_motion][static_cast<int>(shape)];
  if (!out.empty()) return out;
  const auto start = std::chrono::steady_clock::now();
  const auto& its = items(shape);
  const auto& sws = sweeps(shape);
  for (std::size_t i = 0; i < its.size(); ++i) {
    const truth::Crossing c = rigid_motion ? truth::rigid(its[i], shape, sws[i]) : truth::translation(its[i], shape, sws[i]);
    const double time = reference::to_double(c.time), minimum = reference::to_double(c.minimum);
    const bench::Answer a = time == 0 ? bench::Answer{bench::Outcome::at_start, 0}
                            : std::isinf(time) ? bench::Answer{bench::Outcome::none, time}
                                               : bench::Answer{bench::Outcome::hit, time};
    out.push_back({a, !(std::abs(minimum) <= 1e-9) && !(a.outcome == bench::Outcome::hit && window - time <= 1e-9)});
  }
  std::fprintf(stderr, "truth for %s (%s): %.1f s\n", name(shape), rigid_motion ? "rigid" : "translation",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return out;
}

// Answers against the truth: counters n, wrong, missed, late, max_err; then the timing.
template <class Query>
void run_swept(benchmark::State& state, Shape shape, bool rigid_motion, Query query) {
  const auto& want = expected(shape, rigid_motion);
  int n = 0, wrong = 0, missed = 0, late = 0, hits = 0, at_start = 0;
  double max_err = 0;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < want.size(); ++i) {
    index.push_back(i);
    if (!want[i].judged) continue;
    ++n;
    const bench::Answer got = query(i), w = want[i].answer;
    hits += w.outcome == bench::Outcome::hit;
    at_start += w.outcome == bench::Outcome::at_start;
    double err = 0;
    if (got.outcome == bench::Outcome::hit && w.outcome == bench::Outcome::hit) {
      err = std::abs(got.time - w.time) / w.time;
      max_err = std::max(max_err, err);
    }
    wrong += got.outcome != w.outcome || err > 1e-6;
    missed += w.outcome != bench::Outcome::none &&
              (got.outcome == bench::Outcome::none || got.outcome == bench::Outcome::failed);
    late += w.outcome == bench::Outcome::hit && got.outcome == bench::Outcome::hit && got.time > w.time * (1 + 1e-6);
  }
  bench::time_cases(state, index, query);
  state.counters["n"] = n;
  state.counters["wrong"] = wrong;
  state.counters["missed"] = missed;
  state.counters["late"] = late;
  state.counters["max_err"] = max_err;
  state.counters["truth_hits"] = hits;
  state.counters["truth_at_start"] = at_start;
}

template <class Motion>
Contact<double, 3> ellipsect_swept(const Item& it, Shape shape, const Motion& motion, const V& vb) {
  return shape == Shape::triangle ? first_contact(it.a, motion, it.triangle, vb, window)
         : shape == Shape::box    ? first_contact(it.a, motion, it.box, vb, window)
                                  : first_contact(it.a, motion, it.capsule, vb, window);
}

void ellipsect_swept_bench(benchmark::State& state, Shape shape, bool rigid_motion) {
  const auto& its = items(shape);
  const auto& sws = sweeps(shape);
  run_swept(state, shape, rigid_motion, [&](std::size_t i) {
    return rigid_motion ? bench::answer(ellipsect_swept(its[i], shape, RigidMotion<double, 3>{sws[i].va, sws[i].omega}, sws[i].vb))
                        : bench::answer(ellipsect_swept(its[i], shape, VecArg<double, 3>(sws[i].va), sws[i].vb));
  });
}

#ifdef ELLIPSECT_HAVE_FCL
fcl::Transform3d pose(const Mat3<double>& axes, const V& center) {
  fcl::Transform3d p = fcl::Transform3d::Identity();
  Mat3<double> r = axes;
  if (r.determinant() < 0) r.col(2) = -r.col(2);
  p.linear() = r;
  p.translation() = center;
  return p;
}

struct FclItem {
  fcl::Ellipsoidd a;
  fcl::Transform3d pose_a;
  std::shared_ptr<fcl::CollisionGeometryd> b;
  fcl::Transform3d pose_b;
};

FclItem fcl_item(const Item& it, Shape shape) {
  FclItem f{fcl::Ellipsoidd(it.a.radii()[0], it.a.radii()[1], it.a.radii()[2]), pose(it.a.axes(), it.a.center()), nullptr,
            fcl::Transform3d::Identity()};
  if (shape == Shape::triangle) {
    auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
    model->beginModel();
    model->addSubModel({it.triangle.vertex(0), it.triangle.vertex(1), it.triangle.vertex(2)}, {fcl::Triangle(0, 1, 2)});
    model->endModel();
    f.b = model;
  } else if (shape == Shape::box) {
    const V h = it.box.half_extents();
    f.b = std::make_shared<fcl::Boxd>(2 * h[0], 2 * h[1], 2 * h[2]);
    f.pose_b = pose(it.box.axes(), it.box.center());
  } else {
    const V p0 = it.capsule.point(0), p1 = it.capsule.point(1);
    const double length = (p1 - p0).norm();
    f.b = std::make_shared<fcl::Capsuled>(it.capsule.radius(), length);
    // FCL's capsule lies along its local z axis, centered.
    Mat3<double> r = Mat3<double>::Identity();
    if (length > 0) {
      const V z = (p1 - p0) / length;
      const V x = z.unitOrthogonal();
      r.col(0) = x;
      r.col(1) = z.cross(x);
      r.col(2) = z;
    }
    f.pose_b = pose(r, (p0 + p1) / 2);
  }
  return f;
}

double fcl_distance(const FclItem& f) {
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  fcl::distance(&f.a, f.pose_a, f.b.get(), f.pose_b, request, result);
  return result.min_distance;
}

void fcl_distance_bench(benchmark::State& state, Shape shape) {
  const auto its = separated(shape);
  std::vector<FclItem> fs;
  std::vector<double> got;
  for (const auto& it : its) {
    fs.push_back(fcl_item(it, shape));
    got.push_back(fcl_distance(fs.back()));
  }
  bench::time_cases(state, fs, [](const FclItem& f) { return fcl_distance(f); });
  count_errors(state, its, got);
}

bool fcl_collide(const FclItem& f) {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(&f.a, f.pose_a, f.b.get(), f.pose_b, request, result);
  return result.isCollision();
}

void fcl_overlap_bench(benchmark::State& state, Shape shape) {
  const auto& its = items(shape);
  std::vector<FclItem> fs;
  int wrong = 0;
  for (const auto& it : its) {
    fs.push_back(fcl_item(it, shape));
    wrong += wrong_overlap(it, fcl_collide(fs.back()));
  }
  bench::time_cases(state, fs, [](const FclItem& f) { return fcl_collide(f); });
  state.counters["wrong"] = wrong;
}

// continuousCollide from the poses at 0 to those at the window's end: the body's from
// body_at (its rotation only under rigid motion), the shape's translated by window * vb.
void fcl_swept_bench(benchmark::State& state, Shape shape, bool rigid_motion, fcl::CCDMotionType motion) {
  const auto& its = items(shape);
  const auto& sws = sweeps(shape);
  std::vector<bench::FclMotion> ms;
  for (std::size_t i = 0; i < its.size(); ++i) {
    FclItem f = fcl_item(its[i], shape);
    const Ellipsoid<double, 3> a1 =
        body_at(its[i].a, RigidMotion<double, 3>{sws[i].va, rigid_motion ? sws[i].omega : V::Zero()}, window);
    fcl::Transform3d b1 = f.pose_b;
    b1.translation() += window * sws[i].vb;
    ms.push_back({std::make_shared<fcl::Ellipsoidd>(f.a), f.b, f.pose_a, pose(a1.axes(), a1.center()), f.pose_b, b1, window});
  }
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = motion;
  run_swept(state, shape, rigid_motion,
            [&](std::size_t i) { return bench::answer_from_time(bench::fcl_contact_time(ms[i], request)); });
}
#endif

void register_all() {
  for (const Shape shape : {Shape::triangle, Shape::box, Shape::capsule}) {
    benchmark::RegisterBenchmark((std::string("distance/ellipsect/") + name(shape)).c_str(), ellipsect_distance_bench,
                                 shape);
#ifdef ELLIPSECT_HAVE_FCL
    benchmark::RegisterBenchmark((std::string("distance/fcl/") + name(shape)).c_str(), fcl_distance_bench, shape);
#endif
  }
  for (const Shape shape : {Shape::box, Shape::capsule}) {
    benchmark::RegisterBenchmark((std::string("overlap/ellipsect/") + name(shape)).c_str(), ellipsect_overlap_bench,
                                 shape);
#ifdef ELLIPSECT_HAVE_FCL
    benchmark::RegisterBenchmark((std::string("overlap/fcl/") + name(shape)).c_str(), fcl_overlap_bench, shape);
#endif
  }
  for (const bool rigid_motion : {false, true})
    for (const Shape shape : {Shape::box, Shape::capsule, Shape::triangle}) {
      const std::string query = rigid_motion ? "rigid_contact/" : "first_contact/";
      benchmark::RegisterBenchmark((query + "ellipsect/" + name(shape)).c_str(), ellipsect_swept_bench, shape,
                                   rigid_motion);
#ifdef ELLIPSECT_HAVE_FCL
      if (!rigid_motion) {
        benchmark::RegisterBenchmark((query + "fcl/" + name(shape)).c_str(), fcl_swept_bench, shape, false, fcl::CCDM_TRANS);
      } else {
        benchmark::RegisterBenchmark((query + "fcl_screw/" + name(shape)).c_str(), fcl_swept_bench, shape, true,
                                     fcl::CCDM_SCREW);
        benchmark::RegisterBenchmark((query + "fcl_linear/" + name(shape)).c_str(), fcl_swept_bench, shape, true,
                                     fcl::CCDM_LINEAR);
      }
#endif
    }
}

}  // namespace

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, register_all); }
