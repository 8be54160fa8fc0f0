// The one-lane kernel: the one-case sincos (rocker_sincos), no vector unit (see attempt_kernel.hpp).
#include "attempt_kernel.hpp"

namespace pcrf::detail::batch {

KernelSet scalar_kernels() {
  KernelSet k;
  k.name = "scalar";
  k.register_lanes = 1;
  k.exact_trig = k.scalar_trig = k.xsimd_trig = k.sleef_trig = &attempt_all<ScalarPack>;
  k.sincos = &sincos_all<ScalarPack>;
  return k;
}

}  // namespace pcrf::detail::batch
