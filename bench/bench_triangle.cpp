// A body against a triangle and against a 100,000-triangle mesh: ns per query and wrong
// answers, side by side with FCL 0.7 on the same cases.
//
// Triangles (scenarios/triangle.hpp, 3D, 256 cases per category, answers checked against
// the 50-digit reference of tests/reference/triangle_reference.hpp):
//   overlap/ellipsect/*        ellipsect::overlap
//   overlap/fcl/*              fcl::collide of an fcl::Ellipsoidd and the triangle as a
//                              one-triangle fcl::BVHModel<OBBRSSd> (FCL 0.7 has no test
//                              for an ellipsoid and an fcl::TrianglePd: "collision function
//                              between node type 11 and node type 18 is not supported"),
//                              GJK through libccd, FCL's default request
//   first_contact/ellipsect/*  ellipsect::first_contact (the triangle moving, t_max)
//   first_contact/fcl/*        fcl::continuousCollide over [0, t_max] (t_max = infinity: the
//                              reference's search window), default request: CCDC_NAIVE,
//                              fcl::collide at 10 sampled times
// wrong: overlap outside the tangency band 1e-12 differing from the reference; contact: a
// different outcome (hit, none, at the start) where the reference's least gap is not within
// 1e-9 of 0, or a time off by more than 1e-6 relative; max_err: the largest relative time
// error among hits both report.
//
// Mesh (a terrain of 224 x 224 squares, 100,352 triangles, heights 0.5 sin(x / 3) cos(y / 4)
// over unit squares; 256 bodies of radii 0.3 to 1 placed 0 to 3 above it, moving 2 to 6 units
// down and sideways in t in [0, 1]):
//   mesh_overlap/ellipsect     ellipsect::overlap (the hierarchy, then the exact test)
//   mesh_overlap/fcl           fcl::collide with an fcl::BVHModel<OBBRSSd> of the triangles
//   mesh_first_contact/ellipsect  ellipsect::first_contact against the mesh
//   mesh_first_contact/fcl     fcl::continuousCollide (CCDC_NAIVE, 10 samples) against the
//                              BVHModel
// wrong (mesh): answers differing from ellipsect's (whose per-triangle answers are the ones
// checked above): overlap outside the band, or a contact outcome, or a time off by 1e-6.
// Construction: mesh_build/ellipsect and mesh_build/fcl time building the hierarchy.
#include <ellipsect/mesh.hpp>
#include <ellipsect/triangle.hpp>

#include "bench/bench_support.hpp"
#include "scenarios/triangle.hpp"
#include "tests/reference/triangle_reference.hpp"

#include <benchmark/benchmark.h>

#ifdef ELLIPSECT_HAVE_FCL
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/continuous_collision.h>
#endif

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace ellipsect;
using scenarios::TriangleKind;
constexpr int cases_per_category = 256;
constexpr double inf = std::numeric_limits<double>::infinity();

struct Item {
  scenarios::TriangleCase<3> c;
  double gap;       // the reference's d - 1
  double minimum;   // its least gap in the window, d - 1
  double time;      // its first contact time (inf: none; 0: at the start)
};

const std::vector<Item>& items(int category) {
  static std::vector<std::vector<Item>> cache(scenarios::triangle_kinds.size() + 1);
  auto& out = cache[static_cast<std::size_t>(category + 1)];
  if (!out.empty()) return out;
  for (int k = 0; k < static_cast<int>(scenarios::triangle_kinds.size()); ++k) {
    if (category >= 0 && k != category) continue;
    for (int i = 0; i < cases_per_category; ++i) {
      const auto c = scenarios::make_triangle_case<3>(scenarios::triangle_kinds[static_cast<std::size_t>(k)], 900000 + i);
      const reference::Body<3> body{c.a.center(), c.a.axes(), c.a.radii()};
      const std::array<reference::DVec<3>, 3> v{c.b.vertex(0), c.b.vertex(1), c.b.vertex(2)};
      const auto g = reference::triangle_gaps<3>(body, v);
      const auto m = reference::moving_triangle<3>(body, v, c.va, c.vb);
      const auto t = reference::triangle_contact_time<3>(m, reference::Real(c.window));
      out.push_back({c, reference::to_double(g.d - 1), reference::to_double(t.minimum - 1), reference::to_double(t.time)});
    }
  }
  return out;
}

std::string category_name(int category) {
  return category < 0 ? "mix" : scenarios::name(scenarios::triangle_kinds[static_cast<std::size_t>(category)]);
}

bool wrong_overlap(double gap, bool got) { return std::abs(gap) > 1e-12 && got != (gap <= 0); }

// Outcome and time against the reference's; the relative time error of a hit in `err`.
bool wrong_contact(const Item& it, const bench::Answer& got, double& err) {
  err = 0;
  if (std::abs(it.minimum) <= 1e-9 || std::abs(it.gap) <= 1e-12) return false;  // a graze, or touching
  const bench::Answer want = it.time == 0 ? bench::Answer{bench::Outcome::at_start, 0}
                             : std::isinf(it.time) ? bench::Answer{bench::Outcome::none, inf}
                                                   : bench::Answer{bench::Outcome::hit, it.time};
  if (want.outcome == bench::Outcome::hit && std::abs(it.time - it.c.t_max) <= 1e-9 * it.time) return false;
  if (got.outcome != want.outcome) return true;
  if (got.outcome != bench::Outcome::hit) return false;
  err = std::abs(got.time - want.time) / want.time;
  return err > 1e-6;
}

void finish(benchmark::State& state, int wrong, double max_err) {
  state.counters["wrong"] = wrong;
  state.counters["max_err"] = max_err;
}

void ellipsect_overlap(benchmark::State& state, int category) {
  const auto& its = items(category);
  int wrong = 0;
  for (const auto& it : its) wrong += wrong_overlap(it.gap, overlap(it.c.a, it.c.b));
  bench::time_cases(state, its, [](const Item& it) { return overlap(it.c.a, it.c.b); });
  finish(state, wrong, 0);
}

void ellipsect_first_contact(benchmark::State& state, int category) {
  const auto& its = items(category);
  int wrong = 0;
  double max_err = 0, err;
  for (const auto& it : its) {
    wrong += wrong_contact(it, bench::answer(first_contact(it.c.a, it.c.va, it.c.b, it.c.vb, it.c.t_max)), err);
    max_err = std::max(max_err, err);
  }
  bench::time_cases(state, its,
                    [](const Item& it) { return first_contact(it.c.a, it.c.va, it.c.b, it.c.vb, it.c.t_max).time; });
  finish(state, wrong, max_err);
}

// The terrain and its queries.
struct Terrain {
  std::vector<double> vertices;
  std::vector<std::int64_t> triangles;
  TriangleMesh<double, 3> mesh;
  struct Query {
    Ellipsoid<double, 3> body;
    Vec3<double> velocity;
  };
  std::vector<Query> queries;
};

double height(double x, double y) { return 0.5 * std::sin(x / 3) * std::cos(y / 4); }

const Terrain& terrain() {
  static const Terrain t = [] {
    Terrain out;
    constexpr int n = 224;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) out.vertices.insert(out.vertices.end(), {double(i), double(j), height(i, j)});
    const auto at = [](int i, int j) { return std::int64_t(i) * (n + 1) + j; };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        out.triangles.insert(out.triangles.end(),
                             {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    out.mesh = make_triangle_mesh<double, 3>(out.vertices, out.triangles);
    scenarios::detail::Rng rng(42);
    using namespace scenarios::detail;
    for (int q = 0; q < 256; ++q) {
      const Vec3<double> r = radii<3>(rng, 0.6, 3.3);
      const double x = uniform(rng, 10, n - 10), y = uniform(rng, 10, n - 10);
      const Vec3<double> c(x, y, height(x, y) + uniform(rng, 0, 3) + r.maxCoeff());
      const Vec3<double> v(uniform(rng, -3, 3), uniform(rng, -3, 3), -uniform(rng, 2, 6));
      out.queries.push_back({Ellipsoid<double, 3>::from_axes(c, rotation<3>(rng), r), v});
    }
    return out;
  }();
  return t;
}

void ellipsect_mesh_build(benchmark::State& state) {
  const Terrain& t = terrain();
  for (auto _ : state) benchmark::DoNotOptimize(make_triangle_mesh<double, 3>(t.vertices, t.triangles).triangle_count());
  state.counters["triangles"] = double(t.mesh.triangle_count());
}

void ellipsect_mesh_overlap(benchmark::State& state) {
  const Terrain& t = terrain();
  bench::time_cases(state, t.queries, [&](const Terrain::Query& q) { return overlap(q.body, t.mesh); });
  state.counters["queries_per_s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

void ellipsect_mesh_first_contact(benchmark::State& state) {
  const Terrain& t = terrain();
  int hits = 0;
  for (const auto& q : t.queries)
    hits += first_contact(q.body, q.velocity, t.mesh, Vec3<double>::Zero(), 1.0).contact.status == ContactStatus::hit;
  bench::time_cases(state, t.queries, [&](const Terrain::Query& q) {
    return first_contact(q.body, q.velocity, t.mesh, Vec3<double>::Zero(), 1.0).contact.time;
  });
  state.counters["queries_per_s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["hits"] = hits;
}

#ifdef ELLIPSECT_HAVE_FCL
fcl::Transform3d pose_of(const Ellipsoid<double, 3>& e, const Vec3<double>& offset = Vec3<double>::Zero()) {
  fcl::Transform3d pose = fcl::Transform3d::Identity();
  Mat3<double> axes = e.axes();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  pose.linear() = axes;
  pose.translation() = e.center() + offset;
  return pose;
}

fcl::Ellipsoidd shape_of(const Ellipsoid<double, 3>& e) {
  return fcl::Ellipsoidd(e.radii()[0], e.radii()[1], e.radii()[2]);
}

struct FclItem {
  fcl::Ellipsoidd a;
  fcl::Transform3d pose;
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> b;
};

std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fcl_model(const std::vector<fcl::Vector3d>& points,
                                                      const std::vector<fcl::Triangle>& tris) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  model->beginModel();
  model->addSubModel(points, tris);
  model->endModel();
  return model;
}

std::vector<FclItem> fcl_items(const std::vector<Item>& its) {
  std::vector<FclItem> out;
  for (const auto& it : its)
    out.push_back({shape_of(it.c.a), pose_of(it.c.a),
                   fcl_model({it.c.b.vertex(0), it.c.b.vertex(1), it.c.b.vertex(2)}, {fcl::Triangle(0, 1, 2)})});
  return out;
}

bool fcl_collide(const fcl::CollisionGeometryd* a, const fcl::Transform3d& pa, const fcl::CollisionGeometryd* b) {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(a, pa, b, fcl::Transform3d::Identity(), request, result);
  return result.isCollision();
}

// continuousCollide of a moving by va (b by vb) over [0, window]: the time, 0 at the start, -1
// for none.
double fcl_time(const fcl::CollisionGeometryd* a, const Ellipsoid<double, 3>& body, const Vec3<double>& va,
                const fcl::CollisionGeometryd* b, const Vec3<double>& vb, double window) {
  fcl::ContinuousCollisionRequestd request;
  fcl::ContinuousCollisionResultd result;
  fcl::Transform3d b1 = fcl::Transform3d::Identity();
  b1.translation() = window * vb;
  fcl::continuousCollide(a, pose_of(body), pose_of(body, window * va), b, fcl::Transform3d::Identity(), b1, request,
                         result);
  return result.is_collide ? result.time_of_contact * window : -1.0;
}

void fcl_overlap(benchmark::State& state, int category) {
  const auto& its = items(category);
  const auto fs = fcl_items(its);
  int wrong = 0;
  for (std::size_t i = 0; i < its.size(); ++i) wrong += wrong_overlap(its[i].gap, fcl_collide(&fs[i].a, fs[i].pose, fs[i].b.get()));
  bench::time_cases(state, fs, [](const FclItem& f) { return fcl_collide(&f.a, f.pose, f.b.get()); });
  finish(state, wrong, 0);
}

void fcl_first_contact(benchmark::State& state, int category) {
  const auto& its = items(category);
  const auto fs = fcl_items(its);
  int wrong = 0;
  double max_err = 0, err;
  std::vector<std::size_t> index(its.size());
  for (std::size_t i = 0; i < its.size(); ++i) {
    index[i] = i;
    const auto& c = its[i].c;
    wrong += wrong_contact(its[i], bench::answer_from_time(fcl_time(&fs[i].a, c.a, c.va, fs[i].b.get(), c.vb, c.window)), err);
    max_err = std::max(max_err, err);
  }
  bench::time_cases(state, index, [&](std::size_t i) {
    const auto& c = its[i].c;
    return fcl_time(&fs[i].a, c.a, c.va, fs[i].b.get(), c.vb, c.window);
  });
  finish(state, wrong, max_err);
}

std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fcl_mesh(const Terrain& t) {
  std::vector<fcl::Vector3d> points;
  for (std::size_t i = 0; i < t.vertices.size(); i += 3)
    points.emplace_back(t.vertices[i], t.vertices[i + 1], t.vertices[i + 2]);
  std::vector<fcl::Triangle> tris;
  for (std::size_t k = 0; k < t.triangles.size(); k += 3)
    tris.emplace_back(std::size_t(t.triangles[k]), std::size_t(t.triangles[k + 1]), std::size_t(t.triangles[k + 2]));
  return fcl_model(points, tris);
}

void fcl_mesh_build(benchmark::State& state) {
  const Terrain& t = terrain();
  for (auto _ : state) benchmark::DoNotOptimize(fcl_mesh(t)->num_tris);
}

void fcl_mesh_overlap(benchmark::State& state) {
  const Terrain& t = terrain();
  const auto model = fcl_mesh(t);
  int wrong = 0;
  for (const auto& q : t.queries) {
    const MeshRelation r = classify(q.body, t.mesh);
    if (r.relation == Relation::touching) continue;
    const auto shape = shape_of(q.body);
    wrong += fcl_collide(&shape, pose_of(q.body), model.get()) != (r.relation != Relation::separated);
  }
  bench::time_cases(state, t.queries, [&](const Terrain::Query& q) {
    const auto shape = shape_of(q.body);
    return fcl_collide(&shape, pose_of(q.body), model.get());
  });
  state.counters["queries_per_s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["wrong"] = wrong;
}

void fcl_mesh_first_contact(benchmark::State& state) {
  const Terrain& t = terrain();
  const auto model = fcl_mesh(t);
  int wrong = 0;
  double max_err = 0;
  for (const auto& q : t.queries) {
    const auto want = bench::answer(first_contact(q.body, q.velocity, t.mesh, Vec3<double>::Zero(), 1.0).contact);
    const auto shape = shape_of(q.body);
    const auto got = bench::answer_from_time(fcl_time(&shape, q.body, q.velocity, model.get(), Vec3<double>::Zero(), 1.0));
    if (got.outcome != want.outcome) {
      ++wrong;
    } else if (got.outcome == bench::Outcome::hit) {
      const double err = std::abs(got.time - want.time) / want.time;
      max_err = std::max(max_err, err);
      wrong += err > 1e-6;
    }
  }
  bench::time_cases(state, t.queries, [&](const Terrain::Query& q) {
    const auto shape = shape_of(q.body);
    return fcl_time(&shape, q.body, q.velocity, model.get(), Vec3<double>::Zero(), 1.0);
  });
  state.counters["queries_per_s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  finish(state, wrong, max_err);
}
#endif

void register_all() {
  for (int category = -1; category < static_cast<int>(scenarios::triangle_kinds.size()); ++category) {
    const std::string name = category_name(category);
    benchmark::RegisterBenchmark(("overlap/ellipsect/" + name).c_str(), ellipsect_overlap, category);
    benchmark::RegisterBenchmark(("first_contact/ellipsect/" + name).c_str(), ellipsect_first_contact, category);
#ifdef ELLIPSECT_HAVE_FCL
    benchmark::RegisterBenchmark(("overlap/fcl/" + name).c_str(), fcl_overlap, category);
    benchmark::RegisterBenchmark(("first_contact/fcl/" + name).c_str(), fcl_first_contact, category);
#endif
  }
  benchmark::RegisterBenchmark("mesh_build/ellipsect", ellipsect_mesh_build)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("mesh_overlap/ellipsect", ellipsect_mesh_overlap);
  benchmark::RegisterBenchmark("mesh_first_contact/ellipsect", ellipsect_mesh_first_contact);
#ifdef ELLIPSECT_HAVE_FCL
  benchmark::RegisterBenchmark("mesh_build/fcl", fcl_mesh_build)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("mesh_overlap/fcl", fcl_mesh_overlap);
  benchmark::RegisterBenchmark("mesh_first_contact/fcl", fcl_mesh_first_contact);
#endif
}

}  // namespace

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, register_all); }
