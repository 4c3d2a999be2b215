// first_contact of a body in rigid motion against half-spaces, triangles, boxes and capsules
// (contact.hpp, "Rigid motion against shapes") against the 50-digit static references at
// chosen times: the body turned to time t in 50 digits (tests/reference/
// rigid_contact_reference.hpp's rotation), then its relative gap to the moved shape by
// another route than the library's: the half-space's support radius from the inverse
// quadric (half_space_reference.hpp), the triangle's least quadric value by its Lagrange
// conditions (triangle_reference.hpp; a box as its center inside or the least over its
// boundary triangles), the capsule's segment by the search of the sphere of directions
// (support_gap_reference.hpp) less the radius, in units of the largest radius.
//
// Claims under test:
//   hit             the reference's gap at the reported time within 1e-9 of 0, and not below
//                   -1e-12 at 8 earlier times spread over [0, time): not late, no overlap
//                   skipped;
//   no contact      the reference's gap not below -1e-12 at 16 times spread over the window;
//   start states    as the reference's gap at 0;
//   did_not_converge never, on these categories:
// random pairs, fast spin (10 to 100 radians per unit time), needles (aspect 1e3), turning
// in place (no relative velocity: contact, if any, by the turn alone), and random pairs at
// scale 1e-6 and 1e6.
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/triangle.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/reference/bridge.hpp"
#include "tests/reference/half_space_reference.hpp"
#include "tests/reference/rigid_contact_reference.hpp"
#include "tests/reference/support_gap_reference.hpp"
#include "tests/reference/triangle_reference.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
using namespace ellipsect::scenarios::detail;
namespace ref = ellipsect::reference;
using Real = ref::Real;

enum class Shape { half_space, triangle, box, capsule };
enum class Kind { random, fast_spin, needles, in_place, scaled };
constexpr std::array<Kind, 5> kinds{Kind::random, Kind::fast_spin, Kind::needles, Kind::in_place, Kind::scaled};
const char* name(Shape s) {
  return s == Shape::half_space ? "half-space" : s == Shape::triangle ? "triangle" : s == Shape::box ? "box" : "capsule";
}
const char* name(Kind k) {
  return k == Kind::random      ? "random"
         : k == Kind::fast_spin ? "fast spin"
         : k == Kind::needles   ? "needles"
         : k == Kind::in_place  ? "in place"
                                : "scaled";
}

template <int N>
struct Case {
  Ellipsoid<double, N> a;
  RigidMotion<double, N> motion;
  Vec<double, N> velocity_b;
  double t_max;
  HalfSpace<double, N> half_space;
  Triangle<double, N> triangle;
  Box<double, N> box;
  Capsule<double, N> capsule;
};

template <int N>
Case<N> make(Shape shape, Kind kind, int seed) {
  Rng rng(static_cast<std::uint64_t>(seed) * 7919 + static_cast<std::uint64_t>(kind) * 101 +
          static_cast<std::uint64_t>(shape) * 13 + N);
  using V = Vec<double, N>;
  const double scale = kind != Kind::scaled ? 1.0 : seed % 2 ? 1e-6 : 1e6;
  const auto point = [&](double s) { return V(V::NullaryExpr([&](Eigen::Index) { return uniform(rng, -s, s); })); };
  Case<N> c{Ellipsoid<double, N>::from_axes(V::Zero(), rotation<N>(rng), radii<N>(rng, 0.5 * scale, kind == Kind::needles ? 1e3 : 10)),
            {}, scale * point(0.3), 10.0, {}, {}, {}, {}};
  // The shape about the origin, of size about 1.
  const V n = unit_vector<N>(rng);
  c.half_space = make_half_space<double, N>(V(scale * point(0.5)), n);
  c.triangle = make_triangle<double, N>(V(scale * point(1)), V(scale * point(1)), V(scale * point(1)));
  c.box = make_box<double, N>(V(scale * point(0.3)), rotation<N>(rng), V(scale * radii<N>(rng, 0.5, 10)));
  c.capsule = make_capsule<double, N>(V(scale * point(1)), V(scale * point(1)), scale * log_uniform(rng, 0.05, 0.5));
  // The body 2 to 4 sizes out (on the half-space's outer side), heading for the shape, or
  // just clear of it for the turns in place.
  const V out = shape == Shape::half_space ? n : unit_vector<N>(rng);
  const double far = kind == Kind::in_place ? c.a.radii().maxCoeff() / scale + uniform(rng, 0.6, 1.5) : uniform(rng, 2, 4);
  const V center = scale * (far * out + point(0.3));
  c.a = Ellipsoid<double, N>::from_axes(center, c.a.axes(), c.a.radii());
  const double speed = kind == Kind::in_place ? 0 : uniform(rng, 0.5, 2);
  c.motion.velocity = c.velocity_b - scale * speed * out + scale * point(0.2) * (kind != Kind::in_place);
  const double rate = kind == Kind::fast_spin ? log_uniform(rng, 10, 100) : log_uniform(rng, 0.1, 3);
  if constexpr (N == 2) {
    c.motion.angular_velocity = seed % 3 ? rate : -rate;
  } else {
    c.motion.angular_velocity = rate * unit_vector<3>(rng);
  }
  return c;
}

// The body at time t in 50 digits, rounded to double for the references' entry points.
template <int N>
ref::Body<N> body_at_ref(const Case<N>& c, const Real& t) {
  ref::RigidMotionRef<N> m{c.motion.velocity, c.motion.angular_velocity};
  const ref::detail::RBody<N> b = ref::detail::body_at<N>(ref::detail::make_rbody<N>(ref::to_ref<N>(c.a)), m, t);
  ref::Body<N> out;
  for (int i = 0; i < N; ++i) {
    out.center[i] = ref::to_double(b.c(i));
    out.radii[i] = c.a.radii()[i];
    for (int j = 0; j < N; ++j) out.axes(i, j) = ref::to_double(b.axes(i, j));
  }
  return out;
}

// The reference's relative gap at time t (see the top).
template <int N>
double gap_at(const Case<N>& c, Shape shape, double t) {
  const ref::Body<N> body = body_at_ref<N>(c, Real(t));
  const Vec<double, N> shift = t * c.velocity_b;
  switch (shape) {
    case Shape::half_space: {
      const auto g = ref::half_space_gaps<N>(body, Vec<double, N>(c.half_space.point() + shift), c.half_space.normal());
      return ref::to_double(Real(g.lower / g.rho));
    }
    case Shape::triangle:
      return ref::to_double(Real(ref::triangle_gaps<N>(body, {Vec<double, N>(c.triangle.vertex(0) + shift),
                                                                Vec<double, N>(c.triangle.vertex(1) + shift),
                                                                Vec<double, N>(c.triangle.vertex(2) + shift)})
                                       .d -
                                   1));
    case Shape::box: {
      const Vec<double, N> local = c.box.axes().transpose() * (body.center - c.box.center() - shift);
      if ((local.cwiseAbs() - c.box.half_extents()).maxCoeff() < 0) return -1;  // the center inside
      const auto triangles = c.box.translated(shift).triangles();
      Real best = 1e300;
      for (const auto& tri : triangles) {
        const Real d = ref::triangle_gaps<N>(body, {tri.vertex(0), tri.vertex(1), tri.vertex(2)}).d;
        if (d < best) best = d;
      }
      return ref::to_double(Real(best - 1));
    }
    case Shape::capsule: {
      const std::vector<ref::DVec<N>> segment{c.capsule.point(0) + shift, c.capsule.point(1) + shift};
      return ref::to_double(Real((ref::max_support_gap<N>(body, segment).gap - c.capsule.radius()) / c.a.radii().maxCoeff()));
    }
  }
  return 0;
}

template <int N>
Contact<double, N> contact_of(const Case<N>& c, Shape shape) {
  switch (shape) {
    case Shape::half_space: return first_contact(c.a, c.motion, c.half_space, c.velocity_b, c.t_max);
    case Shape::triangle: return first_contact(c.a, c.motion, c.triangle, c.velocity_b, c.t_max);
    case Shape::box: return first_contact(c.a, c.motion, c.box, c.velocity_b, c.t_max);
    case Shape::capsule: return first_contact(c.a, c.motion, c.capsule, c.velocity_b, c.t_max);
  }
  return {};
}

template <int N>
void check_shape(Shape shape, int count) {
  std::map<std::string, int> tally;
  for (const Kind kind : kinds)
    for (int seed = 0; seed < count; ++seed) {
      const Case<N> c = make<N>(shape, kind, seed);
      const std::string what = std::string(name(shape)) + ", " + name(kind) + ", seed " + std::to_string(seed);
      SCOPED_TRACE(what);
      const Contact<double, N> got = contact_of<N>(c, shape);
      tally[std::string(to_string(got.status))]++;
      const double start = gap_at<N>(c, shape, 0);
      switch (got.status) {
        case ContactStatus::overlapping_at_start: ASSERT_LT(start, 1e-12); break;
        case ContactStatus::touching_at_start: ASSERT_LT(std::abs(start), 1e-9); break;
        case ContactStatus::hit: {
          ASSERT_GT(start, -1e-12);
          ASSERT_NEAR(gap_at<N>(c, shape, got.time), 0, 1e-9) << "at t = " << got.time;
          for (int k = 1; k < 8; ++k) ASSERT_GT(gap_at<N>(c, shape, got.time * k / 8), -1e-12) << "at k = " << k;
          ASSERT_NEAR(got.normal.norm(), 1, 1e-12);
          break;
        }
        case ContactStatus::no_contact_in_window:
          for (int k = 0; k <= 16; ++k) ASSERT_GT(gap_at<N>(c, shape, c.t_max * k / 16), -1e-12) << "at k = " << k;
          break;
        default: FAIL() << to_string(got.status);
      }
    }
  std::printf("%s %dD:", name(shape), N);
  for (const auto& [status, n] : tally) std::printf(" %s=%d", status.c_str(), n);
  std::printf("\n");
  EXPECT_GT(tally["hit"], 0);
}

// Cases per category: the capsule's reference searches the sphere (about 50 ms a time in
// 3D), so it runs fewer; the sanitizer pass a quarter.
int count(Shape shape, int n) {
  const int full = shape == Shape::capsule && n == 3 ? 2 : 8;
  return full_case_counts() ? full : std::max(1, full / 4);
}

TEST(RigidShapesProperty, HalfSpace2D) { check_shape<2>(Shape::half_space, count(Shape::half_space, 2)); }
TEST(RigidShapesProperty, HalfSpace3D) { check_shape<3>(Shape::half_space, count(Shape::half_space, 3)); }
TEST(RigidShapesProperty, Triangle2D) { check_shape<2>(Shape::triangle, count(Shape::triangle, 2)); }
TEST(RigidShapesProperty, Triangle3D) { check_shape<3>(Shape::triangle, count(Shape::triangle, 3)); }
TEST(RigidShapesProperty, Box2D) { check_shape<2>(Shape::box, count(Shape::box, 2)); }
TEST(RigidShapesProperty, Box3D) { check_shape<3>(Shape::box, count(Shape::box, 3)); }
TEST(RigidShapesProperty, Capsule2D) { check_shape<2>(Shape::capsule, count(Shape::capsule, 2)); }
TEST(RigidShapesProperty, Capsule3D) { check_shape<3>(Shape::capsule, count(Shape::capsule, 3)); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
