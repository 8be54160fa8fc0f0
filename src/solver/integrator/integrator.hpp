/// \file integrator.hpp
/// \brief The interface every integrator family implements (owned by none of them): the
/// problem (OdeProblem: the two-state ODE with root functions and their closed forms,
/// RootForm), the integrator (OdeIntegrator) and the record's sample grid (SampleGrid,
/// NextSample). The families sit beside this folder (sundials/, dopri5/, taylor/; the
/// fixed-step contender fixed_rk4/ solves whole cases); registry.cpp lists them. Private to
/// the solver.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf::detail {

/// Set-up or run-time failure inside an integrator (SUNDIALS: what() names the call).
class IntegratorError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Times where the right-hand side has a kink (a record's samples): t = k·dt_s, k < count.
struct SampleGrid {
  double dt_s = 0.0;
  std::size_t count = 0;  ///< 0: none

  /// The next sample strictly after t, +∞ when none is left. One a hair ahead of t (a root
  /// may leave t just below a sample) is passed over: no step that short is worth taking.
  double next_after(double t) const {
    if (count == 0 || !(dt_s > 0.0)) return std::numeric_limits<double>::infinity();
    double k = std::max(std::floor(t / dt_s) + 1.0, 1.0);
    double tb = k * dt_s;
    while (tb <= t || tb - t < 1e-9 * dt_s) tb = ++k * dt_s;
    return k <= static_cast<double>(count - 1) ? tb : std::numeric_limits<double>::infinity();
  }
};

/// SampleGrid::next_after for the times of an integrator's steps, which mostly move forward
/// by one sample: the sample found last, or the one after it, is checked first (no division
/// or floor). The same answer as next_after for any t: a sample that is next for t is next for
/// any later t it still lies a hair ahead of, since every earlier one failed for an earlier t.
class NextSample {
 public:
  explicit NextSample(SampleGrid grid)
      : grid_(grid), last_k_(static_cast<double>(grid.count) - 1.0), min_gap_s_(1e-9 * grid.dt_s) {}

  const SampleGrid& grid() const { return grid_; }

  double after(double t) {
    if (k_ > 0.0 && t >= t_) {
      if (ahead(tb_, t)) return remember(t);
      const double k = k_ + 1.0, tb = k * grid_.dt_s;
      if (ahead(tb, t)) {
        k_ = k, tb_ = tb;
        return remember(t);
      }
    }
    tb_ = grid_.next_after(t);
    k_ = std::isfinite(tb_) ? std::round(tb_ / grid_.dt_s) : 0.0;
    return remember(t);
  }

 private:
  bool ahead(double tb, double t) const { return tb > t && !(tb - t < min_gap_s_); }
  double remember(double t) {
    t_ = t;
    return k_ <= last_k_ ? tb_ : std::numeric_limits<double>::infinity();
  }

  SampleGrid grid_;
  double last_k_;     ///< the last sample's index
  double min_gap_s_;  ///< next_after's hair: 1e-9·dt
  double k_ = 0.0;   ///< the sample last found (k_·dt = tb_); 0: none yet
  double tb_ = 0.0;
  double t_ = 0.0;   ///< the time it was found for
};

/// Root function i of a second-order problem (y[1] = dy[0]/dt) as a closed form of y[0]'s
/// time derivatives: what an integrator whose dense output is a series of y[0] (Taylor
/// steps) evaluates and locates without calling OdeProblem::roots.
struct RootForm {
  static constexpr int kNone = -1;      ///< not a closed form: OdeProblem::roots alone
  static constexpr int kConstant = -2;  ///< g_i = offset, never crossing (an inactive root)
  /// d ≥ 0: g_i = y[0]⁽ᵈ⁾ − offset, or |y[0]⁽ᵈ⁾| − offset when `absolute` (d = 0: y[0], 1: y[1],
  /// 2: dy[1]/dt).
  int derivative = kNone;
  bool absolute = false;
  double offset = 0.0;
};

/// g_i from d = (y[0], y[1], dy[1]/dt, …) at one time; `f` is not kNone.
inline double root_value(const RootForm& f, const double* d) {
  if (f.derivative < 0) return f.offset;
  const double v = d[f.derivative];
  return (f.absolute ? std::abs(v) : v) - f.offset;
}

/// The ODE y' = f(t, y), y ∈ ℝ², with root functions g(t, y) ∈ ℝⁿ.
class OdeProblem {
 public:
  virtual ~OdeProblem() = default;
  /// Returns 0 on success, > 0 for a recoverable failure (the integrator retries with a
  /// smaller step), < 0 for an unrecoverable one.
  virtual int rhs(double t, const double* y, double* ydot) = 0;
  virtual int roots(double t, const double* y, double* g) = 0;
  virtual int root_count() const = 0;
  /// Root function i as a closed form (see RootForm); kNone by default.
  virtual RootForm root_form(int /*i*/) const { return {}; }
  /// The state component that root function i is (g_i = y[k]), or −1 when it is anything
  /// else: by default read from root_form(). An integrator with dense output may locate such
  /// a root on the interpolant alone, without calling roots() at every probe.
  virtual int root_state_index(int i) const {
    const RootForm f = root_form(i);
    return (f.derivative == 0 || f.derivative == 1) && !f.absolute && f.offset == 0.0 ? f.derivative : -1;
  }
  /// The first root function that is state component k (root_state_index), −1 when none.
  int root_of_state(int k) const {
    for (int i = 0; i < root_count(); ++i)
      if (root_state_index(i) == k) return i;
    return -1;
  }
  /// ∂f/∂y, row-major 2×2, for implicit methods. Returns 0 on success; a problem without
  /// an analytic Jacobian returns −1 from has_jacobian() == false (difference quotients).
  virtual bool has_jacobian() const { return false; }
  virtual int jacobian(double /*t*/, const double* /*y*/, double* /*dfdy*/) { return -1; }
  /// f(t, y) = ydot was evaluated outside rhs() (by a batch kernel): a problem that
  /// remembers its last evaluation may take this one.
  virtual void evaluated(double /*t*/, const double* /*y*/, const double* /*ydot*/) {}
  /// Highest order of taylor(); 0: the problem has no Taylor series.
  virtual int taylor_order_max() const { return 0; }
  /// The Taylor coefficients a₀…a_order of y[0](t0 + τ), y[1] = dy[0]/dt, valid for τ in
  /// [0, h] (the forcing is smooth there). `for_any_h` says they hold for any shorter step
  /// too (else a shorter step needs new ones). False when not finite or not available.
  virtual bool taylor(double /*t0*/, const double* /*y0*/, double /*h*/, int /*order*/, double* /*a*/,
                      bool& /*for_any_h*/) {
    return false;
  }
};

class OdeIntegrator {
 public:
  /// kPending: only in DormandPrinceIntegrator's lockstep, a step attempt awaits the caller.
  enum class Outcome { kReachedTime, kRoot, kFailure, kPending };

  virtual ~OdeIntegrator() = default;
  OdeIntegrator() = default;
  OdeIntegrator(const OdeIntegrator&) = delete;
  OdeIntegrator& operator=(const OdeIntegrator&) = delete;

  /// Restarts at (t0, y0); `root_dirs` has root_count() entries (−1, 0, +1). A positive
  /// `h0` fixes the first step (0: the integrator's own estimate).
  virtual void restart(double t0, const double* y0, const int* root_dirs, double t_stop, double h0) = 0;
  /// Moves the stop time (no restart): the integrator will not step beyond it.
  virtual void set_stop_time(double t_stop) = 0;
  /// Integrates towards tout (never beyond the stop time); on return t and y hold the
  /// state reached. kRoot: root_info() says which roots were found. `one_step`: return
  /// after a single internal step (its end, or a root or the stop time within it) — the
  /// same steps and roots as without it, and interpolate() then covers [previous return, t].
  virtual Outcome advance(double tout, double& t, double* y, bool one_step = false) = 0;
  /// The state at t from the integrator's interpolant of its last step (dense output).
  virtual void interpolate(double t, double* y) = 0;
  /// found[i] ≠ 0 when root i was found at the last kRoot return.
  virtual void root_info(int* found) = 0;
  /// Counters summed over every restart.
  virtual SolverCounts counts() = 0;
  /// Text of the last failure.
  virtual const std::string& last_error() const = 0;
  /// True when the integrator itself never steps across the sample grid it was made with,
  /// so its caller need not stop it at every sample.
  virtual bool steps_between_samples() const { return false; }
  /// False when restart() does not use `h0` (the caller need not estimate one).
  virtual bool takes_first_step() const { return true; }
  /// Root `root` (a zero of y[0]'s first or second derivative: a peak of |y[0]| or |y[1]|)
  /// matters only where that magnitude may exceed `floor` (the caller's running maximum of
  /// it). An integrator that can bound the magnitude over a step may pass over the root's
  /// crossings in a step whose bound is below (the Taylor steps do); the others locate every
  /// one, as with the default floor, −∞.
  virtual void set_peak_floor(int /*root*/, double /*floor*/) {}
};

}  // namespace pcrf::detail
