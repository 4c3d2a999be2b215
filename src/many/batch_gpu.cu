// The certificate filter on a CUDA GPU (detail/batch_gpu.hpp): one pair per thread, the
// scalar code of detail/certificates-inl.hpp compiled for the device. Built with
// --fmad=false, and nvcc's default correctly rounded division and square root, so that a
// thread runs the IEEE operations the host runs, in the same order.
#include "detail/batch_gpu.hpp"
#include "detail/certificates-inl.hpp"

#include <cuda_runtime.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <mutex>

namespace ellipsect::detail {

namespace {

// Pairs go to the device in rounds, through page-locked staging slots: while round k is
// copied to the device and filtered there, the host's threads pack round k + 1 into the
// other slot (a copy from pageable memory runs at about a seventh of the bus's rate: 6.7
// against 49.6 GB/s on the H100 host measured, bench/RESULTS.md "GPU path").
constexpr std::size_t pairs_per_round = std::size_t(1) << 17;  // 35.7 MB of pinned columns per slot (classify, 3D)
constexpr int slots = 2;
constexpr int threads_per_block = 128;

// The columns the query reads, as device pointers (null for those it does not read).
template <int N>
struct DeviceColumns {
  static constexpr BodyLayout body{N};
  const double* column[2 * body.size()];
};

template <int N>
__device__ cuda::BodyLanes<double, N> load_body(const DeviceColumns<N>& src, int first, std::size_t i,
                                                bool quadric) {
  constexpr BodyLayout layout = DeviceColumns<N>::body;
  cuda::BodyLanes<double, N> b;
  for (int r = 0; r < N; ++r) {
    b.c[r] = src.column[first + layout.center(r)][i];
    for (int c = r; c < N; ++c) {
      b.s[r][c] = b.s[c][r] = src.column[first + layout.s(r, c)][i];
      if (quadric) b.m[r][c] = b.m[c][r] = src.column[first + layout.m(r, c)][i];
    }
  }
  b.rmax = src.column[first + layout.rmax()][i];
  b.rmin = src.column[first + layout.rmin()][i];
  return b;
}

template <int N, bool containment>
__global__ void certify_kernel(DeviceColumns<N> src, std::size_t n, double tol, signed char* codes) {
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= n) return;
  constexpr int body = DeviceColumns<N>::body.size();
  const auto a = load_body<N>(src, 0, i, containment), b = load_body<N>(src, body, i, containment);
  codes[i] = static_cast<signed char>(cuda::certify<double, N, containment>(a, b, tol));
}

constexpr std::size_t max_columns = 2 * BodyLayout{3}.size();
constexpr std::size_t slot_bytes = pairs_per_round * (max_columns * sizeof(double) + 1);

// The staging slots and the device's buffers, made on first use and kept for the process
// (making page-locked memory costs about as much as copying it); one call uses them at a
// time. A slot holds a round's columns, each `count` doubles long, then its `count` codes.
struct Staging {
  std::mutex busy;
  bool ready = false;
  unsigned char* host[slots]{};    // page-locked
  unsigned char* device[slots]{};
  cudaStream_t stream[slots]{};

  bool make() {
    if (ready) return true;
    for (int s = 0; s < slots; ++s) {
      if (!host[s] && cudaMallocHost(&host[s], slot_bytes) != cudaSuccess) return false;
      if (!device[s] && cudaMalloc(&device[s], slot_bytes) != cudaSuccess) return false;
      if (!stream[s] && cudaStreamCreateWithFlags(&stream[s], cudaStreamNonBlocking) != cudaSuccess) return false;
    }
    return ready = true;
  }
  static Staging& get() {
    static Staging* const staging = new Staging();  // never destroyed: the CUDA runtime may be gone at exit
    return *staging;
  }
};

template <int N>
bool certify_on_device(BatchQuery query, const double* const* columns, std::size_t n, double tol,
                       signed char* codes, const ParallelFor& parallel_for) {
  constexpr BodyLayout layout = DeviceColumns<N>::body;
  const bool quadric = query == BatchQuery::classify;
  std::array<int, 2 * layout.size()> used{};  // body columns the query reads, in order
  std::size_t n_used = 0;
  for (int k = 0; k < 2 * layout.size(); ++k) {
    const int within = k % layout.size();
    if (quadric || within < layout.m(0, 0) || within >= layout.rmax()) used[n_used++] = k;
  }
  Staging& staging = Staging::get();
  const std::lock_guard lock(staging.busy);
  if (!staging.make()) return false;
  for (cudaStream_t stream : staging.stream)  // a call that threw may have left copies in flight
    if (cudaStreamSynchronize(stream) != cudaSuccess) return false;
  const std::size_t rounds = (n + pairs_per_round - 1) / pairs_per_round;
  const auto first = [&](std::size_t k) { return k * pairs_per_round; };
  const auto size = [&](std::size_t k) { return std::min(pairs_per_round, n - first(k)); };
  // Waits for round k's slot and copies its codes out.
  const auto collect = [&](std::size_t k) {
    const int s = int(k % slots);
    if (cudaStreamSynchronize(staging.stream[s]) != cudaSuccess) return false;
    std::memcpy(codes + first(k), staging.host[s] + n_used * size(k) * sizeof(double), size(k));
    return true;
  };
  bool ok = true;
  std::size_t k = 0;
  for (; k < rounds && ok; ++k) {
    const int s = int(k % slots);
    if (k >= slots && !(ok = collect(k - slots))) break;
    const std::size_t begin = first(k), count = size(k), values = n_used * count;
    double* const host = reinterpret_cast<double*>(staging.host[s]);
    parallel_for(count, [&](std::size_t from, std::size_t to) {
      for (std::size_t u = 0; u < n_used; ++u)
        std::memcpy(host + u * count + from, columns[used[u]] + begin + from, (to - from) * sizeof(double));
    });
    double* const device = reinterpret_cast<double*>(staging.device[s]);
    signed char* const device_codes = reinterpret_cast<signed char*>(device + values);
    DeviceColumns<N> src{};
    for (std::size_t u = 0; u < n_used; ++u) src.column[used[u]] = device + u * count;
    const cudaStream_t stream = staging.stream[s];
    ok = cudaMemcpyAsync(device, host, values * sizeof(double), cudaMemcpyHostToDevice, stream) == cudaSuccess;
    const unsigned blocks = unsigned((count + threads_per_block - 1) / threads_per_block);
    if (ok && quadric)
      certify_kernel<N, true><<<blocks, threads_per_block, 0, stream>>>(src, count, tol, device_codes);
    if (ok && !quadric)
      certify_kernel<N, false><<<blocks, threads_per_block, 0, stream>>>(src, count, tol, device_codes);
    ok = ok && cudaGetLastError() == cudaSuccess &&
         cudaMemcpyAsync(host + values, device_codes, count, cudaMemcpyDeviceToHost, stream) == cudaSuccess;
  }
  // The rounds still in flight: collected, or at least waited for before the slots are reused.
  for (std::size_t j = k > slots ? k - slots : 0; j < k; ++j) ok = collect(j) && ok;
  return ok;
}

}  // namespace

GpuDevice gpu_device() {
  GpuDevice d;
  int current = 0;
  cudaDeviceProp properties;
  if (cudaGetDeviceCount(&d.count) != cudaSuccess) return {};
  if (d.count > 0 && cudaGetDevice(&current) == cudaSuccess &&
      cudaGetDeviceProperties(&properties, current) == cudaSuccess)
    d.name = properties.name;
  return d;
}

bool certify_pairs_gpu(int dim, BatchQuery query, const double* const* columns, std::size_t n, double tol,
                       signed char* codes, const ParallelFor& parallel_for) {
  int count = 0;
  if (query == BatchQuery::contact || cudaGetDeviceCount(&count) != cudaSuccess || count == 0) return false;
  if (n == 0) return true;
  return dim == 2 ? certify_on_device<2>(query, columns, n, tol, codes, parallel_for)
                  : certify_on_device<3>(query, columns, n, tol, codes, parallel_for);
}

}  // namespace ellipsect::detail
