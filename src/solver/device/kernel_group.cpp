// The case kernel (device/) behind the group-of-cases seam, compiled for the host
// (pcrf/solver/case_group.hpp: kernel_host_group), and the GPU backend where this build has none.
#include <string>

#include "pcrf/solver/case_group.hpp"

namespace pcrf {
namespace {

class KernelHost final : public CaseGroupSolver {
 public:
  std::string_view name() const override { return "kernel-host"; }
  std::vector<GroupCase> solve(std::span<PreparedFrame* const> frames, const Excitation&, const SolverSettings&,
                               const OutputRequest&, const HistorySink&) const override {
    std::vector<GroupCase> cases(frames.size());
    for (GroupCase& c : cases) {
      c.outcome = GroupOutcome::kRefused;
      c.result.status = CaseStatus::kSolverFailure;
      c.result.message = "the case kernel covers no scene yet";
    }
    return cases;
  }
};

}  // namespace

std::unique_ptr<CaseGroupSolver> kernel_host_group() { return std::make_unique<KernelHost>(); }

#ifndef PCRF_HAVE_CUDA
std::unique_ptr<CaseGroupSolver> gpu_group(std::string& why_not) {
  why_not = "this build has no CUDA (PCRF_CUDA=OFF or nvcc not found)";
  return nullptr;
}
#endif

}  // namespace pcrf
