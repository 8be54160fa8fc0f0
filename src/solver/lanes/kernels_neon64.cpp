// The arm64 kernels (two lanes a register; see attempt_kernel.hpp). Advanced SIMD is part
// of every arm64 CPU: no run-time check is needed.
#include "attempt_kernel.hpp"

namespace pcrf::detail::batch {
#if defined(__aarch64__)
KernelSet neon64_kernels() { return vector_kernels<xsimd::neon64>("neon64"); }
#else
KernelSet neon64_kernels() { return {}; }  // not an arm64 build
#endif
}  // namespace pcrf::detail::batch
