// The sse2 kernels (2 lanes a register; see attempt_kernel.hpp). Compiled with this
// instruction set's flags; run only where the CPU has it (choose_kernels).
#include "attempt_kernel.hpp"

namespace pcrf::detail::batch {
#if defined(__x86_64__) || defined(__i386__)
KernelSet sse2_kernels() {
  using Arch = xsimd::sse2;
#ifdef PCRF_HAVE_SLEEF
  return vector_kernels<Arch, SleefTrig<xsimd::batch<double, Arch>, &Sleef_sincosd2_u10sse2>>("sse2");
#else
  return vector_kernels<Arch>("sse2");
#endif
}
#else
KernelSet sse2_kernels() { return {}; }  // not an x86 build
#endif
}  // namespace pcrf::detail::batch
