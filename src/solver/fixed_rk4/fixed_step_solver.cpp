// The fixed-step RK4 contender with sign-change impacts (see fixed_step_solver.hpp).
#include "fixed_step_solver.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "../case/case_common.hpp"


namespace pcrf::detail {
namespace {

struct State {
  double theta, omega;
};

class FixedStepRun {
 public:
  FixedStepRun(const Scene& scene, const Excitation& excitation, const PhysicsOptions& physics,
               const SolverSettings& solver, const HistorySink& history)
      : scene_(scene),
        excitation_(excitation),
        physics_(physics),
        solver_(solver),
        history_(history, scene, excitation),
        r_(scene.restitution()),
        h_(solver.fixed_step_s > 0 ? solver.fixed_step_s : excitation.dt_s()),
        end_(excitation, scene.gravity_m_s2(), physics),
        t_end_(end_.t_end_s),
        stop_(stop_angles(scene, physics)) {}

  CaseResult run() {
    result_ = initial_result(scene_, excitation_, r_, true);
    if (stop_.broken_at_rest()) return finish(CaseStatus::kTendonFracture, 0.0, kBrokenAtRestMessage);
    State y{physics_.theta0_rad, physics_.omega0_rad_s};
    double t = 0.0;
    if (y.theta == 0.0 && y.omega == 0.0) {
      // The paper's procedure starts the motion at its trigger t_RI, held or not by the
      // prestress; the physical criteria start it where the net force opens the joints.
      t = physics_.uplift == UpliftCriterion::kPaperProcedure
              ? paper_trigger_time(excitation_.horizontal(), scene_.lambda_g())
              : first_opening(excitation_, scene_, 0.0, end_.rest_end_s(0.0));
      if (std::isnan(t) || t > end_.rest_end_s(0.0))
        return finish(end_.status(CaseStatus::kAtRest), end_.rest_end_s(0.0), end_.message());
      side_ = uplift_side(excitation_.at(t).horizontal_m_s2);
    } else {
      side_ = initial_side(y.theta, y.omega);
    }
    note_uplift(result_, t);
    emit(t, y, kEventUplift);
    const double t_start = t;
    long k = 0;
    while (t < t_end_) {
      // Step ends at t_start + k h (not a running sum, whose rounding drifts the times).
      const double t_next = std::min(t_start + static_cast<double>(++k) * h_, t_end_);
      const double h = t_next - t;
      State next{};
      if (!step(t, h, y, next)) return finish(CaseStatus::kSolverFailure, t, "linkage cannot close");
      t = t_next;
      ++result_.counts.steps;
      std::uint32_t events = kEventNone;
      const double omega_arriving = next.omega;
      if (side_ * next.theta < 0.0) {  // θ₁ left the branch's side over the step
        // Sign change over the step: impact at the step end, not located.
        next.omega *= r_;
        side_ = -side_;
        note_impact(result_, t);
        events = kEventImpact;
      }
      y = next;
      last_ = y;
      note(t, y);
      if (events == kEventImpact) emit(t, State{y.theta, omega_arriving}, events);
      emit(t, y);
      if (!std::isfinite(y.theta) || !std::isfinite(y.omega))
        return finish(CaseStatus::kSolverFailure, t, "non-finite state");
      if (std::abs(y.theta) >= stop_.stop_rad()) return finish(stop_.status(), t, stop_.message());
    }
    return finish(end_.status(CaseStatus::kRockingAtEnd), t, end_.message());
  }

 private:
  bool rhs(double t, State y, State& dy) const {
    dy.theta = y.omega;
    ++evals_;
    return scene_.acceleration(y.theta, y.omega, excitation_.at(t), side_, dy.omega);
  }

  bool step(double t, double h, State y, State& out) const {
    State k1{}, k2{}, k3{}, k4{};
    auto at = [](State a, State k, double c) { return State{a.theta + c * k.theta, a.omega + c * k.omega}; };
    if (!rhs(t, y, k1) || !rhs(t + 0.5 * h, at(y, k1, 0.5 * h), k2) || !rhs(t + 0.5 * h, at(y, k2, 0.5 * h), k3) ||
        !rhs(t + h, at(y, k3, h), k4))
      return false;
    out.theta = y.theta + h / 6.0 * (k1.theta + 2 * k2.theta + 2 * k3.theta + k4.theta);
    out.omega = y.omega + h / 6.0 * (k1.omega + 2 * k2.omega + 2 * k3.omega + k4.omega);
    return true;
  }

  void note(double t, State y) {
    if (std::abs(y.theta) > result_.theta_max_rad) {
      result_.theta_max_rad = std::abs(y.theta);
      result_.t_theta_max_s = t;
    }
    if (std::abs(y.omega) > result_.omega_max_rad_s) {
      result_.omega_max_rad_s = std::abs(y.omega);
      result_.t_omega_max_s = t;
    }
  }

  void emit(double t, State y, std::uint32_t events = kEventNone) { history_.add(t, y.theta, y.omega, side_, events); }

  CaseResult finish(CaseStatus status, double t, std::string message = {}) {
    history_.end(t, last_.theta, last_.omega, side_, is_collapse(status) ? kEventStop : kEventNone);
    result_.status = status;
    result_.t_end_s = t;
    result_.message = std::move(message);
    result_.counts.rhs_evals = evals_;
    set_peak_strains(scene_, result_);
    return result_;
  }

  const Scene& scene_;
  Excitation excitation_;
  PhysicsOptions physics_;
  SolverSettings solver_;
  HistoryRows history_;
  State last_{0.0, 0.0};  // the state at the last step's end
  double r_;
  double h_;
  CaseEnd end_;
  double t_end_;
  StopAngles stop_;
  int side_ = -1;
  mutable long evals_ = 0;
  CaseResult result_;
};

}  // namespace

CaseResult solve_case_fixed_step(const Scene& scene, const Excitation& excitation,
                                 const PhysicsOptions& physics, const SolverSettings& solver,
                                 const HistorySink& history) {
  FixedStepRun run(scene, excitation, physics, solver, history);
  return run.run();
}

}  // namespace pcrf::detail
