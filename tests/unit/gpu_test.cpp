// The GPU entry points (gpu.hpp) answer as the scalar functions do, pair for pair, on every
// scenario category, on the GPU where one is present and on the CPU path where not; and
// they say which one answered.
#include <ellipsect/gpu.hpp>

#include "tests/unit/scenario_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using ellipsect::testing::scenario_pairs;

// The backend a call must report: the GPU exactly where the library holds the CUDA path,
// a device is present and the pairs are double (float pairs are filtered on the CPU).
template <class T>
Backend expected_backend() {
  const GpuInfo info = gpu_info();
  return info.built && info.devices > 0 && std::is_same_v<T, double> ? Backend::gpu : Backend::cpu;
}

template <class T, int N>
void expect_equals_scalar(int per_category) {
  const Pairs<T, N> pairs = scenario_pairs<T, N>(per_category, 9100);
  const std::size_t n = pairs.size();
  const auto overlaps = std::make_unique<bool[]>(n);
  const auto relations = std::make_unique<Relation[]>(n);
  EXPECT_EQ(overlap_on_gpu(pairs, std::span<bool>(overlaps.get(), n)), expected_backend<T>());
  EXPECT_EQ(classify_on_gpu(pairs, std::span<Relation>(relations.get(), n)), expected_backend<T>());
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(overlaps[i], overlap(pairs.a(i), pairs.b(i))) << "pair " << i;
    EXPECT_EQ(relations[i], classify(pairs.a(i), pairs.b(i))) << "pair " << i;
  }
}

TEST(Gpu, InfoIsConsistent) {
  const GpuInfo info = gpu_info();
  if (!info.built) {
    EXPECT_EQ(info.devices, 0);
  }
  if (info.devices == 0) {
    EXPECT_EQ(info.name, "");
  }
  EXPECT_GE(info.devices, 0);
  EXPECT_EQ(to_string(Backend::gpu), "gpu");
  EXPECT_EQ(to_string(Backend::cpu), "cpu");
}

TEST(Gpu, EqualsScalar3D) { expect_equals_scalar<double, 3>(40); }
TEST(Gpu, EqualsScalar2D) { expect_equals_scalar<double, 2>(40); }
TEST(Gpu, EqualsScalarInFloat) { expect_equals_scalar<float, 3>(20); }

// More pairs than one round on the device (gpu.hpp: rounds of 2^17 pairs; here 2.5
// rounds, the last one partial): every round's answers land on their own pairs.
TEST(Gpu, SeveralRoundsEqualTheCpuBatch) {
  const Pairs<double, 3> scenarios = scenario_pairs<double, 3>(20, 9200);
  Pairs<double, 3> pairs;
  const std::size_t n = (std::size_t(5) << 17) / 2 + 7;
  pairs.reserve(n);
  for (std::size_t i = 0; i < n; ++i)  // a and b from different scenarios too
    pairs.push_back(scenarios.a(i % scenarios.size()), scenarios.b((i * 7) % scenarios.size()));
  const auto gpu_overlaps = std::make_unique<bool[]>(n), cpu_overlaps = std::make_unique<bool[]>(n);
  std::vector<Relation> gpu_relations(n), cpu_relations(n);
  EXPECT_EQ(overlap_on_gpu(pairs, std::span<bool>(gpu_overlaps.get(), n)), expected_backend<double>());
  EXPECT_EQ(classify_on_gpu(pairs, std::span<Relation>(gpu_relations)), expected_backend<double>());
  overlap(pairs, std::span<bool>(cpu_overlaps.get(), n));  // batch.hpp, the CPU filter
  classify(pairs, std::span<Relation>(cpu_relations));
  std::size_t overlap_differ = 0, classify_differ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    overlap_differ += gpu_overlaps[i] != cpu_overlaps[i];
    classify_differ += gpu_relations[i] != cpu_relations[i];
  }
  EXPECT_EQ(overlap_differ, 0u);
  EXPECT_EQ(classify_differ, 0u);
  const auto hits = std::count(cpu_overlaps.get(), cpu_overlaps.get() + n, true);
  EXPECT_GT(hits, 0);  // both answers occur
  EXPECT_LT(hits, std::ptrdiff_t(n));
}

TEST(Gpu, EmptyAndMismatchedSizes) {
  const Pairs<double, 3> none;
  EXPECT_EQ(overlap_on_gpu(none, std::span<bool>()), expected_backend<double>());
  const Pairs<double, 3> some = scenario_pairs<double, 3>(1, 9100);  // one per category
  bool out[1];
  Relation rel[1];
  EXPECT_THROW(overlap_on_gpu(some, std::span<bool>(out, 1)), std::invalid_argument);
  EXPECT_THROW(classify_on_gpu(some, std::span<Relation>(rel, 1)), std::invalid_argument);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
