// Event-driven hard ellipses or ellipsoids in a periodic box (examples/hard_bodies.hpp):
// runs a number of collisions, prints collision events per second and the drift of energy
// and momentum, and writes SVG frames (2D: the ellipses; 3D: their shadows on the xy plane,
// far ones first).
//
//   hard_ellipsoids [--dim 3] [--side 10] [--phi 0.3] [--events 20000] [--frames DIR]
//                   [--frame-every 1000] [--seed 1]
// side^dim bodies on a lattice, radii (1, 0.6, 0.4) in 3D, (1, 0.5) in 2D.
#include "hard_bodies.hpp"

#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

using namespace ellipsect;

// One ellipse of the picture: center, semi-axes and angle (degrees), depth for the order.
struct Shadow {
  double x, y, rx, ry, degrees, depth;
};

// The shadow of an ellipsoid on the xy plane: the ellipse of the upper-left 2x2 block of
// A diag(r^2) A^T (for N = 2 the ellipse itself).
template <int N>
Shadow shadow(const Ellipsoid<double, N>& e) {
  const Mat<double, N> A = e.axes();
  const Mat<double, N> S = A * e.radii().cwiseProduct(e.radii()).asDiagonal() * A.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(S.template topLeftCorner<2, 2>());
  const Eigen::Vector2d major = eig.eigenvectors().col(1);
  return {e.center().x(), e.center().y(), std::sqrt(eig.eigenvalues()[1]), std::sqrt(eig.eigenvalues()[0]),
          std::atan2(major.y(), major.x()) * 180.0 / M_PI, N == 3 ? double(e.center()[N - 1]) : 0.0};
}

template <int N>
void write_frame(const std::string& path, const hard_bodies::Simulation<N>& sim) {
  const double w = sim.box().size[0], h = sim.box().size[1];
  double far = 1.0;
  if constexpr (N == 3) far = sim.box().size[2];
  std::vector<Shadow> shadows;
  for (const auto& e : sim.shapes()) shadows.push_back(shadow(e));
  std::sort(shadows.begin(), shadows.end(), [](const Shadow& a, const Shadow& b) { return a.depth < b.depth; });
  std::ofstream out(path);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " << w << ' ' << h << "\" width=\"600\" height=\""
      << 600.0 * h / w << "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<g transform=\"translate(0 " << h
      << ") scale(1 -1)\" stroke=\"#222\" stroke-width=\"" << 0.003 * w << "\">\n";
  for (const Shadow& s : shadows) {
    const int shade = int(80 + 150 * s.depth / far);
    for (int dx = -1; dx <= 1; ++dx)  // the periodic images that reach into the picture
      for (int dy = -1; dy <= 1; ++dy) {
        const double x = s.x + dx * w, y = s.y + dy * h;
        if (x + s.rx < 0 || x - s.rx > w || y + s.rx < 0 || y - s.rx > h) continue;
        out << "<ellipse cx=\"" << x << "\" cy=\"" << y << "\" rx=\"" << s.rx << "\" ry=\"" << s.ry
            << "\" transform=\"rotate(" << s.degrees << ' ' << x << ' ' << y << ")\" fill=\"rgb(" << shade << ','
            << shade << ",255)\"/>\n";
      }
  }
  out << "</g>\n</svg>\n";
}

template <int N>
int run(int side, double phi, long events, const std::string& frames, long every, unsigned seed) {
  Vec<double, N> radii;
  if constexpr (N == 2)
    radii << 1.0, 0.5;
  else
    radii << 1.0, 0.6, 0.4;
  hard_bodies::Simulation<N> sim(side, radii, phi, seed);
  const auto before = sim.totals();
  if (!frames.empty()) std::filesystem::create_directories(frames);
  int frame = 0;
  double cpu = 0.0;
  for (long k = 0; k < events; ++k) {
    const auto start = std::chrono::steady_clock::now();
    sim.step();
    cpu += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!frames.empty() && k % every == 0) {
      char name[32];
      std::snprintf(name, sizeof name, "/frame_%04d.svg", frame++);
      write_frame(frames + name, sim);
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
