// The one-lane kernel: the C library's sin and cos, no vector unit (see attempt_kernel.hpp).
#include "attempt_kernel.hpp"

namespace pcrf::detail::batch {

KernelSet scalar_kernels() {
  KernelSet k;
  k.name = "scalar";
  k.register_lanes = 1;
  k.libm_trig = k.xsimd_trig = k.sleef_trig = &attempt_all<ScalarPack>;
  return k;
}

}  // namespace pcrf::detail::batch
