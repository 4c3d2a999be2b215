// Bodies against half-spaces (half_space.hpp) against the 50-digit reference
// (tests/reference/half_space_reference.hpp: the support radius from the quadric's inverse,
// the lowest point checked against its Lagrange conditions, the contact time by bisection on
// the gap at each time).
//
// Claims under test, with rho the support radius, scale = largest radius + |distance|:
//   classify exact outside the tangency band widened by 1e-14 rho;
//   |signed distance - L| <= 1e-14 scale; point_a, point_b and the contact point within
//   1e-14 (scale + |point|) of the reference's; the normal exactly -n;
//   contact time within 1e-14 relative, with the reference's status.
// Cases (scenarios/half_space.hpp): random; aspect ratios to 1e4; near tangency (outside and
// inside, relative gaps 1e-13 to 1e-3); containment; far apart; the plane's point 1e3 to 1e15
// sizes along the plane; scale 1e-6 and 1e6; grazing motion (closing speed 1e-9 of the
// speed) and zero closing speed.
#include <ellipsect/half_space.hpp>

#include "scenarios/half_space.hpp"
#include "tests/reference/bridge.hpp"
#include "tests/reference/half_space_reference.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
namespace ref = ellipsect::reference;
using Real = ref::Real;

using scenarios::Plane;
template <int N> using Case = scenarios::PlaneCase<N>;
using scenarios::describe;

// The reference's relation, or nullopt within 1e-14 rho of a band edge.
template <int N>
std::optional<Relation> expected_relation(const ref::HalfSpaceGaps<N>& g, double tolerance) {
  const Real band = Real(tolerance) * g.rho, margin = Real(1e-14) * g.rho;
  for (const Real& edge : {Real(g.lower - band), Real(g.lower + band), Real(g.upper + band)})
    if (abs(edge) <= margin) return std::nullopt;
  if (g.lower > band) return Relation::separated;
  if (g.lower >= -band) return Relation::touching;
  if (g.upper >= -band) return Relation::b_contains_a;
  return Relation::overlapping;
}

template <int N>
double distance_to(const Vec<double, N>& x, const ref::RVec<N>& y) {
  return ref::to_double(Real((x.template cast<Real>() - y).norm()));
}

template <int N>
void check(const Case<N>& c, std::map<std::string, int>& tally) {
  const auto body = ref::to_ref(c.a);
  const ref::HalfSpaceGaps<N> g = ref::half_space_gaps<N>(body, c.b.point(), c.b.normal());
  const double L = ref::to_double(g.lower);
  const double scale = c.a.radii().maxCoeff() + std::abs(L);
  const Options options;

  const std::optional<Relation> want = expected_relation<N>(g, options.tolerance);
  const Relation got = classify(c.a, c.b);
  if (want) {
    ASSERT_EQ(got, *want) << describe(c);
  }
  ASSERT_EQ(overlap(c.a, c.b), got != Relation::separated) << describe(c);
  tally[std::string(to_string(got))]++;

  const Distance<double, N> d = signed_distance(c.a, c.b);
  ASSERT_NEAR(d.distance, L, 1e-14 * scale) << describe(c);
  ASSERT_EQ(d.normal, (Vec<double, N>(-c.b.normal()))) << describe(c);
  const double point_tol = 1e-14 * (scale + d.point_a.norm());
  ASSERT_LE(distance_to<N>(d.point_a, g.lowest), point_tol) << describe(c);
  ASSERT_LE(distance_to<N>(d.point_b, ref::RVec<N>(g.lowest - g.lower * g.normal)), point_tol) << describe(c);
  const Distance<double, N> u = distance(c.a, c.b);
  ASSERT_EQ(u.status, d.status) << describe(c);
  if (u.status == DistanceStatus::overlapping) {
    ASSERT_EQ(u.distance, 0.0);
    ASSERT_TRUE(u.point_a.array().isNaN().all() && u.normal.array().isNaN().all());
  } else {
    ASSERT_EQ(u.distance, d.distance);
  }

  const Contact<double, N> hit = first_contact(c.a, c.va, c.b, c.vb, c.t_max);
  const Real t = ref::half_space_contact_time<N>(body, c.b.point(), c.b.normal(), c.va, c.vb, c.t_max);
  tally[std::string("contact ") + std::string(to_string(hit.status))]++;
  if (!want) return;  // the start relation sits on a band edge
  if (*want == Relation::touching) {
    ASSERT_EQ(hit.status, ContactStatus::touching_at_start) << describe(c);
  } else if (*want != Relation::separated) {
    ASSERT_EQ(hit.status, ContactStatus::overlapping_at_start) << describe(c);
  } else if (t == ref::detail::infinity()) {
    ASSERT_EQ(hit.status, ContactStatus::no_contact_in_window) << describe(c);
  } else {
    const double want_t = ref::to_double(t);
    if (std::abs(want_t - c.t_max) <= 1e-14 * want_t) return;  // contact at the window's end
    ASSERT_EQ(hit.status, ContactStatus::hit) << describe(c);
    ASSERT_NEAR(hit.time, want_t, 1e-14 * want_t) << describe(c);
    const ref::RVec<N> at = g.lowest + t * c.va.template cast<Real>();
    ASSERT_LE(distance_to<N>(hit.point, at), 1e-14 * (scale + hit.point.norm())) << describe(c);
    ASSERT_EQ(hit.normal, (Vec<double, N>(-c.b.normal()))) << describe(c);
  }
}

template <int N>
void run(const char* title) {
  std::map<std::string, int> tally;
  for (const Plane kind : scenarios::planes)
    for (int seed = 0; seed < cases(400); ++seed) {
      check<N>(scenarios::make_plane_case<N>(kind, seed), tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  std::printf("%s:", title);
  for (const auto& [outcome, count] : tally) std::printf(" %s=%d", outcome.c_str(), count);
  std::printf("\n");
  // The mix reaches every outcome the cases aim at.
  if (!full_case_counts()) return;
  for (const char* outcome : {"separated", "touching", "overlapping", "b_contains_a", "contact hit",
                              "contact no_contact_in_window", "contact overlapping_at_start"})
    EXPECT_GT(tally[outcome], 0) << outcome;
}

TEST(HalfSpaceProperty, MatchesReference2D) { run<2>("2D"); }
TEST(HalfSpaceProperty, MatchesReference3D) { run<3>("3D"); }

// float bodies are computed in double with their axes orthonormalized: within 1e-6 of the
// reference on the same (float) values, whose axes deviate from orthonormal by about 1e-7.
TEST(HalfSpaceProperty, FloatWithinTheStatedAccuracy) {
  for (int seed = 0; seed < cases(400); ++seed) {
    const Case<3> c = scenarios::make_plane_case<3>(Plane::random, seed);
    const auto a = Ellipsoid<float, 3>::from_axes(c.a.center().cast<float>(), c.a.axes().cast<float>(),
                                                  c.a.radii().cast<float>());
    const auto b = make_half_space<float, 3>(c.b.point().cast<float>(), c.b.normal().cast<float>());
    const auto got = signed_distance(a, b);
    const ref::Body<3> body{a.center().cast<double>(), a.axes().cast<double>(), a.radii().cast<double>()};
    const auto g = ref::half_space_gaps<3>(body, b.point().cast<double>(), b.normal().cast<double>());
    const double scale = a.radii().maxCoeff() + std::abs(ref::to_double(g.lower));
    ASSERT_NEAR(got.distance, ref::to_double(g.lower), 1e-6 * scale) << seed;
    ASSERT_LE(distance_to<3>(got.point_a.cast<double>(), g.lowest), 1e-6 * (scale + got.point_a.norm())) << seed;
  }
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
