// One case: rest → uplift → rocking with impacts → rest or failure, to the end of the
// record (plus tail). See pcrf/solver/rocking_solver.hpp for the method. The event
// handlers are `inline`, so that fly() holds them (-fPIC inlines no interposable function).
#include "case_run.hpp"

#include <algorithm>
#include <string>

#include "pcrf/model/impact.hpp"

namespace pcrf::detail {

// The flight problem's members: here, not in the header, so that the right-hand side is
// compiled as one function with the table's polynomial in it.

inline bool FlightProblem::acceleration(double t, const double* y, double& acc) {
  if (!omega_peak_) return table_.acceleration(y[0], y[1], forcing_.at(t), side, acc) && std::isfinite(acc);
  if (t == last_t_ && y[0] == last_y_[0] && y[1] == last_y_[1] && side == last_side_) {
    acc = last_acc_;
    return true;
  }
  if (!table_.acceleration(y[0], y[1], forcing_.at(t), side, acc) || !std::isfinite(acc)) return false;
  last_t_ = t;
  last_y_[0] = y[0];
  last_y_[1] = y[1];
  last_side_ = side;
  last_acc_ = acc;
  return true;
}

int FlightProblem::rhs(double t, const double* y, double* ydot) {
  double acc = 0;
  if (!acceleration(t, y, acc)) return 1;
  ydot[0] = y[1];
  ydot[1] = acc;
  return 0;
}

int FlightProblem::roots(double t, const double* y, double* g) {
  double d[3] = {y[0], y[1], 0.0};  // θ̈₁ only for the ω peaks
  if (omega_peak_ && !acceleration(t, y, d[2])) return 1;
  for (int i = 0; i < kRootCount; ++i) g[i] = root_value(root_form(i), d);
  return 0;
}

int FlightProblem::jacobian(double t, const double* y, double* dfdy) {
  double acc = 0, d_theta = 0, d_omega = 0;
  if (!table_.acceleration_jacobian(y[0], y[1], forcing_.at(t), side, acc, d_theta, d_omega)) return 1;
  dfdy[0] = 0.0;
  dfdy[1] = 1.0;
  dfdy[2] = d_theta;
  dfdy[3] = d_omega;
  return 0;
}

void FlightProblem::evaluated(double t, const double* y, const double* ydot) {
  if (!omega_peak_) return;
  last_t_ = t;
  last_y_[0] = y[0];
  last_y_[1] = y[1];
  last_side_ = side;
  last_acc_ = ydot[1];
}

inline GroundLine FlightProblem::ground_line(double t0, double h, bool& exact) {
  GroundLine line;
  exact = forcing_.line_from(t0, line);
  return exact ? line : chord(t0, h);
}

void FlightProblem::load_kernels(int order) {
  kernels_ = {scene_.taylor_kernel(-1, order), scene_.taylor_kernel(1, order)};
  kernel_order_ = order;
}

GroundLine FlightProblem::chord(double t0, double h) {
  // At the record's last sample the ground is already the tail's for any τ > 0.
  const GroundAcceleration a = forcing_.at(t0), b = forcing_.at(t0 + h), start = t0 < record_end_s_ ? a : b;
  return {start.horizontal_m_s2, (b.horizontal_m_s2 - start.horizontal_m_s2) / h, start.vertical_m_s2,
          (b.vertical_m_s2 - start.vertical_m_s2) / h};
}

bool FlightProblem::taylor(double t0, const double* y0, double h, int order, double* a, bool& for_any_h) {
  if (order != kernel_order_) load_kernels(order);
  const TaylorKernel& kernel = kernels_[side > 0 ? 1 : 0];
  return kernel.series != nullptr && kernel.series(kernel.constants.data(), y0[0], y0[1], ground_line(t0, h, for_any_h), a);
}

CaseResult CaseRun::run() {
  begin();
  progress();
  return end();
}

void CaseRun::begin() {
  result_ = detail::initial_result(scene_, excitation_, restitution_, request_.omega_peak);
  try {
    if (stop_.broken_at_rest()) {
      finish(CaseStatus::kTendonFracture, detail::kBrokenAtRestMessage);
    } else if (physics_.theta0_rad != 0.0 || physics_.omega0_rad_s != 0.0) {
      start_displaced();
    }
  } catch (const detail::IntegratorError& e) {
    finish(CaseStatus::kSolverFailure, e.what());
  }
}

bool CaseRun::progress() {
  try {
    while (!done_) {
      if (at_rest_) {
        rest_until_uplift();
      } else if (!fly()) {
        return true;
      }
    }
  } catch (const detail::IntegratorError& e) {
    finish(CaseStatus::kSolverFailure, e.what());
  }
  return false;
}

CaseResult CaseRun::end() {
  history_.end(result_.t_end_s, at_rest_ ? 0.0 : last_y_[0], at_rest_ ? 0.0 : last_y_[1], problem_.side, kEventNone);
  result_.counts = integrator_->counts();
  detail::set_peak_strains(scene_, result_);
  return std::move(result_);
}

void CaseRun::rest_until_uplift() {
  // Both criteria open the frame where the net force at θ₁ = 0 does (see docs/physics.md,
  // "Uplift criteria"): a unilateral contact pushes, it never pulls, so after the paper's
  // trigger a frame still held by its prestress stays closed.
  const double t_stop = end_.rest_end_s(t_);
  const double t_open = t_ < t_stop ? first_opening(excitation_, scene_, t_, t_stop) : std::nan("");
  if (std::isnan(t_open)) {
    emit_rest_until(t_stop);
    t_ = t_stop;
    finish(end_.status(CaseStatus::kAtRest), end_.message());
    return;
  }
  emit_rest_until(t_open);
  t_ = t_open;
  note_uplift(result_, t_open);
  problem_.side = detail::uplift_side(excitation_.at(t_open).horizontal_m_s2);
  const double y0[2] = {0.0, 0.0};
  at_rest_ = false;
  start_flight(t_open, y0, kEventUplift);
}

void CaseRun::start_displaced() {
  const double th = physics_.theta0_rad, w = physics_.omega0_rad_s;
  problem_.side = detail::initial_side(th, w);
  const double y0[2] = {th, w};
  at_rest_ = false;
  note_uplift(result_, 0.0);
  note_theta(0.0, th);
  if (request_.omega_peak) note_omega(0.0, w);
  start_flight(0.0, y0, kEventUplift);
}

inline void CaseRun::start_flight(double t, const double* y, std::uint32_t events) {
  const auto dirs = problem_.directions();
  // A flight leaving θ₁ = 0 with speed v against a closing acceleration a lasts 2v/a.
  // Short flights (late in a Zeno sequence) are shorter than the integrator's own first
  // step guess, which then steps over the whole flight and can lose the return crossing
  // in its interpolant: start with a step that resolves the flight.
  double h0 = 0.0;
  if (y[0] == 0.0 && y[1] != 0.0 && integrator_->takes_first_step()) {
    const double a = std::abs(scene_.rest_acceleration(problem_.ground_at(t), problem_.side));
    const double flight_s = 2.0 * std::abs(y[1]) / a;
    if (std::isfinite(flight_s) && flight_s < 0.01) h0 = flight_s / 16.0;
  }
  integrator_->restart(t, y, dirs.data(), t_end_, h0);
  emit(t, y[0], y[1], events);
}

bool CaseRun::fly() {
  double y[2];
  double t = t_;
  // Advance to the next record sample (kinks of ü_g) when asked, else in chunks so that
  // wall-time limits are honoured; never beyond the next history sample.
  const double dt = excitation_.dt_s();
  double tout = std::min(t_end_, t_ + 1.0);
  if (integrator_->steps_between_samples()) {
    // It stops at the samples itself, without returning.
  } else if (solver_.stop_at_samples && t_ < excitation_.duration_s()) {
    // The next sample strictly after t (a root may leave t a hair below a sample). Not
    // SampleGrid::next_after: past a sample a hair ahead this stops at k·dt + dt, not
    // (k+1)·dt, an ulp apart, and the SUNDIALS answers depend on it at 1e-10.
    double next = (std::floor(t_ / dt) + 1.0) * dt;
    if (next - t_ < 1e-9 * dt) next += dt;
    tout = std::min(tout, next);
    integrator_->set_stop_time(tout);
  } else if (t_ >= excitation_.duration_s()) {
    integrator_->set_stop_time(t_end_);
  }
  // With a history, one step at a time: the rows between steps come from the step's
  // interpolant, and the steps and roots stay those of a run without a history.
  const auto outcome = integrator_->advance(tout, t, y, history_.wanted());
  if (outcome == detail::OdeIntegrator::Outcome::kPending) return false;
  if (outcome != detail::OdeIntegrator::Outcome::kFailure) emit_dense_before(t);
  t_ = t;
  last_y_[0] = y[0];
  last_y_[1] = y[1];
  if (outcome == detail::OdeIntegrator::Outcome::kFailure) {
    finish(CaseStatus::kSolverFailure, integrator_->last_error());
    return true;
  }
  if (!std::isfinite(y[0]) || !std::isfinite(y[1])) {
    finish(CaseStatus::kSolverFailure, "non-finite state at t = " + std::to_string(t) + " s");
    return true;
  }
  if (const char* exceeded = exceeded_budget(solver_, integrator_->counts())) {
    finish(CaseStatus::kSolverFailure, exceeded);
    return true;
  }
  if (outcome == detail::OdeIntegrator::Outcome::kRoot) {
    if (handle_roots(t, y)) return true;
  } else if (history_.wanted() && t >= next_history_time()) {
    emit(t, y[0], y[1]);
  }
  note_theta(t, y[0]);
  if (request_.omega_peak) note_omega(t, y[1]);
  if (t >= t_end_) {
    finish(end_.status(CaseStatus::kRockingAtEnd), end_.message());
  } else if (over_time()) {
    finish(CaseStatus::kTimeLimit, "wall-time limit reached at t = " + std::to_string(t) + " s");
  }
  return true;
}

inline bool CaseRun::handle_roots(double t, double* y) {
  int found[kRootCount] = {0, 0, 0, 0};
  integrator_->root_info(found);
  if (found[kThetaPeak] && !found[kLimit] && std::abs(y[0]) >= stop_.stop_rad()) {
    // A peak beyond the stop angle: |θ₁| crossed it and came back within one step, unseen
    // by the root search (dopri5 checks for this; SUNDIALS' search finds it only when a
    // probe lands beyond). The frame reached the stop angle: never reported as safe.
    stop_at(t, std::copysign(stop_.stop_rad(), y[0]), y[1]);
    return true;
  }
  if (found[kThetaPeak]) {
    note_theta(t, y[0]);
    emit(t, y[0], y[1], kEventThetaPeak);
  }
  if (found[kOmegaPeak] && request_.omega_peak) {
    note_omega(t, y[1]);
    emit(t, y[0], y[1], kEventOmegaPeak);
  }
  if (found[kLimit]) {
    stop_at(t, y[0], y[1]);
    return true;
  }
  if (!found[kImpact]) return false;
  if (problem_.side * y[1] < 0.0) {
    impact(t, y);
    return true;
  }
  // A crossing whose interpolated velocity points away from zero: the flight was below
  // what the tolerances resolve (its θ and θ̇ are noise). The frame is at rest if the
  // force holds it; otherwise the crossing is ignored.
  if (holds_closed(t)) {
    settle(t);
    return true;
  }
  return false;
}

// The case ends at the stop angle: its angle and its speed there count (a history's rows saw
// them), and the stop is an event.
inline void CaseRun::stop_at(double t, double theta, double omega) {
  note_theta(t, theta);
  if (request_.omega_peak) note_omega(t, omega);
  emit(t, theta, omega, kEventStop);
  finish(stop_.status(), stop_.message());
}

inline void CaseRun::impact(double t, double* y) {
  const double omega_before = y[1];
  if (request_.omega_peak) note_omega(t, omega_before);
  emit(t, 0.0, omega_before, kEventImpact);
  note_impact(result_, t);
  const double omega_after = restitution_ * omega_before;
  problem_.side = -problem_.side;
  if (returns_to_rest(t, omega_after)) {
    settle(t);
    return;
  }
  const double y0[2] = {0.0, omega_after};
  start_flight(t, y0);
}

// Return to rest (Zeno). With the ground force below the uplift threshold, the net force
// at θ₁ = 0 pushes the frame back into contact on both sides, with acceleration at least
// a_min. A flight that leaves with speed v lasts at most 2v/a_min, rises at most
// v²/(2 a_min), and the next one leaves with r·v, so the whole remaining sequence ends
// within T = 2v / (a_min (1 − r)). The frame is at rest now when either
//  - T ≤ zeno_time_s: the sequence is over within a negligible time, or
//  - the flight would rise less than rest_rise_rad: a motion too small to count. A physical
//    setting, the same for every preset, so that no solver tolerance decides when a frame
//    rests (or how many impacts it makes).
inline bool CaseRun::returns_to_rest(double t, double omega_after) {
  if (!holds_closed(t) || restitution_ >= 1.0) return false;
  const GroundAcceleration a = problem_.ground_at(t);
  const double a_min = std::min(std::abs(scene_.rest_acceleration(a, -1)), std::abs(scene_.rest_acceleration(a, +1)));
  const double v = std::abs(omega_after);
  const double remaining_s = 2.0 * v / (a_min * (1.0 - restitution_));
  const double rise_rad = v * v / (2.0 * a_min);
  return remaining_s <= physics_.zeno_time_s || rise_rad <= physics_.rest_rise_rad;
}

inline bool CaseRun::holds_closed(double t) {
  return scene_.holds_closed(problem_.ground_at(t));
}

inline void CaseRun::settle(double t) {
  at_rest_ = true;
  t_ = t;
  emit(t, 0.0, 0.0, kEventRest);
}

// Without a history a peak matters only where it raises its maximum: the integrator may
// pass over the peaks that cannot (set_peak_floor); a history records every peak.
inline void CaseRun::note_theta(double t, double theta) {
  if (std::abs(theta) > result_.theta_max_rad) {
    result_.theta_max_rad = std::abs(theta);
    result_.t_theta_max_s = t;
    if (!history_.wanted()) integrator_->set_peak_floor(kThetaPeak, result_.theta_max_rad);
  }
}

inline void CaseRun::note_omega(double t, double omega) {
  if (std::abs(omega) > result_.omega_max_rad_s) {
    result_.omega_max_rad_s = std::abs(omega);
    result_.t_omega_max_s = t;
    if (!history_.wanted()) integrator_->set_peak_floor(kOmegaPeak, result_.omega_max_rad_s);
  }
}

inline void CaseRun::emit(double t, double theta, double omega, std::uint32_t events) {
  if (!history_.wanted()) return;
  history_.add(t, theta, omega, problem_.side, events);
  while (next_history_time() <= t) ++next_history_sample_;
}

inline void CaseRun::emit_dense_before(double t_until) {
  if (!history_.wanted()) return;
  double y[2];
  while (next_history_time() < t_until) {
    const double t = next_history_time();
    integrator_->interpolate(t, y);
    emit(t, y[0], y[1]);
  }
}

void CaseRun::emit_rest_until(double t_until) {
  if (!history_.wanted()) return;
  while (next_history_time() < t_until) emit(next_history_time(), 0.0, 0.0);
}

void CaseRun::finish(CaseStatus status, std::string message) {
  if (status == CaseStatus::kRockingAtEnd && at_rest_) status = CaseStatus::kAtRest;
  result_.status = status;
  result_.message = std::move(message);
  result_.t_end_s = t_;
  done_ = true;
}

inline bool CaseRun::over_time() const {
  if (solver_.wall_time_limit_s <= 0.0) return false;
  return seconds_since(start_) > solver_.wall_time_limit_s;
}

/// A case whose frame rests through the whole record: what CaseRun would report, without
/// its set-up (closing limit, fracture angle, coefficient table, integrator). nullopt when
/// the case needs the full run (it lifts, starts displaced, is broken at rest or records a
/// history).
std::optional<CaseResult> rest_throughout(PreparedFrame& frame, const Excitation& excitation,
                                          const OutputRequest& request, const HistorySink& history) {
  const PhysicsOptions& physics = frame.physics();
  if (history || frame.broken_at_rest() || physics.theta0_rad != 0.0 || physics.omega0_rad_s != 0.0) return std::nullopt;
  const detail::CaseEnd end(excitation, frame.scene().gravity_m_s2(), physics);
  if (end.free_fall) return std::nullopt;  // the full run ends it at the free fall
  const double t_end = end.rest_end_s(0.0);
  if (!std::isnan(first_opening(excitation, frame.scene(), 0.0, t_end))) return std::nullopt;
  CaseResult result = detail::initial_result(frame.scene(), excitation, frame.restitution(), request.omega_peak);
  result.status = CaseStatus::kAtRest;
  result.t_end_s = t_end;
  return result;
}

}  // namespace pcrf::detail
