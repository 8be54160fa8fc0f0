// The avx512f kernels (8 lanes a register; see attempt_kernel.hpp). Compiled with this
// instruction set's flags; run only where the CPU has it (choose_kernels).
#include "attempt_kernel.hpp"

namespace pcrf::detail::batch {
#if defined(__x86_64__) || defined(__i386__)
KernelSet avx512_kernels() {
  using Arch = xsimd::avx512f;
#ifdef PCRF_HAVE_SLEEF
  return vector_kernels<Arch, SleefTrig<xsimd::batch<double, Arch>, &Sleef_sincosd8_u10avx512f>>("avx512f");
#else
  return vector_kernels<Arch>("avx512f");
#endif
}
#else
KernelSet avx512_kernels() { return {}; }  // not an x86 build
#endif
}  // namespace pcrf::detail::batch
