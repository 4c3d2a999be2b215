// ns per query of Niemitalo's 2D methods next to the exact overlap, on the same pairs: the
// seeded scenario mix (scenarios/scenarios.hpp, 256 pairs per category, 2560 in all), with
// b replaced by the circle at its center with the geometric mean of its radii for the
// ellipse-circle queries; and, for the ellipse-circle tests against the document's own code
// (bench/niemitalo_document.hpp), 2560 near-tangent pairs (the circle touching a's boundary
// at a random point, moved by +-1e-9 .. 1e-6 of its radius), where every level runs. /n is
// max_level. Timing and the per-query median: see bench/bench_support.hpp.
#include <ellipsect/classify.hpp>
#include <ellipsect/polygonal2.hpp>
#include <ellipsect/quartic2.hpp>

#include "bench/bench_support.hpp"
#include "bench/niemitalo_document.hpp"
#include "scenarios/scenarios.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

namespace {

using namespace ellipsect;
constexpr int cases_per_category = 256;

template <class T>
struct Pair {
  Ellipse2<T> a, b;   // the scenario pair
  Circle<T> circle;   // the circle standing in for b
  Ellipse2<T> ball;   // the same disk as an Ellipse2, for the exact overlap
};

template <class T>
Ellipse2<T> as(const Ellipse2<double>& e) {
  return Ellipse2<T>::from_axes(e.center().cast<T>(), e.axes().cast<T>(), e.radii().cast<T>());
}

template <class T>
const std::vector<Pair<T>>& pairs() {
  static const auto all = [] {
    std::vector<Pair<T>> v;
    for (const auto c : scenarios::all_categories)
      for (int i = 0; i < cases_per_category; ++i) {
        const auto s = scenarios::make_case<2>(c, 900000 + i);
        const auto circle = make_circle<T>(s.b.center().cast<T>(), T(std::sqrt(s.b.radii().prod())));
        v.push_back({as<T>(s.a), as<T>(s.b), circle, circle.ellipse()});
      }
    return v;
  }();
  return all;
}

// The scenario mix's ellipses a, each with a circle of radius sqrt(r_b0 r_b1), and b itself,
// placed against it at one random boundary point, the gap +-1e-9 .. 1e-6 of the radius.
template <class T>
const std::vector<Pair<T>>& tangent_pairs() {
  static const auto all = [] {
    std::vector<Pair<T>> v;
    scenarios::detail::Rng rng(910000);
    for (const auto c : scenarios::all_categories)
      for (int i = 0; i < cases_per_category; ++i) {
        const auto s = scenarios::make_case<2>(c, 900000 + i);
        const double r = std::sqrt(s.b.radii().prod());
        const double gap = (i % 2 ? -1 : 1) * scenarios::detail::log_uniform(rng, 1e-9, 1e-6);
        const Vec2<double> u = scenarios::detail::unit_vector<2>(rng);
        const Vec2<double> center =
            scenarios::detail::tangent_center<2>(s.a, u, Mat2<double>::Identity(), Vec2<double>(r, r), gap);
        const auto b = Ellipse2<double>::from_axes(
            scenarios::detail::tangent_center<2>(s.a, u, s.b.axes(), s.b.radii(), gap), s.b.axes(), s.b.radii());
        const auto circle = make_circle<T>(center.cast<T>(), T(r));
        v.push_back({as<T>(s.a), as<T>(b), circle, circle.ellipse()});
      }
    return v;
  }();
  return all;
}

template <class T, class Query>
void cycle(benchmark::State& state, Query query) {
  ellipsect::bench::time_cases(state, pairs<T>(), query);
}

// The document's test takes an axis-aligned ellipse: the circle's center is turned into
// a's axes inside the timed query.
template <class T>
bool document_collide(const ellipsect::bench::DocumentTests<T>& test, const Pair<T>& p) {
  const Vec2<T> local = p.a.axes().transpose() * (p.circle.center() - p.a.center());
  return test.collide(T(0), T(0), p.a.radii()[0], p.a.radii()[1], local.x(), local.y(), p.circle.radius());
}

// The document's ellipse-ellipse test takes each ellipse as its first radius vector and the
// ratio of the second radius to the first.
template <class T>
bool document_collide_ellipses(const ellipsect::bench::DocumentTests<T>& test, const Pair<T>& p) {
  const Vec2<T> wa = p.a.radii()[0] * p.a.axes().col(0), wb = p.b.radii()[0] * p.b.axes().col(0);
  return test.collide(p.a.center().x(), p.a.center().y(), wa.x(), wa.y(), p.a.radii()[1] / p.a.radii()[0],
                      p.b.center().x(), p.b.center().y(), wb.x(), wb.y(), p.b.radii()[1] / p.b.radii()[0]);
}

// The document's test with max_iterations = n (the benchmark's argument), and
// polygonal_overlap at max_level = n, on `cases`.
template <class T, class Collide>
void time_document(benchmark::State& state, const std::vector<Pair<T>>& cases, Collide collide) {
  const ellipsect::bench::DocumentTests<T> test(static_cast<int>(state.range(0)));
  ellipsect::bench::time_cases(state, cases, [&](const Pair<T>& p) { return collide(test, p); });
}

template <class T, class Query>
void time_levels(benchmark::State& state, const std::vector<Pair<T>>& cases, Query query) {
  const int n = static_cast<int>(state.range(0));
  ellipsect::bench::time_cases(state, cases, [&](const Pair<T>& p) { return query(p, n).verdict; });
}

template <class T>
void BM_document_ellipses(benchmark::State& state) {
  time_document(state, pairs<T>(), document_collide_ellipses<T>);
}

template <class T>
void BM_polygonal_ellipses_tangent(benchmark::State& state) {
  time_levels(state, tangent_pairs<T>(), [](const Pair<T>& p, int n) { return polygonal_overlap(p.a, p.b, n); });
}

template <class T>
void BM_document_ellipses_tangent(benchmark::State& state) {
  time_document(state, tangent_pairs<T>(), document_collide_ellipses<T>);
}

template <class T>
void BM_document_circle(benchmark::State& state) {
  time_document(state, pairs<T>(), document_collide<T>);
}

template <class T>
void BM_polygonal_circle_tangent(benchmark::State& state) {
  time_levels(state, tangent_pairs<T>(), [](const Pair<T>& p, int n) { return polygonal_overlap(p.a, p.circle, n); });
}

template <class T>
void BM_document_circle_tangent(benchmark::State& state) {
  time_document(state, tangent_pairs<T>(), document_collide<T>);
}

template <class T>
void BM_polygonal_circle(benchmark::State& state) {
  time_levels(state, pairs<T>(), [](const Pair<T>& p, int n) { return polygonal_overlap(p.a, p.circle, n); });
}

template <class T>
void BM_circle_cover(benchmark::State& state) {
  time_levels(state, pairs<T>(), [](const Pair<T>& p, int n) { return circle_cover_overlap(p.a, p.circle, n); });
}

template <class T>
void BM_polygonal_ellipses(benchmark::State& state) {
  time_levels(state, pairs<T>(), [](const Pair<T>& p, int n) { return polygonal_overlap(p.a, p.b, n); });
}

// The closed forms answer the same ellipse-circle question: collision when the center is
// inside or the closest point is within the radius.
template <class T>
void BM_closed_form_circle(benchmark::State& state) {
  cycle<T>(state, [](const Pair<T>& p) {
    const auto q = closest_point_closed_form(p.a, p.circle.center());
    return q.status == QuarticStatus::inside || q.distance <= p.circle.radius();
  });
}

template <class T>
void BM_quartic_circle(benchmark::State& state) {
  cycle<T>(state, [](const Pair<T>& p) {
    const auto q = closest_point_quartic(p.a, p.circle.center());
    return q.status == QuarticStatus::inside || q.distance <= p.circle.radius();
  });
}

template <class T>
void BM_overlap_circle(benchmark::State& state) {
  cycle<T>(state, [](const Pair<T>& p) { return overlap(p.a, p.ball); });
}

template <class T>
void BM_overlap_ellipses(benchmark::State& state) {
  cycle<T>(state, [](const Pair<T>& p) { return overlap(p.a, p.b); });
}

BENCHMARK(BM_polygonal_circle<double>)->DenseRange(1, 10);
BENCHMARK(BM_polygonal_circle<float>)->DenseRange(1, 10);
BENCHMARK(BM_document_circle<double>)->DenseRange(1, 10);
BENCHMARK(BM_document_circle<float>)->DenseRange(1, 10);
BENCHMARK(BM_polygonal_circle_tangent<double>)->DenseRange(1, 10);
BENCHMARK(BM_polygonal_circle_tangent<float>)->DenseRange(1, 10);
BENCHMARK(BM_document_circle_tangent<double>)->DenseRange(1, 10);
BENCHMARK(BM_document_circle_tangent<float>)->DenseRange(1, 10);
BENCHMARK(BM_circle_cover<double>)->DenseRange(1, 10);
BENCHMARK(BM_closed_form_circle<double>);
BENCHMARK(BM_closed_form_circle<float>);
BENCHMARK(BM_quartic_circle<double>);
BENCHMARK(BM_quartic_circle<float>);
BENCHMARK(BM_overlap_circle<double>);
BENCHMARK(BM_overlap_circle<float>);
BENCHMARK(BM_polygonal_ellipses<double>)->DenseRange(1, 10);
BENCHMARK(BM_polygonal_ellipses<float>)->DenseRange(1, 10);
BENCHMARK(BM_document_ellipses<double>)->DenseRange(1, 10);
BENCHMARK(BM_polygonal_ellipses_tangent<double>)->DenseRange(1, 10);
BENCHMARK(BM_document_ellipses_tangent<double>)->DenseRange(1, 10);
BENCHMARK(BM_overlap_ellipses<double>);
BENCHMARK(BM_overlap_ellipses<float>);

}  // namespace

BENCHMARK_MAIN();
