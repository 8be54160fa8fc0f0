// The avx2 kernels (4 lanes a register; see attempt_kernel.hpp). Compiled with this
// instruction set's flags; run only where the CPU has it (choose_kernels).
#include "attempt_kernel.hpp"

namespace pcrf::detail::batch {
#if defined(__x86_64__) || defined(__i386__)
KernelSet avx2_kernels() {
  using Arch = xsimd::fma3<xsimd::avx2>;
#ifdef PCRF_HAVE_SLEEF
  using Batch = xsimd::batch<double, Arch>;
  // Exact: SLEEF's deterministic (cinz) function of this width; fast: its 1-ulp one.
  return vector_kernels<Arch, SleefTrig<Batch, &Sleef_cinz_sincosd4_u35avx>, SleefTrig<Batch, &Sleef_sincosd4_u10avx2>>("avx2");
#else
  return vector_kernels<Arch>("avx2");
#endif
}
#else
KernelSet avx2_kernels() { return {}; }  // not an x86 build
#endif
}  // namespace pcrf::detail::batch
