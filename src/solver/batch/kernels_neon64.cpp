// The arm64 kernels (two lanes a register; see attempt_kernel.hpp). Advanced SIMD is part
// of every arm64 CPU: no run-time check is needed.
#include "attempt_kernel.hpp"

namespace pcrf::detail::batch {
#if defined(__aarch64__)
KernelSet neon64_kernels() {
#ifdef PCRF_HAVE_SLEEF
  using Batch = xsimd::batch<double, xsimd::neon64>;
  // Exact: SLEEF's deterministic (cinz) function of this width; fast: its 1-ulp one.
  return vector_kernels<xsimd::neon64, SleefTrig<Batch, &Sleef_cinz_sincosd2_u35advsimdnofma>,
                        SleefTrig<Batch, &Sleef_sincosd2_u10advsimd>>("neon64");
#else
  return vector_kernels<xsimd::neon64>("neon64");
#endif
}
#else
KernelSet neon64_kernels() { return {}; }  // not an arm64 build
#endif
}  // namespace pcrf::detail::batch
