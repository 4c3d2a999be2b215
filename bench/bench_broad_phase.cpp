// All overlapping pairs among N random ellipsoids (broad_phase.hpp), side by side with the
// naive all-pairs loop and with FCL 0.7's DynamicAABBTreeCollisionManager on the same
// bodies.
//
// Scenes: N ellipsoids with radii uniform in [0.25, 1] on each axis (aspect up to 4),
// uniformly random orientations, centers uniform in a cube whose side gives the packing
// fraction phi = N * mean volume / side^3 (overlaps allowed: a random, not a jammed,
// packing), seed 7; N in 1e4, 1e5, 1e6, phi in 0.1, 0.4.
//
// BM_overlapping_pairs/<method>/<N>/<phi in percent>, one iteration, wall-clock seconds:
//   ellipsect   overlapping_pairs(bodies) on every core (the grid, then the batch overlap)
//   naive       overlap(bodies[i], bodies[j]) for every i < j on one core (N = 1e4 only)
//   fcl         DynamicAABBTreeCollisionManagerd: registerObjects + setup + collide, the
//               callback running fcl::collide on each pair whose AABBs meet (GJK, FCL's
//               default request), on one core (FCL has no threads)
// Counters: pairs (overlapping pairs found), tested (pairs given the exact test: the
// candidates of the grid, all pairs for naive, the AABB pairs for FCL), differ (pairs in
// which the answer differs from ellipsect's: found by one and not the other; for naive the
// exact same test, so 0 means the grid misses nothing).
//
// Run:
//   cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release && cmake --build build/release
//   build/release/bench/bench_broad_phase
#include <ellipsect/broad_phase.hpp>
#include <ellipsect/classify.hpp>

#include "bench/bench_support.hpp"
#include "bench/peers.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#ifdef ELLIPSECT_HAVE_FCL
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/narrowphase/collision.h>
#endif

namespace {

using namespace ellipsect;

std::vector<Ellipsoid3<double>> random_scene(std::size_t n, double phi) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> radius(0.25, 1.0), unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double mean_volume = 4.0 / 3.0 * M_PI * std::pow(0.625, 3);  // E[abc] for independent radii
  const double side = std::cbrt(double(n) * mean_volume / phi);
  std::vector<Ellipsoid3<double>> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3<double> c(side * unit(rng), side * unit(rng), side * unit(rng));
    const Vec3<double> r(radius(rng), radius(rng), radius(rng));
    const Quat<double> q = Quat<double>(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    out.push_back(make_ellipsoid(c, q, r));
  }
  return out;
}

// Scenes and ellipsect's answers, made once per (N, phi).
struct Case {
  std::vector<Ellipsoid3<double>> bodies;
  std::vector<IndexPair> pairs;
};

const Case& case_of(std::size_t n, int phi_percent) {
  static std::map<std::pair<std::size_t, int>, Case> cases;
  Case& c = cases[{n, phi_percent}];
  if (c.bodies.empty()) {
    c.bodies = random_scene(n, phi_percent / 100.0);
    c.pairs = overlapping_pairs<double, 3>(c.bodies);
  }
  return c;
}

// Pairs found by one list and not the other (both sorted).
std::size_t differ(const std::vector<IndexPair>& a, const std::vector<IndexPair>& b) {
  std::vector<IndexPair> d;
  std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(d));
  return d.size();
}

void BM_ellipsect(benchmark::State& state) {
  const Case& c = case_of(std::size_t(state.range(0)), int(state.range(1)));
  std::vector<IndexPair> pairs;
  for (auto _ : state) pairs = overlapping_pairs<double, 3>(c.bodies);
  state.counters["pairs"] = double(pairs.size());
  state.counters["tested"] = double(candidate_pairs<double, 3>(c.bodies).size());
  state.counters["differ"] = double(differ(pairs, c.pairs));
}

void BM_naive(benchmark::State& state) {
  const Case& c = case_of(std::size_t(state.range(0)), int(state.range(1)));
  std::vector<IndexPair> pairs;
  for (auto _ : state) {
    pairs.clear();
    for (std::uint32_t i = 0; i < c.bodies.size(); ++i)
      for (std::uint32_t j = i + 1; j < c.bodies.size(); ++j)
        if (overlap(c.bodies[i], c.bodies[j])) pairs.emplace_back(i, j);
  }
  const double n = double(c.bodies.size());
  state.counters["pairs"] = double(pairs.size());
  state.counters["tested"] = n * (n - 1) / 2;
  state.counters["differ"] = double(differ(pairs, c.pairs));
}

#ifdef ELLIPSECT_HAVE_FCL
struct FclScene {
  std::vector<std::shared_ptr<fcl::CollisionObjectd>> objects;
  std::vector<IndexPair> pairs;
  std::size_t tested = 0;
};

bool fcl_callback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  auto& scene = *static_cast<FclScene*>(data);
  ++scene.tested;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(o1, o2, request, result);
  if (result.isCollision()) {
    const auto i = std::uint32_t(reinterpret_cast<std::uintptr_t>(o1->getUserData()));
    const auto j = std::uint32_t(reinterpret_cast<std::uintptr_t>(o2->getUserData()));
    scene.pairs.emplace_back(std::min(i, j), std::max(i, j));
  }
  return false;  // keep going
}

void BM_fcl(benchmark::State& state) {
  const Case& c = case_of(std::size_t(state.range(0)), int(state.range(1)));
  FclScene scene;
  for (auto _ : state) {
    scene = FclScene{};
    std::vector<fcl::CollisionObjectd*> raw;
    for (std::size_t i = 0; i < c.bodies.size(); ++i) {
      scene.objects.push_back(bench::fcl_object(c.bodies[i]));
      scene.objects.back()->setUserData(reinterpret_cast<void*>(std::uintptr_t(i)));
      scene.objects.back()->computeAABB();
      raw.push_back(scene.objects.back().get());
    }
    fcl::DynamicAABBTreeCollisionManagerd manager;
    manager.registerObjects(raw);
    manager.setup();
    manager.collide(&scene, fcl_callback);
  }
  std::sort(scene.pairs.begin(), scene.pairs.end());
  state.counters["pairs"] = double(scene.pairs.size());
  state.counters["tested"] = double(scene.tested);
  state.counters["differ"] = double(differ(scene.pairs, c.pairs));
}
#endif

void add(const char* method, void (*f)(benchmark::State&), long n, int phi) {
  benchmark::RegisterBenchmark((std::string("BM_overlapping_pairs/") + method).c_str(), f)
      ->Args({n, phi})
      ->Iterations(1)
      ->UseRealTime()
      ->Unit(benchmark::kSecond);
}

void register_all() {
  for (const int phi : {10, 40}) {
    for (const long n : {10000L, 100000L, 1000000L}) add("ellipsect", BM_ellipsect, n, phi);
    add("naive", BM_naive, 10000, phi);
#ifdef ELLIPSECT_HAVE_FCL
    for (const long n : {10000L, 100000L, 1000000L}) add("fcl", BM_fcl, n, phi);
#endif
  }
}

}  // namespace

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, register_all); }
