// Bodies against triangles (triangle.hpp) against the 50-digit reference
// (tests/reference/triangle_reference.hpp: the quadric minimized over the triangle in world
// coordinates, the minimizer checked against its optimality condition, contact times by
// searching the convex gap function in time).
//
// Claims under test, with d and D the reference's nearest and farthest scale factors:
//   classify exact outside the tangency band widened by 1e-14;
//   first_contact: the reference's start status; where the reference finds a contact in the
//   window (its minimum of d more than 1e-9 below 1: not a graze) a hit, at a time where the
//   reference's d is within 1e-12 of 1 and, where the approach is not grazing, within 1e-13
//   relative of the reference's time; the point within 1e-12 (size + |point|) of the
//   reference's contact point and the normal within 1e-12 of its normal; no hit where the
//   reference's minimum stays more than 1e-9 above 1.
// Cases (scenarios/triangle.hpp): random; aspect ratios to 1e4; near tangency at faces,
// edges and vertices (relative gaps 1e-13 to 1e-3, either side); containment; triangles 1e3
// to 1e6 radii across; needles, segments and points; scale 1e-6 and 1e6; grazing; zero
// relative velocity; and each of these made collinear, nearly collinear (a vertex 1 to 4 ulps
// off the segment), a point or nearly a point (tests/property/degenerate.hpp).
#include <ellipsect/triangle.hpp>

#include "scenarios/triangle.hpp"
#include "tests/property/degenerate.hpp"
#include "tests/reference/bridge.hpp"
#include "tests/reference/triangle_reference.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
namespace ref = ellipsect::reference;
using Real = ref::Real;

using scenarios::TriangleKind;
template <int N> using Case = scenarios::TriangleCase<N>;
using scenarios::describe;

template <int N>
std::array<ref::DVec<N>, 3> vertices_of(const Triangle<double, N>& t) {
  return {t.vertex(0), t.vertex(1), t.vertex(2)};
}

template <int N>
double distance_to(const Vec<double, N>& x, const ref::RVec<N>& y) {
  return ref::to_double(Real((x.template cast<Real>() - y).norm()));
}

template <int N>
void check(const Case<N>& c, std::map<std::string, int>& tally) {
  const auto body = ref::to_ref(c.a);
  const auto vertices = vertices_of<N>(c.b);
  const ref::TriangleGaps<N> g = ref::triangle_gaps<N>(body, vertices);
  const Options options;
  const std::optional<Relation> want = expected_relation(g.d, g.D, options.tolerance);
  const Relation got = classify(c.a, c.b);
  if (want) {
    ASSERT_EQ(got, *want) << describe(c) << "\n  d - 1 = " << Real(g.d - 1).str(3);
  }
  ASSERT_EQ(overlap(c.a, c.b), got != Relation::separated) << describe(c);
  tally[std::string(to_string(got))]++;

  const Contact<double, N> hit = first_contact(c.a, c.va, c.b, c.vb, c.t_max);
  tally[std::string("contact ") + std::string(to_string(hit.status))]++;
  const double size = c.a.radii().maxCoeff();
  if (!want) return;  // the start relation sits on a band edge
  if (*want == Relation::touching) {
    ASSERT_EQ(hit.status, ContactStatus::touching_at_start) << describe(c);
    return;
  }
  if (*want != Relation::separated) {
    ASSERT_EQ(hit.status, ContactStatus::overlapping_at_start) << describe(c);
    return;
  }
  const auto moving = ref::moving_triangle<N>(body, vertices, c.va, c.vb);
  const ref::TriangleContact want_hit = ref::triangle_contact_time<N>(moving, Real(c.window));
  if (abs(want_hit.minimum - 1) <= Real(1e-9)) return;  // a graze: either answer is right
  if (want_hit.time == ref::detail::infinity()) {
    ASSERT_EQ(hit.status, ContactStatus::no_contact_in_window) << describe(c);
    return;
  }
  const double want_t = ref::to_double(want_hit.time);
  if (std::abs(want_t - c.t_max) <= 1e-12 * want_t) return;  // contact at the window's end
  ASSERT_EQ(hit.status, ContactStatus::hit) << describe(c) << "\n  reference time " << want_t;
  const ref::TriangleGaps<N> at = moving.at(Real(hit.time));
  ASSERT_LE(abs(at.d - 1), Real(1e-12)) << describe(c) << "\n  time " << hit.time << " reference " << want_t;
  if (c.kind == TriangleKind::grazing) return;
  ASSERT_NEAR(hit.time, want_t, 1e-13 * want_t) << describe(c);
  // The reference's contact point: the nearest point of the triangle at the contact time.
  const ref::TriangleGaps<N> then = moving.at(want_hit.time);
  ASSERT_LE(distance_to<N>(hit.point, then.nearest), 1e-12 * (size + hit.point.norm())) << describe(c);
  const ref::RVec<N> normal = then.gradient / sqrt(then.gradient.squaredNorm());
  ASSERT_LE(distance_to<N>(hit.normal, normal), 1e-12) << describe(c);
}

void report(const char* title, std::map<std::string, int>& tally) {
  std::printf("%s:", title);
  for (const auto& [outcome, count] : tally) std::printf(" %s=%d", outcome.c_str(), count);
  std::printf("\n");
  // The mix reaches every outcome the cases aim at.
  if (!full_case_counts()) return;
  for (const char* outcome : {"separated", "touching", "overlapping", "a_contains_b", "contact hit",
                              "contact no_contact_in_window", "contact overlapping_at_start",
                              "contact touching_at_start"})
    EXPECT_GT(tally[outcome], 0) << outcome;
}

template <int N>
void run(const char* title) {
  std::map<std::string, int> tally;
  for (const TriangleKind kind : scenarios::triangle_kinds)
    for (int seed = 0; seed < cases(150); ++seed) {
      check<N>(scenarios::make_triangle_case<N>(kind, seed), tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  report(title, tally);
}

// A triangle with vertices in [-3, 3]^N about a body centered in [-1, 1]^N, both moving at
// random (speeds to 5 per unit time), t_max = 1: relative motions at any angle to the
// triangle's edges.
template <int N>
Case<N> random_motion_case(int seed) {
  using namespace scenarios::detail;
  using V = Vec<double, N>;
  Rng rng(static_cast<std::uint64_t>(seed) * 4099 + 7);
  const auto point = [&](double s) { return V(V::NullaryExpr([&](Eigen::Index) { return uniform(rng, -s, s); })); };
  const auto a = Ellipsoid<double, N>::from_axes(point(1), rotation<N>(rng), radii<N>(rng, 0.5, 10));
  const auto b = make_triangle<double, N>(point(3), point(3), point(3));
  const V va = unit_vector<N>(rng) * uniform(rng, 0, 5), vb = unit_vector<N>(rng) * uniform(rng, 0, 5);
  return {TriangleKind::random, seed, a, b, va, vb, 1.0, 1.0, 0.0};
}

// Every scenario's triangle, and the random moving ones above, made collinear, nearly
// collinear, a point or nearly a point in world coordinates (tests/property/degenerate.hpp):
// the same claims.
template <int N>
void run_degenerate(const char* title) {
  std::map<std::string, int> tally;
  for (const Degenerate d : degenerate_kinds) {
    SCOPED_TRACE(name(d));
    for (const TriangleKind kind : scenarios::triangle_kinds)
      for (int seed = 0; seed < (full_case_counts() ? 4 : 2); ++seed) {
        check<N>(degenerate<N>(scenarios::make_triangle_case<N>(kind, seed), d), tally);
        if (::testing::Test::HasFatalFailure()) return;
      }
    for (int seed = 0; seed < (full_case_counts() ? 100 : 20); ++seed) {
      check<N>(degenerate<N>(random_motion_case<N>(seed), d), tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  report(title, tally);
}

TEST(TriangleProperty, MatchesReference2D) { run<2>("2D"); }
TEST(TriangleProperty, MatchesReference3D) { run<3>("3D"); }
TEST(TriangleProperty, DegenerateMatchReference2D) { run_degenerate<2>("degenerate 2D"); }
TEST(TriangleProperty, DegenerateMatchReference3D) { run_degenerate<3>("degenerate 3D"); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
