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
// distance: timed and checked on the separated cases only (FCL's distance is not a
// penetration depth); wrong: an error above 1e-6 (largest radius + |distance|); max_err: the
// largest error in those units. overlap: all cases, wrong outside a relative band of 1e-12.
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/triangle.hpp>

#include "bench/bench_support.hpp"
#include "scenarios/scenarios.hpp"
#include "tests/reference/support_gap_reference.hpp"

#include <benchmark/benchmark.h>

#ifdef ELLIPSECT_HAVE_FCL
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#endif

#include <cmath>
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

void ellipsect_overlap_bench(benchmark::State& state) {
  const auto& its = items(Shape::capsule);
  int wrong = 0;
  for (const auto& it : its) wrong += wrong_overlap(it, overlap(it.a, it.capsule));
  bench::time_cases(state, its, [](const Item& it) { return overlap(it.a, it.capsule); });
  state.counters["wrong"] = wrong;
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

void fcl_overlap_bench(benchmark::State& state) {
  const auto& its = items(Shape::capsule);
  std::vector<FclItem> fs;
  int wrong = 0;
  for (const auto& it : its) {
    fs.push_back(fcl_item(it, Shape::capsule));
    wrong += wrong_overlap(it, fcl_collide(fs.back()));
  }
  bench::time_cases(state, fs, [](const FclItem& f) { return fcl_collide(f); });
  state.counters["wrong"] = wrong;
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
  benchmark::RegisterBenchmark("overlap/ellipsect/capsule", ellipsect_overlap_bench);
#ifdef ELLIPSECT_HAVE_FCL
  benchmark::RegisterBenchmark("overlap/fcl/capsule", fcl_overlap_bench);
#endif
}

}  // namespace

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, register_all); }
