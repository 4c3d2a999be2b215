// ns per query of each value and of its value-and-gradient form (gradient.hpp), side by side
// on the same seeded cases (scenarios/scenarios.hpp), per category:
//
//   signed_distance/N/{value,gradient}/*   signed_distance, signed_distance_gradient
//   perram_wertheim/N/{value,gradient}/*   perram_wertheim, perram_wertheim_gradient
//   first_contact/N/{value,gradient}/*     first_contact (linear), first_contact_gradient, on
//                                          the pairs made to touch at a known time that hit
//                                          (not those that overlap at the start)
//   overlap_area/2/{value,gradient}/*      overlap_area, overlap_area_gradient
//   iou/2/{value,gradient}/*               intersection_over_union, intersection_over_union_gradient
//   closest_approach/N/{value,gradient}/*  closest_approach, closest_approach_gradient, along the
//                                          line of centers
//   {half_space,box,triangle,capsule}/N/{value,gradient}/mix
//                                          signed_distance against the shape and its gradient,
//                                          on the shapes' test cases (scenarios/half_space.hpp,
//                                          box.hpp, triangle.hpp; capsules on the triangles'
//                                          first edges)
//
// Counter: median_ns, the median over pairs of the time of one query (bench_support.hpp).
// The last name component is the category ("mix": the pairs of every category together).
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/intersect2.hpp>
#include <ellipsect/triangle.hpp>

#include "bench/bench_support.hpp"
#include "scenarios/box.hpp"
#include "scenarios/half_space.hpp"
#include "scenarios/scenarios.hpp"
#include "scenarios/triangle.hpp"

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

// The contact cases that hit (the gradient's cost is that of a hit: the others return
// first_contact's answer with constant derivatives).
template <int N>
std::vector<scenarios::Case<N>> hits(int category) {
  std::vector<scenarios::Case<N>> out;
  for (const auto& c : cases<N>(category, true))
    if (first_contact(c.a, c.va, c.b, c.vb, c.t_max).status == ContactStatus::hit) out.push_back(c);
  return out;
}

template <int N, bool gradient>
void first_contact_query(benchmark::State& state, int category) {
  bench::time_cases(state, hits<N>(category), [](const scenarios::Case<N>& c) {
    if constexpr (gradient) {
      return first_contact_gradient(c.a, c.va, c.b, c.vb, c.t_max).a.center[0];
    } else {
      return first_contact(c.a, c.va, c.b, c.vb, c.t_max).time;
    }
  });
}

template <int N, bool gradient>
void closest_approach_query(benchmark::State& state, int category) {
  bench::time_cases(state, cases<N>(category, false), [](const scenarios::Case<N>& c) {
    const Vec<double, N> u = c.b.center() == c.a.center() ? Vec<double, N>::Unit(0) : Vec<double, N>(c.b.center() - c.a.center());
    if constexpr (gradient) {
      return closest_approach_gradient(c.a, c.b, u).a.radii[0];
    } else {
      return closest_approach(c.a, c.b, u).distance;
    }
  });
}

// A body and a shape.
template <int N, class Shape>
struct ShapeCase {
  Ellipsoid<double, N> a;
  Shape b;
};

template <int N>
std::vector<ShapeCase<N, HalfSpace<double, N>>> half_space_cases() {
  std::vector<ShapeCase<N, HalfSpace<double, N>>> out;
  for (int i = 0; i < 1024; ++i) {
    const auto c = scenarios::make_plane_case<N>(scenarios::planes[i % scenarios::planes.size()], 800000 + i);
    out.push_back({c.a, c.b});
  }
  return out;
}

template <int N>
std::vector<ShapeCase<N, Box<double, N>>> box_cases() {
  std::vector<ShapeCase<N, Box<double, N>>> out;
  for (int i = 0; i < 1024; ++i) {
    const auto [a, b] = scenarios::make_box_pair<N>(i % scenarios::box_kinds, 800000 + i);
    out.push_back({a, b});
  }
  return out;
}

template <int N>
std::vector<ShapeCase<N, Triangle<double, N>>> triangle_cases() {
  std::vector<ShapeCase<N, Triangle<double, N>>> out;
  for (int i = 0; i < 1024; ++i) {
    const auto c = scenarios::make_triangle_case<N>(scenarios::triangle_kinds[i % scenarios::triangle_kinds.size()],
                                                    800000 + i);
    out.push_back({c.a, c.b});
  }
  return out;
}

template <int N>
std::vector<ShapeCase<N, Capsule<double, N>>> capsule_cases() {
  std::vector<ShapeCase<N, Capsule<double, N>>> out;
  for (const auto& c : triangle_cases<N>())
    out.push_back({c.a, make_capsule<double, N>(c.b.vertex(0), c.b.vertex(1), 0.3 * c.a.radii().minCoeff())});
  return out;
}

template <int N, bool gradient, class Shape>
void shape_query(benchmark::State& state, const std::vector<ShapeCase<N, Shape>>& cases) {
  bench::time_cases(state, cases, [](const ShapeCase<N, Shape>& c) {
    if constexpr (gradient) {
      return signed_distance_gradient(c.a, c.b).a.center[0];
    } else {
      return signed_distance(c.a, c.b).distance;
    }
  });
}

template <int N>
void register_shapes() {
  const std::string n = "/" + std::to_string(N);
  const auto both = [&](const std::string& name, const auto& cases) {
    using Shape = decltype(cases.front().b);
    benchmark::RegisterBenchmark((name + n + "/value/mix").c_str(),
                                 [cases](benchmark::State& state) { shape_query<N, false, Shape>(state, cases); });
    benchmark::RegisterBenchmark((name + n + "/gradient/mix").c_str(),
                                 [cases](benchmark::State& state) { shape_query<N, true, Shape>(state, cases); });
  };
  both("half_space", half_space_cases<N>());
  both("box", box_cases<N>());
  both("triangle", triangle_cases<N>());
  both("capsule", capsule_cases<N>());
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
  benchmark::RegisterBenchmark(("closest_approach" + n + "/value" + cat).c_str(), closest_approach_query<N, false>,
                               category);
  benchmark::RegisterBenchmark(("closest_approach" + n + "/gradient" + cat).c_str(), closest_approach_query<N, true>,
                               category);
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
  register_shapes<3>();
  register_shapes<2>();
}

}  // namespace

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, register_all); }
