// Run-time choice of the kernel set: the CPU's instruction sets (xsimd's cpuid), never the
// build machine's. The default build is portable; each kernel file carries its own flags.
// Without xsimd (libxsimd-dev) the build has the scalar kernels alone.
#include <stdexcept>
#include <string>
#include <vector>

#ifdef PCRF_HAVE_XSIMD
#include <xsimd/xsimd.hpp>
#endif

#include "lane_arrays.hpp"

namespace pcrf::detail::batch {
namespace {

/// Every set this binary has, widest first, with whether this CPU runs it.
struct Candidate {
  KernelSet set;
  bool runs;
};

std::vector<Candidate> candidates() {
  std::vector<Candidate> all;
#ifdef PCRF_HAVE_XSIMD
  const auto cpu = xsimd::available_architectures();
  all = {
      {avx512_kernels(), cpu.avx512f != 0 && cpu.avx512cd != 0 && cpu.avx512dq != 0},  // its compile flags
      {avx2_kernels(), cpu.fma3_avx2 != 0},
      {sse2_kernels(), cpu.sse2 != 0},
      {neon64_kernels(), cpu.neon64 != 0},
  };
#endif
  all.push_back({scalar_kernels(), true});
  std::erase_if(all, [](const Candidate& c) { return c.set.exact_trig == nullptr; });
  return all;
}

}  // namespace

KernelSet choose_kernels(int lanes, const std::string& name) {
  std::string known;
  for (const Candidate& c : candidates()) {
    if (name.empty() ? c.runs && c.set.register_lanes <= lanes : name == c.set.name) {
      if (!c.runs) throw std::invalid_argument("batch kernels '" + name + "': this CPU does not run them");
      return c.set;
    }
    known += std::string(known.empty() ? "" : ", ") + c.set.name;
  }
  throw std::invalid_argument("unknown batch kernels '" + name + "' (this build has " + known + ")");
}

}  // namespace pcrf::detail::batch
