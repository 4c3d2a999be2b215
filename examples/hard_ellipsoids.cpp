// Event-driven hard ellipses or ellipsoids in a periodic box (packing.hpp's HardBodies):
// runs a number of collisions, prints collision events per second and the drift of energy
// and momentum, and writes SVG frames (2D: the ellipses; 3D: their shadows on the xy plane,
// far ones first).
//
//   hard_ellipsoids [--dim 3] [--side 10] [--phi 0.3] [--events 20000] [--frames DIR]
//                   [--frame-every 1000] [--seed 1]
// side^dim bodies on a lattice, radii (1, 0.6, 0.4) in 3D, (1, 0.5) in 2D.
#include "hard_bodies.hpp"
#include "picture.hpp"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

namespace {

using namespace ellipsect;
using picture::write_picture;

template <int N>
int run(int side, double phi, long events, const std::string& frames, long every, unsigned seed) {
  Vec<double, N> radii;
  if constexpr (N == 2)
    radii << 1.0, 0.5;
  else
    radii << 1.0, 0.6, 0.4;
  HardBodies<N> sim = hard_bodies::lattice<N>(side, radii, phi, seed);
  const auto before = sim.totals();
  if (!frames.empty()) std::filesystem::create_directories(frames);
  int frame = 0;
  double cpu = 0.0;
  for (long k = 0; k < events; ++k) {
    const auto start = std::chrono::steady_clock::now();
    if (sim.step().status != HardStatus::collided) {
      std::printf("no event left after %ld collisions\n", k);
      return 1;
    }
    cpu += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!frames.empty() && k % every == 0) {
      char name[32];
      std::snprintf(name, sizeof name, "/frame_%04d.svg", frame++);
      write_picture(frames + name, sim.shapes(), sim.box());
    }
  }
  const auto after = sim.totals();
  std::printf("%d^%d = %zu bodies, packing fraction %.3g, %ld collisions to t = %.6g (%zu neighbor-list rebuilds)\n",
              side, N, sim.shapes().size(), phi, events, sim.now(), sim.rebuilds());
  std::printf("collision events per second: %.0f\n", double(events) / cpu);
  std::printf("relative energy drift: %.3g, momentum drift: %.3g\n", std::abs(after.energy / before.energy - 1.0),
              (after.momentum - before.momentum).norm());
  std::printf("predictions that found an overlap: %zu, that stopped: %zu\n", sim.overlaps(), sim.stopped());
  if (!frames.empty()) std::printf("%d frames in %s\n", frame, frames.c_str());
  return sim.overlaps() == 0 && sim.stopped() == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Event-driven hard ellipses or ellipsoids in a periodic box"};
  int dim = 3, side = 10;
  double phi = 0.3;
  long events = 20000, every = 1000;
  unsigned seed = 1;
  std::string frames;
  app.add_option("--dim", dim, "2 or 3")->check(CLI::IsMember({2, 3}));
  app.add_option("--side", side, "bodies per side of the starting lattice")->check(CLI::Range(6, 200));
  app.add_option("--phi", phi, "packing fraction")->check(CLI::Range(0.01, 0.45));
  app.add_option("--events", events, "collisions to run")->check(CLI::NonNegativeNumber);
  app.add_option("--frames", frames, "directory for SVG frames");
  app.add_option("--frame-every", every, "collisions between frames")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "random velocities");
  CLI11_PARSE(app, argc, argv);
  return dim == 2 ? run<2>(side, phi, events, frames, every, seed) : run<3>(side, phi, events, frames, every, seed);
}
