// The avx2 kernels (4 lanes a register; see attempt_kernel.hpp). Compiled with this
// instruction set's flags; run only where the CPU has it (choose_kernels).
#include "attempt_kernel.hpp"

namespace pcrf::detail::batch {
#if defined(__x86_64__) || defined(__i386__)
KernelSet avx2_kernels() {
  using Arch = xsimd::fma3<xsimd::avx2>;
#ifdef PCRF_HAVE_SLEEF
  return vector_kernels<Arch, SleefTrig<xsimd::batch<double, Arch>, &Sleef_sincosd4_u10avx2>>("avx2");
#else
  return vector_kernels<Arch>("avx2");
#endif
}
#else
KernelSet avx2_kernels() { return {}; }  // not an x86 build
#endif
}  // namespace pcrf::detail::batch
