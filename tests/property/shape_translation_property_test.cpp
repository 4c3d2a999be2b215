// Translation invariance of the shape queries: a body and a half-space, triangle, box,
// capsule or mesh (and a query point for closest_point), moved together by an offset of 1e3
// to 1e6 sizes, keep the accuracy their headers state relative to the pair's size, not to
// the magnitude of the coordinates.
//
// The scenes lie on the grid of 2^-20 within 8 of the origin and the offsets are multiples
// of 2^-20 below 2^21: every translated coordinate is exact, so the translated pair is the
// same geometry and the 50-digit references on the untranslated input are those of the
// translated input. Claims under test (scale = largest radius + the shape's extent from the
// body's center, about 1 to 10):
//   classify, overlap       the untranslated relation wherever the reference's gap (support
//                           gap, or the half-space's lower gap; for a mesh each triangle's)
//                           is beyond 1e-9 scale of 0;
//   signed_distance         within the header's bound of the reference: 1e-14 (R + |L|)
//                           for a half-space, 1e-12 scale for triangles, boxes and capsules
//                           (polytope_distance.hpp), and for a mesh (its triangles');
//   closest_point           within 1e-14 scale of the untranslated distance, the point the
//                           untranslated point plus the offset to 1e-14 scale and the
//                           rounding of its coordinates;
//   first_contact           linear and rigid, turning and turning while growing (contact.hpp,
//                           "Rigid motion against shapes"):
//                           the untranslated status, and the untranslated time to 1e-12
//                           of scale / closing speed for head-on approaches (the contact
//                           is transversal);
//   collide_and_slide       through half-spaces and through a mesh: the untranslated
//                           status and moves, to 64 units of the offset's last bit, and
//                           the guarantees of slide.hpp on the translated input.
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/mesh.hpp>
#include <ellipsect/point.hpp>
#include <ellipsect/slide.hpp>
#include <ellipsect/triangle.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/reference/bridge.hpp"
#include "tests/reference/half_space_reference.hpp"
#include "tests/reference/support_gap_reference.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
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
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double grid = 0x1p-20;

double on_grid(double x) { return std::round(x / grid) * grid; }

template <int N>
Vec<double, N> on_grid(const Vec<double, N>& v) {
  return v.unaryExpr([](double x) { return on_grid(x); });
}

// A random body about the origin, its center and radii on the grid.
template <int N>
Ellipsoid<double, N> random_body(Rng& rng) {
  const Vec<double, N> c = on_grid<N>(Vec<double, N>::NullaryExpr([&](Eigen::Index) { return uniform(rng, -1, 1); }));
  return Ellipsoid<double, N>::from_axes(c, rotation<N>(rng), on_grid<N>(radii<N>(rng, 1.0, 20)));
}

// A point of the grid at distance about `d` from x along a random direction.
template <int N>
Vec<double, N> near_point(Rng& rng, const Vec<double, N>& x, double d) {
  return on_grid<N>(Vec<double, N>(x + d * unit_vector<N>(rng)));
}

// An offset of about 10^3 .. 10^6 on the grid.
template <int N>
Vec<double, N> random_offset(Rng& rng) {
  return on_grid<N>(Vec<double, N>(log_uniform(rng, 1e3, 1e6) * unit_vector<N>(rng)));
}

template <int N>
double detail_max_abs(const Vec<double, N>& v) {
  return v.cwiseAbs().maxCoeff();
}

template <int N>
std::string show(const Vec<double, N>& v) {
  std::ostringstream s;
  s.precision(17);
  s << v.transpose();
  return s.str();
}

// The outcomes counted, on one line: "title ND: outcome=count ...".
void print_tally(const char* title, int n, const std::map<std::string, int>& tally) {
  std::printf("%s %dD:", title, n);
  for (const auto& [outcome, count] : tally) std::printf(" %s=%d", outcome.c_str(), count);
  std::printf("\n");
}

// The relative gap beyond which the reference decides the relation (see the header).
constexpr double decided = 1e-9;

template <int N>
double scale_of(const Ellipsoid<double, N>& a, const std::vector<ref::DVec<N>>& vertices, double grow = 0) {
  double s = a.radii().maxCoeff() + grow;
  for (const auto& v : vertices) s = std::max(s, a.radii().maxCoeff() + grow + (v - a.center()).norm());
  return s;
}

// Linear and rigid first contact (turning, and turning while growing), translated against
// untranslated, for head-on motion.
template <int N, class Shape, class Query>
void check_contacts(const std::string& what, double scale, const Vec<double, N>& w, const Query& query) {
  const Contact<double, N> c0 = query(false, false, 0.0), c1 = query(true, false, 0.0);
  ASSERT_EQ(c1.status, c0.status) << what;
  if (c0.status == ContactStatus::hit) {
    ASSERT_NEAR(c1.time, c0.time, 1e-12 * scale / w.norm()) << what;
  }
  for (const double growth : {0.0, 0.2}) {
    const Contact<double, N> r0 = query(false, true, growth), r1 = query(true, true, growth);
    if (r0.status == ContactStatus::did_not_converge || r1.status == ContactStatus::did_not_converge) continue;
    ASSERT_EQ(r1.status, r0.status) << what << " (rigid, growth " << growth << ")";
    // The rigid query against a shape runs in the body's frame (contact.hpp); it formed the
    // body and the shape's vertices in world coordinates, whose times moved by up to 4.7e-9
    // of size / speed 1e6 sizes out.
    if (r0.status == ContactStatus::hit) {
      ASSERT_NEAR(r1.time, r0.time, 1e-12 * scale / w.norm()) << what << " (rigid, growth " << growth << ")";
    }
  }
}

template <int N>
RigidMotion<double, N> spinning(const Vec<double, N>& velocity, double growth) {
  RigidMotion<double, N> m;
  m.velocity = velocity;
  m.growth = growth;
  if constexpr (N == 2) {
    m.angular_velocity = 0.3;
  } else {
    m.angular_velocity = Vec<double, N>(0.1, -0.2, 0.25);
  }
  return m;
}

// The body against a convex polytope shape (triangle, box, capsule) with its vertices (the
// segment for a capsule, grown by `grow`).
template <int N, class Shape>
void check_polytope(const std::string& kind, int seed, const Ellipsoid<double, N>& a, const Shape& b,
                    const std::vector<ref::DVec<N>>& vertices, double grow, const Vec<double, N>& offset,
                    std::map<std::string, int>& tally) {
  std::ostringstream s;
  s << kind << " N=" << N << " seed=" << seed << " offset=" << show<N>(offset);
  const std::string what = s.str();
  const auto a1 = a.translated(offset);
  const auto b1 = b.translated(offset);
  const double scale = scale_of<N>(a, vertices, grow);
  ref::SupportGapMaximum<N> want = ref::max_support_gap<N>(ref::to_ref(a), vertices);
  const double gap = ref::to_double(Real(want.gap - Real(grow)));
  const Relation r0 = classify(a, b), r1 = classify(a1, b1);
  if (std::abs(gap) > decided * scale) {
    ASSERT_EQ(r1, r0) << what << " gap " << gap;
    ASSERT_EQ(r0 == Relation::separated, gap > 0) << what << " gap " << gap;
    ASSERT_EQ(overlap(a1, b1), gap < 0) << what;
  }
  tally[kind + " " + std::string(to_string(r1))]++;
  const Distance<double, N> d1 = signed_distance(a1, b1);
  ASSERT_NEAR(d1.distance, gap, 1e-12 * scale) << what;
  // Head-on: the shape's centroid heads for the body's center.
  Vec<double, N> centroid = Vec<double, N>::Zero();
  for (const auto& v : vertices) centroid += v / double(vertices.size());
  const Vec<double, N> w = (a.center() - centroid).normalized();
  check_contacts<N, Shape>(what, scale, w, [&](bool moved, bool rigid, double growth) {
    const auto& a_ = moved ? a1 : a;
    const auto& b_ = moved ? b1 : b;
    if (rigid) return first_contact(a_, spinning<N>(Vec<double, N>::Zero(), growth), b_, w, inf);
    return first_contact(a_, Vec<double, N>::Zero(), b_, w, inf);
  });
}

template <int N>
void run_shapes(int cases) {
  std::map<std::string, int> tally;
  for (int seed = 0; seed < cases; ++seed) {
    Rng rng(static_cast<std::uint64_t>(seed) * 7919 + N);
    const auto a = random_body<N>(rng);
    const double R = a.radii().maxCoeff();
    const Vec<double, N> offset = random_offset<N>(rng);
    // Shapes about the body's boundary: a distance of 0.5 to 2 largest radii from its center.
    const Vec<double, N> at = near_point<N>(rng, a.center(), R * uniform(rng, 0.5, 2));
    {  // Triangle.
      std::vector<ref::DVec<N>> v;
      for (int k = 0; k < 3; ++k) v.push_back(near_point<N>(rng, at, uniform(rng, 0.1, 2)));
      check_polytope<N>("triangle", seed, a, make_triangle<double, N>(v[0], v[1], v[2]), v, 0, offset, tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
    {  // Capsule (every fourth a ball: p0 = p1).
      const Vec<double, N> p0 = at, p1 = seed % 4 == 0 ? at : near_point<N>(rng, at, uniform(rng, 0.1, 3));
      const double radius = on_grid(uniform(rng, 0.05, 1));
      check_polytope<N>("capsule", seed, a, make_capsule<double, N>(p0, p1, radius), {p0, p1}, radius, offset, tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
    if (N == 2 || seed % 3 == 0) {  // Box (a third in 3D: the reference searches 8 corners' strata).
      const Vec<double, N> h = on_grid<N>(radii<N>(rng, 1.0, 10));
      // The axes as rounded: a grid box needs axes whose products with h land on the grid;
      // a rotation by an angle of rational tangent would, but any axes will do here: the
      // corners are computed from the stored fields either way, and the reference takes them.
      const auto b = make_box<double, N>(at, rotation<N>(rng), h);
      std::vector<ref::DVec<N>> v;
      for (int k = 0; k < (1 << N); ++k) v.push_back(b.corner(k));
      check_polytope<N>("box", seed, a, b, v, 0, offset, tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  print_tally("translated shapes", N, tally);
}

// Half-spaces: the relation, the signed distance (1e-14 (R + |L|)), first contact; and the
// closest point of the body to a query point.
template <int N>
void run_half_spaces_and_points(int cases) {
  std::map<std::string, int> tally;
  for (int seed = 0; seed < cases; ++seed) {
    Rng rng(static_cast<std::uint64_t>(seed) * 104729 + N);
    const auto a = random_body<N>(rng);
    const double R = a.radii().maxCoeff();
    const Vec<double, N> offset = random_offset<N>(rng);
    std::ostringstream s;
    s << "N=" << N << " seed=" << seed << " offset=" << show<N>(offset);
    const std::string what = s.str();
    const auto a1 = a.translated(offset);
    {
      const Vec<double, N> point = near_point<N>(rng, a.center(), R * uniform(rng, 0, 2));
      const Vec<double, N> normal = on_grid<N>(unit_vector<N>(rng));
      const auto h = make_half_space<double, N>(point, normal);
      const auto h1 = h.translated(offset);
      const ref::HalfSpaceGaps<N> g = ref::half_space_gaps<N>(ref::to_ref(a), h.point(), h.normal());
      const double lower = ref::to_double(g.lower);
      const Relation r0 = classify(a, h), r1 = classify(a1, h1);
      if (std::abs(lower) > decided * R) {
        ASSERT_EQ(r1, r0) << what;
        ASSERT_EQ(r1 == Relation::separated, lower > 0) << what;
      }
      tally["half-space " + std::string(to_string(r1))]++;
      ASSERT_NEAR(signed_distance(a1, h1).distance, lower, 1e-14 * (R + std::abs(lower))) << what;
      const Vec<double, N> w = -h.normal();
      check_contacts<N, HalfSpace<double, N>>(what, R + std::abs(lower), w, [&](bool moved, bool rigid, double growth) {
        const auto& a_ = moved ? a1 : a;
        const auto& h_ = moved ? h1 : h;
        if (rigid) return first_contact(a_, spinning<N>(Vec<double, N>::Zero(), growth), h_, w, inf);
        return first_contact(a_, Vec<double, N>::Zero(), h_, w, inf);
      });
      if (::testing::Test::HasFatalFailure()) return;
    }
    {
      const Vec<double, N> x = near_point<N>(rng, a.center(), R * log_uniform(rng, 1e-3, 4));
      const double scale = R + (x - a.center()).norm();
      const ClosestPoint<double, N> p0 = closest_point(a, x), p1 = closest_point(a1, Vec<double, N>(x + offset));
      ASSERT_NEAR(p1.signed_distance, p0.signed_distance, 2e-14 * scale) << what;
      const double ulp = 4 * std::numeric_limits<double>::epsilon() * detail_max_abs<N>(p1.point);
      ASSERT_LE((p1.point - offset - p0.point).cwiseAbs().maxCoeff(), 2e-14 * scale + ulp) << what;
    }
  }
  print_tally("translated half-spaces", N, tally);
}

// A mesh of a few triangles about the body (a strip), and collide_and_slide through it and
// through half-spaces (a floor and a wall).
template <int N>
void run_meshes_and_slides(int cases) {
  std::map<std::string, int> tally;
  std::map<std::string, double> worst;
  for (int seed = 0; seed < cases; ++seed) {
    Rng rng(static_cast<std::uint64_t>(seed) * 15485863 + N);
    const auto a = random_body<N>(rng);
    const double R = a.radii().maxCoeff();
    const Vec<double, N> offset = random_offset<N>(rng);
    std::ostringstream s;
    s << "N=" << N << " seed=" << seed << " offset=" << show<N>(offset);
    const std::string what = s.str();
    const auto a1 = a.translated(offset);
    // Five vertices about a point near the body, triangles (0 1 2) (1 2 3) (2 3 4).
    const Vec<double, N> at = near_point<N>(rng, a.center(), R * uniform(rng, 0.5, 2));
    std::vector<double> xs, xs1;
    std::vector<ref::DVec<N>> v;
    for (int k = 0; k < 5; ++k) {
      v.push_back(near_point<N>(rng, at, uniform(rng, 0.2, 2)));
      for (int i = 0; i < N; ++i) {
        xs.push_back(v.back()[i]);
        xs1.push_back(v.back()[i] + offset[i]);
      }
    }
    const std::vector<std::int64_t> index{0, 1, 2, 1, 2, 3, 2, 3, 4};
    const auto m = make_triangle_mesh<double, N>(xs, index), m1 = make_triangle_mesh<double, N>(xs1, index);
    double scale = 0, least = inf;
    bool decides = true;
    for (int t = 0; t < 3; ++t) {
      const std::vector<ref::DVec<N>> tri{v[t], v[t + 1], v[t + 2]};
      scale = std::max(scale, scale_of<N>(a, tri));
      const double g = ref::to_double(ref::max_support_gap<N>(ref::to_ref(a), tri).gap);
      least = std::min(least, g);
      decides = decides && std::abs(g) > decided * scale_of<N>(a, tri);
    }
    const MeshRelation r0 = classify(a, m), r1 = classify(a1, m1);
    if (decides) {
      ASSERT_EQ(r1.relation, r0.relation) << what;
      ASSERT_EQ(r1.relation == Relation::separated, least > 0) << what;
    }
    tally["mesh " + std::string(to_string(r1.relation))]++;
    ASSERT_NEAR(signed_distance(a1, m1).distance.distance, least, 1e-12 * scale) << what;
    const Vec<double, N> w = (a.center() - at).normalized();
    check_contacts<N, TriangleMesh<double, N>>(what, scale, w, [&](bool moved, bool rigid, double growth) {
      const auto& a_ = moved ? a1 : a;
      const auto& m_ = moved ? m1 : m;
      if (rigid) return first_contact(a_, spinning<N>(Vec<double, N>::Zero(), growth), m_, w, inf).contact;
      return first_contact(a_, Vec<double, N>::Zero(), m_, w, inf).contact;
    });
    if (::testing::Test::HasFatalFailure()) return;
    // Sliding: the body moved towards the strip by three times the distance, through it and
    // through a floor below the body and a wall ahead of it.
    const Vec<double, N> displacement = on_grid<N>(Vec<double, N>(-3 * (scale + 1) * w));
    const Vec<double, N> down = on_grid<N>(unit_vector<N>(rng));
    const std::vector<HalfSpace<double, N>> world{
        make_half_space<double, N>(on_grid<N>(Vec<double, N>(a.center() + 1.5 * R * down)), -down),
        make_half_space<double, N>(on_grid<N>(Vec<double, N>(a.center() - 2 * (scale + 1) * w)), w)};
    const std::vector<HalfSpace<double, N>> world1{world[0].translated(offset), world[1].translated(offset)};
    // Both slides run in their start body's frame (slide.hpp), where the two scenes are the
    // same numbers: the same status and the same moves, the translated end off the
    // untranslated one only by its rounding and the steps that clear it (a few units of the
    // offset's last bit). And slide.hpp's guarantees on the translated input: never ending
    // inside an obstacle, the moves within the displacement and adding up to the end center.
    for (const bool through_mesh : {false, true}) {
      const Slide<double, N> s0 = through_mesh ? collide_and_slide(a, displacement, m)
                                               : collide_and_slide<double, N>(a, displacement, world);
      const Slide<double, N> s1 = through_mesh ? collide_and_slide(a1, displacement, m1)
                                               : collide_and_slide<double, N>(a1, displacement, world1);
      const std::string where = through_mesh ? "mesh" : "half-spaces";
      tally["slide " + where + " " + std::string(to_string(s1.status))]++;
      ASSERT_EQ(s1.status, s0.status) << what << " " << where;
      ASSERT_LE((s1.moved - s0.moved).norm(), 64 * std::numeric_limits<double>::epsilon() * offset.norm())
          << what << " " << where;
      worst[where] = std::max(worst[where], (s1.moved - s0.moved).norm() / displacement.norm());
      if (s1.status == SlideStatus::overlapping_at_start) continue;
      bool inside = false;
      if (through_mesh) {
        const Relation end = classify(s1.body, m1).relation;
        inside = end != Relation::separated && end != Relation::touching;
      } else {
        for (const auto& h : world1) {
          const Relation end = classify(s1.body, h);
          inside = inside || (end != Relation::separated && end != Relation::touching);
        }
      }
      ASSERT_FALSE(inside) << what << " " << where;
      ASSERT_LE(s1.moved.norm(), displacement.norm() * (1 + 1e-15) + 64 * std::numeric_limits<double>::epsilon() * offset.norm())
          << what << " " << where;
      ASSERT_LE((s1.body.center() - a1.center() - s1.moved).norm(),
                64 * std::numeric_limits<double>::epsilon() * offset.norm())
          << what << " " << where;
    }
  }
  for (const auto& [where, w] : worst) std::printf("slide %s: moves apart by up to %.3g of the displacement\n", where.c_str(), w);
  print_tally("translated meshes and slides", N, tally);
}

TEST(ShapeTranslation, HalfSpacesAndPoints2D) { run_half_spaces_and_points<2>(cases(200)); }
TEST(ShapeTranslation, HalfSpacesAndPoints3D) { run_half_spaces_and_points<3>(cases(200)); }
TEST(ShapeTranslation, MeshesAndSlides2D) { run_meshes_and_slides<2>(cases(60)); }
TEST(ShapeTranslation, MeshesAndSlides3D) { run_meshes_and_slides<3>(cases(40)); }
TEST(ShapeTranslation, ConvexShapes2D) { run_shapes<2>(cases(30)); }
TEST(ShapeTranslation, ConvexShapes3D) { run_shapes<3>(cases(12)); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
