// ellipsect inside MuJoCo (modules/mujoco) against MuJoCo's own ellipsoid functions, in one run:
//   pair/<who>/<category>   one call of the collision table's ellipsoid-ellipsoid entry on a
//                           pair MuJoCo holds (its geom_xpos, geom_xmat and geom_size: the
//                           bodies are built from MuJoCo's pose inside the timed call), margin 0;
//                           MuJoCo's entry is libccd's MPR on the ellipsoid's support. The
//                           counters: `agree` the share of pairs whose contact (or none) and
//                           depth agree with ellipsect's to 1e-6 of the size (ellipsect's answers
//                           are checked against the 50-digit reference in tests/engines).
//   step/<who>              one mj_step of 100 ellipsoids settling in a box
//                           (scenarios/mujoco_scenes.hpp's pile), after 0.5 s, with its contacts.
#include <ellipsect/distance.hpp>
#include <ellipsect/mujoco.hpp>

#include "bench/bench_support.hpp"
#include "scenarios/mujoco_scenes.hpp"
#include "scenarios/scenarios.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace ellipsect::bench {
namespace {

using Vec3d = Vec3<double>;

using Loaded = scenarios::MujocoScene;
Loaded load(const std::string& xml) { return Loaded(xml, "/tmp/ellipsect_bench_mujoco.xml"); }

constexpr int pairs = 256;

// A model holding `pairs` pairs of free ellipsoids, geoms 2i and 2i + 1, posed as the
// category's seeded cases.
Loaded pair_model(scenarios::Category category) {
  std::string xml = R"(<mujoco><option gravity="0 0 0"/><worldbody>)";
  for (int i = 0; i < 2 * pairs; ++i) xml += R"(<body><freejoint/><geom type="ellipsoid" size="1 1 1"/></body>)";
  Loaded l = load(xml + "</worldbody></mujoco>");
  mjModel* m = l.m.get();
  for (int i = 0; i < pairs; ++i) {
    const auto c = scenarios::make_case<3>(category, static_cast<std::uint64_t>(i));
    for (int k = 0; k < 2; ++k) {
      const Ellipsoid3<double>& e = k == 0 ? c.a : c.b;
      const int g = 2 * i + k;
      Mat3<double> r = e.axes();
      if (r.determinant() < 0) r.col(2) = -r.col(2);
      const Eigen::Quaterniond q(r);
      const int a = m->jnt_qposadr[m->body_jntadr[m->geom_bodyid[g]]];
      for (int j = 0; j < 3; ++j) l.d->qpos[a + j] = e.center()[j], m->geom_size[3 * g + j] = e.radii()[j];
      l.d->qpos[a + 3] = q.w(), l.d->qpos[a + 4] = q.x(), l.d->qpos[a + 5] = q.y(), l.d->qpos[a + 6] = q.z();
    }
  }
  mj_kinematics(m, l.d.get());
  return l;
}

// MuJoCo's own entries, kept before install().
std::array<std::array<mjfCollision, mjNGEOMTYPES>, mjNGEOMTYPES> own_table;

void pair_bench(benchmark::State& state, scenarios::Category category, bool ours) {
  const Loaded l = pair_model(category);
  const mjfCollision f = ours ? &mujoco::collide : own_table[mjGEOM_ELLIPSOID][mjGEOM_ELLIPSOID];
  std::vector<int> cases(pairs);
  for (int i = 0; i < pairs; ++i) cases[static_cast<std::size_t>(i)] = i;
  mjContact con[mjMAXCONPAIR];
  time_cases(state, cases, [&](int i) { return f(l.m.get(), l.d.get(), con, 2 * i, 2 * i + 1, 0); });
  int agree = 0;
  for (int i = 0; i < pairs; ++i) {
    mjContact mine[mjMAXCONPAIR], theirs[mjMAXCONPAIR];
    const int a = mujoco::collide(l.m.get(), l.d.get(), mine, 2 * i, 2 * i + 1, 0);
    const int b = f(l.m.get(), l.d.get(), theirs, 2 * i, 2 * i + 1, 0);
    const double* s = l.m->geom_size + 6 * i;
    const double scale = std::max({s[0], s[1], s[2], s[3], s[4], s[5]});
    agree += (a == 0 && b == 0) || (a > 0 && b > 0 && std::abs(mine[0].dist - theirs[0].dist) <= 1e-6 * scale);
  }
  state.counters["agree"] = double(agree) / pairs;
}

void step_bench(benchmark::State& state, bool ours) {
  if (ours) mujoco::install();
  Loaded l = load(scenarios::pile_mjcf(5, 4));
  for (int i = 0; i < 250; ++i) mj_step(l.m.get(), l.d.get());
  long contacts = 0, steps = 0;
  for (auto _ : state) {
    mj_step(l.m.get(), l.d.get());
    contacts += l.d->ncon;
    ++steps;
  }
  state.counters["contacts"] = double(contacts) / double(steps);
  if (ours) mujoco::uninstall();
}

void register_all() {
  for (int i = 0; i < mjNGEOMTYPES; ++i)
    for (int j = 0; j < mjNGEOMTYPES; ++j) own_table[i][j] = mjCOLLISIONFUNC[i][j];
  for (const auto category : scenarios::all_categories) {
    if (category == scenarios::Category::zero_velocity || category == scenarios::Category::grazing) continue;
    for (const bool ours : {true, false})
      benchmark::RegisterBenchmark(
          (std::string("pair/") + (ours ? "ellipsect/" : "mujoco/") + std::string(scenarios::name(category))).c_str(),
          pair_bench, category, ours);
  }
  for (const bool ours : {true, false})
    benchmark::RegisterBenchmark((std::string("step/") + (ours ? "ellipsect" : "mujoco")).c_str(), step_bench, ours);
}

}  // namespace
}  // namespace ellipsect::bench

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, ellipsect::bench::register_all); }
