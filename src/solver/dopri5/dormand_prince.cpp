// Dormand–Prince 5(4) with dense output, breakpoints and events (see dormand_prince.hpp).
// The parts of a step are `inline`: the library is built with -fPIC, where GCC inlines no
// function that could be interposed, and a step is the hot loop of every case.
#include "dormand_prince.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pcrf/number_text.hpp"

namespace pcrf::detail {
namespace {

const double kLogErrFloor = std::log(1e-4);  // err_old ≥ 1e-4 in the PI control

}  // namespace

DormandPrinceIntegrator::DormandPrinceIntegrator(const SolverSettings& settings, OdeProblem& problem,
                                                 SampleGrid breakpoints)
    : settings_(settings),
      problem_(problem),
      next_sample_(breakpoints),
      nroots_(problem.root_count()),
      velocity_root_(problem.root_of_state(1)),
      atol_{settings.atol_theta_rad, settings.atol_omega_rad_s} {
  if (nroots_ < 0 || nroots_ > kMaxRoots) throw IntegratorError("dopri5: too many root functions");
}

void DormandPrinceIntegrator::restart(double t0, const double* y0, const int* root_dirs, double t_stop, double h0) {
  if (counts_.steps > 0 || counts_.rhs_evals > 0) ++counts_.reinits;
  t0_ = t1_ = tcur_ = t0;
  y0_ = y1_ = {y0[0], y0[1]};
  t_stop_ = t_stop;
  have_step_ = false;
  pending_ = attempt_failed_ = false;
  log_err_old_ = kLogErrFloor;
  error_.clear();
  std::fill(found_.begin(), found_.end(), 0);
  for (int i = 0; i < nroots_; ++i) dirs_[static_cast<std::size_t>(i)] = root_dirs[i];
  ++counts_.rhs_evals;
  if (problem_.rhs(t0, y0_.data(), k1_.data()) != 0) {
    fail("dopri5: the right-hand side failed at the start, t = " + number_text(t0) + " s");
    k1_ = {std::nan(""), std::nan("")};
  }
  k7_ = k1_;
  // After an impact the flight goes on at the same time scale: the last step is a better
  // start than a fresh estimate (which costs a right-hand side).
  if (h0 > 0.0) {
    h_ = h0;
  } else if (!(counts_.steps > 0 && h_ > 0.0)) {
    h_ = initial_step();
  }
  // Root functions at the start. One that is zero there is judged a little later, on the
  // Euler extrapolation (as SUNDIALS does): a flight leaving θ₁ = 0 takes the sign it
  // moves into, and a function still zero stays inactive until it moves away from zero.
  ++counts_.root_evals;
  problem_.roots(t0, y0_.data(), g_cur_.data());
  bool zero = false;
  for (int i = 0; i < nroots_; ++i) zero = zero || g_cur_[static_cast<std::size_t>(i)] == 0.0;
  if (zero && std::isfinite(k1_[0])) {
    const double dt = std::max(root_tolerance(t0, h_), 0.1 * h_);
    const Vec y = {y0_[0] + dt * k1_[0], y0_[1] + dt * k1_[1]};
    std::array<double, kMaxRoots> g{};
    ++counts_.root_evals;
    problem_.roots(t0 + dt, y.data(), g.data());
    for (int i = 0; i < nroots_; ++i) {
      auto k = static_cast<std::size_t>(i);
      if (g_cur_[k] == 0.0) g_cur_[k] = g[k];
    }
  }
}

double DormandPrinceIntegrator::initial_step() {
  // Hairer, Nørsett & Wanner §II.4, "Starting step size" (DOPRI5's HINIT), order 5.
  double hmax = t_stop_ - t0_;
  if (settings_.max_step_s > 0.0) hmax = std::min(hmax, settings_.max_step_s);
  if (!(hmax > 0.0)) return 0.0;
  double dnf = 0.0, dny = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double sk = weight(i, std::abs(y0_[i]));
    dnf += (k1_[i] / sk) * (k1_[i] / sk);
    dny += (y0_[i] / sk) * (y0_[i] / sk);
  }
  double h = dnf <= 1e-10 || dny <= 1e-10 ? 1e-6 : std::sqrt(dny / dnf) * 0.01;
  h = std::min(h, hmax);
  const Vec y1 = {y0_[0] + h * k1_[0], y0_[1] + h * k1_[1]};
  Vec f1{};
  ++counts_.rhs_evals;
  if (problem_.rhs(t0_ + h, y1.data(), f1.data()) != 0) return h;
  double der2 = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double sk = weight(i, std::abs(y0_[i]));
    der2 += ((f1[i] - k1_[i]) / sk) * ((f1[i] - k1_[i]) / sk);
  }
  der2 = std::sqrt(der2 / 2.0) / h;
  const double der12 = std::max(std::abs(der2), std::sqrt(dnf / 2.0));
  const double h1 = der12 <= 1e-15 ? std::max(1e-6, std::abs(h) * 1e-3) : std::pow(0.01 / der12, 0.2);
  return std::min({100.0 * h, h1, hmax});
}

namespace {

/// dopri5_attempt's operations on one double.
struct ScalarOps {
  using P = double;
  using M = bool;
  static P select(M m, P a, P b) { return m ? a : b; }
  static M finite(P v) { return std::isfinite(v); }
  static P abs(P v) { return std::abs(v); }
  static P sqrt(P v) { return std::sqrt(v); }
  static bool none(M m) { return !m; }
};

}  // namespace

inline void DormandPrinceIntegrator::try_step() {
  // Inputs in locals: the right-hand side is a virtual call, after which members would be
  // read again.
  const double t = attempt_.t0, h = attempt_.h;
  const double y0[2] = {attempt_.y0[0], attempt_.y0[1]}, k1[2] = {attempt_.k1[0], attempt_.k1[1]};
  const double atol[2] = {atol_[0], atol_[1]};
  long evals = 0;
  auto f = [&](double ts, const double* s, double* k, bool& alive) {  // called while alive
    ++evals;
    alive = problem_.rhs(ts, s, k) == 0;
  };
  attempt_.ok = dopri5_attempt<ScalarOps>(t, h, y0, k1, atol, settings_.rtol, f, attempt_.out);
  attempt_.evals = evals;
}

bool DormandPrinceIntegrator::step() {
  t0_ = tcur_;
  y0_ = y1_;
  k1_ = k7_;
  if (!std::isfinite(k1_[0]) || !std::isfinite(k1_[1])) return fail(error_.empty() ? "dopri5: non-finite derivative" : error_);
  limit_ = std::min(next_sample_.after(t0_), t_stop_);
  h_trial_ = h_;
  if (settings_.max_step_s > 0.0) h_trial_ = std::min(h_trial_, settings_.max_step_s);
  rejected_ = false;
  failures_ = 0;
  return attempt_until_accepted();
}

inline bool DormandPrinceIntegrator::attempt_until_accepted() {
  for (;;) {
    if (!prepare_attempt()) return false;
    if (lockstep_) {
      pending_ = true;
      return true;
    }
    try_step();
    if (conclude_attempt()) return true;
  }
}

inline bool DormandPrinceIntegrator::prepare_attempt() {
  if (failures_ > kMaxFailures) return fail_attempt();
  // Land on the breakpoint (or stop time) when the step would reach it or nearly so.
  clamped_ = t0_ + 1.01 * h_trial_ >= limit_;
  h_try_ = clamped_ ? limit_ - t0_ : h_trial_;
  if (!(h_try_ > 16.0 * kEps * std::abs(t0_)) || !(h_try_ > 0.0)) return fail_attempt();
  attempt_.t0 = t0_, attempt_.h = h_try_;
  attempt_.y0[0] = y0_[0], attempt_.y0[1] = y0_[1];
  attempt_.k1[0] = k1_[0], attempt_.k1[1] = k1_[1];
  return true;
}

bool DormandPrinceIntegrator::fail_attempt() {
  if (failures_ > kMaxFailures)
    return fail("dopri5: " + std::to_string(kMaxFailures) + " failed step attempts in a row at t = " + number_text(t0_) + " s");
  return fail("dopri5: step size " + number_text(h_try_) + " s too small at t = " + number_text(t0_) + " s");
}

inline bool DormandPrinceIntegrator::conclude_attempt() {
  counts_.rhs_evals += attempt_.evals;
  const double err = attempt_.out.err;
  if (!attempt_.ok) {  // the mechanism does not exist at a stage: shrink
    h_trial_ = 0.25 * h_try_;
  } else if (err > 1.0) {
    h_trial_ = h_try_ / std::min(1.0 / kFacMin, std::pow(err, kExpo) / kSafety);
  } else {
    accept();
    return true;
  }
  rejected_ = true;
  ++failures_;
  return false;
}

void DormandPrinceIntegrator::take_attempt() {
  pending_ = false;
  if (conclude_attempt()) {
    // The last stage was f at the step's end: a problem that remembers it need not redo it.
    problem_.evaluated(t0_ + 1.0 * h_try_, attempt_.out.y1, attempt_.out.k7);
    problem_.roots(t1_, y1_.data(), g_end_.data());
    return;
  }
  if (!attempt_until_accepted()) attempt_failed_ = true;
}

inline void DormandPrinceIntegrator::accept() {
  // A step cut short by a breakpoint says little about the step the solution allows: the
  // one the controller proposed before it is kept unless the PI control of this step
  // proposes a longer one, which it cannot when even its largest growth (kFacMax) stays
  // below (no pow() then: most steps of a record end at a sample).
  const double err = attempt_.out.err;
  const double log_err = std::log(std::max(err, 1e-300));
  if (clamped_ && kFacMax * h_try_ <= h_trial_) {
    h_ = h_trial_;
  } else {
    // err^α / err_old^β, with one exp instead of two pow().
    double fac = std::exp(kExpo * log_err - kBeta * log_err_old_) / kSafety;
    fac = std::clamp(fac, 1.0 / kFacMax, 1.0 / kFacMin);
    double h_next = h_try_ / fac;
    if (rejected_) h_next = std::min(h_next, h_try_);
    h_ = clamped_ ? std::max(h_next, h_trial_) : h_next;
  }
  log_err_old_ = std::max(log_err, kLogErrFloor);
  t1_ = clamped_ ? limit_ : t0_ + h_try_;
  y1_ = {attempt_.out.y1[0], attempt_.out.y1[1]};
  k7_ = {attempt_.out.k7[0], attempt_.out.k7[1]};
  h_step_ = h_try_;
  have_step_ = true;
  ++counts_.steps;
  ++counts_.root_evals;
  if (!lockstep_) problem_.roots(t1_, y1_.data(), g_end_.data());
}

void DormandPrinceIntegrator::dense(double t, Vec& y) const {
  if (!have_step_) {
    y = y1_;
    return;
  }
  for (int i = 0; i < 2; ++i) y[i] = dense_component(t, i);
}

bool DormandPrinceIntegrator::roots_at(double t, double* g) {
  Vec y{};
  dense(t, y);
  ++counts_.root_evals;
  return problem_.roots(t, y.data(), g) == 0;
}

void DormandPrinceIntegrator::locate(int i, double& lo, double& glo, double& hi, double& ghi, double ttol) {
  // A root that is a state component: Newton on the interpolant, no call of the problem.
  const int component = problem_.root_state_index(i);
  if (component >= 0) {
    newton_in_bracket([&](double t, double& v, double& slope, double&) { dense_value_slope(t, component, v, slope); },
                      lo, glo, hi, ghi, ttol);
  } else {
    illinois_in_bracket<kMaxRoots>([this](double t, double* g) { return roots_at(t, g); }, i, lo, glo, hi, ghi, ttol);
  }
}

bool DormandPrinceIntegrator::find_roots(double a, const double* g_a, double b, const double* g_b) {
  auto roots_at = [this](double t, double* g) { return this->roots_at(t, g); };
  auto locate = [this](int i, double& lo, double& glo, double& hi, double& ghi, double ttol) {
    this->locate(i, lo, glo, hi, ghi, ttol);
  };
  if (!earliest_crossing(nroots_, dirs_, velocity_root_, a, g_a, b, g_b, root_tolerance(b, h_step_), roots_at, locate,
                         root_time_, found_, g_root_))
    return false;
  ++tally_.root_searches;
  return true;
}

bool DormandPrinceIntegrator::continue_alone() {
  // advance()'s loop below, taken only where it would return nothing before its next attempt.
  if (pending_) return true;  // a rejected attempt: the next one is pending already
  if (attempt_failed_ || !have_step_ || !(tcur_ < t1_) || pending_one_step_) return false;
  if (root_candidate(g_cur_.data(), g_end_.data())) return false;
  if (!(t1_ < pending_tout_)) return false;
  if (t_stop_ - t1_ <= 16.0 * kEps * std::max(1.0, std::abs(t_stop_)) || counts_.steps > settings_.max_steps) return false;
  tcur_ = t1_;
  g_cur_ = g_end_;
  step();
  if (!pending_) attempt_failed_ = true;  // error_ says why; advance() reports it at tcur_
  return true;
}

OdeIntegrator::Outcome DormandPrinceIntegrator::advance(double tout, double& t, double* y, bool one_step) {
  pending_tout_ = tout, pending_one_step_ = one_step;
  if (pending_) return Outcome::kPending;
  if (attempt_failed_) {  // lockstep: the step that take_attempt() went on with failed
    attempt_failed_ = false;
    t = tcur_;
    y[0] = y1_[0], y[1] = y1_[1];
    return Outcome::kFailure;
  }
  for (;;) {
    if (!have_step_ || tcur_ >= t1_) {
      // A root may leave the state a few ulp short of the stop time: no step that short
      // exists, so the state is taken as the stop time's.
      if (t_stop_ - tcur_ <= 16.0 * kEps * std::max(1.0, std::abs(t_stop_))) tcur_ = std::max(tcur_, t_stop_);
      if (tcur_ >= t_stop_) {
        t = tcur_;
        y[0] = y1_[0], y[1] = y1_[1];
        return Outcome::kReachedTime;
      }
      if (counts_.steps > settings_.max_steps) {
        fail("more than max_steps steps");
      } else {
        step();
      }
      if (pending_) return Outcome::kPending;
      if (!error_.empty()) {
        t = tcur_;
        y[0] = y1_[0], y[1] = y1_[1];
        return Outcome::kFailure;
      }
    }
    // Roots in (tcur_, t1_] of the current step.
    if (find_roots(tcur_, g_cur_.data(), t1_, g_end_.data())) {
      Vec yr{};
      dense(root_time_, yr);
      tcur_ = root_time_;
      g_cur_ = g_root_;
      ++tally_.roots;
      t = tcur_;
      y[0] = yr[0], y[1] = yr[1];
      return Outcome::kRoot;
    }
    if (tout < t1_) {  // tout inside the step: the state there; the step goes on
      Vec yo{};
      dense(tout, yo);
      tcur_ = tout;
      g_cur_ = g_end_;  // no root in between: the signs are those at the step's end
      // y1_ keeps the step's end: the next call continues within the step.
      t = tout;
      y[0] = yo[0], y[1] = yo[1];
      return Outcome::kReachedTime;
    }
    tcur_ = t1_;
    g_cur_ = g_end_;
    if (tcur_ >= tout || one_step) {
      t = tcur_;
      y[0] = y1_[0], y[1] = y1_[1];
      return Outcome::kReachedTime;
    }
  }
}

void DormandPrinceIntegrator::interpolate(double t, double* y) {
  Vec v{};
  dense(t, v);
  y[0] = v[0], y[1] = v[1];
}

void DormandPrinceIntegrator::root_info(int* found) {
  for (int i = 0; i < nroots_; ++i) found[i] = found_[static_cast<std::size_t>(i)];
}

bool DormandPrinceIntegrator::fail(const std::string& text) {
  error_ = text;
  return false;
}

}  // namespace pcrf::detail
