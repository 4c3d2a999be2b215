// The worker pool (include/ellipsect/parallel.hpp): every index once on any thread count,
// the first exception on the caller, nested calls and concurrent callers.
#include <ellipsect/parallel.hpp>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <stdexcept>
#include <thread>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using ellipsect::parallel_for;

std::vector<int> visits(std::size_t count, int threads) {
  std::vector<std::atomic<int>> seen(count);
  parallel_for(count, threads, [&](std::size_t k) { seen[k].fetch_add(1); });
  std::vector<int> out(count);
  for (std::size_t k = 0; k < count; ++k) out[k] = seen[k].load();
  return out;
}

TEST(Parallel, EveryIndexOnceOnAnyThreadCount) {
  for (const std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(10000)})
    for (const int threads : {0, 1, 2, 3, 64}) {
      const std::vector<int> v = visits(count, threads);
      for (std::size_t k = 0; k < count; ++k) ASSERT_EQ(v[k], 1) << "count " << count << ", threads " << threads;
    }
}

TEST(Parallel, FirstExceptionReachesTheCallerAndStopsTheRest) {
  std::atomic<std::size_t> ran{0};
  std::atomic<bool> thrown{false};
  std::atomic<int> graced{0};
  const std::size_t count = 100000;
  EXPECT_THROW(parallel_for(count, 0,
                            [&](std::size_t k) {
                              ran.fetch_add(1);
                              if (k == 10) {
                                thrown = true;
                                throw std::runtime_error("body 10");
                              }
                              // Beyond the first chunks, wait for the throw (at most 10 s): a
                              // loaded machine may not run index 10's worker before the others
                              // would have taken every index.
                              const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
                              while (k > 1000 && !thrown && std::chrono::steady_clock::now() < until)
                                std::this_thread::yield();
                              // The handing out stops in the pool's handler, after the throw
                              // unwinds: the first bodies past it give the throwing thread 50 ms
                              // to get there (on a loaded machine the others ran every index
                              // in between).
                              if (k > 1000 && graced.fetch_add(1) < 8)
                                std::this_thread::sleep_for(std::chrono::milliseconds(50));
                            }),
               std::runtime_error);
  EXPECT_LT(ran.load(), count);  // the handing out stopped
  // The pool serves the next call as before.
  const std::vector<int> v = visits(5000, 0);
  for (const int x : v) ASSERT_EQ(x, 1);
  // On the caller alone too.
  EXPECT_THROW(parallel_for(3, 1, [](std::size_t k) {
                 if (k == 2) throw std::invalid_argument("body 2");
               }),
               std::invalid_argument);
}

TEST(Parallel, NestedCallsRunOnTheirCaller) {
  const std::size_t outer = 64, inner = 100;
  std::vector<std::atomic<int>> seen(outer * inner);
  parallel_for(outer, 0, [&](std::size_t i) {
    parallel_for(inner, 0, [&](std::size_t j) { seen[i * inner + j].fetch_add(1); });
  });
  for (const auto& s : seen) ASSERT_EQ(s.load(), 1);
}

TEST(Parallel, ConcurrentCallersEachGetEveryIndex) {
  constexpr int callers = 4;
  std::vector<std::vector<int>> results(callers);
  std::vector<std::thread> threads;
  for (int c = 0; c < callers; ++c) threads.emplace_back([&, c] { results[c] = visits(20000, 0); });
  for (auto& t : threads) t.join();
  for (const auto& v : results)
    for (const int x : v) ASSERT_EQ(x, 1);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
