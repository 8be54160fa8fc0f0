// The arm64 kernels (two lanes a register; see attempt_kernel.hpp). Advanced SIMD is part
// of every arm64 CPU: no run-time check is needed.
#if defined(__aarch64__)
#include <xsimd/xsimd.hpp>

#include "attempt_kernel.hpp"

namespace pcrf::detail::batch {
namespace {

using Batch = xsimd::batch<double, xsimd::neon64>;

struct XsimdTrig {
  static void sincos(const Batch& x, Batch& s, Batch& c) {
    auto sc = xsimd::sincos(x);
    s = sc.first, c = sc.second;
  }
};

}  // namespace

KernelSet neon64_kernels() {
  KernelSet k;
  k.name = "neon64";
  k.register_lanes = 2;
  k.libm_trig = &attempt_all<VectorPack<Batch, LibmTrig<Batch>>>;
  k.xsimd_trig = &attempt_all<VectorPack<Batch, XsimdTrig>>;
  return k;
}

}  // namespace pcrf::detail::batch
#else
#include "lane_arrays.hpp"
namespace pcrf::detail::batch {
KernelSet neon64_kernels() { return {}; }  // not an arm64 build
}  // namespace pcrf::detail::batch
#endif
