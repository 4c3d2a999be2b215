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
// in batch.hpp, and the returned Backend says which one answered. Pairs<float, N> are
// always filtered on the CPU (batch.hpp's float filter; the device runs the double one).
//
// Pairs go to the device in rounds of 2^17, packed by the batch's threads into page-locked
// buffers while the previous round is copied and filtered. The buffers (two rounds: 71 MB of
// page-locked host memory and as much device memory) are made at the first call, on the
// device current then, and kept until the process ends; one call at a time uses them
// (concurrent calls wait). Speed: the columns must cross the bus, 176 bytes per 3D overlap
// pair; on the H100 host measured (PCIe 5, 16 cores) that caps the path below what all 16
// cores answer on the CPU (bench/RESULTS.md, "GPU path"), while the device's filter alone
// runs at about 8 G pairs per second.
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
