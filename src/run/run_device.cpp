// Where a run's cases are solved (see run_device.hpp).
#include "pcrf/run/run_device.hpp"

#include <atomic>
#include <mutex>
#include <string>
#include <utility>

namespace pcrf::run {
namespace {

/// The GPU backend, with the CPU engine for the cases it refuses (a scene, integrator or
/// output the case kernel does not cover): every case gets the engine's answer, the kernel's
/// where it has one. A case the CPU engine refuses as well stays refused.
class GpuThenCpu final : public CaseGroupSolver {
 public:
  GpuThenCpu(std::unique_ptr<CaseGroupSolver> gpu, std::unique_ptr<CaseGroupSolver> cpu)
      : gpu_(std::move(gpu)), cpu_(std::move(cpu)) {}
  std::string_view name() const override { return gpu_->name(); }
  std::vector<GroupCase> solve(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                               const SolverSettings& solver, const OutputRequest& request,
                               const HistorySink& history) const override {
    std::vector<GroupCase> answers = gpu_->solve(frames, excitation, solver, request, history);
    std::vector<std::size_t> refused;
    std::vector<PreparedFrame*> again;
    for (std::size_t i = 0; i < answers.size(); ++i)
      if (answers[i].outcome == GroupOutcome::kRefused) {
        refused.push_back(i);
        again.push_back(frames[i]);
      }
    if (refused.empty()) return answers;
    refused_ += refused.size();
    {
      std::lock_guard lock(mutex_);
      if (first_reason_.empty()) first_reason_ = answers[refused.front()].result.message;
    }
    std::vector<GroupCase> cpu = cpu_->solve(again, excitation, solver, request, history);
    for (std::size_t k = 0; k < refused.size(); ++k) answers[refused[k]] = std::move(cpu[k]);
    return answers;
  }

  /// Cases refused so far, and the first one's reason.
  std::pair<std::int64_t, std::string> refusals() const {
    std::lock_guard lock(mutex_);
    return {static_cast<std::int64_t>(refused_.load()), first_reason_};
  }

 private:
  std::unique_ptr<CaseGroupSolver> gpu_;
  std::unique_ptr<CaseGroupSolver> cpu_;
  mutable std::atomic<std::size_t> refused_{0};
  mutable std::mutex mutex_;
  mutable std::string first_reason_;
};

}  // namespace

std::string gpu_refusal_note(const CaseGroupSolver& group) {
  const auto* gpu = dynamic_cast<const GpuThenCpu*>(&group);
  if (gpu == nullptr) return {};
  const auto [refused, reason] = gpu->refusals();
  if (refused == 0) return {};
  return std::to_string(refused) + " case" + (refused == 1 ? "" : "s") +
         " of this rank went to the CPU engine, which the GPU's case kernel does not cover (the first: " + reason +
         "); docs/gpu.md says what it covers";
}

Where device_where(const StudyRunOptions& options, const study::Study& study) {
  for (const auto& [setting, value] : options.run_overrides)
    if (setting->key == "device") return Where{{"device"}, {}, 0};  // --device, device=
  return study.where(std::string(study::run_settings().name) + ".device");
}

std::shared_ptr<const CaseGroupSolver> device_group_solver(const study::Study& study, const Where& where,
                                                           const GpuBackend& backend) {
  if (!on_gpu(study)) return make_group_solver(study.solver, static_cast<int>(study.run.lanes));
  std::string why_not;
  std::unique_ptr<CaseGroupSolver> gpu = backend ? backend(why_not) : gpu_group(why_not);
  if (gpu == nullptr)
    throw UserError(where, "\"gpu\" cannot be used here: " + (why_not.empty() ? std::string("no usable CUDA device") : why_not) +
                               "; use \"cpu\" (docs/gpu.md)");
  return std::make_shared<GpuThenCpu>(std::move(gpu), make_group_solver(study.solver, static_cast<int>(study.run.lanes)));
}

}  // namespace pcrf::run
