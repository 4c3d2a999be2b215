// Batch overlap and classify on a CUDA GPU: the certificate filter of batch.hpp run one
// pair per GPU thread, the pairs it leaves open answered by the scalar functions on the
// host's threads.
//
// Contract: out[i] equals batch.hpp's answer (and so the scalar function's) for pair i, on
// the GPU or not. The filter's code on the device is the scalar code of
// detail/certificates-inl.hpp, compiled without fused multiply-adds and with correctly
// rounded division and square root, so a certified answer is the one the exact path gives;
// undecided pairs take that path. Where the library was built without CUDA (CMake option
// ELLIPSECT_CUDA: AUTO builds it where a CUDA compiler is found, not in sanitized builds),
// no device is present, or a CUDA call fails (device memory), the filter runs on the CPU as
// in batch.hpp, and the returned Backend says which one answered. Pairs go to the device in
// rounds of 4M (about 0.75 GB of device memory for classify in 3D).
#pragma once

#include <ellipsect/batch.hpp>

#include <span>
#include <string>
#include <string_view>

namespace ellipsect {

struct GpuInfo {
  bool built = false;  // the library holds the CUDA path
  int devices = 0;     // CUDA devices present (0 also where there is no driver)
  std::string name;    // the current device's name, "" where none
};
GpuInfo gpu_info();

enum class Backend { gpu, cpu };
std::string_view to_string(Backend b) noexcept;

// out.size() must equal pairs.size() (std::invalid_argument otherwise).
template <class T, int N>
Backend overlap_on_gpu(const Pairs<T, N>& pairs, std::span<bool> out, const BatchOptions& options = {});
template <class T, int N>
Backend classify_on_gpu(const Pairs<T, N>& pairs, std::span<Relation> out, const BatchOptions& options = {});

}  // namespace ellipsect
