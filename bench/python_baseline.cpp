// The C++ side of bench/bench_python.py: the batch overlap and classify of ellipsect.hpp's
// span overloads on the same pairs the Python module gets, for the binding's overhead.
//
//   python_baseline DIR N   DIR holds a_centers, a_radii, a_quaternions, b_... as raw
//                           float64 files (N rows each); prints one JSON line of the best
//                           of 5 seconds per query, all cores: from the bodies (the span
//                           overloads, which build the Pairs), on Pairs built once, and on
//                           float Pairs of the bodies rounded to float (as pairs(...,
//                           dtype=float32) rounds them).
#include <ellipsect/batch.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

using namespace ellipsect;

namespace {

std::vector<double> read(const std::string& path, std::size_t count) {
  std::vector<double> out(count);
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(out.data()), std::streamsize(count * sizeof(double)))) {
    std::fprintf(stderr, "cannot read %zu doubles from %s\n", count, path.c_str());
    std::exit(2);
  }
  return out;
}

// The bodies as the binding builds them (make_ellipsoid from a quaternion (w, x, y, z)).
std::vector<Ellipsoid3<double>> bodies(const std::string& dir, const std::string& side, std::size_t n) {
  const auto c = read(dir + "/" + side + "_centers", 3 * n), r = read(dir + "/" + side + "_radii", 3 * n),
             q = read(dir + "/" + side + "_quaternions", 4 * n);
  std::vector<Ellipsoid3<double>> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = make_ellipsoid<double>(Vec3<double>(c[3 * i], c[3 * i + 1], c[3 * i + 2]),
                                    Quat<double>(q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]),
                                    Vec3<double>(r[3 * i], r[3 * i + 1], r[3 * i + 2]));
  return out;
}

std::vector<Ellipsoid3<float>> rounded_to_float(const std::vector<Ellipsoid3<double>>& bodies) {
  std::vector<Ellipsoid3<float>> out;
  out.reserve(bodies.size());
  for (const auto& x : bodies)
    out.push_back(Ellipsoid3<float>::from_axes(x.center().cast<float>(), x.axes().cast<float>(),
                                               x.radii().cast<float>()));
  return out;
}

template <class F>
double best_of_5(const F& f) {
  double best = 1e300;
  for (int k = 0; k < 5; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: python_baseline DIR N\n");
    return 2;
  }
  const std::string dir = argv[1];
  const auto n = std::size_t(std::strtoull(argv[2], nullptr, 10));
  const auto a = bodies(dir, "a", n), b = bodies(dir, "b", n);
  const auto flags = std::make_unique<bool[]>(n);
  std::vector<Relation> relations(n);
  const double overlap_s = best_of_5([&] {
    overlap<double, 3>(a, b, std::span<bool>(flags.get(), n));
  });
  const double classify_s = best_of_5([&] { classify<double, 3>(a, b, std::span<Relation>(relations)); });
  Pairs<double, 3> pairs;
  pairs.reserve(n);
  for (std::size_t i = 0; i < n; ++i) pairs.push_back(a[i], b[i]);
  const double overlap_pairs_s = best_of_5([&] { overlap(pairs, std::span<bool>(flags.get(), n)); });
  const double classify_pairs_s = best_of_5([&] { classify(pairs, std::span<Relation>(relations)); });
  const std::size_t hits = std::size_t(std::count(flags.get(), flags.get() + n, true));
  Pairs<float, 3> single;
  const auto fa = rounded_to_float(a), fb = rounded_to_float(b);
  single.assign(std::span<const Ellipsoid3<float>>(fa), std::span<const Ellipsoid3<float>>(fb));
  const double overlap_float_s = best_of_5([&] { overlap(single, std::span<bool>(flags.get(), n)); });
  const double classify_float_s = best_of_5([&] { classify(single, std::span<Relation>(relations)); });
  std::printf(
      "{\"overlap\": %.6f, \"classify\": %.6f, \"overlap_pairs\": %.6f, \"classify_pairs\": %.6f, "
      "\"overlap_pairs_float\": %.6f, \"classify_pairs_float\": %.6f, \"hits\": %zu}\n",
      overlap_s, classify_s, overlap_pairs_s, classify_pairs_s, overlap_float_s, classify_float_s, hits);
}
