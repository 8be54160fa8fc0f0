// One case: rest → uplift → rocking with impacts → rest or failure, to the end of the
// record (plus tail). See pcrf/solver/rocking_solver.hpp for the method; the case's state
// machine is case_run.hpp's.
#include "pcrf/solver/rocking_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "case/case_common.hpp"
#include "case/case_run.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/solver/integrator_registry.hpp"
#include "case/prepared_frame.hpp"

namespace pcrf {

void check_initial_state(const Scene& eom, const PhysicsOptions& physics) {
  if (physics.theta0_rad == 0.0) return;
  if (!(std::fabs(physics.theta0_rad) < eom.overturn_angle_rad())) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "|θ₀| = %.6g rad is not below this frame's overturning angle %.6g rad "
                  "(95 %% of its closing limit %.6g rad)",
                  std::fabs(physics.theta0_rad), eom.overturn_angle_rad(), eom.closing_limit_rad());
    throw UserError("theta0_rad", text);
  }
}

void check_initial_state(const Frame& frame, const PhysicsOptions& physics) {
  if (physics.theta0_rad != 0.0) check_initial_state(EquationOfMotion(frame), physics);
}

namespace {

/// The perturbation factors of the verdict check: the record scaled by 1 ± 1e-9, 1 ± 1e-7
/// and 1 ± 1e-6, far below any real uncertainty of a record (issue 11's definition of a
/// well-conditioned case).
constexpr double kPerturbations[] = {1e-9, -1e-9, 1e-7, -1e-7, 1e-6, -1e-6};

/// Fills the verdict-check metrics of `nominal`. The twins are run only where a verdict can
/// flip: a case that collapsed, or that came within half of its stop angle (fracture or
/// overturning). Further from collapse a 1e-6 perturbation does not double θ_max (the worst
/// measured sensitivity is 19 % for 1e-9): the verdict is stable, and the spread not measured.
void check_verdict(PreparedFrame& frame, const Excitation& excitation, const SolverSettings& solver,
                   const OutputRequest& request, CaseResult& nominal) {
  const Verdict verdict = verdict_of(nominal.status);
  const bool near = is_collapse(nominal.status) || verdict == Verdict::kNone ||
                    (nominal.theta_max_rad > 0.0 && nominal.theta_max_rad >= 0.5 * frame.stop_angles().stop_rad());
  nominal.collapse_fraction = is_collapse(nominal.status) ? 1.0 : 0.0;
  if (!near) {
    nominal.status_stable = 1.0;
    return;
  }
  SolverSettings twin_settings = solver;
  twin_settings.verdict_check = false;
  double lo = nominal.theta_max_rad, hi = nominal.theta_max_rad, collapses = nominal.collapse_fraction;
  bool stable = true;
  for (double e : kPerturbations) {
    const ScaledExcitation scaled(excitation, 1.0 + e);
    const CaseResult twin = solve_case(frame, scaled.view(), twin_settings, request);
    stable = stable && verdict_of(twin.status) == verdict;
    collapses += is_collapse(twin.status) ? 1.0 : 0.0;
    lo = std::min(lo, twin.theta_max_rad);
    hi = std::max(hi, twin.theta_max_rad);
  }
  nominal.status_stable = stable ? 1.0 : 0.0;
  nominal.collapse_fraction = collapses / (1.0 + std::size(kPerturbations));
  nominal.theta_max_spread = nominal.theta_max_rad > 0.0 ? (hi - lo) / nominal.theta_max_rad : 0.0;
}

}  // namespace

double longest_case_s(double record_s, const PhysicsOptions& physics) {
  return record_s + (physics.tail_s == kTailUntilRest ? physics.max_tail_s : physics.tail_s);
}

CaseResult solve_case(PreparedFrame& frame, const Excitation& excitation, const SolverSettings& solver,
                      const OutputRequest& request, const HistorySink& history) {
  detail::validate(solver, frame.physics());
  check_initial_state(frame.scene(), frame.physics());
  if (history) check_history_interval(longest_case_s(excitation.duration_s(), frame.physics()), request.history_dt_s,
                                      excitation.dt_s());
  // Timed here, so that the per-case set-up (linkage limits, fracture angle, r) counts.
  const double start_cpu_s = detail::thread_cpu_s();
  CaseResult result;
  if (const auto solve_whole = registry_entry(solver.integrator).solve) {  // a method with its own case loop
    result = solve_whole(frame.scene(), excitation, frame.physics(), solver, history);
  } else if (auto at_rest = detail::rest_throughout(frame, excitation, request, history)) {
    result = std::move(*at_rest);
  } else {
    detail::CaseRun run(frame, excitation, solver, request, history);
    result = run.run();
  }
  if (solver.verdict_check) check_verdict(frame, excitation, solver, request, result);
  result.cpu_time_s = detail::thread_cpu_s() - start_cpu_s;
  return result;
}

CaseResult solve_case(const Frame& frame, const Excitation& excitation, const PhysicsOptions& physics,
                      const SolverSettings& solver, const OutputRequest& request, const HistorySink& history) {
  detail::validate(solver, physics);  // settings first: they are the caller's, the frame may be the study's
  PreparedFrame prepared(frame, physics);
  return solve_case(prepared, excitation, solver, request, history);
}

}  // namespace pcrf
