// The Bullet integration (include/ellipsect/bullet.hpp) inside Bullet 3.24, against Bullet's own
// algorithm for the same exact-support ellipsoid shape (btConvexConvexAlgorithm: GJK, and EPA
// for penetration), on the same seeded pairs (scenarios/scenarios.hpp, moved so that the middle
// of the centers is the origin):
//
//   pair/<category>/<algorithm>  one narrow-phase call as a world's step makes it: the pair's
//                                algorithm (the dispatcher's findAlgorithm, kept across calls)
//                                processCollision into its persistent manifold; ns per pair,
//                                and median_ns (bench_support.hpp);
//   pile/<algorithm>             one btDiscreteDynamicsWorld::stepSimulation (dt = 1/240) of 64
//                                ellipsoids settled in a 2 x 2 box of static planes (after 2 s).
//
// algorithm 0: ellipsect's (register_algorithms), 1: Bullet's own. Counter contacts: the
// manifold points per pair (pair/*) or in the world (pile/*) at the end.
#include <ellipsect/bullet.hpp>

#include "bench/bench_support.hpp"
#include "scenarios/bullet_scenes.hpp"
#include "scenarios/scenarios.hpp"

#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace ellipsect;
using V3 = Vec3<double>;
constexpr int cases_per_category = 256;

// The collision machinery of one algorithm's pairs.
struct Dispatch {
  explicit Dispatch(bool ellipsect) {
    if (ellipsect) bullet::register_algorithms(dispatcher);
  }
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDispatcherInfo info;
};

// One pair with its algorithm and manifold result, as a world's narrow phase holds them.
class Pair {
public:
  Pair(Dispatch& d, const scenarios::Case<3>& c)
      : dispatch_(d),
        shape_a_(scenarios::to_bt(c.a.radii())),
        shape_b_(scenarios::to_bt(c.b.radii())),
        w0_(nullptr, &shape_a_, &a_, pose_a_, -1, -1),
        w1_(nullptr, &shape_b_, &b_, pose_b_, -1, -1),
        result_(&w0_, &w1_) {
    pose_a_ = scenarios::bullet_pose(c.a.axes(), c.a.center());
    pose_b_ = scenarios::bullet_pose(c.b.axes(), c.b.center());
    a_.setCollisionShape(&shape_a_);
    b_.setCollisionShape(&shape_b_);
    a_.setWorldTransform(pose_a_);
    b_.setWorldTransform(pose_b_);
    algorithm_ = d.dispatcher.findAlgorithm(&w0_, &w1_, nullptr, BT_CONTACT_POINT_ALGORITHMS);
  }
  ~Pair() {
    algorithm_->~btCollisionAlgorithm();
    dispatch_.dispatcher.freeCollisionAlgorithm(algorithm_);
  }
  Pair(const Pair&) = delete;
  Pair& operator=(const Pair&) = delete;

  int process() {
    algorithm_->processCollision(&w0_, &w1_, dispatch_.info, &result_);
    return result_.getPersistentManifold()->getNumContacts();
  }

private:
  Dispatch& dispatch_;
  bullet::EllipsoidShape shape_a_, shape_b_;
  btCollisionObject a_, b_;
  btTransform pose_a_, pose_b_;
  btCollisionObjectWrapper w0_, w1_;
  btManifoldResult result_;
  btCollisionAlgorithm* algorithm_ = nullptr;
};

void pair_benchmark(benchmark::State& state, scenarios::Category category, bool ellipsect) {
  Dispatch dispatch(ellipsect);
  std::vector<std::unique_ptr<Pair>> pairs;
  for (int i = 0; i < cases_per_category; ++i) {
    auto c = scenarios::make_case<3>(category, static_cast<std::uint64_t>(i));
    const V3 mid = (c.a.center() + c.b.center()) / 2;
    c.a = c.a.translated(-mid);
    c.b = c.b.translated(-mid);
    pairs.push_back(std::make_unique<Pair>(dispatch, c));
  }
  bench::time_cases(state, pairs, [](const std::unique_ptr<Pair>& p) { return p->process(); });
  double contacts = 0;
  for (const auto& p : pairs) contacts += p->process();
  state.counters["contacts"] = contacts / double(pairs.size());
}

// 64 ellipsoids dropped into the pile's box (scenarios/bullet_scenes.hpp) and left to settle
// for 2 s.
void pile_benchmark(benchmark::State& state, bool ellipsect) {
  scenarios::BulletWorld world(ellipsect);
  scenarios::add_pile(world, 64);
  world.run(2.0, 1.0 / 240);
  for (auto _ : state) world.run(1.0 / 240, 1.0 / 240);
  state.counters["contacts"] = world.contacts();
}

void register_all() {
  for (const auto category :
       {scenarios::Category::random, scenarios::Category::high_aspect, scenarios::Category::near_tangent,
        scenarios::Category::containment, scenarios::Category::spheres})
    for (const int algorithm : {0, 1})
      benchmark::RegisterBenchmark(
          ("pair/" + std::string(scenarios::name(category)) + "/" + std::to_string(algorithm)).c_str(),
          [=](benchmark::State& s) { pair_benchmark(s, category, algorithm == 0); });
  for (const int algorithm : {0, 1})
    benchmark::RegisterBenchmark(("pile/" + std::to_string(algorithm)).c_str(), [=](benchmark::State& s) {
      pile_benchmark(s, algorithm == 0);
    })->Unit(benchmark::kMicrosecond);
}

}  // namespace

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, register_all); }
