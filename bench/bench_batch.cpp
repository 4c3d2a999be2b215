// Batch queries (include/ellipsect/batch.hpp: SIMD filter, threads) side by side with the
// scalar functions, FCL 0.7 and libccd 2.1, on the same seeded cases, with the answers
// that disagree with the 50-digit reference (tests/reference/reference.hpp) counted.
//
// Cases: make_case<N>(category, 800000 + i), i < 1024, for the categories random,
// high_aspect, near_tangent, containment, far_apart, spheres (equal axes), scaled_small,
// scaled_large and grazing (scenarios/scenarios.hpp); 3D for
// every method, 2D also for ellipsect's classify. The last name component is the category.
//
// BM_overlap3/*
//   ellipsect_scalar          overlap(a, b), one pair per call
//   ellipsect_batch_1thread   overlap(pairs, out, options) over the category's 1024 pairs,
//   ellipsect_batch_allcores  options.threads = 1, or 0 (every hardware thread; real time;
//                             arrays this short get no extra thread, see BM_overlap3_cached)
//   fcl_collide               fcl::collide on two fcl::CollisionObjectd holding fcl::Ellipsoidd
//                             (rotation = axes, translation = center; bench/peers.hpp), default
//                             CollisionRequestd: GST_LIBCCD, i.e. ccdMPRIntersect with
//                             max_iterations 500 and mpr_tolerance eps^(7/8) = 2e-14
//   fcl_collide_indep         the same with gjk_solver_type = GST_INDEP: FCL's own GJK,
//                             128 iterations, tolerance 2e-14
//   ccd_gjk, ccd_mpr          ccdGJKIntersect, ccdMPRIntersect with the support point
//                             c + A diag(r^2) A^T d / |diag(r) A^T d| and the center c
//                             (bench/peers.hpp); ccd_t as CCD_INIT leaves it: max_iterations
//                             (unsigned long)-1, epa_tolerance 1e-4, mpr_tolerance 1e-4,
//                             dist_tolerance 1e-6, first_dir ccdFirstDirDefault
// BM_overlap3_from_pose/*  the same pairs built inside the timed query from their poses
//                          (bench_support.hpp: center, unit quaternion, radii), as a
//                          simulation step rebuilding its bodies would:
//   ellipsect                 overlap(make_ellipsoid(pose a), make_ellipsoid(pose b))
//   fcl_collide, fcl_collide_indep  fcl::Ellipsoidd shapes and Transform3d poses (rotation
//                             from the quaternion) built, then fcl::collide on geometries and
//                             transforms, with the requests above
//   ccd_gjk, ccd_mpr          the bodies' rotation matrices from the quaternions, then as above
// BM_classify3/*, BM_classify2/*
//   ellipsect scalar, batch 1 thread, batch all cores (no peer classifies);
//   ellipsect_scalar_exact: classify at Options::tolerance = 0 (exact relations)
// BM_classify3/ellipsect_exact_fallback/exactly_tangent, BM_classify2/...
//   exact classify over 9 exactly tangent pairs and their one-ulp moves (each takes the
//   rational fallback): the fallback's cost per call
// BM_first_contact3/*
//   ellipsect scalar, batch 1 thread, batch all cores
//   fcl_naive_trans,          fcl::continuousCollide from the poses at t = 0 to those at
//   fcl_naive_linear          t = T, default ContinuousCollisionRequestd: CCDC_NAIVE, i.e.
//                             fcl::collide (default request) at t = T i / 9, i = 0..9
//                             (num_max_iterations 10, toc_err 1e-4); motion CCDM_TRANS or
//                             CCDM_LINEAR. T = t_max; for t_max = inf, T = t_c + (Ra + Rb) / |v|
//                             with t_c >= 0 the closest approach of the centers, Ra, Rb the
//                             largest radii, v the relative velocity: no contact can happen
//                             later (a tighter window than any fixed clamp). Answer: no
//                             contact if !is_collide, contact at the start if
//                             time_of_contact = 0, else a hit at time_of_contact * T.
//   Not usable on ellipsoids in FCL 0.7: CCDC_CONSERVATIVE_ADVANCEMENT (no ellipsoid entry
//   in its function table: a warning and no answer), CCDC_RAY_SHOOTING (not implemented:
//   returns -1), CCDC_POLYNOMIAL_SOLVER (BVH meshes only). CCDC_NAIVE ignores
//   gjk_solver_type, so there is no separate indep mode.
// BM_overlap3_cached/*  batch overlap over 1 << 14 pairs (the random cases cycled, static;
//                       16 chunks: two threads), 4.5 MB of columns, in the L3 cache
// BM_overlap3_large/*   the same over 1 << 20 pairs, 285 MB, streamed from memory
// BM_overlap3_cached/ellipsect_gpu/random, BM_overlap3_large/ellipsect_gpu/random
//                       the same through overlap_on_gpu (gpu.hpp; the filter on the GPU, the
//                       pairs it leaves open on every core; columns copied to the device in
//                       each call, through page-locked memory); registered only where a CUDA
//                       device is present
// BM_overlap3_large/ellipsect_spans_allcores/random, BM_classify3_large/ellipsect_spans_allcores/random
//                       the same 1 << 20 pairs from arrays of bodies, through the span
//                       overloads (no Pairs: each thread fills its chunk's columns)
// BM_overlap3_large/ellipsect_build_pairs_allcores/random
//                       a Pairs built from the arrays in each call (reserve, push_back), then
//                       overlap on it: what the span overloads did before
// BM_pairs3_large/push_back/random, BM_pairs3_large/assign_allcores/random
//                       building a Pairs of the 1 << 20 pairs from the arrays: reserve and
//                       push_back per pair, or Pairs::assign (columns on every core)
// BM_classify3_large/ellipsect_batch_allcores/random, BM_classify3_large/ellipsect_gpu/random
//                       batch classify over the same 1 << 20 pairs, on every core and
//                       through classify_on_gpu
// BM_overlap3_filter/random  the SIMD certificate pass alone over the 1024 random pairs
//                             (counter undecided: the share left to the exact path)
// BM_overlap3_simd/TARGET/random
//   batch overlap, 1 thread, pinned to each instruction set of simd_targets()
//   (set_simd_target; the widest is restored afterwards)
//
// Counters: items_per_second (pairs per second) and time_per_pair, from Google Benchmark's
// time (real time for all cores); median_ns (scalar and peers): the median over pairs of
// one query's time (bench/bench_support.hpp); n: the pairs the reference decides; wrong:
// the answers among them that disagree with it. Not counted, as in tests/property: pairs
// within the band 2 * Options::tolerance = 2e-12 of a tangency, i.e. |mu - 1| <= 2e-12
// for overlap (mu: the Perram-Wertheim contact scale factor), any of the reference's
// tangency measures for classify (except equal bodies), and for first_contact mu at t = 0,
// or the smallest mu over the window when the reference says hit or no contact. A
// first_contact answer is wrong when it differs from the reference in hit / contact at
// the start / no contact, or when a hit's time t has |t - t_ref| >
// 1e-6 * max(t_ref, scale / |v|), scale = the largest radius; the time is not judged on
// grazing paths (relative velocity within asin(1e-3) of the contact plane), where it is
// ill-conditioned. The reference of a category is computed on its first use (time on
// stderr).
//
// Run:
//   cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release && cmake --build build/release
//   build/release/bench/bench_batch --benchmark_min_time=0.2
#include <ellipsect/batch.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/gpu.hpp>

#include "bench/bench_support.hpp"
#include "detail/batch_kernels.hpp"
#include "bench/peers.hpp"
#include "scenarios/scenarios.hpp"
#include "tests/reference/bridge.hpp"

#include <benchmark/benchmark.h>

#ifdef ELLIPSECT_HAVE_FCL
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/continuous_collision.h>
#endif

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace {

using namespace ellipsect;
namespace ref = ellipsect::reference;
using scenarios::Category;

constexpr int cases_per_category = 1024;
constexpr std::size_t cached_size = std::size_t{1} << 14;  // 4.5 MB of columns: in the L3 cache
constexpr std::size_t large_size = std::size_t{1} << 20;   // 285 MB: streamed from memory
constexpr double band = 2 * Options{}.tolerance;
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr std::array categories = {Category::random,       Category::high_aspect,  Category::near_tangent,
                                   Category::containment,  Category::far_apart,    Category::spheres,
                                   Category::scaled_small, Category::scaled_large, Category::grazing};

// ---- cases ------------------------------------------------------------------------------

template <int N>
struct Cases {
  std::vector<scenarios::Case<N>> list;  // scalar functions and peers
  Pairs<double, N> pairs;                // the same, for the batch functions
};

template <int N>
const Cases<N>& cases(int k) {
  static const auto all = [] {
    std::vector<Cases<N>> out(categories.size());
    for (std::size_t j = 0; j < categories.size(); ++j)
      for (int i = 0; i < cases_per_category; ++i) {
        const auto c = scenarios::make_case<N>(categories[j], 800000 + i);
        out[j].list.push_back(c);
        out[j].pairs.push_back(c.a, c.va, c.b, c.vb, c.t_max);
      }
    return out;
  }();
  return all[static_cast<std::size_t>(k)];
}

std::string category_name(int k) { return std::string(scenarios::name(categories[static_cast<std::size_t>(k)])); }

// ---- reference answers (nullopt: inside the tolerance band, not counted) ----------------

using ref::from_ref;
using ref::to_ref;

using bench::Answer;
using bench::Outcome;
using bench::answer;

struct ContactTruth {
  Answer expected;
  double time_tolerance;  // inf: status only (grazing path)
};

template <class T>
using Truth = std::vector<std::optional<T>>;

struct StaticTruth {
  Truth<Relation> relation;
  Truth<bool> overlap;
};

template <class Compute>
auto timed(const char* what, int k, Compute compute) {
  const auto t0 = std::chrono::steady_clock::now();
  auto out = compute();
  const std::chrono::duration<double> s = std::chrono::steady_clock::now() - t0;
  std::fprintf(stderr, "reference %s/%s: %d cases in %.1f s\n", what, category_name(k).c_str(), cases_per_category,
               s.count());
  return out;
}

template <int N>
const StaticTruth& static_truth(int k) {
  static std::map<int, StaticTruth> cache;
  if (const auto it = cache.find(k); it != cache.end()) return it->second;
  return cache[k] = timed(N == 2 ? "classify2" : "classify3", k, [k] {
           StaticTruth t;
           for (const auto& c : cases<N>(k).list) {
             const auto r = ref::classify<N>(to_ref(c.a), to_ref(c.b), band);
             const Relation want = from_ref(r.relation);
             const bool mu_decided = ref::to_double(abs(r.mu - 1)) > band;
             t.relation.push_back(r.margin > band || want == Relation::equal ? std::optional(want) : std::nullopt);
             t.overlap.push_back(mu_decided ? std::optional(want != Relation::separated) : std::nullopt);
           }
           return t;
         });
}

const Truth<ContactTruth>& contact_truth(int k) {
  static std::map<int, Truth<ContactTruth>> cache;
  if (const auto it = cache.find(k); it != cache.end()) return it->second;
  return cache[k] = timed("first_contact3", k, [k] {
           Truth<ContactTruth> t;
           for (const auto& c : cases<3>(k).list) {
             const auto r = ref::first_contact<3>(to_ref(c.a), c.va, to_ref(c.b), c.vb, c.t_max, band);
             const bool grazing_band = std::abs(ref::to_double(r.min_mu) - 1) <= band;
             if (r.kind == ref::ContactKind::touching_at_start) {
               t.emplace_back();
             } else if (r.kind == ref::ContactKind::overlapping_at_start) {
               t.push_back(ContactTruth{{Outcome::at_start, 0}, inf});
             } else if (grazing_band) {
               t.emplace_back();
             } else if (r.kind == ref::ContactKind::none) {
               t.push_back(ContactTruth{{Outcome::none, inf}, inf});
             } else {
               const Vec3<double> v = c.vb - c.va;
               const double t_ref = ref::to_double(r.time);
               const double sin_angle = std::abs(ref::to_double<3>(r.normal).dot(v.normalized()));
               const double scale = std::max(c.a.radii().maxCoeff(), c.b.radii().maxCoeff());
               const double tol = sin_angle < 1e-3 ? inf : 1e-6 * std::max(t_ref, scale / v.norm());
               t.push_back(ContactTruth{{Outcome::hit, t_ref}, tol});
             }
           }
           return t;
         });
}


bool disagrees(bool want, bool got) { return want != got; }
bool disagrees(Relation want, Relation got) { return want != got; }
bool disagrees(const ContactTruth& want, const Answer& got) {
  return got.outcome != want.expected.outcome ||
         (got.outcome == Outcome::hit && !(std::abs(got.time - want.expected.time) <= want.time_tolerance));
}
bool disagrees(const ContactTruth& want, const Contact<double, 3>& got) { return disagrees(want, answer(got)); }

// ---- timing and counters ----------------------------------------------------------------

template <class T, class Answers>
void count_wrong(benchmark::State& state, const Truth<T>& truth, const Answers& got) {
  int n = 0, wrong = 0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    if (truth[i]) {
      ++n;
      wrong += disagrees(*truth[i], got[i]);
    }
  state.counters["n"] = n;
  state.counters["wrong"] = wrong;
}

// items_per_second (pairs/s) and time_per_pair, from Google Benchmark's time (the real
// time for benchmarks marked UseRealTime).
void per_pair(benchmark::State& state, std::size_t pairs_per_iteration) {
  const auto items = state.iterations() * static_cast<std::int64_t>(pairs_per_iteration);
  state.SetItemsProcessed(items);
  state.counters["time_per_pair"] =
      benchmark::Counter(static_cast<double>(items), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// One pair per call: every item answered once for the counters, then the timing loop.
template <class T, class Items, class Query>
void run_queries(benchmark::State& state, const Truth<T>& truth, const Items& items, Query query) {
  std::vector<decltype(query(items[0]))> got;
  for (const auto& item : items) got.push_back(query(item));
  count_wrong(state, truth, got);
  bench::time_cases(state, items, query);
  per_pair(state, 1);
}

// The whole array per call (answers of the first call for the counters).
template <class Out, class T, class P, class Batch>
void run_batch(benchmark::State& state, const Truth<T>& truth, const P& pairs, int threads, Batch batch) {
  const auto out = std::make_unique<Out[]>(pairs.size());
  const std::span<Out> span(out.get(), pairs.size());
  const BatchOptions options{.query = {}, .threads = threads};
  batch(pairs, span, options);
  count_wrong(state, truth, out.get());
  for (auto _ : state) batch(pairs, span, options);
  per_pair(state, pairs.size());
}

constexpr auto batch_overlap = [](const auto& p, auto out, const BatchOptions& o) { overlap(p, out, o); };
constexpr auto batch_classify = [](const auto& p, auto out, const BatchOptions& o) { classify(p, out, o); };
constexpr auto batch_first_contact = [](const auto& p, auto out, const BatchOptions& o) { first_contact(p, out, o); };

// ---- ellipsect --------------------------------------------------------------------------

void overlap_scalar(benchmark::State& state, int k) {
  run_queries(state, static_truth<3>(k).overlap, cases<3>(k).list,
              [](const scenarios::Case<3>& c) { return overlap(c.a, c.b); });
}

// Pose pairs of category k's 3D cases.
const std::vector<std::pair<bench::Pose3, bench::Pose3>>& poses(int k) {
  static std::map<int, std::vector<std::pair<bench::Pose3, bench::Pose3>>> cache;
  auto& out = cache[k];
  if (out.empty())
    for (const auto& c : cases<3>(k).list) out.emplace_back(bench::pose_of(c.a), bench::pose_of(c.b));
  return out;
}

void overlap_from_pose(benchmark::State& state, int k) {
  run_queries(state, static_truth<3>(k).overlap, poses(k),
              [](const auto& p) { return overlap(bench::body_of(p.first), bench::body_of(p.second)); });
}

void overlap_batch(benchmark::State& state, int k, int threads) {
  run_batch<bool>(state, static_truth<3>(k).overlap, cases<3>(k).pairs, threads, batch_overlap);
}

template <int N>
void classify_scalar(benchmark::State& state, int k) {
  run_queries(state, static_truth<N>(k).relation, cases<N>(k).list,
              [](const scenarios::Case<N>& c) { return classify(c.a, c.b); });
}

template <int N>
void classify_scalar_exact(benchmark::State& state, int k) {
  run_queries(state, static_truth<N>(k).relation, cases<N>(k).list, [](const scenarios::Case<N>& c) {
    return classify(c.a, c.b, Options{.tolerance = Tolerance::exact});
  });
}

// Exactly tangent pairs and the same one ulp apart or into each other, where exact classify
// always takes its rational fallback: external tangency (balls of radii 3 and 2, centers
// 5 apart), internal tangency (the ball of radius 2 about an ellipse of radii 2, 1, ...),
// equal sets stored differently (axes turned by a quarter turn, radii swapped).
template <int N>
std::vector<std::pair<Ellipsoid<double, N>, Ellipsoid<double, N>>> exactly_tangent_pairs() {
  using E = Ellipsoid<double, N>;
  Vec<double, N> zero = Vec<double, N>::Zero(), x = zero, radii = Vec<double, N>::Ones(), swapped = radii;
  radii[0] = swapped[1] = 2;
  Mat<double, N> turn = Mat<double, N>::Identity();
  turn(0, 0) = turn(1, 1) = 0;
  turn(1, 0) = 1;
  turn(0, 1) = -1;
  std::vector<std::pair<E, E>> pairs;
  for (const double ulps : {0, 1, -1}) {
    x[0] = ulps == 0 ? 5.0 : std::nextafter(5.0, 5 + ulps);
    pairs.emplace_back(make_ball<double, N>(zero, 3), make_ball<double, N>(x, 2));
    Vec<double, N> r = radii;
    r[0] = ulps == 0 ? 2.0 : std::nextafter(2.0, 2 + ulps);
    pairs.emplace_back(make_ball<double, N>(zero, 2), E::from_axes(zero, Mat<double, N>::Identity(), r));
    pairs.emplace_back(E::from_axes(zero, Mat<double, N>::Identity(), r), E::from_axes(zero, turn, swapped));
  }
  return pairs;
}

template <int N>
void classify_exact_fallback(benchmark::State& state) {
  const auto pairs = exactly_tangent_pairs<N>();
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& [a, b] = pairs[i++ % pairs.size()];
    benchmark::DoNotOptimize(classify(a, b, Options{.tolerance = Tolerance::exact}));
  }
  state.counters["pairs"] = double(pairs.size());
}

template <int N>
void classify_batch(benchmark::State& state, int k, int threads) {
  run_batch<Relation>(state, static_truth<N>(k).relation, cases<N>(k).pairs, threads, batch_classify);
}

void contact_scalar(benchmark::State& state, int k) {
  run_queries(state, contact_truth(k), cases<3>(k).list,
              [](const scenarios::Case<3>& c) { return first_contact(c.a, c.va, c.b, c.vb, c.t_max); });
}

void contact_batch(benchmark::State& state, int k, int threads) {
  run_batch<Contact<double, 3>>(state, contact_truth(k), cases<3>(k).pairs, threads, batch_first_contact);
}

// Pair i is (a[i], b[i]).
struct Bodies {
  std::vector<Ellipsoid<double, 3>> a, b;
  std::size_t size() const { return a.size(); }
};

Ellipsoid<float, 3> in_float(const Ellipsoid<double, 3>& e) {
  return Ellipsoid<float, 3>::from_axes(e.center().cast<float>(), e.axes().cast<float>(), e.radii().cast<float>());
}

// The random cases cycled to `size` pairs (static: no motion), with the reference's answers;
// and the same bodies rounded to float, with the scalar functions' answers for those (equal
// to the reference's wherever the rounding, ~1e-7, does not move a pair across the band).
template <std::size_t size>
const auto& cycled() {
  static const auto out = [] {
    struct {
      Pairs<double, 3> pairs;
      Pairs<float, 3> pairs_in_float;
      Bodies bodies;
      Truth<bool> overlap, overlap_in_float;
      Truth<Relation> relation, relation_in_float;
    } c;
    c.pairs.reserve(size);
    c.pairs_in_float.reserve(size);
    for (std::size_t i = 0; i < size; ++i) {
      const auto& x = cases<3>(0).list[i % cases_per_category];
      const auto a = in_float(x.a), b = in_float(x.b);
      c.pairs.push_back(x.a, x.b);
      c.pairs_in_float.push_back(a, b);
      c.bodies.a.push_back(x.a);
      c.bodies.b.push_back(x.b);
      c.overlap.push_back(static_truth<3>(0).overlap[i % cases_per_category]);
      c.relation.push_back(static_truth<3>(0).relation[i % cases_per_category]);
      c.overlap_in_float.push_back(overlap(a, b));
      c.relation_in_float.push_back(classify(a, b));
    }
    return c;
  }();
  return out;
}

// The batch query, or through its GPU entry point (which must answer on the GPU).
template <class Out, std::size_t size, class Truth, class Batch, class OnGpu>
void run_cycled(benchmark::State& state, const Truth& truth, int threads, bool gpu, Batch batch, OnGpu on_gpu) {
  if (!gpu) return run_batch<Out>(state, truth, cycled<size>().pairs, threads, batch);
  run_batch<Out>(state, truth, cycled<size>().pairs, threads, [on_gpu](const auto& p, auto out, const BatchOptions& o) {
    if (on_gpu(p, out, o) != Backend::gpu) throw std::runtime_error("the GPU entry point answered on the CPU");
  });
}

// Pairs<float, 3>: the float filter.
template <std::size_t size>
void overlap_cycled_in_float(benchmark::State& state, int threads) {
  run_batch<bool>(state, cycled<size>().overlap_in_float, cycled<size>().pairs_in_float, threads, batch_overlap);
}

template <std::size_t size>
void classify_cycled_in_float(benchmark::State& state, int threads) {
  run_batch<Relation>(state, cycled<size>().relation_in_float, cycled<size>().pairs_in_float, threads,
                      batch_classify);
}

template <std::size_t size>
void overlap_cycled(benchmark::State& state, int threads, bool gpu) {
  run_cycled<bool, size>(state, cycled<size>().overlap, threads, gpu, batch_overlap,
                         [](const auto& p, auto out, const BatchOptions& o) { return overlap_on_gpu(p, out, o); });
}

template <std::size_t size>
void classify_cycled(benchmark::State& state, int threads, bool gpu) {
  run_cycled<Relation, size>(state, cycled<size>().relation, threads, gpu, batch_classify,
                             [](const auto& p, auto out, const BatchOptions& o) { return classify_on_gpu(p, out, o); });
}

Pairs<double, 3> pushed(const Bodies& x) {
  Pairs<double, 3> pairs;
  pairs.reserve(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) pairs.push_back(x.a[i], x.b[i]);
  return pairs;
}

// From arrays of bodies: the span overloads, or a Pairs built in each call, then queried.
template <std::size_t size>
void overlap_from_bodies(benchmark::State& state, bool build_pairs) {
  const auto& c = cycled<size>();
  run_batch<bool>(state, c.overlap, c.bodies, 0, [build_pairs](const Bodies& x, auto out, const BatchOptions& o) {
    if (!build_pairs) return overlap<double, 3>(x.a, x.b, out, o);
    overlap(pushed(x), out, o);
  });
}

// A Pairs from the arrays: push_back per pair, or assign (on every core).
template <std::size_t size>
void build_pairs(benchmark::State& state, bool assign) {
  const auto& c = cycled<size>();
  for (auto _ : state) {
    Pairs<double, 3> pairs;
    if (assign)
      pairs.assign(c.bodies.a, c.bodies.b);
    else
      pairs = pushed(c.bodies);
    benchmark::DoNotOptimize(pairs.column(0));
  }
  per_pair(state, size);
}

template <std::size_t size>
void classify_from_bodies(benchmark::State& state) {
  const auto& c = cycled<size>();
  run_batch<Relation>(state, c.relation, c.bodies, 0, [](const Bodies& x, auto out, const BatchOptions& o) {
    classify<double, 3>(x.a, x.b, out, o);
  });
}

// The vector certificate pass alone (no scalar fallback, no thread), on the random pairs
// (double, or the float filter on them rounded to float): `undecided` is the share it
// leaves to the exact path.
template <class T>
void filter(benchmark::State& state, detail::BatchQuery query) {
  const auto& pairs = [] {
    if constexpr (std::is_same_v<T, double>) {
      return cases<3>(0).pairs;
    } else {
      Pairs<float, 3> p;
      for (const auto& c : cases<3>(0).list) p.push_back(in_float(c.a), in_float(c.b));
      return p;
    }
  }();
  std::vector<const T*> columns;
  for (int k = 0; k < Pairs<T, 3>::columns; ++k) columns.push_back(pairs.column(k));
  std::vector<signed char> codes(pairs.size());
  for (auto _ : state) {
    detail::certify_pairs(3, query, columns.data(), 0, pairs.size(), 1e-12, codes.data());
    benchmark::DoNotOptimize(codes.data());
  }
  state.counters["undecided"] = double(std::count(codes.begin(), codes.end(), 0)) / double(codes.size());
  per_pair(state, pairs.size());
}

void overlap_simd(benchmark::State& state, const std::string& target) {
  set_simd_target(target);
  overlap_batch(state, 0, 1);
  set_simd_target("");
}

// ---- FCL --------------------------------------------------------------------------------

#ifdef ELLIPSECT_HAVE_FCL
struct FclPair {
  std::shared_ptr<fcl::CollisionObjectd> a, b;
};

void fcl_overlap(benchmark::State& state, int k, fcl::GJKSolverType solver) {
  std::vector<FclPair> items;
  for (const auto& c : cases<3>(k).list) items.push_back({bench::fcl_object(c.a), bench::fcl_object(c.b)});
  fcl::CollisionRequestd request;
  request.gjk_solver_type = solver;
  run_queries(state, static_truth<3>(k).overlap, items, [&request](const FclPair& p) {
    fcl::CollisionResultd result;
    fcl::collide(p.a.get(), p.b.get(), request, result);
    return result.isCollision();
  });
}

void fcl_overlap_from_pose(benchmark::State& state, int k, fcl::GJKSolverType solver) {
  fcl::CollisionRequestd request;
  request.gjk_solver_type = solver;
  run_queries(state, static_truth<3>(k).overlap, poses(k), [&request](const auto& p) {
    const fcl::Ellipsoidd a = bench::fcl_shape(p.first), b = bench::fcl_shape(p.second);
    fcl::CollisionResultd result;
    fcl::collide(&a, bench::fcl_pose(p.first), &b, bench::fcl_pose(p.second), request, result);
    return result.isCollision();
  });
}

bench::FclMotion fcl_motion(const scenarios::Case<3>& c) {
  double window = c.t_max;
  if (std::isinf(window)) {
    const Vec3<double> r = c.b.center() - c.a.center(), v = c.vb - c.va;
    const double reach = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
    window = v.squaredNorm() > 0 ? std::max(0.0, -r.dot(v)) / v.squaredNorm() + reach / v.norm() : 1.0;
  }
  return {bench::fcl_shape(c.a),
          bench::fcl_shape(c.b),
          bench::fcl_pose(c.a),
          bench::fcl_pose(c.a, c.va * window),
          bench::fcl_pose(c.b),
          bench::fcl_pose(c.b, c.vb * window),
          window};
}

void fcl_contact(benchmark::State& state, int k, fcl::CCDMotionType motion) {
  std::vector<bench::FclMotion> items;
  for (const auto& c : cases<3>(k).list) items.push_back(fcl_motion(c));
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = motion;
  run_queries(state, contact_truth(k), items, [&request](const bench::FclMotion& m) {
    return bench::answer_from_time(bench::fcl_contact_time(m, request));
  });
}
#endif

// ---- libccd -----------------------------------------------------------------------------

#ifdef ELLIPSECT_HAVE_CCD
using CcdIntersect = int (*)(const void*, const void*, const ccd_t*);

using CcdPair = std::pair<bench::CcdBody, bench::CcdBody>;

void ccd_overlap(benchmark::State& state, int k, CcdIntersect method) {
  std::vector<CcdPair> items;
  for (const auto& c : cases<3>(k).list) items.emplace_back(bench::ccd_body(c.a), bench::ccd_body(c.b));
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccd.support2 = bench::ccd_support;
  ccd.center1 = ccd.center2 = bench::ccd_center;
  run_queries(state, static_truth<3>(k).overlap, items,
              [&](const CcdPair& b) { return method(&b.first, &b.second, &ccd) == 1; });
}

void ccd_overlap_from_pose(benchmark::State& state, int k, CcdIntersect method) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccd.support2 = bench::ccd_support;
  ccd.center1 = ccd.center2 = bench::ccd_center;
  run_queries(state, static_truth<3>(k).overlap, poses(k), [&](const auto& p) {
    const bench::CcdBody a = bench::ccd_body(p.first), b = bench::ccd_body(p.second);
    return method(&a, &b, &ccd) == 1;
  });
}
#endif

// ---- registration -----------------------------------------------------------------------

template <class Fn, class... Args>
benchmark::internal::Benchmark* add(const std::string& name, Fn fn, Args... args) {
  return benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) { fn(state, args...); });
}

template <int N>
void add_classify(int n) {
  const std::string family = "BM_classify" + std::to_string(N);
  for (int k = 0; k < n; ++k) {
    const std::string cat = "/" + category_name(k);
    add(family + "/ellipsect_scalar" + cat, classify_scalar<N>, k);
    add(family + "/ellipsect_scalar_exact" + cat, classify_scalar_exact<N>, k);
    add(family + "/ellipsect_batch_1thread" + cat, classify_batch<N>, k, 1);
    add(family + "/ellipsect_batch_allcores" + cat, classify_batch<N>, k, 0)->UseRealTime();
  }
  add(family + "/ellipsect_exact_fallback/exactly_tangent", classify_exact_fallback<N>);
}

void register_all() {
  const int n = static_cast<int>(categories.size());
  for (int k = 0; k < n; ++k) {
    const std::string cat = "/" + category_name(k);
    add("BM_overlap3/ellipsect_scalar" + cat, overlap_scalar, k);
    add("BM_overlap3/ellipsect_batch_1thread" + cat, overlap_batch, k, 1);
    add("BM_overlap3/ellipsect_batch_allcores" + cat, overlap_batch, k, 0)->UseRealTime();
#ifdef ELLIPSECT_HAVE_FCL
    add("BM_overlap3/fcl_collide" + cat, fcl_overlap, k, fcl::GST_LIBCCD);
    add("BM_overlap3/fcl_collide_indep" + cat, fcl_overlap, k, fcl::GST_INDEP);
#endif
#ifdef ELLIPSECT_HAVE_CCD
    add("BM_overlap3/ccd_gjk" + cat, ccd_overlap, k, &ccdGJKIntersect);
    add("BM_overlap3/ccd_mpr" + cat, ccd_overlap, k, &ccdMPRIntersect);
#endif
  }
  for (int k = 0; k < n; ++k) {
    const std::string cat = "/" + category_name(k);
    add("BM_overlap3_from_pose/ellipsect" + cat, overlap_from_pose, k);
#ifdef ELLIPSECT_HAVE_FCL
    add("BM_overlap3_from_pose/fcl_collide" + cat, fcl_overlap_from_pose, k, fcl::GST_LIBCCD);
    add("BM_overlap3_from_pose/fcl_collide_indep" + cat, fcl_overlap_from_pose, k, fcl::GST_INDEP);
#endif
#ifdef ELLIPSECT_HAVE_CCD
    add("BM_overlap3_from_pose/ccd_gjk" + cat, ccd_overlap_from_pose, k, &ccdGJKIntersect);
    add("BM_overlap3_from_pose/ccd_mpr" + cat, ccd_overlap_from_pose, k, &ccdMPRIntersect);
#endif
  }
  add_classify<3>(n);
  add_classify<2>(n);
  for (int k = 0; k < n; ++k) {
    const std::string cat = "/" + category_name(k);
    add("BM_first_contact3/ellipsect_scalar" + cat, contact_scalar, k);
    add("BM_first_contact3/ellipsect_batch_1thread" + cat, contact_batch, k, 1);
    add("BM_first_contact3/ellipsect_batch_allcores" + cat, contact_batch, k, 0)->UseRealTime();
#ifdef ELLIPSECT_HAVE_FCL
    add("BM_first_contact3/fcl_naive_trans" + cat, fcl_contact, k, fcl::CCDM_TRANS);
    add("BM_first_contact3/fcl_naive_linear" + cat, fcl_contact, k, fcl::CCDM_LINEAR);
#endif
  }
  add("BM_overlap3_cached/ellipsect_batch_1thread/random", overlap_cycled<cached_size>, 1, false);
  add("BM_overlap3_cached/ellipsect_batch_allcores/random", overlap_cycled<cached_size>, 0, false)->UseRealTime();
  add("BM_overlap3_large/ellipsect_batch_1thread/random", overlap_cycled<large_size>, 1, false);
  add("BM_overlap3_large/ellipsect_batch_allcores/random", overlap_cycled<large_size>, 0, false)->UseRealTime();
  add("BM_classify3_large/ellipsect_batch_allcores/random", classify_cycled<large_size>, 0, false)->UseRealTime();
  add("BM_overlap3_cached/ellipsect_batch_float_1thread/random", overlap_cycled_in_float<cached_size>, 1);
  add("BM_overlap3_cached/ellipsect_batch_float_allcores/random", overlap_cycled_in_float<cached_size>, 0)
      ->UseRealTime();
  add("BM_overlap3_large/ellipsect_batch_float_allcores/random", overlap_cycled_in_float<large_size>, 0)
      ->UseRealTime();
  add("BM_classify3_cached/ellipsect_batch_allcores/random", classify_cycled<cached_size>, 0, false)->UseRealTime();
  add("BM_classify3_cached/ellipsect_batch_float_allcores/random", classify_cycled_in_float<cached_size>, 0)
      ->UseRealTime();
  add("BM_classify3_large/ellipsect_batch_float_allcores/random", classify_cycled_in_float<large_size>, 0)
      ->UseRealTime();
  add("BM_overlap3_large/ellipsect_spans_allcores/random", overlap_from_bodies<large_size>, false)->UseRealTime();
  add("BM_overlap3_large/ellipsect_build_pairs_allcores/random", overlap_from_bodies<large_size>, true)->UseRealTime();
  add("BM_classify3_large/ellipsect_spans_allcores/random", classify_from_bodies<large_size>)->UseRealTime();
  add("BM_pairs3_large/push_back/random", build_pairs<large_size>, false)->UseRealTime();
  add("BM_pairs3_large/assign_allcores/random", build_pairs<large_size>, true)->UseRealTime();
  if (gpu_info().devices > 0) {
    add("BM_overlap3_cached/ellipsect_gpu/random", overlap_cycled<cached_size>, 0, true)->UseRealTime();
    add("BM_overlap3_large/ellipsect_gpu/random", overlap_cycled<large_size>, 0, true)->UseRealTime();
    add("BM_classify3_large/ellipsect_gpu/random", classify_cycled<large_size>, 0, true)->UseRealTime();
  }
  for (const auto& target : simd_targets()) add("BM_overlap3_simd/" + target + "/random", overlap_simd, target);
  for (const auto& [name, query] : {std::pair("BM_overlap3_filter", detail::BatchQuery::overlap),
                                    std::pair("BM_classify3_filter", detail::BatchQuery::classify)}) {
    add(std::string(name) + "/random", filter<double>, query);
    add(std::string(name) + "/float/random", filter<float>, query);
  }
}

}  // namespace

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, register_all); }
