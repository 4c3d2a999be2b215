// The certificate filter on a CUDA GPU (batch_gpu.cu), behind include/ellipsect/gpu.hpp.
// Built where CMake finds a CUDA compiler (ELLIPSECT_CUDA); elsewhere these report that no
// GPU is there and the batch functions filter on the CPU.
#pragma once

#include "batch_kernels.hpp"

#include <cstddef>
#include <functional>
#include <string>

namespace ellipsect::detail {

struct GpuDevice {
  int count = 0;     // CUDA devices present
  std::string name;  // the current device's name
};

// parallel_for(n, work) calls work(begin, end) on pieces covering [0, n), on the batch's threads.
using ParallelFor = std::function<void(std::size_t, const std::function<void(std::size_t, std::size_t)>&)>;

#ifdef ELLIPSECT_CUDA
inline constexpr bool gpu_built = true;
GpuDevice gpu_device();
// codes[i] = the certificate code of pair i of [0, n), columns laid out as in Pairs<T, dim>,
// computed on the current CUDA device with the scalar code's operations; parallel_for packs
// the columns into page-locked memory. False where no device is present or a CUDA call
// fails; codes may then hold anything. One call at a time per process uses the device (a
// second waits).
bool certify_pairs_gpu(int dim, BatchQuery query, const double* const* columns, std::size_t n, double tol,
                       signed char* codes, const ParallelFor& parallel_for);
#else
inline constexpr bool gpu_built = false;
inline GpuDevice gpu_device() { return {}; }
inline bool certify_pairs_gpu(int, BatchQuery, const double* const*, std::size_t, double, signed char*,
                              const ParallelFor&) {
  return false;
}
#endif

}  // namespace ellipsect::detail
