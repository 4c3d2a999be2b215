// Shared timing loop of the benchmark programs.
#pragma once

#include <ellipsect/contact.hpp>
#include <ellipsect/shapes.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace ellipsect::bench {

// A 3D body as a simulation holds it between steps: center, unit quaternion, radii. The
// "from pose" benchmarks build the bodies from these inside the timed query.
struct Pose3 {
  Vec3<double> center;
  Quat<double> rotation;
  Vec3<double> radii;
};

// e's pose: its axes as a rotation (a reflection's last column negated, which describes the
// same set) turned into a unit quaternion.
inline Pose3 pose_of(const Ellipsoid3<double>& e) {
  Mat3<double> r = e.axes();
  if (r.determinant() < 0) r.col(2) = -r.col(2);
  return {e.center(), Quat<double>(r).normalized(), e.radii()};
}

inline Ellipsoid3<double> body_of(const Pose3& p) { return make_ellipsoid(p.center, p.rotation, p.radii); }

// A first contact as the benchmarks compare it with the reference.
enum class Outcome { at_start, hit, none, failed };

struct Answer {
  Outcome outcome;
  double time;
};

template <class T, int N>
Answer answer(const Contact<T, N>& c) {
  switch (c.status) {
    case ContactStatus::hit: return {Outcome::hit, double(c.time)};
    case ContactStatus::touching_at_start:
    case ContactStatus::overlapping_at_start: return {Outcome::at_start, 0};
    case ContactStatus::no_contact_in_window: return {Outcome::none, std::numeric_limits<double>::infinity()};
    default: return {Outcome::failed, NAN};
  }
}

// A peer's time of contact: negative for none, 0 for contact at the start.
inline Answer answer_from_time(double t) {
  if (t < 0) return {Outcome::none, std::numeric_limits<double>::infinity()};
  return t == 0 ? Answer{Outcome::at_start, 0} : Answer{Outcome::hit, t};
}

// Times `query` while cycling through `cases` in a fixed order (Google Benchmark's time is
// the mean over them), then adds the counter `median_ns`: the median over cases of the
// time of one query, each case timed over 32 back-to-back calls.
template <class Cases, class Query>
void time_cases(benchmark::State& state, const Cases& cases, Query&& query) {
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(query(cases[i++ % cases.size()]));
  constexpr int repeat = 32;
  std::vector<double> ns;
  ns.reserve(cases.size());
  for (const auto& c : cases) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < repeat; ++r) benchmark::DoNotOptimize(query(c));
    const auto t1 = std::chrono::steady_clock::now();
    ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / repeat);
  }
  std::nth_element(ns.begin(), ns.begin() + ns.size() / 2, ns.end());
  state.counters["median_ns"] = ns[ns.size() / 2];
}

// main() of a program whose benchmarks `register_all` registers at run time.
inline int run_main(int argc, char** argv, void (*register_all)()) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace ellipsect::bench
