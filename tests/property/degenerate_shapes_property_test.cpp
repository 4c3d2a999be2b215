// Degenerate shapes as first-class cases against the 50-digit references (tests/reference/);
// the degenerate triangles' relation and linear first contact are in
// triangle_property_test.cpp. Claims under test:
//   * signed_distance of collinear, nearly collinear, point and nearly point triangles
//     (tests/property/degenerate.hpp) against the search of the sphere of directions
//     (support_gap_reference.hpp): as triangle.hpp states, the distance within 1e-12 scale
//     of the maximum of the support gap and the gap at the returned normal within 1e-12
//     scale of it (scale: the largest radius plus the largest |vertex - center|), point_a
//     on the body, the status classify's;
//   * first_contact of a turning body (contact.hpp, rigid motion; every other case also
//     growing, the reference body's radii times 1 + growth t) against those triangles,
//     against the least quadric value over the triangle (triangle_reference.hpp) with the
//     body turned in 50 digits (rigid_contact_reference.hpp), as
//     rigid_shapes_property_test.cpp: a hit where the reference's gap is within 1e-9 of 0
//     and not below -1e-12 at 8 earlier times; no contact where it stays above -1e-12 at
//     16 times of the window;
//   * first_contact of a turning (and every other case growing) body against a zero-length
//     capsule, against the pair reference for the body and the capsule's ball
//     (rigid_contact_reference.hpp): hit where it hits, never late, within 1e-9 of the time
//     scale where not grazing; no contact where it finds none;
//   * meshes of coplanar pieces: a square of a plane split into k x k squares of two
//     triangles each (3D; in 2D a segment split into k collinear segments), as floors, walls
//     and ramps, the body over its middle: classify and first_contact against the
//     reference for the unsplit square (its two triangles: triangle_reference.hpp), as
//     triangle.hpp states them (the time to the rounding of the pieces' vertices off the
//     square's plane besides); signed_distance, where apart, against the plane's
//     (half_space_reference.hpp) to 1e-12 scale; collide_and_slide against the same plane
//     as a half-space (the slide stays over the square), and box rooms with split walls
//     against the six half-spaces: the same end to 1e-12 of the size of the move.
#include <ellipsect/capsule.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/mesh.hpp>
#include <ellipsect/slide.hpp>
#include <ellipsect/triangle.hpp>

#include "scenarios/triangle.hpp"
#include "tests/property/degenerate.hpp"
#include "tests/reference/bridge.hpp"
#include "tests/reference/half_space_reference.hpp"
#include "tests/reference/rigid_contact_reference.hpp"
#include "tests/reference/support_gap_reference.hpp"
#include "tests/reference/triangle_reference.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
using namespace ellipsect::scenarios::detail;
namespace ref = ellipsect::reference;
using Real = ref::Real;
using scenarios::TriangleKind;

void report(const char* title, const std::map<std::string, int>& tally) {
  std::printf("%s:", title);
  for (const auto& [outcome, count] : tally) std::printf(" %s=%d", outcome.c_str(), count);
  std::printf("\n");
}

// The scenarios the degenerate triangles are made from here: random, thin bodies, and near
// tangency at the edge and the vertex that the segment and the point keep.
constexpr std::array<TriangleKind, 4> base_kinds{TriangleKind::random, TriangleKind::aspect, TriangleKind::near_edge,
                                                 TriangleKind::near_vertex};

template <int N>
void distance_of_degenerate_triangles() {
  std::map<std::string, int> tally;
  // The reference searches the sphere (about 100 ms a case in 3D).
  const int seeds = full_case_counts() && N == 2 ? 3 : 1;
  for (const Degenerate d : degenerate_kinds)
    for (const TriangleKind kind : base_kinds)
      for (int seed = 0; seed < seeds; ++seed) {
        const auto c = degenerate<N>(scenarios::make_triangle_case<N>(kind, seed), d);
        const std::string what = std::string(name(d)) + " " + scenarios::describe(c);
        const Distance<double, N> got = signed_distance(c.a, c.b);
        const std::vector<ref::DVec<N>> v{c.b.vertex(0), c.b.vertex(1), c.b.vertex(2)};
        const auto body = ref::to_ref(c.a);
        const ref::SupportGapMaximum<N> want = ref::max_support_gap<N>(body, v);
        double scale = c.a.radii().maxCoeff();
        for (const auto& x : v) scale = std::max(scale, c.a.radii().maxCoeff() + (x - c.a.center()).norm());
        const Relation relation = classify(c.a, c.b);
        ASSERT_EQ(got.status, relation == Relation::separated  ? DistanceStatus::separated
                              : relation == Relation::touching ? DistanceStatus::touching
                                                               : DistanceStatus::overlapping)
            << what;
        ASSERT_NEAR(got.distance, ref::to_double(want.gap), 1e-12 * scale) << what;
        ASSERT_LE(ref::to_double(Real(want.gap - ref::support_gap_at<N>(body, v, got.normal))), 1e-12 * scale) << what;
        const Vec<double, N> u = c.a.axes().transpose() * (got.point_a - c.a.center());
        ASSERT_NEAR(u.cwiseQuotient(c.a.radii()).norm(), 1, 1e-12) << what;
        tally[std::string(to_string(got.status))]++;
      }
  report(N == 2 ? "distance 2D" : "distance 3D", tally);
}

TEST(DegenerateShapes, TriangleDistance2D) { distance_of_degenerate_triangles<2>(); }
TEST(DegenerateShapes, TriangleDistance3D) { distance_of_degenerate_triangles<3>(); }

// The reference's relative gap of the body turned to time t and the triangle moved there.
template <int N>
double rigid_gap_at(const scenarios::TriangleCase<N>& c, const RigidMotion<double, N>& motion, double t) {
  const ref::RigidMotionRef<N> m{motion.velocity, motion.angular_velocity};
  const auto b = ref::detail::body_at<N>(ref::detail::make_rbody<N>(ref::to_ref<N>(c.a)), m, Real(t));
  ref::Body<N> body;
  for (int i = 0; i < N; ++i) {
    body.center[i] = ref::to_double(b.c(i));
    body.radii[i] = ref::to_double(Real(c.a.radii()[i]) * (1 + Real(motion.growth) * Real(t)));
    for (int j = 0; j < N; ++j) body.axes(i, j) = ref::to_double(b.axes(i, j));
  }
  std::array<ref::DVec<N>, 3> v;
  for (int k = 0; k < 3; ++k) v[k] = c.b.vertex(k) + t * c.vb;
  return ref::to_double(Real(ref::triangle_gaps<N>(body, v).d - 1));
}

// A motion at `velocity`, turning at `rate`, log-uniform in [0.1, 3], about a random axis,
// and where `growing` growing at a rate log-uniform in [0.01, 1].
template <int N>
RigidMotion<double, N> turning(Rng& rng, const Vec<double, N>& velocity, bool growing, double& rate) {
  RigidMotion<double, N> motion;
  motion.velocity = velocity;
  rate = log_uniform(rng, 0.1, 3);
  if constexpr (N == 2) {
    motion.angular_velocity = rate;
  } else {
    motion.angular_velocity = rate * unit_vector<3>(rng);
  }
  if (growing) motion.growth = log_uniform(rng, 0.01, 1);
  return motion;
}

template <int N>
void rigid_contact_of_degenerate_triangles() {
  std::map<std::string, int> tally;
  for (const Degenerate d : degenerate_kinds)
    for (const TriangleKind kind : base_kinds)
      for (int seed = 0; seed < cases(25) / 5; ++seed) {
        const auto c = degenerate<N>(scenarios::make_triangle_case<N>(kind, seed), d);
        Rng rng(static_cast<std::uint64_t>(seed) * 11 + 5);
        double rate;  // every other case grows (radii times 1 + growth t) as it turns
        const RigidMotion<double, N> motion = turning<N>(rng, c.va, seed % 2 == 1, rate);
        const double t_max = c.window;
        SCOPED_TRACE(std::string(name(d)) + " " + scenarios::describe(c) + " growth " + std::to_string(motion.growth));
        const Contact<double, N> got = first_contact(c.a, motion, c.b, c.vb, t_max);
        tally[std::string(to_string(got.status)) + (motion.growth > 0 ? " growing" : "")]++;
        const double start = rigid_gap_at<N>(c, motion, 0);
        switch (got.status) {
          case ContactStatus::overlapping_at_start: ASSERT_LT(start, 1e-12); break;
          case ContactStatus::touching_at_start: ASSERT_LT(std::abs(start), 1e-9); break;
          case ContactStatus::hit:
            ASSERT_GT(start, -1e-12);
            ASSERT_NEAR(rigid_gap_at<N>(c, motion, got.time), 0, 1e-9) << "at t = " << got.time;
            for (int k = 1; k < 8; ++k) ASSERT_GT(rigid_gap_at<N>(c, motion, got.time * k / 8), -1e-12) << k;
            break;
          case ContactStatus::no_contact_in_window:
            for (int k = 0; k <= 16; ++k) ASSERT_GT(rigid_gap_at<N>(c, motion, t_max * k / 16), -1e-12) << k;
            break;
          default: FAIL() << to_string(got.status);
        }
      }
  report(N == 2 ? "rigid 2D" : "rigid 3D", tally);
  EXPECT_GT(tally["hit"], 0);
  EXPECT_GT(tally["hit growing"], 0);
}

// A zero-length capsule (both end points equal: a ball of the capsule's radius) against a
// turning body, every other one growing, the capsule heading for the body: against the pair reference's
// first contact of the body and that ball (rigid_contact_reference.hpp, a different route
// from the capsule's advancement): hit where it hits, never late, and within 1e-9 of the
// time scale (size / speed) where the approach is not grazing (sine >= 1e-3); no contact
// where it finds none.
template <int N>
void rigid_contact_of_zero_length_capsules() {
  std::map<std::string, int> tally;
  for (int seed = 0; seed < cases(40); ++seed) {
    const auto c = scenarios::make_triangle_case<N>(base_kinds[std::size_t(seed) % base_kinds.size()], seed);
    Rng rng(static_cast<std::uint64_t>(seed) * 13 + 7);
    const Vec<double, N> p = c.b.vertex(std::size_t(seed) % 3);
    const double radius = c.a.radii().minCoeff() * log_uniform(rng, 0.01, 3);
    double rate;
    const RigidMotion<double, N> motion = turning<N>(rng, c.va, seed % 2 == 1, rate);
    // The capsule heads for the body's center (most cases hit), through a window long enough.
    const double speed = std::max(1.0, c.vb.norm());
    const Vec<double, N> vb = (c.a.center() - p).normalized() * speed;
    const double t_max = 4 * (c.a.center() - p).norm() / speed;
    SCOPED_TRACE(scenarios::describe(c) + " capsule at vertex " + std::to_string(seed % 3) + " radius " +
                 std::to_string(radius) + " growth " + std::to_string(motion.growth));
    const Contact<double, N> got = first_contact(c.a, motion, make_capsule<double, N>(p, p, radius), vb, t_max);
    const ref::RigidContact<N> want = ref::rigid_first_contact<N>(
        ref::to_ref(c.a), {motion.velocity, motion.angular_velocity, motion.growth}, ref::to_ref(make_ball<double, N>(p, radius)),
        {vb, RigidMotion<double, N>{}.angular_velocity, 0}, t_max, 1e-30, 6000);
    if (!want.resolved) {
      tally["unresolved"]++;
      continue;
    }
    tally[std::string(to_string(got.status)) + (motion.growth > 0 ? " growing" : "")]++;
    const double size = c.a.radii().maxCoeff() + radius;
    const double rates = (vb - c.va).norm() + (rate + motion.growth) * c.a.radii().maxCoeff();
    switch (want.kind) {
      case ref::ContactKind::hit: {
        ASSERT_EQ(got.status, ContactStatus::hit);
        ASSERT_LE(Real(got.time), want.time * (1 + Real(1e-15))) << "late by " << ref::to_double(Real(got.time) - want.time);
        if (want.approach_sine >= Real(1e-3)) {
          ASSERT_NEAR(got.time, ref::to_double(want.time), 1e-9 * size / rates);
        }
        break;
      }
      case ref::ContactKind::none: ASSERT_EQ(got.status, ContactStatus::no_contact_in_window); break;
      default: ASSERT_TRUE(got.status == ContactStatus::overlapping_at_start || got.status == ContactStatus::touching_at_start);
    }
  }
  report(N == 2 ? "zero-length capsules, rigid 2D" : "zero-length capsules, rigid 3D", tally);
  EXPECT_GT(tally["hit growing"], 0);
}

TEST(DegenerateShapes, TriangleRigidContact2D) { rigid_contact_of_degenerate_triangles<2>(); }
TEST(DegenerateShapes, TriangleRigidContact3D) { rigid_contact_of_degenerate_triangles<3>(); }
TEST(DegenerateShapes, ZeroLengthCapsuleRigidContact2D) { rigid_contact_of_zero_length_capsules<2>(); }
TEST(DegenerateShapes, ZeroLengthCapsuleRigidContact3D) { rigid_contact_of_zero_length_capsules<3>(); }

// A square of side 2 H about q in the plane normal to m (3D; in 2D the segment of length
// 2 H), split into k x k squares of two triangles (k collinear segments (a, b, b)); and the
// unsplit square's two triangles (the whole segment).
template <int N>
struct Plane {
  Vec<double, N> q, m, e1, e2;
  double H;
  // Appends the k x k split's vertices and triangles to v and t.
  void append(int k, std::vector<double>& v, std::vector<std::int64_t>& t) const {
    const std::int64_t base = std::int64_t(v.size() / N);
    const auto at = [&](int i, int j) { return base + std::int64_t(i) * (N == 3 ? k + 1 : 1) + j; };
    for (int i = 0; i <= k; ++i)
      for (int j = 0; j <= (N == 3 ? k : 0); ++j) {
        Vec<double, N> x = q + (-H + 2 * H * i / k) * e1;
        if constexpr (N == 3) x += (-H + 2 * H * j / k) * e2;
        v.insert(v.end(), x.data(), x.data() + N);
      }
    for (int i = 0; i < k; ++i) {
      if constexpr (N == 2) {
        t.insert(t.end(), {at(i, 0), at(i + 1, 0), at(i + 1, 0)});
      } else {
        for (int j = 0; j < k; ++j)
          t.insert(t.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  }
  TriangleMesh<double, N> split(int k) const {
    std::vector<double> v;
    std::vector<std::int64_t> t;
    append(k, v, t);
    return make_triangle_mesh<double, N>(v, t);
  }
  std::vector<std::array<ref::DVec<N>, 3>> whole() const {
    const Vec<double, N> a = q - H * e1, b = q + H * e1;
    if constexpr (N == 2) return {{a, b, b}};
    return {{Vec<double, N>(a - H * e2), Vec<double, N>(b - H * e2), Vec<double, N>(b + H * e2)},
            {Vec<double, N>(a - H * e2), Vec<double, N>(b + H * e2), Vec<double, N>(a + H * e2)}};
  }
};

template <int N>
struct PlaneCase {
  Plane<N> plane;
  int k;
  Ellipsoid<double, N> a;
  Vec<double, N> va;
  double t_max, gap;
  std::string what;
};

// Floors (m the last axis), walls (the first) and ramps (random), k from 1 to 8, the body
// at a relative gap in [-0.5, 2] or near tangency (1e-13 to 1e-3, either side) over the
// square's middle, moving towards the plane or away.
template <int N>
PlaneCase<N> make_plane_case(int kind, int seed) {
  Rng rng(static_cast<std::uint64_t>(seed) * 7907 + static_cast<std::uint64_t>(kind) * 131 + N);
  using V = Vec<double, N>;
  PlaneCase<N> c;
  const Mat<double, N> axes = rotation<N>(rng);
  const V r = radii<N>(rng, 1.0, 10);
  const double R = r.maxCoeff();
  // Columns of the frame: the normal, then the square's sides.
  const Mat<double, N> frame = kind == 2 ? rotation<N>(rng) : Mat<double, N>::Identity();
  const int normal = kind == 0 ? N - 1 : 0;
  c.plane.m = frame.col(normal);
  c.plane.e1 = frame.col((normal + 1) % N);
  c.plane.e2 = frame.col((normal + 2) % N);
  c.plane.q = V::NullaryExpr([&](Eigen::Index) { return uniform(rng, -3, 3); });
  c.plane.H = 20 * R;
  c.k = 1 + static_cast<int>(uniform(rng, 0, 8));
  const bool near = seed % 2 == 0;
  c.gap = near ? (uniform(rng, 0, 1) < 0.5 ? -1 : 1) * log_uniform(rng, 1e-13, 1e-3) : uniform(rng, -0.5, 2);
  const double rho = (r.asDiagonal() * axes.transpose() * c.plane.m).norm();
  V center = c.plane.q + (1 + c.gap) * rho * c.plane.m + uniform(rng, -2, 2) * R * c.plane.e1;
  if constexpr (N == 3) center += uniform(rng, -2, 2) * R * c.plane.e2;
  c.a = Ellipsoid<double, N>::from_axes(center, axes, r);
  const double sine = uniform(rng, -0.3, 1), speed = log_uniform(rng, 0.1, 10) * R;
  c.va = speed * (-sine * c.plane.m + std::sqrt(1 - sine * sine) * c.plane.e1);
  c.t_max = 5 * R / speed;
  std::ostringstream s;
  s.precision(17);
  s << (kind == 0 ? "floor" : kind == 1 ? "wall" : "ramp") << " seed " << seed << " k " << c.k << " gap " << c.gap;
  c.what = s.str();
  return c;
}

template <int N>
void check_plane(const PlaneCase<N>& c, std::map<std::string, int>& tally) {
  SCOPED_TRACE(c.what);
  const TriangleMesh<double, N> mesh = c.plane.split(c.k);
  const auto body = ref::to_ref(c.a);
  const auto pieces = c.plane.whole();
  // The unsplit square: d the least over its triangles (the body never contains it).
  Real d = 1e300;
  for (const auto& t : pieces) d = std::min(d, ref::triangle_gaps<N>(body, t).d);
  const std::optional<Relation> want = expected_relation(d, Real(1e300), 1e-12);
  const Relation got = classify(c.a, mesh).relation;
  tally[std::string(to_string(got))]++;
  if (want) {
    ASSERT_EQ(got, *want);
  }
  // signed_distance where apart: the plane's.
  if (want == Relation::separated) {
    const auto g = ref::half_space_gaps<N>(body, c.plane.q, c.plane.m);
    const MeshDistance<double, N> dist = signed_distance(c.a, mesh);
    ASSERT_NEAR(dist.distance.distance, ref::to_double(g.lower), 1e-12 * (c.a.radii().maxCoeff() + 2 * c.plane.H));
  }
  if (want != Relation::separated) return;
  // first_contact against the unsplit square's.
  const MeshContact<double, N> hit = first_contact(c.a, c.va, mesh, Vec<double, N>::Zero(), c.t_max);
  tally[std::string("contact ") + std::string(to_string(hit.contact.status))]++;
  Real when = ref::detail::infinity(), least = 1e300;
  std::vector<ref::MovingTriangle<N>> moving;
  for (const auto& t : pieces) {
    moving.push_back(ref::moving_triangle<N>(body, t, c.va, Vec<double, N>::Zero()));
    const ref::TriangleContact tc = ref::triangle_contact_time<N>(moving.back(), Real(c.t_max));
    when = std::min(when, tc.time);
    least = std::min(least, tc.minimum);
  }
  if (abs(least - 1) <= Real(1e-9)) return;  // a graze
  if (when == ref::detail::infinity()) {
    ASSERT_EQ(hit.contact.status, ContactStatus::no_contact_in_window);
    return;
  }
  ASSERT_EQ(hit.contact.status, ContactStatus::hit);
  Real at = 1e300;
  for (const auto& m : moving) at = std::min(at, m.at(Real(hit.contact.time)).d);
  ASSERT_LE(abs(at - 1), Real(1e-12)) << "time " << hit.contact.time;
  // The pieces' vertices lie off the square's plane by their rounding (about 2 eps their
  // magnitude), which moves the time by that over the approach speed.
  const double rounding = 8 * std::numeric_limits<double>::epsilon() * (c.plane.q.norm() + 2 * c.plane.H);
  ASSERT_NEAR(hit.contact.time, ref::to_double(when),
              1e-13 * ref::to_double(when) + rounding / std::abs(c.va.dot(c.plane.m)));
}

template <int N>
void split_planes() {
  std::map<std::string, int> tally;
  for (int kind = 0; kind < 3; ++kind)
    for (int seed = 0; seed < cases(40); ++seed) {
      check_plane<N>(make_plane_case<N>(kind, seed), tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  report(N == 2 ? "split planes 2D" : "split planes 3D", tally);
  if (!full_case_counts()) return;
  for (const char* outcome : {"separated", "touching", "overlapping", "contact hit", "contact no_contact_in_window"})
    EXPECT_GT(tally[outcome], 0) << outcome;
}

TEST(DegenerateShapes, SplitPlanes2D) { split_planes<2>(); }
TEST(DegenerateShapes, SplitPlanes3D) { split_planes<3>(); }

// collide_and_slide over a split plane and over the plane as a half-space: the same end.
template <int N>
void slides_over_split_planes() {
  std::map<std::string, int> tally;
  for (int kind = 0; kind < 3; ++kind)
    for (int seed = 0; seed < cases(40); ++seed) {
      const PlaneCase<N> c = make_plane_case<N>(kind, seed);
      SCOPED_TRACE(c.what);
      if (c.gap < 1e-12) continue;  // starting inside the half-space
      Rng rng(static_cast<std::uint64_t>(seed) + 99);
      const double R = c.a.radii().maxCoeff();
      Vec<double, N> move = -uniform(rng, 0, 2) * (1 + c.gap) * R * c.plane.m + uniform(rng, -5, 5) * R * c.plane.e1;
      if constexpr (N == 3) move += uniform(rng, -5, 5) * R * c.plane.e2;
      const std::vector<HalfSpace<double, N>> plane{make_half_space<double, N>(c.plane.q, c.plane.m)};
      const Slide<double, N> want = collide_and_slide(c.a, move, std::span<const HalfSpace<double, N>>(plane));
      const Slide<double, N> got = collide_and_slide(c.a, move, c.plane.split(c.k));
      tally[std::string(to_string(got.status))]++;
      ASSERT_EQ(got.status, want.status);
      ASSERT_LE((got.body.center() - want.body.center()).norm(), 1e-12 * (R + move.norm()));
    }
  report(N == 2 ? "slides 2D" : "slides 3D", tally);
  if (!full_case_counts()) return;
  EXPECT_GT(tally["slid"], 0);
}

TEST(DegenerateShapes, SlidesOverSplitPlanes2D) { slides_over_split_planes<2>(); }
TEST(DegenerateShapes, SlidesOverSplitPlanes3D) { slides_over_split_planes<3>(); }

// The room [-3, 3]^N with each wall split into k x k squares (k segments), and the same
// walls as half-spaces: the same end of long moves that bounce along walls into corners.
template <int N>
TriangleMesh<double, N> room(double L, int k) {
  std::vector<double> v;
  std::vector<std::int64_t> t;
  for (int axis = 0; axis < N; ++axis)
    for (int side = -1; side <= 1; side += 2) {
      Plane<N> wall;
      wall.m = Vec<double, N>::Unit(axis);
      wall.e1 = Vec<double, N>::Unit((axis + 1) % N);
      wall.e2 = Vec<double, N>::Unit((axis + 2) % N);
      wall.q = side * L * wall.m;
      wall.H = L;
      wall.append(k, v, t);
    }
  return make_triangle_mesh<double, N>(v, t);
}

template <int N>
void rooms() {
  Rng rng(5);
  const double L = 3;
  std::vector<HalfSpace<double, N>> walls;
  for (int axis = 0; axis < N; ++axis)
    for (int side = -1; side <= 1; side += 2)
      walls.push_back(make_half_space<double, N>(Vec<double, N>(side * L * Vec<double, N>::Unit(axis)),
                                                 Vec<double, N>(-side * Vec<double, N>::Unit(axis))));
  std::vector<TriangleMesh<double, N>> split;
  for (const int k : {1, 2, 5}) split.push_back(room<N>(L, k));
  std::map<std::string, int> tally;
  for (int i = 0; i < cases(60); ++i) {
    const auto body = Ellipsoid<double, N>::from_axes(Vec<double, N>::NullaryExpr([&](Eigen::Index) { return uniform(rng, -0.5, 0.5); }),
                                                      rotation<N>(rng), radii<N>(rng, 0.3, 20));
    const Vec<double, N> move = unit_vector<N>(rng) * log_uniform(rng, 1, 30);
    const Slide<double, N> want = collide_and_slide(body, move, std::span<const HalfSpace<double, N>>(walls));
    tally[std::string(to_string(want.status))]++;
    for (const auto& mesh : split) {
      const Slide<double, N> got = collide_and_slide(body, move, mesh);
      ASSERT_EQ(got.status, want.status) << "case " << i;
      ASSERT_LE((got.body.center() - want.body.center()).norm(), 1e-12 * L) << "case " << i;
    }
  }
  report(N == 2 ? "rooms 2D" : "rooms 3D", tally);
}

TEST(DegenerateShapes, RoomsOfSplitWalls2D) { rooms<2>(); }
TEST(DegenerateShapes, RoomsOfSplitWalls3D) { rooms<3>(); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
