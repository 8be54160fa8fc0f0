// The avx2 kernels (4 lanes a register; see attempt_kernel.hpp). Compiled with this
// instruction set's flags; run only where the CPU has it (choose_kernels).
#if defined(__x86_64__) || defined(__i386__)
#include <xsimd/xsimd.hpp>

#include "attempt_kernel.hpp"
#ifdef PCRF_HAVE_SLEEF
#include <sleef.h>
#endif

namespace pcrf::detail::batch {
namespace {

using Batch = xsimd::batch<double, xsimd::fma3<xsimd::avx2>>;

struct XsimdTrig {
  static void sincos(const Batch& x, Batch& s, Batch& c) {
    auto sc = xsimd::sincos(x);
    s = sc.first, c = sc.second;
  }
};

#ifdef PCRF_HAVE_SLEEF
struct SleefTrig {
  static void sincos(const Batch& x, Batch& s, Batch& c) {
    const auto sc = Sleef_sincosd4_u10avx2(x);
    s = Batch(sc.x), c = Batch(sc.y);
  }
};
#endif

}  // namespace

KernelSet avx2_kernels() {
  KernelSet k;
  k.name = "avx2";
  k.register_lanes = 4;
  k.libm_trig = &attempt_all<VectorPack<Batch, LibmTrig<Batch>>>;
  k.xsimd_trig = &attempt_all<VectorPack<Batch, XsimdTrig>>;
#ifdef PCRF_HAVE_SLEEF
  k.sleef_trig = &attempt_all<VectorPack<Batch, SleefTrig>>;
#endif
  return k;
}

}  // namespace pcrf::detail::batch
#else
#include "lane_arrays.hpp"
namespace pcrf::detail::batch {
KernelSet avx2_kernels() { return {}; }  // not an x86 build
}  // namespace pcrf::detail::batch
#endif
