// Batch queries equal the scalar ones bit for bit: on every scenario category, for every
// SIMD target the CPU offers, at several thread counts, through both entry points.
#include <ellipsect/batch.hpp>

#include "detail/batch_kernels.hpp"
#include "detail/certificates-inl.hpp"
#include "scenarios/scenarios.hpp"
#include "tests/support.hpp"
#include "tests/unit/scenario_pairs.hpp"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using ellipsect::testing::scenario_pairs;

template <class T>
bool same_bits(T x, T y) {
  return (std::isnan(x) && std::isnan(y)) || x == y;
}

template <class T, int N>
void expect_same(const Contact<T, N>& batch, const Contact<T, N>& scalar, std::size_t i) {
  EXPECT_EQ(batch.status, scalar.status) << "pair " << i;
  EXPECT_EQ(batch.iterations, scalar.iterations) << "pair " << i;
  EXPECT_TRUE(same_bits(batch.time, scalar.time)) << "pair " << i << ": " << batch.time << " vs " << scalar.time;
  for (int k = 0; k < N; ++k) {
    EXPECT_TRUE(same_bits(batch.point[k], scalar.point[k])) << "pair " << i;
    EXPECT_TRUE(same_bits(batch.normal[k], scalar.normal[k])) << "pair " << i;
  }
}

template <class T, int N>
void expect_batch_equals_scalar(const Pairs<T, N>& pairs, int threads) {
  const std::size_t n = pairs.size();
  const BatchOptions options{.query = {}, .threads = threads};
  const auto overlaps = std::make_unique<bool[]>(n);
  std::vector<Relation> relations(n);
  std::vector<Contact<T, N>> contacts(n);
  overlap(pairs, std::span<bool>(overlaps.get(), n), options);
  classify(pairs, std::span<Relation>(relations), options);
  first_contact(pairs, std::span<Contact<T, N>>(contacts), options);
  for (std::size_t i = 0; i < n; ++i) {
    const auto &a = pairs.a(i), &b = pairs.b(i);
    EXPECT_EQ(overlaps[i], overlap(a, b)) << "pair " << i;
    EXPECT_EQ(relations[i], classify(a, b)) << "pair " << i;
    expect_same(contacts[i], first_contact(a, pairs.velocity_a(i), b, pairs.velocity_b(i), pairs.t_max(i)), i);
  }
}

template <class T, int N>
void every_target(int per_category) {
  const auto pairs = scenario_pairs<T, N>(ellipsect::testing::cases(per_category));
  for (const auto& target : simd_targets()) {
    SCOPED_TRACE(target);
    set_simd_target(target);
    EXPECT_EQ(simd_target(), target);
    expect_batch_equals_scalar(pairs, 1);
  }
  set_simd_target("");
}

TEST(Batch, EqualsScalarOnEveryTarget2D) { every_target<double, 2>(60); }
TEST(Batch, EqualsScalarOnEveryTarget3D) { every_target<double, 3>(60); }
TEST(Batch, EqualsScalarInFloat) {
  every_target<float, 2>(20);
  every_target<float, 3>(20);
}

// The vector filter's code for each pair is the scalar certificate's, on every target
// (one pair's overlap may decide more, by the centre line), and it decides most pairs of
// the random category (the point of the filter).
template <int N>
void codes_equal_scalar() {
  namespace hw = detail::HWY_NAMESPACE;
  const auto pairs = scenario_pairs<double, N>(ellipsect::testing::cases(50));
  const auto columns = ellipsect::testing::columns_of(pairs);
  const std::size_t n = pairs.size();
  std::vector<signed char> codes(n);
  for (const auto& target : simd_targets()) {
    SCOPED_TRACE(target);
    set_simd_target(target);
    for (const auto query : {detail::BatchQuery::overlap, detail::BatchQuery::classify, detail::BatchQuery::contact}) {
      detail::certify_pairs(N, query, columns.data(), 0, n, 1e-12, codes.data());
      std::size_t random = 0, decided = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const auto a = hw::lanes_of(pairs.a(i), hw::Fill::balls), b = hw::lanes_of(pairs.b(i), hw::Fill::balls);
        double va[N], vb[N];
        for (int k = 0; k < N; ++k) {
          va[k] = pairs.velocity_a(i)[k];
          vb[k] = pairs.velocity_b(i)[k];
        }
        const double scalar = query == detail::BatchQuery::overlap    ? hw::certificate_code<false>(pairs.a(i), pairs.b(i), 1e-12)
                              : query == detail::BatchQuery::classify ? hw::certificate_code<true>(pairs.a(i), pairs.b(i), 1e-12)
                                                                      : hw::swept_code<double, N>(a, va, b, vb, pairs.t_max(i), 1e-12);
        // One pair's overlap also tries the centre line, which reads the axes the columns
        // do not hold: a pair it decides may be open in the filter, nothing else differs.
        const bool by_centre_line = query == detail::BatchQuery::overlap && codes[i] == 0 && scalar == 1 &&
                                    hw::centre_line_meets(pairs.a(i), pairs.b(i), a, b);
        if (!by_centre_line) {
          ASSERT_EQ(codes[i], static_cast<signed char>(scalar)) << "pair " << i;
        }
        if (i < n / scenarios::all_categories.size()) {  // the random category comes first
          ++random;
          decided += codes[i] != 0;
        }
      }
      if (query == detail::BatchQuery::overlap) {
        EXPECT_GT(decided, random / 2);
      }
    }
  }
  set_simd_target("");
}

TEST(Batch, FilterCodesEqualScalarCertificates) {
  codes_equal_scalar<2>();
  codes_equal_scalar<3>();
}

// What a classify code stands for (certificates-inl.hpp): -1 separated, +1 overlapping,
// +2 a contains b, +3 b contains a.
Relation classify_code_relation(signed char code) {
  switch (code) {
    case -1: return Relation::separated;
    case 1: return Relation::overlapping;
    case 2: return Relation::a_contains_b;
    case 3: return Relation::b_contains_a;
  }
  ADD_FAILURE() << "no relation for code " << int(code);
  return Relation::equal;
}

// The float filter (Pairs<float>'s overlap and classify): every code it gives is the
// scalar function's answer, on every category and target, and on random pairs it decides
// nearly all that the double certificates decide (each category's counts are printed:
// near-tangent pairs are left to the scalar functions).
template <int N>
void float_codes_are_scalar_answers() {
  namespace hw = detail::HWY_NAMESPACE;
  const auto pairs = scenario_pairs<float, N>(ellipsect::testing::cases(200));
  const auto columns = ellipsect::testing::columns_of(pairs);
  const std::size_t n = pairs.size(), per_category = n / scenarios::all_categories.size();
  std::vector<signed char> codes(n);
  for (const auto& target : simd_targets()) {
    SCOPED_TRACE(target);
    set_simd_target(target);
    for (const auto query : {detail::BatchQuery::overlap, detail::BatchQuery::classify}) {
      detail::certify_pairs(N, query, columns.data(), 0, n, 1e-12, codes.data());
      std::vector<std::size_t> decided(scenarios::all_categories.size()), by_double(decided.size());
      for (std::size_t i = 0; i < n; ++i) {
        const auto &a = pairs.a(i), &b = pairs.b(i);
        const bool overlap_query = query == detail::BatchQuery::overlap;
        by_double[i / per_category] += (overlap_query ? hw::certificate_code<false>(a, b, 1e-12)
                                                      : hw::certificate_code<true>(a, b, 1e-12)) != 0;
        if (codes[i] == 0) continue;
        ++decided[i / per_category];
        if (query == detail::BatchQuery::overlap) {
          ASSERT_EQ(codes[i] > 0, overlap(a, b)) << "pair " << i;
        } else {
          ASSERT_EQ(classify(a, b), classify_code_relation(codes[i])) << "pair " << i;
        }
      }
      std::string counts;
      for (std::size_t c = 0; c < decided.size(); ++c)
        counts += std::string(scenarios::name(scenarios::all_categories[c])) + " " + std::to_string(decided[c]) + " (" +
                  std::to_string(by_double[c]) + ") ";
      std::printf("%dD %s, decided of %zu per category, float (double): %s\n", N,
                  query == detail::BatchQuery::overlap ? "overlap" : "classify", per_category, counts.c_str());
      EXPECT_GE(decided[0], by_double[0] * 95 / 100);  // the random category comes first
    }
  }
  set_simd_target("");
}

TEST(Batch, FloatFilterCodesAreScalarAnswers) {
  float_codes_are_scalar_answers<2>();
  float_codes_are_scalar_answers<3>();
}

// Pairs at float's resolution from the boundaries the float filter must not cross: b
// moved along the line of centers to relative offsets g (1e-7 to 1e-3) from where it just
// touches a from outside (random pairs) or from inside (containment pairs), both found by
// bisection on the scalar answers. Every code the float filter gives there is the scalar
// answer, and it decides the pairs well outside the band.
template <int N>
void float_filter_near_boundaries() {
  using E = Ellipsoid<float, N>;
  auto moved = [](const E& a, const E& b, double t) {
    const Vec<double, N> from = a.center().template cast<double>(), to = b.center().template cast<double>();
    return E::from_axes((from + t * (to - from)).template cast<float>(), b.axes(), b.radii());
  };
  // The boundary of `inside(t)` (true at t = 1) along t >= 1.
  auto boundary = [](const auto& inside) {
    double lo = 1, hi = 2;
    while (inside(hi)) hi *= 2;
    for (int k = 0; k < 60; ++k) ((inside((lo + hi) / 2)) ? lo : hi) = (lo + hi) / 2;
    return lo;
  };
  Pairs<float, N> pairs;
  const double offsets[] = {1e-7, 3e-7, 1e-6, 3e-6, 1e-5, 3e-5, 1e-4, 1e-3};
  for (const auto category : {scenarios::Category::random, scenarios::Category::containment})
    for (std::uint64_t seed = 0; seed < 100; ++seed) {
      const auto c = scenarios::make_case<N>(category, 9300 + seed);
      const E a = ellipsect::testing::as<float>(c.a), b = ellipsect::testing::as<float>(c.b);
      const bool contained = category == scenarios::Category::containment;
      if (contained ? classify(a, b) != Relation::a_contains_b : !overlap(a, b)) continue;
      const double t =
          contained ? boundary([&](double s) { return classify(a, moved(a, b, s)) == Relation::a_contains_b; })
                    : boundary([&](double s) { return overlap(a, moved(a, b, s)); });
      for (const double g : offsets)
        for (const double sign : {-1.0, 1.0}) pairs.push_back(a, moved(a, b, t * (1 + sign * g)));
    }
  const auto columns = ellipsect::testing::columns_of(pairs);
  const std::size_t n = pairs.size();
  ASSERT_GT(n, 1000u);
  std::vector<signed char> codes(n);
  for (const auto query : {detail::BatchQuery::overlap, detail::BatchQuery::classify}) {
    detail::certify_pairs(N, query, columns.data(), 0, n, 1e-12, codes.data());
    std::array<std::size_t, 8> decided{};  // by offset
    for (std::size_t i = 0; i < n; ++i) {
      if (codes[i] == 0) continue;
      const auto &a = pairs.a(i), &b = pairs.b(i);
      if (query == detail::BatchQuery::overlap) {
        ASSERT_EQ(codes[i] > 0, overlap(a, b)) << "pair " << i;
      } else {
        ASSERT_EQ(classify(a, b), classify_code_relation(codes[i])) << "pair " << i;
      }
      ++decided[(i % 16) / 2];
    }
    std::printf("%dD %s near boundaries, decided of %zu per offset:", N,
                query == detail::BatchQuery::overlap ? "overlap" : "classify", n / 8);
    for (std::size_t k = 0; k < 8; ++k) std::printf(" %g: %zu", offsets[k], decided[k]);
    std::printf("\n");
    EXPECT_GT(decided[7], n / 8 / 4);  // offset 1e-3
  }
}

TEST(Batch, FloatFilterNearBoundaries) {
  float_filter_near_boundaries<2>();
  float_filter_near_boundaries<3>();
}

TEST(Batch, IndependentOfThreadCount) {
  // Enough chunks (1024 pairs) for five threads: the scenario pairs repeated.
  const auto base = scenario_pairs<double, 3>(ellipsect::testing::cases(100));
  Pairs<double, 3> pairs;
  while (pairs.size() < 40000)
    for (std::size_t i = 0; i < base.size(); ++i)
      pairs.push_back(base.a(i), base.velocity_a(i), base.b(i), base.velocity_b(i), base.t_max(i));
  expect_batch_equals_scalar(pairs, 1);
  const std::size_t n = pairs.size();
  auto run = [&](int threads) {
    const BatchOptions options{.query = {}, .threads = threads};
    std::vector<Relation> relations(n);
    std::vector<Contact<double, 3>> contacts(n);
    classify(pairs, std::span<Relation>(relations), options);
    first_contact(pairs, std::span<Contact<double, 3>>(contacts), options);
    return std::pair(relations, contacts);
  };
  const auto [relations, contacts] = run(1);
  for (const int threads : {0, 2, 3, 5}) {
    SCOPED_TRACE(threads);
    const auto [r, c] = run(threads);
    EXPECT_EQ(r, relations);
    for (std::size_t i = 0; i < n; ++i) expect_same(c[i], contacts[i], i);
  }
}

// Calls from several threads at once: one holds the worker pool, the others run alone;
// every answer is the one-thread answer. A forked child runs without the pool.
TEST(Batch, ConcurrentCallsAndForkedChild) {
  const auto base = scenario_pairs<double, 3>(ellipsect::testing::cases(20));
  Pairs<double, 3> pairs;
  while (pairs.size() < 20000)
    for (std::size_t i = 0; i < base.size(); ++i) pairs.push_back(base.a(i), base.b(i));
  const std::size_t n = pairs.size();
  auto run = [&](int threads) {
    std::vector<Relation> relations(n);
    classify(pairs, std::span<Relation>(relations), {.query = {}, .threads = threads});
    return relations;
  };
  const auto expected = run(1);
  std::vector<std::vector<Relation>> got(4);
  {
    std::vector<std::jthread> callers;
    for (auto& g : got) callers.emplace_back([&] { g = run(0); });
  }
  for (const auto& g : got) EXPECT_EQ(g, expected);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) _exit(run(0) == expected ? 0 : 1);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

// `per_category` cases of every scenario category as arrays: pair i is (a[i], b[i]).
struct CaseArrays {
  std::vector<Ellipsoid<double, 3>> a, b;
  std::vector<Vec3<double>> va, vb;
  std::vector<double> t_max;

  CaseArrays(int per_category, std::uint64_t seed) {
    for (const auto category : scenarios::all_categories)
      for (int i = 0; i < per_category; ++i) {
        const auto c = scenarios::make_case<3>(category, seed + std::uint64_t(i));
        a.push_back(c.a);
        b.push_back(c.b);
        va.push_back(c.va);
        vb.push_back(c.vb);
        t_max.push_back(c.t_max);
      }
  }
};

// The span overloads pack each chunk's columns on the thread that filters it: more than
// two chunks of 1024, on two threads, every category (rescaled and long double pairs too).
TEST(Batch, ArrayOfStructsEntryPoints) {
  const CaseArrays cases(220, 100);
  const auto& [a, b, va, vb, t_max] = cases;
  const std::size_t n = a.size();
  const auto overlaps = std::make_unique<bool[]>(n);
  std::vector<Relation> relations(n);
  std::vector<Contact<double, 3>> contacts(n);
  const BatchOptions two_threads{.query = {}, .threads = 2};
  overlap<double, 3>(a, b, std::span<bool>(overlaps.get(), n), two_threads);
  classify<double, 3>(a, b, relations, two_threads);
  first_contact<double, 3>(a, va, b, vb, t_max, contacts, two_threads);
  ASSERT_GT(n, 2 * 1024u);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(overlaps[i], overlap(a[i], b[i]));
    EXPECT_EQ(relations[i], classify(a[i], b[i]));
    expect_same(contacts[i], first_contact(a[i], va[i], b[i], vb[i], t_max[i]), i);
  }
}

// Pairs::assign stores what push_back stores, bit for bit (NaN radii of rescaled and long
// double pairs too), on every thread count, and replaces what was there.
TEST(Batch, AssignEqualsPushBack) {
  const CaseArrays cases(900, 300);  // 9000 pairs: enough for every thread to take a share
  const auto& [a, b, va, vb, t_max] = cases;
  Pairs<double, 3> pushed;
  for (std::size_t i = 0; i < a.size(); ++i) pushed.push_back(a[i], va[i], b[i], vb[i], t_max[i]);
  const auto expect_equal = [&](const Pairs<double, 3>& p) {
    ASSERT_EQ(p.size(), pushed.size());
    std::size_t differ = 0;
    for (int k = 0; k < Pairs<double, 3>::columns; ++k)
      for (std::size_t i = 0; i < p.size(); ++i) differ += !same_bits(p.column(k)[i], pushed.column(k)[i]);
    for (std::size_t i = 0; i < p.size(); ++i)
      differ += std::memcmp(&p.a(i), &pushed.a(i), sizeof(p.a(i))) != 0 ||
                std::memcmp(&p.b(i), &pushed.b(i), sizeof(p.b(i))) != 0;
    EXPECT_EQ(differ, 0u);
  };
  for (const int threads : {1, 2, 0}) {
    Pairs<double, 3> assigned;
    assigned.push_back(b[0], a[0]);  // replaced
    assigned.assign(a, va, b, vb, t_max, threads);
    expect_equal(assigned);
  }
  Pairs<double, 3> still, pushed_still;
  still.assign(a, b);
  for (std::size_t i = 0; i < a.size(); ++i) pushed_still.push_back(a[i], b[i]);
  pushed = pushed_still;
  expect_equal(still);
  EXPECT_THROW(still.assign(std::span(a), std::span(b).first(3)), std::invalid_argument);
  EXPECT_THROW(still.assign(a, va, b, std::span(vb).first(3), t_max), std::invalid_argument);
}

TEST(Batch, InvalidMotionIsReportedPerPair) {
  const auto a = make_ball<double, 3>({0, 0, 0}, 1), b = make_ball<double, 3>({5, 0, 0}, 1);
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  Pairs<double, 3> pairs;
  pairs.push_back(a, {inf, 0, 0}, b, {0, 0, 0}, 1);   // velocity not finite
  pairs.push_back(a, {0, 0, 0}, b, {0, nan, 0}, 1);   // velocity not finite
  pairs.push_back(a, {0, 0, 0}, b, {-1, 0, 0}, -1);   // negative window
  pairs.push_back(a, {0, 0, 0}, b, {-1, 0, 0}, nan);  // NaN window
  pairs.push_back(a, {0, 0, 0}, b, {-1, 0, 0}, 10);   // valid: hit at t = 3
  std::vector<Contact<double, 3>> out(pairs.size());
  first_contact(pairs, std::span<Contact<double, 3>>(out));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(out[std::size_t(i)].status, ContactStatus::invalid_input) << i;
  EXPECT_EQ(out[4].status, ContactStatus::hit);
  EXPECT_NEAR(out[4].time, 3.0, 1e-12);
}

TEST(Batch, SizesAndTargetsAreChecked) {
  Pairs<double, 2> pairs;
  std::vector<Relation> none;
  classify(pairs, std::span<Relation>(none));  // empty batch: nothing to do
  pairs.push_back(make_ball<double, 2>({0, 0}, 1), make_ball<double, 2>({1, 0}, 1));
  EXPECT_THROW(classify(pairs, std::span<Relation>(none)), std::invalid_argument);
  try {
    set_simd_target("NO_SUCH_TARGET");
    FAIL() << "an unknown instruction set was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "simd_target");
  }
  ASSERT_FALSE(simd_targets().empty());
  EXPECT_EQ(simd_target(), simd_targets().front());
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
