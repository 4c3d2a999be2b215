// Bullet simulations with ellipsect as the ellipsoid narrow phase (ellipsect/bullet.hpp), or with
// Bullet's own algorithm on the same exact ellipsoid shape (--own), writing side views as SVG:
//
//   bullet_scenes pile [--bodies 64] [--seconds 3] [--own] [--frames DIR] [--frame-every 60]
//   bullet_scenes spheroid [--tilt 0.44] [--seconds 2] [--own] [--frames DIR] [--frame-every 60]
//
// pile: ellipsoids dropped into a 2 x 2 box of static planes (scenarios/bullet_scenes.hpp); prints
// the deepest overlap of the final poses by ellipsect's signed distance. spheroid: a prolate
// spheroid (radii 0.4, 0.2, 0.2) let go tilted on the floor; prints the largest gap between its
// centre's height and its exact support height. Steps of 1/240 s.
#include <ellipsect/bullet.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/half_space.hpp>

#include "picture.hpp"
#include "scenarios/bullet_scenes.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace ellipsect;
using Vec3d = Vec3<double>;

Ellipsoid3<double> body_of(const btRigidBody* b) {
  return static_cast<const bullet::EllipsoidShape*>(b->getCollisionShape())->body(b->getWorldTransform());
}

// Runs the world for `seconds`, a frame of `bodies` every `every` steps, `observe` after each step.
template <class Observe>
void run(scenarios::BulletWorld& world, const std::vector<btRigidBody*>& bodies, double seconds,
         const std::string& frames, int every, const std::vector<picture::Block>& blocks, double half_width,
         double height, Observe&& observe) {
  constexpr double dt = 1.0 / 240;
  if (!frames.empty()) std::filesystem::create_directories(frames);
  const int steps = static_cast<int>(std::lround(seconds / dt));
  int written = 0;
  for (int i = 0; i <= steps; ++i) {
    if (!frames.empty() && i % every == 0) {
      std::vector<Ellipsoid3<double>> shapes;
      for (const btRigidBody* b : bodies) shapes.push_back(body_of(b));
      std::array<char, 32> name{};
      std::snprintf(name.data(), name.size(), "/frame_%05d.svg", written++);
      picture::write_side_view(frames + name.data(), shapes, blocks, half_width, height);
    }
    if (i < steps) {
      world.run(dt, dt);
      observe();
    }
  }
  if (!frames.empty()) std::printf("%d frames in %s\n", written, frames.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Bullet scenes with ellipsect's ellipsoid contacts"};
  app.require_subcommand(1);
  bool own = false;
  double seconds = 3, tilt = 25 * M_PI / 180;
  int bodies = 64, every = 60;
  std::string frames;
  auto* pile = app.add_subcommand("pile", "ellipsoids dropped into a box");
  pile->add_option("--bodies", bodies, "ellipsoids")->check(CLI::Range(1, 500));
  auto* spheroid = app.add_subcommand("spheroid", "a prolate spheroid rocking down on a plane");
  spheroid->add_option("--tilt", tilt, "start angle of its long axis below the horizontal, radians")
      ->check(CLI::Range(0.0, 1.5));
  for (auto* sub : {pile, spheroid}) {
    sub->add_option("--seconds", seconds, "simulated time")->check(CLI::Range(0.0, 60.0));
    sub->add_flag("--own", own, "Bullet's own algorithm (GJK/EPA on the exact shape) instead of ellipsect's");
    sub->add_option("--frames", frames, "folder for SVG side views");
    sub->add_option("--frame-every", every, "steps between frames")->check(CLI::PositiveNumber);
  }
  CLI11_PARSE(app, argc, argv);
  const char* who = own ? "Bullet's own algorithm" : "ellipsect";
  scenarios::BulletWorld world(!own);
  if (pile->parsed()) {
    const std::vector<btRigidBody*> e = scenarios::add_pile(world, bodies);
    // The walls x = +-1 drawn as thin blocks.
    const std::vector<picture::Block> walls = {{Vec3d(-1.02, 0, 1.2), Vec3d(0.02, 1, 1.2)},
                                               {Vec3d(1.02, 0, 1.2), Vec3d(0.02, 1, 1.2)}};
    run(world, e, seconds, frames, every, walls, 1.1, 2.4, [] {});
    double depth = 0;
    for (std::size_t i = 0; i < e.size(); ++i) {
      const auto a = body_of(e[i]);
      for (std::size_t j = i + 1; j < e.size(); ++j) depth = std::max(depth, -signed_distance(a, body_of(e[j])).distance);
      for (const auto& [n, k] : scenarios::pile_walls)
        depth = std::max(depth, -signed_distance(a, make_half_space<double, 3>(n * k, n)).distance);
    }
    std::printf("%d ellipsoids after %g s (%s): deepest overlap %.3g (smallest radius 0.1)\n", bodies, seconds, who,
                depth);
  } else {
    const double a = 0.4, b = 0.2;
    btRigidBody* e = scenarios::add_spheroid(world, a, b, tilt);
    double worst = 0;
    run(world, {e}, seconds, frames, every, {}, 1.0, 0.8, [&] {
      const auto s = body_of(e);
      const double uz = s.axes()(2, 0);
      worst = std::max(worst, std::abs(s.center().z() - std::sqrt(a * a * uz * uz + b * b * (1 - uz * uz))));
    });
    std::printf("spheroid after %g s (%s): centre within %.3g of its support height\n", seconds, who, worst);
  }
  if (!own) std::printf("queries that did not converge: %llu\n", static_cast<unsigned long long>(bullet::unconverged_queries()));
  return 0;
}
