// Jammed packings of ellipses or ellipsoids by Lubachevsky-Stillinger compression
// (packing.hpp's jam_packing): prints the packing fraction, reduced pressure, contact
// numbers and collisions per second; writes the packing as an SVG picture (2D: the
// ellipses; 3D: their shadows on the xy plane) and as a JSON scene.
//
//   packing [--dim 3] [--bodies 1000] [--radii 1.25,1,0.8] [--bidisperse 1.4]
//           [--rate 0.01] [--slow-rate R --slow-from P] [--pressure 1e6] [--phi0 0.2]
//           [--skin 0.1] [--seed 1] [--svg FILE] [--scene FILE]
// --bidisperse s: half the bodies scaled by s (disks that do not crystallize: 1.4).
#include "picture.hpp"

#include <ellipsect/packing.hpp>

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace ellipsect;

template <int N>
void write_scene(const std::string& path, const Packing<N>& p) {
  std::ofstream out(path);
  out.precision(17);
  out << "{\n  \"title\": \"jammed packing, density " << p.density << "\",\n  \"comment\": \"periodic box of sides";
  for (int k = 0; k < N; ++k) out << ' ' << p.box.size[k];
  out << "; centers wrapped into it\",\n  \"bodies\": [\n";
  for (std::size_t i = 0; i < p.bodies.size(); ++i) {
    const auto& b = p.bodies[i];
    out << "    {\"id\": " << i << ", \"center\": [";
    for (int k = 0; k < N; ++k) out << (k ? ", " : "") << b.center()[k];
    out << "], \"radii\": [";
    for (int k = 0; k < N; ++k) out << (k ? ", " : "") << b.radii()[k];
    out << "], \"rotation\": [";
    for (int r = 0; r < N; ++r) {
      out << (r ? ", [" : "[");
      for (int c = 0; c < N; ++c) out << (c ? ", " : "") << b.axes()(r, c);
      out << ']';
    }
    out << "]}" << (i + 1 < p.bodies.size() ? ",\n" : "\n");
  }
  out << "  ]\n}\n";
}

template <int N>
int run(int bodies, const std::vector<double>& shape, double bidisperse, const PackingOptions& options,
        const std::string& svg, const std::string& scene) {
  if (int(shape.size()) != N) {
    std::fprintf(stderr, "--radii needs %d numbers\n", N);
    return 2;
  }
  std::vector<Vec<double, N>> radii(bodies);
  for (int i = 0; i < bodies; ++i)
    for (int k = 0; k < N; ++k) radii[i][k] = shape[k] * (i % 2 == 1 ? bidisperse : 1.0);
  const auto start = std::chrono::steady_clock::now();
  const Packing<N> p = jam_packing<N>(radii, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%d bodies, radii", bodies);
  for (double r : shape) std::printf(" %g", r);
  if (bidisperse != 1.0) std::printf(" (half of them x %g)", bidisperse);
  std::printf(", seed %llu\n", static_cast<unsigned long long>(options.seed));
  std::printf("status %s: packing fraction %.5f at reduced pressure %.3g after %llu collisions\n",
              std::string(to_string(p.status)).c_str(), p.density, p.pressure,
              static_cast<unsigned long long>(p.collisions));
  std::printf("contacts (mu - 1 < %.3g): mean %.3f per body, %.3f without the %zu rattlers\n",
              options.contact_gap > 0 ? double(options.contact_gap) : 100.0 / options.pressure, p.mean_contacts,
              p.mean_contacts_without_rattlers, p.rattlers);
  std::printf("%.1f s, %.0f collisions per second, %zu neighbor-list rebuilds\n", seconds, double(p.collisions) / seconds,
              p.rebuilds);
  std::printf("overlapping pairs at the end: %zu; predictions that found an overlap: %zu, that stopped: %zu\n",
              p.overlapping, p.predictions_overlapping, p.predictions_stopped);
  if (!svg.empty()) picture::write_picture<N>(svg, p.bodies, p.box);
  if (!scene.empty()) write_scene<N>(scene, p);
  return p.overlapping == 0 && p.predictions_overlapping == 0 && p.predictions_stopped == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Jammed packings of ellipses or ellipsoids by Lubachevsky-Stillinger compression"};
  int dim = 3, bodies = 1000;
  std::vector<double> shape;
  double bidisperse = 1.0, rate = 1e-2, slow_rate = 0.0, slow_from = 0.0;
  // The options as given (PackingOptions validates them when they are set, below).
  const PackingOptions defaults;
  double pressure = defaults.pressure, phi0 = defaults.initial_density, skin = defaults.skin;
  std::uint64_t seed = defaults.seed, max_collisions = defaults.max_collisions;
  std::string svg, scene;
  app.add_option("--dim", dim, "2 or 3")->check(CLI::IsMember({2, 3}));
  app.add_option("--bodies", bodies, "number of bodies")->check(CLI::Range(2, 10000000));
  app.add_option("--radii", shape, "the radii of a body, comma separated (default 1.25,1,0.8 / 1,1)")->delimiter(',');
  app.add_option("--bidisperse", bidisperse, "half the bodies scaled by this")->check(CLI::PositiveNumber);
  app.add_option("--rate", rate, "growth rate (thermal speeds per largest diameter)")->check(CLI::PositiveNumber);
  app.add_option("--slow-rate", slow_rate, "a second growth rate, from reduced pressure --slow-from on");
  app.add_option("--slow-from", slow_from, "reduced pressure at which --slow-rate starts");
  app.add_option("--pressure", pressure, "reduced pressure at which the packing counts as jammed");
  app.add_option("--phi0", phi0, "packing fraction of the random start");
  app.add_option("--skin", skin, "neighbor-list skin, of the largest radius");
  app.add_option("--seed", seed, "random start");
  app.add_option("--max-collisions", max_collisions, "stop after this many collisions");
  app.add_option("--svg", svg, "write the packing as an SVG picture");
  app.add_option("--scene", scene, "write the packing as a JSON scene");
  CLI11_PARSE(app, argc, argv);
  if (shape.empty()) shape = dim == 2 ? std::vector<double>{1, 1} : std::vector<double>{1.25, 1, 0.8};
  try {
    PackingOptions options;
    options.seed = seed;
    options.initial_density = phi0;
    options.schedule = slow_rate > 0 ? GrowthSchedule{{0.0, rate}, {slow_from, slow_rate}} : GrowthSchedule{{0.0, rate}};
    options.pressure = pressure;
    options.max_collisions = max_collisions;
    options.skin = skin;
    return dim == 2 ? run<2>(bodies, shape, bidisperse, options, svg, scene)
                    : run<3>(bodies, shape, bidisperse, options, svg, scene);
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
