// How the columns of a batch reach a CUDA device: the cost that bounds overlap_on_gpu and
// classify_on_gpu for pairs held on the host (gpu.hpp, docs/batch.md "On a GPU"). Built
// only with the CUDA path (bench/CMakeLists.txt). One round: the 22 columns of 3D overlap
// (double) for `pairs` pairs, 176 bytes per pair.
//
// BM_transfer/pageable_copy/P       cudaMemcpy of each column from ordinary memory
// BM_transfer/register_copy/P       cudaHostRegister each column, copy, cudaHostUnregister
// BM_transfer/pinned_copy/P         cudaMemcpyAsync of each column from page-locked memory
// BM_transfer/pack/P/threads:T      T threads copying the columns into page-locked memory
//                                   (what the GPU path does before its page-locked copy)
// Counters: bytes_per_second, items_per_second (pairs).
#include <benchmark/benchmark.h>
#include <cuda_runtime.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr int columns = 22;

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw std::runtime_error(std::string(what) + ": " + cudaGetErrorString(e));
}

// The host's columns, a device buffer and a page-locked buffer for `pairs` pairs.
struct Buffers {
  std::size_t pairs;
  std::vector<std::vector<double>> host;
  double* device = nullptr;
  double* pinned = nullptr;

  explicit Buffers(std::size_t n) : pairs(n), host(columns, std::vector<double>(n)) {
    for (int c = 0; c < columns; ++c)
      for (std::size_t i = 0; i < n; ++i) host[c][i] = c + 1e-3 * double(i);
    check(cudaMalloc(&device, bytes()), "cudaMalloc");
    check(cudaMallocHost(&pinned, bytes()), "cudaMallocHost");
  }
  ~Buffers() {
    cudaFree(device);
    cudaFreeHost(pinned);
  }
  std::size_t bytes() const { return columns * pairs * sizeof(double); }
  double* to(int c) const { return device + c * pairs; }
};

void count(benchmark::State& state, const Buffers& b) {
  state.SetBytesProcessed(std::int64_t(state.iterations() * b.bytes()));
  state.SetItemsProcessed(std::int64_t(state.iterations() * b.pairs));
}

void pageable_copy(benchmark::State& state) {
  Buffers b(std::size_t(state.range(0)));
  for (auto _ : state)
    for (int c = 0; c < columns; ++c)
      check(cudaMemcpy(b.to(c), b.host[c].data(), b.pairs * sizeof(double), cudaMemcpyHostToDevice), "cudaMemcpy");
  count(state, b);
}

void register_copy(benchmark::State& state) {
  Buffers b(std::size_t(state.range(0)));
  for (auto _ : state) {
    for (auto& h : b.host) check(cudaHostRegister(h.data(), b.pairs * sizeof(double), 0), "cudaHostRegister");
    for (int c = 0; c < columns; ++c)
      check(cudaMemcpyAsync(b.to(c), b.host[c].data(), b.pairs * sizeof(double), cudaMemcpyHostToDevice),
            "cudaMemcpyAsync");
    check(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
    for (auto& h : b.host) check(cudaHostUnregister(h.data()), "cudaHostUnregister");
  }
  count(state, b);
}

void pinned_copy(benchmark::State& state) {
  Buffers b(std::size_t(state.range(0)));
  for (auto _ : state) {
    check(cudaMemcpyAsync(b.device, b.pinned, b.bytes(), cudaMemcpyHostToDevice), "cudaMemcpyAsync");
    check(cudaDeviceSynchronize(), "cudaDeviceSynchronize");
  }
  count(state, b);
}

void pack(benchmark::State& state) {
  Buffers b(std::size_t(state.range(0)));
  const int threads = int(state.range(1));
  for (auto _ : state) {
    std::vector<std::thread> team;
    for (int t = 0; t < threads; ++t)
      team.emplace_back([&b, t, threads] {
        const std::size_t from = b.pairs * t / threads, to = b.pairs * (t + 1) / threads;
        for (int c = 0; c < columns; ++c)
          std::memcpy(b.pinned + c * b.pairs + from, b.host[c].data() + from, (to - from) * sizeof(double));
      });
    for (auto& t : team) t.join();
  }
  count(state, b);
}

}  // namespace

int main(int argc, char** argv) {
  int devices = 0;
  if (cudaGetDeviceCount(&devices) != cudaSuccess || devices == 0) {
    std::fprintf(stderr, "bench_gpu_transfer: no CUDA device\n");
    return 0;
  }
  for (std::int64_t pairs : {std::int64_t(1) << 17, std::int64_t(1) << 20}) {
    benchmark::RegisterBenchmark("BM_transfer/pageable_copy", pageable_copy)->Arg(pairs)->UseRealTime();
    benchmark::RegisterBenchmark("BM_transfer/register_copy", register_copy)->Arg(pairs)->UseRealTime();
    benchmark::RegisterBenchmark("BM_transfer/pinned_copy", pinned_copy)->Arg(pairs)->UseRealTime();
    for (int threads : {1, 2, 4, 8, 16})
      benchmark::RegisterBenchmark("BM_transfer/pack", pack)
          ->Args({pairs, threads})
          ->ArgNames({"", "threads"})
          ->UseRealTime();
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
