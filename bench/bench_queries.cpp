// ns per query of overlap, classify, first_contact, perram_wertheim and closest_approach
// (along a fixed direction), 2D and 3D, on the seeded scenario
// mix of the tests (scenarios/scenarios.hpp): every category in equal parts, or one
// category alone (the /category argument is its index in all_categories; -1 = the mix).
// BM_perram_wertheim_needles/k: touching needles and discs of aspect ratio 10^k.
// BM_classify_moved is classify on the same pairs moved 1e6 sizes from the origin.
// BM_overlap_from_pose/3 builds both bodies from their poses (bench_support.hpp: center,
// quaternion, radii) inside the timed query; BM_make_* and BM_from_axes time one factory
// call on the bodies of the mix (both bodies of every case).
// Cases are cycled in a fixed order so every run times the same work; see
// bench/bench_support.hpp for the mean and the per-query median (`median_ns`).
#include <ellipsect/ellipsect.hpp>

#include "bench/bench_support.hpp"
#include "scenarios/scenarios.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <utility>
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

// The same pairs moved together 1e6 sizes from the origin (along a fixed direction; the
// moved coordinates round): classify's cost should not depend on where the pair lies.
template <int N>
std::vector<scenarios::Case<N>> moved_cases(int category) {
  std::vector<scenarios::Case<N>> out = cases<N>(category);
  const Vec<double, N> direction = Vec<double, N>::Ones().normalized();
  for (auto& c : out) {
    const Vec<double, N> offset = direction * (1e6 * std::max(c.a.radii().maxCoeff(), c.b.radii().maxCoeff()));
    c.a = c.a.translated(offset);
    c.b = c.b.translated(offset);
  }
  return out;
}

template <int N>
void BM_classify_moved(benchmark::State& state) {
  bench::time_cases(state, moved_cases<N>(static_cast<int>(state.range(0))), [](const auto& c) { return classify(c.a, c.b); });
  label(state);
}

// perram_wertheim on touching needles (or, in 3D, needle against disc) of aspect ratio 10^k
// (state.range(0) = k): from k = 6 on the pair's aspect ratios multiply beyond 1e12 and it
// is solved in the world frame (contact_function.hpp).
template <int N>
void BM_perram_wertheim_needles(benchmark::State& state) {
  using namespace scenarios::detail;
  const double aspect = std::pow(10.0, double(state.range(0))) * 0.99;
  std::vector<std::pair<Ellipsoid<double, N>, Ellipsoid<double, N>>> pairs;
  for (int i = 0; i < cases_per_category; ++i) {
    Rng rng(static_cast<std::uint64_t>(i) + 4400);
    Vec<double, N> ra = Vec<double, N>::Constant(1), rb = Vec<double, N>::Constant(1.5);
    ra[N - 1] = 1.001 / aspect;
    rb[0] = 1.5 / aspect;
    if constexpr (N == 3) ra[1] = 1 / aspect;
    const auto a = Ellipsoid<double, N>::from_axes(unit_vector<N>(rng), rotation<N>(rng), ra);
    const Mat<double, N> axes_b = rotation<N>(rng);
    const Vec<double, N> cb = tangent_center<N>(a, unit_vector<N>(rng), axes_b, rb, 1e-6);
    pairs.emplace_back(a, Ellipsoid<double, N>::from_axes(cb, axes_b, rb));
  }
  bench::time_cases(state, pairs, [](const auto& p) { return perram_wertheim(p.first, p.second).f; });
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

template <int N>
void BM_overlap_from_pose(benchmark::State& state) {
  std::vector<std::pair<bench::Pose3, bench::Pose3>> poses;
  for (const auto& c : cases<N>(static_cast<int>(state.range(0)))) poses.emplace_back(bench::pose_of(c.a), bench::pose_of(c.b));
  bench::time_cases(state, poses, [](const auto& p) { return overlap(bench::body_of(p.first), bench::body_of(p.second)); });
  label(state);
}

// Every body of the 3D or 2D mix, for the factory benchmarks.
template <int N>
std::vector<Ellipsoid<double, N>> bodies() {
  std::vector<Ellipsoid<double, N>> out;
  for (const auto& c : cases<N>(-1)) {
    out.push_back(c.a);
    out.push_back(c.b);
  }
  return out;
}

void BM_make_ellipsoid_quaternion(benchmark::State& state) {
  std::vector<bench::Pose3> poses;
  for (const auto& e : bodies<3>()) poses.push_back(bench::pose_of(e));
  bench::time_cases(state, poses, [](const bench::Pose3& p) { return bench::body_of(p); });
}

void BM_make_ellipsoid_matrix(benchmark::State& state) {
  std::vector<bench::Pose3> poses;
  for (const auto& e : bodies<3>()) poses.push_back(bench::pose_of(e));
  std::vector<std::pair<bench::Pose3, Mat3<double>>> items;
  for (const auto& p : poses) items.emplace_back(p, p.rotation.toRotationMatrix());
  bench::time_cases(state, items, [](const auto& x) { return make_ellipsoid(x.first.center, x.second, x.first.radii); });
}

void BM_make_ellipse(benchmark::State& state) {
  struct Item {
    Vec2<double> center;
    double angle;
    Vec2<double> radii;
  };
  std::vector<Item> items;
  for (const auto& e : bodies<2>()) items.push_back({e.center(), std::atan2(e.axes()(1, 0), e.axes()(0, 0)), e.radii()});
  bench::time_cases(state, items, [](const Item& x) { return make_ellipse(x.center, x.angle, x.radii); });
}

template <int N>
void BM_from_axes(benchmark::State& state) {
  bench::time_cases(state, bodies<N>(), [](const Ellipsoid<double, N>& e) {
    return Ellipsoid<double, N>::from_axes(e.center(), e.axes(), e.radii());
  });
}

void BM_make_ball(benchmark::State& state) {
  bench::time_cases(state, bodies<3>(), [](const Ellipsoid3<double>& e) { return make_ball<double, 3>(e.center(), e.radii()[0]); });
}

void categories(benchmark::internal::Benchmark* b) {
  b->Arg(-1);
  for (int i = 0; i < static_cast<int>(scenarios::all_categories.size()); ++i) b->Arg(i);
}

BENCHMARK(BM_overlap<2>)->Apply(categories);
BENCHMARK(BM_overlap<3>)->Apply(categories);
BENCHMARK(BM_classify<2>)->Apply(categories);
BENCHMARK(BM_classify<3>)->Apply(categories);
BENCHMARK(BM_classify_moved<2>)->Apply(categories);
BENCHMARK(BM_classify_moved<3>)->Apply(categories);
BENCHMARK(BM_first_contact<2>)->Apply(categories);
BENCHMARK(BM_first_contact<3>)->Apply(categories);
BENCHMARK(BM_perram_wertheim<2>)->Apply(categories);
BENCHMARK(BM_perram_wertheim<3>)->Apply(categories);
BENCHMARK(BM_perram_wertheim_needles<2>)->DenseRange(2, 8, 2);
BENCHMARK(BM_perram_wertheim_needles<3>)->DenseRange(2, 8, 2);
BENCHMARK(BM_closest_approach<2>)->Apply(categories);
BENCHMARK(BM_closest_approach<3>)->Apply(categories);
BENCHMARK(BM_overlap_from_pose<3>)->Apply(categories);
BENCHMARK(BM_make_ellipsoid_quaternion);
BENCHMARK(BM_make_ellipsoid_matrix);
BENCHMARK(BM_make_ellipse);
BENCHMARK(BM_from_axes<2>);
BENCHMARK(BM_from_axes<3>);
BENCHMARK(BM_make_ball);

}  // namespace

BENCHMARK_MAIN();
