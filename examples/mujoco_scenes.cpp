// MuJoCo simulations with ellipsect as the ellipsoid narrow phase (ellipsect/mujoco.hpp), or
// with MuJoCo's own functions (--own), writing side views as SVG frames:
//
//   mujoco_scenes pile [--side 5] [--layers 4] [--seconds 1.5] [--own] [--frames DIR] [--frame-every 50]
//   mujoco_scenes spheroid [--tilt 0.7] [--seconds 2] [--own] [--frames DIR] [--frame-every 50]
//
// pile: side x side x layers ellipsoids poured into a box (scenarios/mujoco_scenes.hpp); prints
// the deepest overlap of the settled pile by ellipsect's signed distance of its final poses.
// spheroid: a prolate spheroid let go tilted on a plane; prints the largest gap between its
// centre's height and its exact support height sqrt(a^2 (1 - u_z^2) + c^2 u_z^2).
#include <ellipsect/box.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/mujoco.hpp>

#include "picture.hpp"
#include "scenarios/mujoco_scenes.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace ellipsect;
using Vec3d = Vec3<double>;
using Mat3d = Mat3<double>;
using Scene = scenarios::MujocoScene;

Ellipsoid3<double> body_of(const Scene& s, int g) {
  const Vec3d c = Eigen::Map<const Vec3d>(s.d->geom_xpos + 3 * g);
  const Mat3d r = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(s.d->geom_xmat + 9 * g);
  const Vec3d size = Eigen::Map<const Vec3d>(s.m->geom_size + 3 * g);
  return make_ellipsoid(c, r, s.m->geom_type[g] == mjGEOM_SPHERE ? Vec3d::Constant(size[0]) : size);
}

// The scene's side view (picture.hpp): its ellipsoids and spheres, its boxes (the walls are
// axis-aligned).
void write_side_view(const std::string& path, const Scene& s, double half_width, double height) {
  std::vector<Ellipsoid3<double>> bodies;
  std::vector<picture::Block> blocks;
  for (int g = 0; g < s.m->ngeom; ++g) {
    const int type = s.m->geom_type[g];
    if (type == mjGEOM_ELLIPSOID || type == mjGEOM_SPHERE) bodies.push_back(body_of(s, g));
    if (type == mjGEOM_BOX)
      blocks.push_back({Eigen::Map<const Vec3d>(s.d->geom_xpos + 3 * g), Eigen::Map<const Vec3d>(s.m->geom_size + 3 * g)});
  }
  picture::write_side_view(path, bodies, blocks, half_width, height);
}

// Steps the scene for `seconds`, writing a frame every `every` steps; `observe` after each step.
template <class Observe>
int run(Scene& s, double seconds, const std::string& frames, int every, double half_width, double height,
        Observe&& observe) {
  if (!frames.empty()) std::filesystem::create_directories(frames);
  const int steps = static_cast<int>(std::lround(seconds / s.m->opt.timestep));
  mj_forward(s.m.get(), s.d.get());  // the poses of the first frame
  int written = 0;
  for (int i = 0; i <= steps; ++i) {
    if (!frames.empty() && i % every == 0) {
      std::array<char, 32> name{};
      std::snprintf(name.data(), name.size(), "/frame_%05d.svg", written++);
      write_side_view(frames + name.data(), s, half_width, height);
    }
    if (i < steps) {
      s.step(1);
      observe();
    }
  }
  if (!frames.empty()) std::printf("%d frames in %s\n", written, frames.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"MuJoCo scenes with ellipsect's ellipsoid contacts"};
  app.require_subcommand(1);
  bool own = false;
  double seconds = 1.5, tilt = 0.7;
  int side = 5, layers = 4, every = 50;
  std::string frames;
  auto* pile = app.add_subcommand("pile", "ellipsoids poured into a box");
  pile->add_option("--side", side, "bodies along x and y")->check(CLI::Range(1, 5));
  pile->add_option("--layers", layers, "layers of bodies")->check(CLI::Range(1, 20));
  auto* spheroid = app.add_subcommand("spheroid", "a prolate spheroid rocking down on a plane");
  spheroid->add_option("--tilt", tilt, "start angle of its long axis from the vertical, radians")
      ->check(CLI::Range(0.0, 1.5));
  for (auto* sub : {pile, spheroid}) {
    sub->add_option("--seconds", seconds, "simulated time")->check(CLI::Range(0.0, 60.0));
    sub->add_flag("--own", own, "MuJoCo's own ellipsoid functions instead of ellipsect's");
    sub->add_option("--frames", frames, "folder for SVG side views");
    sub->add_option("--frame-every", every, "steps between frames")->check(CLI::PositiveNumber);
  }
  CLI11_PARSE(app, argc, argv);
  if (!own) mujoco::install();
  if (pile->parsed()) {
    Scene s(scenarios::pile_mjcf(side, layers), "/tmp/ellipsect_mujoco_pile.xml");
    run(s, seconds, frames, every, 0.7, 1.1, [] {});
    std::vector<Ellipsoid3<double>> e;
    std::vector<int> walls;
    for (int g = 0; g < s.m->ngeom; ++g) {
      if (s.m->geom_type[g] == mjGEOM_ELLIPSOID) e.push_back(body_of(s, g));
      if (s.m->geom_type[g] == mjGEOM_BOX) walls.push_back(g);
    }
    double depth = 0;
    for (std::size_t i = 0; i < e.size(); ++i) {
      for (std::size_t j = i + 1; j < e.size(); ++j) depth = std::max(depth, -signed_distance(e[i], e[j]).distance);
      depth = std::max(depth, -signed_distance(e[i], make_half_space<double, 3>(Vec3d::Zero(), Vec3d::UnitZ())).distance);
      for (const int g : walls) {
        const Vec3d c = Eigen::Map<const Vec3d>(s.d->geom_xpos + 3 * g), h = Eigen::Map<const Vec3d>(s.m->geom_size + 3 * g);
        depth = std::max(depth, -signed_distance(e[i], make_box<double, 3>(c, Mat3d::Identity(), h)).distance);
      }
    }
    std::printf("%zu ellipsoids after %g s (%s): deepest overlap %.3g (smallest radius 0.05)\n", e.size(), seconds,
                own ? "MuJoCo's own functions" : "ellipsect", depth);
  } else {
    const double a = 0.1, c = 0.3;
    Scene s(scenarios::spheroid_mjcf(a, c, tilt), "/tmp/ellipsect_mujoco_spheroid.xml");
    const int g = s.geom("spheroid");
    double worst = 0;
    run(s, seconds, frames, every, 0.6, 0.7, [&] {
      const double uz = s.d->geom_xmat[9 * g + 8];  // the long axis' vertical component
      const double h = std::sqrt(a * a * (1 - uz * uz) + c * c * uz * uz);
      worst = std::max(worst, std::abs(h - s.d->geom_xpos[3 * g + 2]));
    });
    std::printf("spheroid after %g s (%s): centre within %.3g of its support height\n", seconds,
                own ? "MuJoCo's own functions" : "ellipsect", worst);
  }
  const auto k = mujoco::counters();
  if (!own)
    std::printf("ellipsect's collide: %llu calls, %llu contacts, %llu not converged\n",
                static_cast<unsigned long long>(k.calls), static_cast<unsigned long long>(k.contacts),
                static_cast<unsigned long long>(k.not_converged));
  return 0;
}
