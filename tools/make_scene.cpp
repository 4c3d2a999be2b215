// Deterministic generator of large CSV scenes (the same bytes on every platform: integer
// random numbers, fixed formatting).
//
//   ellipsect_make_scene bodies --count 10000 --seed 1 [--dim 2|3] [--extent 2000] [--velocity] -o FILE
//       one body per row, centers uniform in [0, extent]^dim, radii 1..8, aspect 1..4
//   ellipsect_make_scene pairs --count 1000000 --seed 1 [--dim 2|3] [--velocity] -o FILE
//       one pair per row, both bodies inline, b placed near a (a mix of separated,
//       touching-close, overlapping and containing pairs; with --velocity, b moves
//       towards or past a)
//
// examples/scenes/bodies_10k.csv is `bodies --count 10000 --seed 1`.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

struct Rng {
  std::uint64_t s;
  std::uint64_t next() {  // splitmix64
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }       // [0, 1)
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
};

constexpr double pi = 3.14159265358979323846;

int usage() {
  std::fprintf(stderr,
               "usage: ellipsect_make_scene bodies|pairs --count N [--seed S] [--dim 2|3] [--extent E] [--velocity] "
               "-o FILE\n");
  return 1;
}

// A unit quaternion (w, x, y, z), uniform on the sphere (Shoemake).
void quaternion(Rng& rng, double q[4]) {
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  q[0] = a * std::sin(2 * pi * u2);
  q[1] = a * std::cos(2 * pi * u2);
  q[2] = b * std::sin(2 * pi * u3);
  q[3] = b * std::cos(2 * pi * u3);
}

// One body's fields (center given), written without the id.
void write_body(std::FILE* f, Rng& rng, int dim, const double* c, bool velocity, const double* v) {
  const double r0 = rng.uniform(1.0, 8.0);
  for (int i = 0; i < dim; ++i) std::fprintf(f, "%.6g,", c[i]);
  std::fprintf(f, "%.6g", r0);
  for (int i = 1; i < dim; ++i) std::fprintf(f, ",%.6g", r0 / rng.uniform(1.0, 4.0));
  if (dim == 2) {
    std::fprintf(f, ",%.6g", rng.uniform(0.0, pi));
  } else {
    double q[4];
    quaternion(rng, q);
    std::fprintf(f, ",%.9g,%.9g,%.9g,%.9g", q[0], q[1], q[2], q[3]);
  }
  if (velocity)
    for (int i = 0; i < dim; ++i) std::fprintf(f, ",%.6g", v[i]);
}

void body_header(std::FILE* f, int dim, const char* prefix, bool velocity) {
  static const char* axes[3] = {"x", "y", "z"};
  static const char* radii[3] = {"rx", "ry", "rz"};
  static const char* vel[3] = {"vx", "vy", "vz"};
  for (int i = 0; i < dim; ++i) std::fprintf(f, "%s%s,", prefix, axes[i]);
  for (int i = 0; i < dim; ++i) std::fprintf(f, "%s%s%s", i ? "," : "", prefix, radii[i]);
  if (dim == 2) {
    std::fprintf(f, ",%sangle", prefix);
  } else {
    std::fprintf(f, ",%sqw,%sqx,%sqy,%sqz", prefix, prefix, prefix, prefix);
  }
  if (velocity)
    for (int i = 0; i < dim; ++i) std::fprintf(f, ",%s%s", prefix, vel[i]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  const std::string mode = argv[1];
  if (mode != "bodies" && mode != "pairs") return usage();
  long long count = -1;
  std::uint64_t seed = 1;
  int dim = 2;
  double extent = 2000;
  bool velocity = false;
  std::string out;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) std::exit(usage());
      return argv[++i];
    };
    if (a == "--count") count = std::atoll(value());
    else if (a == "--seed") seed = std::strtoull(value(), nullptr, 10);
    else if (a == "--dim") dim = std::atoi(value());
    else if (a == "--extent") extent = std::atof(value());
    else if (a == "--velocity") velocity = true;
    else if (a == "-o") out = value();
    else return usage();
  }
  if (count < 0 || (dim != 2 && dim != 3) || out.empty()) return usage();
  std::FILE* f = out == "-" ? stdout : std::fopen(out.c_str(), "wb");
  if (f == nullptr) {
    std::perror(out.c_str());
    return 3;
  }
  Rng rng{seed};
  if (mode == "bodies") {
    std::fprintf(f, "# ellipsect_make_scene bodies --count %lld --seed %llu --dim %d --extent %g%s\n", count,
                 static_cast<unsigned long long>(seed), dim, extent, velocity ? " --velocity" : "");
    std::fprintf(f, "id,");
    body_header(f, dim, "", velocity);
    std::fprintf(f, "\n");
    for (long long k = 0; k < count; ++k) {
      double c[3], v[3];
      for (int i = 0; i < dim; ++i) c[i] = rng.uniform(0.0, extent);
      for (int i = 0; i < dim; ++i) v[i] = rng.uniform(-1.0, 1.0);
      std::fprintf(f, "e%05lld,", k);
      write_body(f, rng, dim, c, velocity, v);
      std::fprintf(f, "\n");
    }
  } else {
    body_header(f, dim, "a_", velocity);
    std::fprintf(f, ",");
    body_header(f, dim, "b_", velocity);
    std::fprintf(f, "\n");
    for (long long k = 0; k < count; ++k) {
      double ca[3], cb[3], va[3], vb[3];
      for (int i = 0; i < dim; ++i) {
        ca[i] = rng.uniform(-100.0, 100.0);
        cb[i] = ca[i] + rng.uniform(-20.0, 20.0);
        va[i] = rng.uniform(-1.0, 1.0);
        // b heads roughly towards a: a hit for many rows, a miss for the rest.
        vb[i] = 0.2 * (ca[i] - cb[i]) + rng.uniform(-1.0, 1.0);
      }
      write_body(f, rng, dim, ca, velocity, va);
      std::fprintf(f, ",");
      write_body(f, rng, dim, cb, velocity, vb);
      std::fprintf(f, "\n");
    }
  }
  if (std::ferror(f) || (f != stdout && std::fclose(f) != 0)) {
    std::perror(out.c_str());
    return 3;
  }
  return 0;
}
