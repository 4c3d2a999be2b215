// ns per query of overlap, classify and first_contact, 2D and 3D, on the seeded scenario
// mix of the tests (scenarios/scenarios.hpp): every category in equal parts, or one
// category alone (the /category argument is its index in all_categories; -1 = the mix).
// Cases are cycled in a fixed order so every run times the same work. The reported time
// is the mean over the cycled cases; the counter `median_ns` is the median over cases of
// the per-query time (each case timed over 32 back-to-back calls), the figure that the
// goals are stated in.
#include <ellipsect/ellipsect.hpp>

#include "scenarios/scenarios.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
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

// Names the category and adds the per-case median time of `query` over `cs`.
template <class Cases, class Query>
void finish(benchmark::State& state, const Cases& cs, Query&& query) {
  const auto cat = state.range(0);
  state.SetLabel(cat < 0 ? "mix" : std::string(scenarios::name(scenarios::all_categories[cat])));
  constexpr int repeat = 32;
  std::vector<double> ns;
  ns.reserve(cs.size());
  for (const auto& c : cs) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < repeat; ++r) benchmark::DoNotOptimize(query(c));
    const auto t1 = std::chrono::steady_clock::now();
    ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / repeat);
  }
  std::nth_element(ns.begin(), ns.begin() + ns.size() / 2, ns.end());
  state.counters["median_ns"] = ns[ns.size() / 2];
}

template <int N>
void BM_overlap(benchmark::State& state) {
  const auto& cs = cases<N>(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& c = cs[i++ % cs.size()];
    benchmark::DoNotOptimize(overlap(c.a, c.b));
  }
  finish(state, cs, [](const auto& c) { return overlap(c.a, c.b); });
}

template <int N>
void BM_classify(benchmark::State& state) {
  const auto& cs = cases<N>(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& c = cs[i++ % cs.size()];
    benchmark::DoNotOptimize(classify(c.a, c.b));
  }
  finish(state, cs, [](const auto& c) { return classify(c.a, c.b); });
}

template <int N>
void BM_first_contact(benchmark::State& state) {
  const auto& cs = cases<N>(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& c = cs[i++ % cs.size()];
    benchmark::DoNotOptimize(first_contact(c.a, c.va, c.b, c.vb, c.t_max));
  }
  finish(state, cs, [](const auto& c) { return first_contact(c.a, c.va, c.b, c.vb, c.t_max); });
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

}  // namespace

BENCHMARK_MAIN();
