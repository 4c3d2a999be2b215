// ns per query of each value and of its value-and-gradient form (gradient.hpp), side by side
// on the same seeded cases (scenarios/scenarios.hpp), per category:
//
//   signed_distance/N/{value,gradient}/*   signed_distance, signed_distance_gradient
//   perram_wertheim/N/{value,gradient}/*   perram_wertheim, perram_wertheim_gradient
//   first_contact/N/{value,gradient}/*     first_contact (linear), first_contact_gradient, on
//                                          pairs that touch at a known time
//   overlap_area/2/{value,gradient}/*      overlap_area, overlap_area_gradient
//   iou/2/{value,gradient}/*               intersection_over_union, intersection_over_union_gradient
//
// Counter: median_ns, the median over pairs of the time of one query (bench_support.hpp).
// The last name component is the category ("mix": the pairs of every category together).
#include <ellipsect/contact.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/intersect2.hpp>

#include "bench/bench_support.hpp"
#include "scenarios/scenarios.hpp"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace {

using namespace ellipsect;
constexpr int cases_per_category = 256;

constexpr std::array<scenarios::Category, 6> categories = {
    scenarios::Category::random,       scenarios::Category::high_aspect,  scenarios::Category::near_tangent,
    scenarios::Category::containment,  scenarios::Category::scaled_large, scenarios::Category::far_apart};

// The cases of one category (-1: all); contact cases touch at a known time.
template <int N>
std::vector<scenarios::Case<N>> cases(int category, bool contact) {
  std::vector<scenarios::Case<N>> out;
  for (int k = 0; k < static_cast<int>(categories.size()); ++k) {
    if (category >= 0 && k != category) continue;
    for (int i = 0; i < cases_per_category; ++i)
      out.push_back(contact ? scenarios::make_contact_case<N>(categories[k], 800000 + i, 1e-2)
                            : scenarios::make_case<N>(categories[k], 800000 + i));
  }
  return out;
}

template <int N, bool gradient>
void signed_distance_query(benchmark::State& state, int category) {
  bench::time_cases(state, cases<N>(category, false), [](const scenarios::Case<N>& c) {
    if constexpr (gradient) {
      return signed_distance_gradient(c.a, c.b).a.center[0];
    } else {
      return signed_distance(c.a, c.b).distance;
    }
  });
}

template <int N, bool gradient>
void perram_wertheim_query(benchmark::State& state, int category) {
  bench::time_cases(state, cases<N>(category, false), [](const scenarios::Case<N>& c) {
    if constexpr (gradient) {
      return perram_wertheim_gradient(c.a, c.b).a.center[0];
    } else {
      return perram_wertheim(c.a, c.b).f;
    }
  });
}

template <int N, bool gradient>
void first_contact_query(benchmark::State& state, int category) {
  bench::time_cases(state, cases<N>(category, true), [](const scenarios::Case<N>& c) {
    if constexpr (gradient) {
      return first_contact_gradient(c.a, c.va, c.b, c.vb, c.t_max).a.center[0];
    } else {
      return first_contact(c.a, c.va, c.b, c.vb, c.t_max).time;
    }
  });
}

// 2D: overlap_area and intersection_over_union with their gradients.
template <bool gradient>
void overlap_area_query(benchmark::State& state, int category) {
  bench::time_cases(state, cases<2>(category, false), [](const scenarios::Case<2>& c) {
    if constexpr (gradient) {
      return overlap_area_gradient(c.a, c.b).a.center[0];
    } else {
      return overlap_area(c.a, c.b).area;
    }
  });
}

template <bool gradient>
void iou_query(benchmark::State& state, int category) {
  bench::time_cases(state, cases<2>(category, false), [](const scenarios::Case<2>& c) {
    if constexpr (gradient) {
      return intersection_over_union_gradient(c.a, c.b).a.center[0];
    } else {
      return intersection_over_union(c.a, c.b);
    }
  });
}

template <int N>
void register_dimension(const std::string& cat, int category) {
  const std::string n = "/" + std::to_string(N);
  benchmark::RegisterBenchmark(("signed_distance" + n + "/value" + cat).c_str(), signed_distance_query<N, false>, category);
  benchmark::RegisterBenchmark(("signed_distance" + n + "/gradient" + cat).c_str(), signed_distance_query<N, true>, category);
  benchmark::RegisterBenchmark(("perram_wertheim" + n + "/value" + cat).c_str(), perram_wertheim_query<N, false>, category);
  benchmark::RegisterBenchmark(("perram_wertheim" + n + "/gradient" + cat).c_str(), perram_wertheim_query<N, true>,
                               category);
  benchmark::RegisterBenchmark(("first_contact" + n + "/value" + cat).c_str(), first_contact_query<N, false>, category);
  benchmark::RegisterBenchmark(("first_contact" + n + "/gradient" + cat).c_str(), first_contact_query<N, true>, category);
  if constexpr (N == 2) {
    benchmark::RegisterBenchmark(("overlap_area/2/value" + cat).c_str(), overlap_area_query<false>, category);
    benchmark::RegisterBenchmark(("overlap_area/2/gradient" + cat).c_str(), overlap_area_query<true>, category);
    benchmark::RegisterBenchmark(("iou/2/value" + cat).c_str(), iou_query<false>, category);
    benchmark::RegisterBenchmark(("iou/2/gradient" + cat).c_str(), iou_query<true>, category);
  }
}

void register_all() {
  for (int category = -1; category < static_cast<int>(categories.size()); ++category) {
    const std::string cat = "/" + (category < 0 ? std::string("mix") : std::string(scenarios::name(categories[category])));
    register_dimension<3>(cat, category);
    register_dimension<2>(cat, category);
  }
}

}  // namespace

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, register_all); }
