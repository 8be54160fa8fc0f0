// The case kernel (case_kernel.hpp) behind the group-of-cases seam (pcrf/solver/case_group.hpp):
// kernel_host_group, the kernel compiled for the host, and gpu_group, the same kernel on a
// CUDA device (case_kernel.cu) where the build has CUDA.
#include <exception>
#include <stdexcept>
#include <string>

#include "kernel_cases.hpp"
#include "../case/case_common.hpp"
#include "../case/prepared_frame.hpp"
#include "../group/group_answers.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/solver/case_group.hpp"

#ifdef PCRF_HAVE_CUDA
#include "kernel_launch.hpp"
#endif

namespace pcrf {
namespace device {

std::string kernel_refuses(const Excitation& excitation, const SolverSettings& solver, bool history) {
  if (solver.integrator != Integrator::kDormandPrince5) return "the case kernel steps integrator dopri5 only";
  if (solver.verdict_check) return "the case kernel does not run the verdict check's twins";
  if (solver.wall_time_limit_s > 0.0) return "the case kernel has no wall-time limit (wall_time_limit_s > 0)";
  if (history) return "the case kernel records no history";
  if (excitation.has_vertical()) return "the case kernel takes a horizontal record only (this one has a vertical component)";
  return {};
}

std::string kernel_case(PreparedFrame& frame, const Excitation& excitation, const SolverSettings& solver,
                        const OutputRequest& request, KernelCase& c, KernelTableStore& tables) {
  // solve_case's checks first: a case it refuses is refused here with its message.
  detail::validate(solver, frame.physics());
  check_initial_state(frame.scene(), frame.physics());
  const Scene& scene = frame.scene();
  const std::optional<RockerCoefficients> rocker = scene.rocker_coefficients();
  if (!rocker && !scene.worth_tabulating())
    return "the case kernel covers the rigid rockers and the tabulated prestressed frame only";
  const PhysicsOptions& physics = frame.physics();
  const detail::CaseEnd end(excitation, scene.gravity_m_s2(), physics);
  c = KernelCase{};
  c.gravity_m_s2 = scene.gravity_m_s2();
  if (rocker) {
    c.rigid = true;
    c.slenderness_rad = rocker->slenderness_rad;
    c.moment_over_inertia_per_m = rocker->moment_over_inertia_per_m;
    if (c.gravity_m_s2 != rocker->gravity_m_s2) return "the case kernel: a rocker whose gravity is not its scene's";
  } else {  // the frame's table, every cell built (the CPU builds them as flights visit them: the same cells)
    const EomTable::Cells cells = frame.table().all_cells();
    c.rigid = false;
    c.table_first = tables.tabulated.size();
    c.table_cells = cells.tabulated.size();
    c.table_inv_cell_per_rad = cells.inv_cell_per_rad;
    tables.coefficients.insert(tables.coefficients.end(), cells.coefficients.begin(), cells.coefficients.end());
    tables.tabulated.insert(tables.tabulated.end(), cells.tabulated.begin(), cells.tabulated.end());
  }
  const EomTerms& rest = scene.rest();
  c.rest_I = rest.I, c.rest_G = rest.G, c.rest_K = rest.K, c.rest_S = rest.S;
  c.uplift_threshold_m_s2 = scene.uplift_threshold_m_s2();
  c.restitution = frame.restitution();
  c.broken_at_rest = frame.broken_at_rest();
  c.stop_rad = c.broken_at_rest ? 0.0 : frame.stop_angles().stop_rad();
  c.theta0_rad = physics.theta0_rad, c.omega0_rad_s = physics.omega0_rad_s;
  c.zeno_time_s = physics.zeno_time_s, c.rest_rise_rad = physics.rest_rise_rad;
  c.t_end_s = end.t_end_s;
  c.record_end_s = end.record_end_s;
  c.until_rest = end.until_rest;
  c.rtol = solver.rtol, c.atol_theta_rad = solver.atol_theta_rad, c.atol_omega_rad_s = solver.atol_omega_rad_s;
  c.max_step_s = solver.max_step_s;
  c.max_steps = solver.max_steps;
  c.omega_peak = request.omega_peak;
  return {};
}

KernelRecord kernel_record(const GroundMotion& record) {
  KernelRecord r;
  r.samples_m_s2 = record.samples_m_s2().data();
  r.count = record.size();
  r.dt_s = record.dt_s();
  r.inv_dt_per_s = record.inverse_dt_per_s();
  r.pga_m_s2 = record.pga_m_s2();
  return r;
}

namespace {

/// The CPU path's message of a kernel failure (dormand_prince.cpp, case_run.cpp).
std::string failure_message(const KernelResult& k) {
  switch (k.error) {
    case KernelError::kRhsAtStart: return "dopri5: the right-hand side failed at the start, t = " + number_text(k.error_a) + " s";
    case KernelError::kNonFiniteDerivative: return "dopri5: non-finite derivative";
    case KernelError::kTooManyFailures:
      return "dopri5: " + std::to_string(detail::kMaxFailures) + " failed step attempts in a row at t = " +
             number_text(k.error_a) + " s";
    case KernelError::kStepTooSmall:
      return "dopri5: step size " + number_text(k.error_b) + " s too small at t = " + number_text(k.error_a) + " s";
    case KernelError::kMaxSteps: return "more than max_steps steps";
    case KernelError::kNonFiniteState: return "non-finite state at t = " + std::to_string(k.error_a) + " s";
    case KernelError::kNone: break;
  }
  return "the case kernel failed without a cause";
}

}  // namespace

CaseResult kernel_result(PreparedFrame& frame, const Excitation& excitation, const OutputRequest& request,
                         const KernelResult& k) {
  const Scene& scene = frame.scene();
  CaseResult r = detail::initial_result(scene, excitation, frame.restitution(), request.omega_peak);
  const detail::CaseEnd end(excitation, scene.gravity_m_s2(), frame.physics());
  switch (k.end) {
    case KernelEnd::kReachedEnd:
      r.status = end.status(k.at_rest ? CaseStatus::kAtRest : CaseStatus::kRockingAtEnd);
      r.message = end.message();
      break;
    case KernelEnd::kAtRestEnd:
      r.status = end.status(CaseStatus::kAtRest);
      r.message = end.message();
      break;
    case KernelEnd::kStopped:
      r.status = frame.stop_angles().status();
      r.message = frame.stop_angles().message();
      break;
    case KernelEnd::kBrokenAtRest:
      r.status = CaseStatus::kTendonFracture;
      r.message = detail::kBrokenAtRestMessage;
      break;
    case KernelEnd::kSolverFailure:
      r.status = CaseStatus::kSolverFailure;
      r.message = failure_message(k);
      break;
    case KernelEnd::kLeftTable: break;  // no answer: the caller refuses the case (kernel_answers)
  }
  r.t_uplift_s = k.t_uplift_s;
  r.theta_max_rad = k.theta_max_rad;
  r.t_theta_max_s = k.t_theta_max_s;
  r.omega_max_rad_s = k.omega_max_rad_s;
  r.t_omega_max_s = k.t_omega_max_s;
  r.impacts = k.impacts;
  r.t_end_s = k.t_end_s;
  r.counts.steps = k.steps;
  r.counts.rhs_evals = k.rhs_evals;
  r.counts.root_evals = k.root_evals;
  r.counts.reinits = k.reinits;
  detail::set_peak_strains(scene, r);
  return r;
}

}  // namespace device

namespace {

constexpr const char* kLeftTableMessage =
    "the case kernel: the frame reached an angle its table does not hold (the CPU path's exact terms)";

using detail::check_group_history;
using detail::refused_case;

/// The kernel compiled for the host, case by case.
class KernelHost final : public CaseGroupSolver {
 public:
  std::string_view name() const override { return "kernel-host"; }
  std::vector<GroupCase> solve(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                               const SolverSettings& solver, const OutputRequest& request,
                               const HistorySink& history) const override {
    check_group_history(frames.size(), history);
    std::vector<GroupCase> cases(frames.size());
    const std::string group_why = device::kernel_refuses(excitation, solver, static_cast<bool>(history));
    const device::KernelRecord record = device::kernel_record(excitation.horizontal());
    for (std::size_t i = 0; i < frames.size(); ++i) {
      if (!group_why.empty()) {
        cases[i] = refused_case(group_why);
        continue;
      }
      try {
        const double start_cpu_s = detail::thread_cpu_s();
        device::KernelCase c;
        device::KernelTableStore tables;
        if (std::string why = device::kernel_case(*frames[i], excitation, solver, request, c, tables); !why.empty()) {
          cases[i] = refused_case(std::move(why));
          continue;
        }
        device::KernelResult k;
        device::solve_kernel_case(c, record, tables.view(), k);
        if (k.end == device::KernelEnd::kLeftTable) {
          cases[i] = refused_case(kLeftTableMessage);
          continue;
        }
        cases[i].result = device::kernel_result(*frames[i], excitation, request, k);
        cases[i].result.cpu_time_s = detail::thread_cpu_s() - start_cpu_s;
      } catch (const std::exception& e) {  // what solve_case would throw: the case's answer
        cases[i] = refused_case(e.what());
      }
    }
    return cases;
  }
};

}  // namespace

std::unique_ptr<CaseGroupSolver> kernel_host_group() { return std::make_unique<KernelHost>(); }

#ifdef PCRF_HAVE_CUDA
namespace {

/// The kernel on CUDA device 0: the cases it takes set up on the host, solved on the device
/// together (one thread per case), their answers made on the host.
class Gpu final : public CaseGroupSolver {
 public:
  explicit Gpu(std::string device) : device_(std::move(device)) {}
  std::string_view name() const override { return "gpu"; }
  std::vector<GroupCase> solve(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                               const SolverSettings& solver, const OutputRequest& request,
                               const HistorySink& history) const override {
    check_group_history(frames.size(), history);
    std::vector<GroupCase> cases(frames.size());
    const std::string group_why = device::kernel_refuses(excitation, solver, static_cast<bool>(history));
    if (!group_why.empty()) {
      for (GroupCase& c : cases) c = refused_case(group_why);
      return cases;
    }
    const double start_cpu_s = detail::thread_cpu_s();
    std::vector<device::KernelCase> taken;
    device::KernelTableStore tables;
    std::vector<std::size_t> index;  // taken[j] is case index[j]
    for (std::size_t i = 0; i < frames.size(); ++i) {
      try {
        device::KernelCase c;
        if (std::string why = device::kernel_case(*frames[i], excitation, solver, request, c, tables); !why.empty()) {
          cases[i] = refused_case(std::move(why));
          continue;
        }
        taken.push_back(c);
        index.push_back(i);
      } catch (const std::exception& e) {
        cases[i] = refused_case(e.what());
      }
    }
    std::vector<device::KernelResult> results(taken.size());
    std::string error;
    if (!device::cuda_solve_cases(taken.data(), taken.size(), device::kernel_record(excitation.horizontal()), tables,
                                  results.data(), error)) {
      for (std::size_t i : index) cases[i] = refused_case("the GPU (" + device_ + ") did not run the cases: " + error);
      return cases;
    }
    // The host thread's CPU time (set-up, transfers, the wait), shared equally.
    const double share_s = taken.empty() ? 0.0 : (detail::thread_cpu_s() - start_cpu_s) / static_cast<double>(taken.size());
    for (std::size_t j = 0; j < taken.size(); ++j) {
      if (results[j].end == device::KernelEnd::kLeftTable) {
        cases[index[j]] = refused_case(kLeftTableMessage);
        continue;
      }
      cases[index[j]].result = device::kernel_result(*frames[index[j]], excitation, request, results[j]);
      cases[index[j]].result.cpu_time_s = share_s;
    }
    return cases;
  }

 private:
  std::string device_;
};

}  // namespace

std::unique_ptr<CaseGroupSolver> gpu_group(std::string& why_not) {
  std::string name;
  why_not = device::cuda_device_problem(name);
  if (!why_not.empty()) return nullptr;
  return std::make_unique<Gpu>(name);
}
#else
std::unique_ptr<CaseGroupSolver> gpu_group(std::string& why_not) {
  why_not = "this build has no CUDA (PCRF_CUDA=OFF or nvcc not found)";
  return nullptr;
}
#endif

}  // namespace pcrf
