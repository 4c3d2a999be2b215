// The core's double-precision arithmetic peak for the operation mix of the batch filter
// (separate multiplies and adds: the filter is built without FMA contraction so that its
// lanes round as the scalar code), and the throughput of division, per vector width. bench/RESULTS.md compares the batch figures against these.
//
// Each loop keeps 6 independent chains of multiplies and 6 of adds in flight (at least
// latency x pipes on current x86 cores, and 14 registers: no spills even with AVX2's 16),
// and 8 chains of divisions, so the time is throughput, not latency. Rates: `flops`,
// double operations per second on one core.
#include <benchmark/benchmark.h>

namespace {

typedef double Vec64 __attribute__((vector_size(64)));
typedef double Vec32 __attribute__((vector_size(32)));
typedef double Vec16 __attribute__((vector_size(16)));

#define ELLIPSECT_PEAK_KERNELS(TARGET, BYTES, SUFFIX)                                              \
  __attribute__((target(TARGET), noinline)) void mul_add_##SUFFIX(benchmark::State& state) {      \
    Vec##BYTES m, c, x[6], y[6];                                                                  \
    for (int k = 0; k < (BYTES / 8); ++k) m[k] = 1.0, c[k] = 0.5;                               \
    benchmark::DoNotOptimize(m); /* opaque: no folding of x * 1 */                              \
    benchmark::DoNotOptimize(c);                                                                  \
    for (int i = 0; i < 6; ++i) x[i] = m * double(i), y[i] = c * double(i);                       \
    for (auto _ : state) {                                                                        \
      for (int r = 0; r < 64; ++r)                                                                \
        for (int i = 0; i < 6; ++i) x[i] = x[i] * m, y[i] = y[i] + c;                             \
      benchmark::DoNotOptimize(x);                                                                \
      benchmark::DoNotOptimize(y);                                                                \
    }                                                                                             \
    state.counters["flops"] = benchmark::Counter(double(state.iterations()) * 64 * 12 * (BYTES / 8), \
                                                 benchmark::Counter::kIsRate);                    \
  }                                                                                               \
  __attribute__((target(TARGET), noinline)) void div_##SUFFIX(benchmark::State& state) {          \
    Vec##BYTES one, x[8];                                                                         \
    for (int k = 0; k < (BYTES / 8); ++k) one[k] = 1.0;                                          \
    benchmark::DoNotOptimize(one);                                                                \
    for (int i = 0; i < 8; ++i) x[i] = one * (2.0 + i);                                           \
    for (auto _ : state) {                                                                        \
      for (int r = 0; r < 16; ++r)                                                                \
        for (int i = 0; i < 8; ++i) x[i] = (one * 3.0) / x[i];                                    \
      benchmark::DoNotOptimize(x);                                                                \
    }                                                                                             \
    state.counters["flops"] = benchmark::Counter(double(state.iterations()) * 16 * 8 * (BYTES / 8), \
                                                 benchmark::Counter::kIsRate);                    \
  }

ELLIPSECT_PEAK_KERNELS("avx512f", 64, avx512)
ELLIPSECT_PEAK_KERNELS("avx2", 32, avx2)
ELLIPSECT_PEAK_KERNELS("sse2", 16, sse2)
#undef ELLIPSECT_PEAK_KERNELS

BENCHMARK(mul_add_avx512);
BENCHMARK(mul_add_avx2);
BENCHMARK(mul_add_sse2);
BENCHMARK(div_avx512);
BENCHMARK(div_avx2);
BENCHMARK(div_sse2);

}  // namespace

BENCHMARK_MAIN();
