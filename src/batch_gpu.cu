// The certificate filter on a CUDA GPU (detail/batch_gpu.hpp): one pair per thread, the
// scalar code of detail/certificates-inl.hpp compiled for the device. Built with
// --fmad=false, and nvcc's default correctly rounded division and square root, so that a
// thread runs the IEEE operations the host runs, in the same order.
#include "detail/batch_gpu.hpp"
#include "detail/certificates-inl.hpp"

#include <cuda_runtime.h>

#include <algorithm>
#include <array>

namespace ellipsect::detail {

namespace {

constexpr std::size_t pairs_per_round = std::size_t(1) << 22;  // bounds the device memory: ~0.75 GB (classify, 3D)
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

// Device memory freed on every path out.
struct DeviceBuffer {
  void* data = nullptr;
  ~DeviceBuffer() {
    if (data) cudaFree(data);
  }
};

template <int N>
bool certify_on_device(BatchQuery query, const double* const* columns, std::size_t n, double tol,
                       signed char* codes) noexcept {
  constexpr BodyLayout layout = DeviceColumns<N>::body;
  const bool quadric = query == BatchQuery::classify;
  std::array<int, 2 * layout.size()> used{};  // body columns the query reads, in order
  std::size_t n_used = 0;
  for (int k = 0; k < 2 * layout.size(); ++k) {
    const int within = k % layout.size();
    if (quadric || within < layout.m(0, 0) || within >= layout.rmax()) used[n_used++] = k;
  }
  const std::size_t round = std::min(n, pairs_per_round);
  DeviceBuffer buffer;
  const std::size_t values = n_used * round;
  if (cudaMalloc(&buffer.data, values * sizeof(double) + round) != cudaSuccess) return false;
  double* const device_columns = static_cast<double*>(buffer.data);
  signed char* const device_codes = reinterpret_cast<signed char*>(device_columns + values);
  for (std::size_t begin = 0; begin < n; begin += round) {
    const std::size_t count = std::min(round, n - begin);
    DeviceColumns<N> src{};
    for (std::size_t u = 0; u < n_used; ++u) {
      double* const to = device_columns + u * round;
      if (cudaMemcpy(to, columns[used[u]] + begin, count * sizeof(double), cudaMemcpyHostToDevice) != cudaSuccess)
        return false;
      src.column[used[u]] = to;
    }
    const unsigned blocks = unsigned((count + threads_per_block - 1) / threads_per_block);
    if (quadric) {
      certify_kernel<N, true><<<blocks, threads_per_block>>>(src, count, tol, device_codes);
    } else {
      certify_kernel<N, false><<<blocks, threads_per_block>>>(src, count, tol, device_codes);
    }
    if (cudaGetLastError() != cudaSuccess) return false;
    if (cudaMemcpy(codes + begin, device_codes, count, cudaMemcpyDeviceToHost) != cudaSuccess) return false;
  }
  return true;
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
                       signed char* codes) noexcept {
  int count = 0;
  if (query == BatchQuery::contact || cudaGetDeviceCount(&count) != cudaSuccess || count == 0) return false;
  if (n == 0) return true;
  return dim == 2 ? certify_on_device<2>(query, columns, n, tol, codes)
                  : certify_on_device<3>(query, columns, n, tol, codes);
}

}  // namespace ellipsect::detail
