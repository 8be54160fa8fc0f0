/// \file case_run.hpp
/// \brief One case under the dopri5 or SUNDIALS integrators: the flight problem and the
/// case's state machine (see pcrf/solver/rocking_solver.hpp for the method). The
/// one-case solver (rocking_solver.cpp) runs it start to end; the batch (batch/) runs many,
/// each stopping at every step attempt. Private to the solver.
#pragma once

#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "case_common.hpp"
#include "../dopri5/dormand_prince.hpp"
#include "../integrator/integrator.hpp"
#include "../integrator/registry.hpp"
#include "pcrf/model/eom_table.hpp"
#include "pcrf/solver/history.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "prepared_frame.hpp"

namespace pcrf::detail {

/// Root indices.
enum Root { kImpact = 0, kThetaPeak = 1, kOmegaPeak = 2, kLimit = 3, kRootCount = 4 };

/// The ODE of one flight (between two impacts) on a fixed side.
class FlightProblem final : public detail::OdeProblem {
 public:
  FlightProblem(const Scene& scene, const EomTable& table, const Excitation& excitation, double theta_stop_rad,
                bool omega_peak)
      : scene_(scene),
        table_(table),
        forcing_(excitation),
        record_end_s_(excitation.horizontal().duration_s()),
        theta_stop_rad_(theta_stop_rad),
        omega_peak_(omega_peak) {}

  int side = -1;

  int rhs(double t, const double* y, double* ydot) override;
  int roots(double t, const double* y, double* g) override;

  int root_count() const override { return kRootCount; }
  /// θ₁, θ̇₁, θ̈₁ (or the constant 1 when ω peaks are not requested), |θ₁| − θ_stop.
  RootForm root_form(int i) const override {
    switch (i) {
      case kImpact: return {0, false, 0.0};
      case kThetaPeak: return {1, false, 0.0};
      case kOmegaPeak: return omega_peak_ ? RootForm{2, false, 0.0} : RootForm{RootForm::kConstant, false, 1.0};
      case kLimit: return {0, true, theta_stop_rad_};
      default: return {};
    }
  }

  /// The ground at t (Excitation::at, bit for bit, through the flight's cursor).
  GroundAcceleration ground_at(double t) { return forcing_.at(t); }

  bool has_jacobian() const override { return true; }
  int jacobian(double t, const double* y, double* dfdy) override;
  void evaluated(double t, const double* y, const double* ydot) override;
  int taylor_order_max() const override { return scene_.taylor_order_max(); }
  /// The scene's series under the record's line over the sample interval holding t0 (for
  /// any h), else under the chord over [t0, t0 + h].
  bool taylor(double t0, const double* y0, double h, int order, double* a, bool& for_any_h) override;

  /// Root directions for the current side: the impact only while closing, θ peaks only
  /// where |θ| is maximal, the limit only while opening.
  std::array<int, kRootCount> directions() const {
    return {-side, -side, 0, 1};
  }

 private:
  /// θ̈₁ at (t, y). With the θ̈₁ root, remembering the last evaluation: the root functions
  /// are evaluated at step ends, where the right-hand side has just been evaluated (FSAL
  /// methods, CVODE's corrector), so that root costs almost nothing.
  bool acceleration(double t, const double* y, double& acc);

  /// The ground over [t0, t0 + h]: the record's interval holding t0 (`exact`), else
  /// (after the record, components on their own time axes) the chord.
  GroundLine ground_line(double t0, double h, bool& exact);
  /// The chord of the ground over [t0, t0 + h] (out of line: after the record, or components
  /// on their own time axes).
  [[gnu::noinline]] GroundLine chord(double t0, double h);
  /// The scene's series kernels of `order` (once per case, out of line).
  [[gnu::noinline]] void load_kernels(int order);

  const Scene& scene_;
  const EomTable& table_;  // the prepared frame's: built once for every case of the frame
  ExcitationCursor forcing_;  // linear between samples: most stages fall in the last interval
  double record_end_s_;
  double theta_stop_rad_;
  bool omega_peak_;
  double last_t_ = std::numeric_limits<double>::quiet_NaN();
  double last_y_[2] = {0.0, 0.0};
  int last_side_ = 0;
  double last_acc_ = 0.0;
  std::array<TaylorKernel, 2> kernels_{};  ///< the scene's series on sides −1 and +1, of order kernel_order_
  int kernel_order_ = 0;
};

/// The state machine of one case: rest → uplift → flights and impacts → rest or failure.
class CaseRun {
 public:
  /// `lockstep`: the dopri5 integrator in lockstep (dormand_prince.hpp), for a batch; then
  /// progress() may stop with an attempt pending.
  CaseRun(PreparedFrame& frame, const Excitation& excitation, const SolverSettings& solver, const OutputRequest& request,
          const HistorySink& history, bool lockstep = false)
      : scene_(frame.scene()),
        excitation_(excitation),
        physics_(frame.physics()),
        solver_(solver),
        request_(request),
        history_(history, frame.scene(), excitation),
        history_dt_s_(request.history_dt_s > 0.0 ? request.history_dt_s : excitation.dt_s()),
        restitution_(frame.restitution()),
        stop_(frame.stop_angles()),
        problem_(frame.scene(), frame.table(), excitation_, stop_.stop_rad(), request.omega_peak),
        samples_{excitation.dt_s(), excitation.horizontal().size()},
        integrator_(make_integrator(solver, problem_, samples_, lockstep)),
        end_(excitation, frame.scene().gravity_m_s2(), physics_),
        t_end_(end_.t_end_s) {
    // The registry's one lockstep stepper is dopri5 (make_integrator refuses any other).
    if (lockstep) lockstep_ = static_cast<DormandPrinceIntegrator*>(integrator_.get());
  }

  /// The whole case: begin(), progress(), end().
  CaseResult run();

  /// Starts the case (a displaced start, a frame broken at rest).
  void begin();
  /// Runs the case until it ends (false) or, in lockstep, a step attempt is pending (true:
  /// lockstep()'s attempt() to fill, take_attempt(), then progress() again).
  bool progress();
  /// The result of an ended case.
  CaseResult end();
  /// The lockstep integrator (null when not in lockstep).
  DormandPrinceIntegrator* lockstep() const { return lockstep_; }
  FlightProblem& flight() { return problem_; }

 private:
  void rest_until_uplift();
  void start_displaced();
  /// One advance of the integrator and what it met; false: a lockstep attempt is pending.
  bool fly();
  bool handle_roots(double t, double* y);
  /// Ends the case at the stop angle, (θ₁, θ̇₁) there.
  void stop_at(double t, double theta, double omega);
  void impact(double t, double* y);
  bool returns_to_rest(double t, double omega_after);
  bool holds_closed(double t);
  void settle(double t);
  void start_flight(double t, const double* y, std::uint32_t events = kEventNone);
  void note_theta(double t, double theta);
  void note_omega(double t, double omega);
  void emit(double t, double theta, double omega, std::uint32_t events = kEventNone);
  void emit_rest_until(double t);
  /// History rows at the output times before t_until, from the last step's interpolant.
  void emit_dense_before(double t_until);
  double next_history_time() const { return static_cast<double>(next_history_sample_) * history_dt_s_; }
  void finish(CaseStatus status, std::string message = {});
  bool over_time() const;

  const Scene& scene_;
  Excitation excitation_;
  PhysicsOptions physics_;
  SolverSettings solver_;
  OutputRequest request_;
  detail::HistoryRows history_;
  double history_dt_s_;  // output interval of the history
  double restitution_;
  detail::StopAngles stop_;
  FlightProblem problem_;
  detail::SampleGrid samples_;  // the record's samples: kinks of ü_g
  std::unique_ptr<detail::OdeIntegrator> integrator_;
  DormandPrinceIntegrator* lockstep_ = nullptr;
  detail::CaseEnd end_;
  double t_end_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();

  // Progress.
  bool at_rest_ = true;
  bool done_ = false;
  double t_ = 0.0;
  double last_y_[2] = {0.0, 0.0};  // state at t_ while in flight
  std::size_t next_history_sample_ = 0;
  CaseResult result_;
};

/// A case whose frame rests through the whole record: what CaseRun would report, without
/// its set-up (closing limit, fracture angle, coefficient table, integrator). nullopt when
/// the case needs the full run (it lifts, starts displaced, is broken at rest or records a
/// history).
std::optional<CaseResult> rest_throughout(PreparedFrame& frame, const Excitation& excitation,
                                          const OutputRequest& request, const HistorySink& history);

}  // namespace pcrf::detail
