// first_contact of a body in rigid motion against half-spaces, triangles, boxes, capsules and
// meshes (contact.hpp, "Rigid motion against shapes"): closed forms, the translational
// special cases, start states, no contact ever, input errors and the step cap (the
// comparison with the 50-digit references is tests/property/rigid_shapes_property_test.cpp).
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/mesh.hpp>
#include <ellipsect/triangle.hpp>

#include "scenarios/scenarios.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using V2 = Vec<double, 2>;
using V3 = Vec<double, 3>;
constexpr double inf = std::numeric_limits<double>::infinity();

// A floor under the plane x_N = 0 as each shape: its top at x_N = 0 over [-10, 10]^(N-1).
template <int N>
struct Floors {
  HalfSpace<double, N> half_space = make_half_space<double, N>(Vec<double, N>::Zero(), Vec<double, N>::Unit(N - 1));
  Box<double, N> box = make_box<double, N>(-Vec<double, N>::Unit(N - 1), Mat<double, N>::Identity(),
                                           Vec<double, N>(Vec<double, N>::Constant(10) - 9 * Vec<double, N>::Unit(N - 1)));
  Capsule<double, N> capsule = make_capsule<double, N>(Vec<double, N>(-10 * Vec<double, N>::Unit(0) - Vec<double, N>::Unit(N - 1)),
                                                       Vec<double, N>(10 * Vec<double, N>::Unit(0) - Vec<double, N>::Unit(N - 1)), 1.0);
};

// A rod (radii 2 and 0.1) lying along x at height 1 above the floor, turning at rate w about
// the axis normal to the plane of x and x_N (2D: the plane's normal). Its lowest point along
// -x_N is sqrt(4 sin^2 + 0.01 cos^2) below the center at angle w t, so it touches the floor
// when sin^2(w t) = (1 - 0.01) / (4 - 0.01).
template <int N>
Ellipsoid<double, N> rod() {
  Vec<double, N> r = Vec<double, N>::Constant(0.1);
  r[0] = 2;
  return Ellipsoid<double, N>::from_axes(Vec<double, N>::Unit(N - 1), Mat<double, N>::Identity(), r);
}

template <int N>
RigidMotion<double, N> turning(double rate) {
  RigidMotion<double, N> m;
  if constexpr (N == 2) {
    m.angular_velocity = rate;
  } else {
    m.angular_velocity = V3(0, -rate, 0);  // x turns towards +z
  }
  return m;
}

const double rod_angle = std::asin(std::sqrt(0.99 / 3.99));

template <int N>
void expect_rod_hit(const Contact<double, N>& c, double rate, const char* what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_NEAR(c.time, rod_angle / rate, 1e-11 * rod_angle / rate);
  // The lowest point: the rod's support point along -x_N at that angle, on the floor.
  const double s = std::sin(rod_angle), co = std::cos(rod_angle);
  const double x = -(4 * s * co - 0.01 * s * co) / 1.0;  // -(r0^2 - r1^2) s c / rho, rho = 1
  EXPECT_NEAR(std::abs(c.point[0]), std::abs(x), 1e-9);
  EXPECT_NEAR(c.point[N - 1], 0, 1e-9);
  EXPECT_NEAR(c.normal[N - 1], -1, 1e-9);
}

template <int N>
void rod_tips_onto_every_floor() {
  const Floors<N> f;
  const auto a = rod<N>();
  for (const double rate : {0.5, 3.0}) {
    const auto m = turning<N>(rate);
    const Vec<double, N> still = Vec<double, N>::Zero();
    expect_rod_hit<N>(first_contact(a, m, f.half_space, still, 10.0), rate, "half-space");
    expect_rod_hit<N>(first_contact(a, m, f.box, still, 10.0), rate, "box");
    expect_rod_hit<N>(first_contact(a, m, f.capsule, still, 10.0), rate, "capsule");
    if constexpr (N == 3) {
      // A triangle of the floor's plane around the origin.
      const auto flat = make_triangle<double, 3>(V3(-10, -10, 0), V3(10, -10, 0), V3(0, 10, 0));
      expect_rod_hit<3>(first_contact(a, m, flat, still, 10.0), rate, "triangle");
      const std::vector<double> v{-10, -10, 0, 10, -10, 0, 10, 10, 0, -10, 10, 0};
      const std::vector<std::int64_t> t{0, 1, 2, 0, 2, 3};
      const MeshContact<double, 3> mc = first_contact(a, m, make_triangle_mesh<double, 3>(v, t), still, 10.0);
      expect_rod_hit<3>(mc.contact, rate, "mesh");
      EXPECT_GE(mc.triangle, 0);
    } else {
      // The segment y = 0 as a triangle of collinear points.
      const auto flat = make_triangle<double, 2>(V2(-10, 0), V2(10, 0), V2(0, 0));
      expect_rod_hit<2>(first_contact(a, m, flat, still, 10.0), rate, "segment");
    }
  }
}

TEST(RigidShapes, RodTipsOntoEveryFloor2D) { rod_tips_onto_every_floor<2>(); }
TEST(RigidShapes, RodTipsOntoEveryFloor3D) { rod_tips_onto_every_floor<3>(); }

// The floor rising at speed u towards the turning rod: contact where sqrt(4 sin^2(w t) +
// 0.01 cos^2(w t)) = 1 - u t, found here by bisection on that explicit function.
TEST(RigidShapes, RisingFloorMeetsTheTurningRod) {
  const double w = 1.0, u = 0.2;
  const auto gap = [&](long double t) {
    const long double s = std::sin(w * t), c = std::cos(w * t);
    return 1 - u * t - std::sqrt(4 * s * s + 0.01L * c * c);
  };
  long double lo = 0, hi = rod_angle / w;
  for (int i = 0; i < 200; ++i) (gap((lo + hi) / 2) > 0 ? lo : hi) = (lo + hi) / 2;
  const double want = double(lo);
  const Floors<3> f;
  const auto a = rod<3>();
  const auto m = turning<3>(w);
  for (const Contact<double, 3>& c :
       {first_contact(a, m, f.half_space, V3(0, 0, u), 10.0), first_contact(a, m, f.box, V3(0, 0, u), 10.0),
        first_contact(a, m, f.capsule, V3(0, 0, u), 10.0)}) {
    ASSERT_EQ(c.status, ContactStatus::hit);
    EXPECT_NEAR(c.time, want, 1e-11 * want);
    EXPECT_NEAR(c.point[2], u * want, 1e-9);  // on the floor, moved with it
  }
}

// A ball turning about any axis, or a spheroid turning about its axis of symmetry, is the
// same set at every turn: the translational answer (closed form), to the advancement's
// accuracy.
template <int N>
void symmetric_bodies_match_translation() {
  const Floors<N> f;
  Vec<double, N> c = Vec<double, N>::Zero();
  c[N - 1] = 3;
  c[0] = 0.7;
  RigidMotion<double, N> ball_spin, spheroid_spin;
  Vec<double, N> spheroid = Vec<double, N>::Constant(0.5);
  if constexpr (N == 2) {
    ball_spin.angular_velocity = 5;
  } else {
    ball_spin.angular_velocity = V3(2, -3, 4);
    spheroid_spin.angular_velocity = V3(0, 0, 5);  // about its symmetry axis z
    spheroid[2] = 0.25;
  }
  std::vector<std::pair<Ellipsoid<double, N>, RigidMotion<double, N>>> cases{
      {Ellipsoid<double, N>::from_axes(c, Mat<double, N>::Identity(), Vec<double, N>::Constant(0.5)), ball_spin}};
  if constexpr (N == 3) cases.push_back({Ellipsoid<double, 3>::from_axes(c, Mat<double, 3>::Identity(), spheroid), spheroid_spin});
  for (auto [a, m] : cases) {
    m.velocity = Vec<double, N>::Zero();
    m.velocity[N - 1] = -1;
    m.velocity[0] = 0.3;
    const Vec<double, N> still = Vec<double, N>::Zero();
    const auto check = [&](const Contact<double, N>& got, const Contact<double, N>& want) {
      ASSERT_EQ(got.status, ContactStatus::hit);
      ASSERT_EQ(want.status, ContactStatus::hit);
      EXPECT_NEAR(got.time, want.time, 1e-11 * want.time);
      EXPECT_LT((got.point - want.point).norm(), 1e-9);
      EXPECT_LT((got.normal - want.normal).norm(), 1e-9);
    };
    check(first_contact(a, m, f.half_space, still, 10.0), first_contact(a, m.velocity, f.half_space, still, 10.0));
    check(first_contact(a, m, f.box, still, 10.0), first_contact(a, m.velocity, f.box, still, 10.0));
    check(first_contact(a, m, f.capsule, still, 10.0), first_contact(a, m.velocity, f.capsule, still, 10.0));
  }
}

TEST(RigidShapes, SymmetricBodiesMatchTranslation2D) { symmetric_bodies_match_translation<2>(); }
TEST(RigidShapes, SymmetricBodiesMatchTranslation3D) { symmetric_bodies_match_translation<3>(); }

// Zero angular velocity: the translational answer, bit for bit.
TEST(RigidShapes, NoSpinIsTranslational) {
  const Floors<3> f;
  const auto a = rod<3>();
  const RigidMotion<double, 3> m{V3(0.1, 0.2, -0.3), V3::Zero()};
  const auto same = [](const Contact<double, 3>& x, const Contact<double, 3>& y) {
    EXPECT_EQ(x.status, y.status);
    const auto equal = [](double p, double q) { return p == q || (std::isnan(p) && std::isnan(q)); };
    EXPECT_TRUE(equal(x.time, y.time)) << x.time << " " << y.time;
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(equal(x.point[i], y.point[i]) && equal(x.normal[i], y.normal[i]));
  };
  same(first_contact(a, m, f.half_space, V3::Zero(), inf), first_contact(a, m.velocity, f.half_space, V3::Zero(), inf));
  same(first_contact(a, m, f.box, V3::Zero(), inf), first_contact(a, m.velocity, f.box, V3::Zero(), inf));
  same(first_contact(a, m, f.capsule, V3::Zero(), inf), first_contact(a, m.velocity, f.capsule, V3::Zero(), inf));
  const std::vector<double> v{-10, -10, 0, 10, -10, 0, 10, 10, 0, -10, 10, 0};
  const std::vector<std::int64_t> t{0, 1, 2, 0, 2, 3};
  const auto mesh = make_triangle_mesh<double, 3>(v, t);
  const MeshContact<double, 3> x = first_contact(a, m, mesh, V3::Zero(), inf), y = first_contact(a, m.velocity, mesh, V3::Zero(), inf);
  same(x.contact, y.contact);
  EXPECT_EQ(x.triangle, y.triangle);
}

// The rod turning high above the floor (its reach 2 below a center at height 3) never meets
// it, also in an unbounded window; a rod already on the floor reports its start state.
TEST(RigidShapes, StartStatesAndNoContactEver) {
  const Floors<3> f;
  const auto high = Ellipsoid<double, 3>::from_axes(V3(0, 0, 3), Mat<double, 3>::Identity(), V3(2, 0.1, 0.1));
  const auto m = turning<3>(4.0);
  EXPECT_EQ(first_contact(high, m, f.half_space, V3::Zero(), inf).status, ContactStatus::no_contact_in_window);
  EXPECT_EQ(first_contact(high, m, f.box, V3::Zero(), inf).status, ContactStatus::no_contact_in_window);
  EXPECT_EQ(first_contact(high, m, f.capsule, V3::Zero(), inf).status, ContactStatus::no_contact_in_window);
  // The rod reaches the floor at t = 0.2618 (rate 1): not within [0, 0.2].
  EXPECT_EQ(first_contact(rod<3>(), turning<3>(1.0), f.box, V3::Zero(), 0.2).status, ContactStatus::no_contact_in_window);
  const auto low = Ellipsoid<double, 3>::from_axes(V3(0, 0, 0.05), Mat<double, 3>::Identity(), V3(2, 0.1, 0.1));
  EXPECT_EQ(first_contact(low, m, f.box, V3::Zero(), 1.0).status, ContactStatus::overlapping_at_start);
  const auto resting = Ellipsoid<double, 3>::from_axes(V3(0, 0, 0.1), Mat<double, 3>::Identity(), V3(2, 0.1, 0.1));
  const Contact<double, 3> c = first_contact(resting, m, f.half_space, V3::Zero(), 1.0);
  EXPECT_EQ(c.status, ContactStatus::touching_at_start);
  EXPECT_EQ(c.time, 0.0);
}

// A mesh's answer is the earliest of its triangles' (ties: the lowest index): the hierarchy's
// ball sweep never drops the triangle that is hit first. Random meshes of 40 triangles in
// [-3, 3]^3 and turning rods thrown through them.
TEST(RigidShapes, MeshIsTheEarliestTriangle) {
  scenarios::detail::Rng rng(77);
  const auto u = [&](double s) { return scenarios::detail::uniform(rng, -s, s); };
  int hits = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<double> v;
    std::vector<std::int64_t> t;
    for (int k = 0; k < 40; ++k) {
      const V3 base(u(3), u(3), u(3));
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) v.push_back(base[i] + u(0.7));
      for (int j = 0; j < 3; ++j) t.push_back(3 * k + j);
    }
    const auto mesh = make_triangle_mesh<double, 3>(v, t);
    const auto a = Ellipsoid<double, 3>::from_axes(V3(u(1), u(1), 6), scenarios::detail::rotation<3>(rng), V3(0.8, 0.2, 0.1));
    const RigidMotion<double, 3> m{V3(u(0.5), u(0.5), -1), V3(u(3), u(3), u(3))};
    const V3 drift(u(0.2), u(0.2), u(0.2));
    const MeshContact<double, 3> got = first_contact(a, m, mesh, drift, 12.0);
    Contact<double, 3> want;
    want.status = ContactStatus::no_contact_in_window;
    std::int64_t triangle = -1;
    for (std::size_t k = 0; k < mesh.triangle_count(); ++k) {
      const Contact<double, 3> c = first_contact(a, m, mesh.triangle(k), drift, 12.0);
      ASSERT_NE(c.status, ContactStatus::did_not_converge);
      if (c.status == ContactStatus::hit && (triangle < 0 || c.time < want.time)) {
        want = c;
        triangle = std::int64_t(k);
      }
    }
    ASSERT_EQ(got.contact.status, want.status) << trial;
    if (want.status != ContactStatus::hit) continue;
    ++hits;
    EXPECT_EQ(got.triangle, triangle) << trial;
    EXPECT_EQ(got.contact.time, want.time) << trial;
    EXPECT_EQ(got.contact.point, want.point) << trial;
  }
  EXPECT_GT(hits, 10);
}

TEST(RigidShapes, InvalidInputAndStepCap) {
  const Floors<3> f;
  const auto a = rod<3>();
  RigidMotion<double, 3> bad = turning<3>(1.0);
  bad.angular_velocity[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(first_contact(a, bad, f.box, V3::Zero(), 1.0).status, ContactStatus::invalid_input);
  EXPECT_EQ(first_contact(a, turning<3>(1.0), f.box, V3(inf, 0, 0), 1.0).status, ContactStatus::invalid_input);
  EXPECT_EQ(first_contact(a, turning<3>(1.0), f.box, V3::Zero(), -1.0).status, ContactStatus::invalid_input);
  // One step: not enough to reach the contact; the time is a lower bound on it.
  Options one;
  one.max_motion_steps = 1;
  const Contact<double, 3> c = first_contact(a, turning<3>(1.0), f.half_space, V3::Zero(), 10.0, one);
  EXPECT_EQ(c.status, ContactStatus::did_not_converge);
  EXPECT_LT(c.time, rod_angle);
  EXPECT_TRUE(std::isnan(c.point[0]));
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
