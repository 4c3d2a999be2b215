// Shared timing loop of the benchmark programs.
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

namespace ellipsect::bench {

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
