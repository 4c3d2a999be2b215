// ns per query of overlap, classify, first_contact, perram_wertheim and closest_approach
// (along a fixed direction), 2D and 3D, on the seeded scenario
// mix of the tests (scenarios/scenarios.hpp): every category in equal parts, or one
// category alone (the /category argument is its index in all_categories; -1 = the mix).
// Cases are cycled in a fixed order so every run times the same work; see
// bench/bench_support.hpp for the mean and the per-query median (`median_ns`).
#include <ellipsect/ellipsect.hpp>

#include "bench/bench_support.hpp"
#include "scenarios/scenarios.hpp"

#include <benchmark/benchmark.h>

#include <vector>

namespace {

using namespace ellipsect;
constexpr int cases_per_category = 256;

template <int N>
const std::vector<scenarios::Case<N>>& cases(int category) {
  static const auto all = [] {
    std::vector<std::vector<scenarios::Case<N>>> by;
    std::vector<scenarios::Case<N>> mix;
    for (const auto c : scenarios::all_categories) {
      by.emplace_back();
      for (int i = 0; i < cases_per_category; ++i) {
        by.back().push_back(scenarios::make_case<N>(c, 900000 + i));
        mix.push_back(by.back().back());
      }
    }
    by.push_back(mix);
    return by;
  }();
  return all[category < 0 ? all.size() - 1 : static_cast<std::size_t>(category)];
}

void label(benchmark::State& state) {
  const auto cat = state.range(0);
  state.SetLabel(cat < 0 ? "mix" : std::string(scenarios::name(scenarios::all_categories[cat])));
}

template <int N>
void BM_overlap(benchmark::State& state) {
  bench::time_cases(state, cases<N>(static_cast<int>(state.range(0))), [](const auto& c) { return overlap(c.a, c.b); });
  label(state);
}

template <int N>
void BM_classify(benchmark::State& state) {
  bench::time_cases(state, cases<N>(static_cast<int>(state.range(0))), [](const auto& c) { return classify(c.a, c.b); });
  label(state);
}

template <int N>
void BM_first_contact(benchmark::State& state) {
  bench::time_cases(state, cases<N>(static_cast<int>(state.range(0))), [](const auto& c) { return first_contact(c.a, c.va, c.b, c.vb, c.t_max); });
  label(state);
}

template <int N>
void BM_perram_wertheim(benchmark::State& state) {
  bench::time_cases(state, cases<N>(static_cast<int>(state.range(0))), [](const auto& c) { return perram_wertheim(c.a, c.b); });
  label(state);
}

template <int N>
void BM_closest_approach(benchmark::State& state) {
  const Vec<double, N> u = Vec<double, N>::LinSpaced(1.0, 0.3);
  bench::time_cases(state, cases<N>(static_cast<int>(state.range(0))), [&](const auto& c) { return closest_approach(c.a, c.b, u); });
  label(state);
}

void categories(benchmark::internal::Benchmark* b) {
  b->Arg(-1);
  for (int i = 0; i < static_cast<int>(scenarios::all_categories.size()); ++i) b->Arg(i);
}

BENCHMARK(BM_overlap<2>)->Apply(categories);
BENCHMARK(BM_overlap<3>)->Apply(categories);
BENCHMARK(BM_classify<2>)->Apply(categories);
BENCHMARK(BM_classify<3>)->Apply(categories);
BENCHMARK(BM_first_contact<2>)->Apply(categories);
BENCHMARK(BM_first_contact<3>)->Apply(categories);
BENCHMARK(BM_perram_wertheim<2>)->Apply(categories);
BENCHMARK(BM_perram_wertheim<3>)->Apply(categories);
BENCHMARK(BM_closest_approach<2>)->Apply(categories);
BENCHMARK(BM_closest_approach<3>)->Apply(categories);

}  // namespace

BENCHMARK_MAIN();
