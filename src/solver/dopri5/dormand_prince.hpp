/// \file dormand_prince.hpp
/// \brief The purpose-built integrator of the rocking scenes: Dormand–Prince 5(4) with its
/// dense output, stepping between record samples, events located on the dense output.
/// Private to the solver.
///
/// Method:
///  - the explicit Runge–Kutta pair of J. R. Dormand and P. J. Prince, "A family of embedded
///    Runge–Kutta formulae", J. Comput. Appl. Math. 6 (1980) 19–26 (seven stages, first
///    same as last: six right-hand-side evaluations per accepted step), propagating the
///    5th-order solution;
///  - its 4th-order continuous extension by L. F. Shampine, "Some practical Runge–Kutta
///    formulas", Math. Comp. 46 (1986) 135–150, in the form of E. Hairer, S. P. Nørsett and
///    G. Wanner, Solving Ordinary Differential Equations I, 2nd ed., Springer 1993, §II.6
///    (DOPRI5's CONTD5);
///  - the step-size control of the same book, §II.4 and §IV.2: the error of the embedded
///    4th-order solution in the weighted RMS norm with weights atol_i + rtol·max(|y_i|,
///    |ŷ_i|), a PI controller (β = 0.04, safety 0.9, factor bounds 0.2…10), and the starting
///    step of §II.4 (two right-hand-side evaluations) unless the caller gives one;
///  - root functions checked for sign changes at step ends (directional, as SUNDIALS' root
///    finding), and each crossing located on the dense output (root_search.hpp) to 100 ulp of
///    the time, reporting the bracket's far end as SUNDIALS does: a root that is a state
///    component (the rocking problem's θ and θ̇) by Newton's method on the interpolant, with
///    no call of the problem; any other by the Illinois variant of regula falsi (M. Dowell and
///    P. Jarratt, BIT 11 (1971) 168–174) on OdeProblem::roots at the interpolated state.
///
/// The breakpoints (the record's samples, where ü_g has a kink) are part of the integrator:
/// no step crosses one, and the step size the controller wanted is kept across it, so the
/// integrator runs sample to sample without returning to its caller and without a restart
/// (the right-hand side is continuous at a kink: the last stage of a step is still the first
/// of the next). No heap allocation after construction; no N_Vector.
///
/// In lockstep (set_lockstep, the batch of src/solver/lanes/) the integrator does not compute
/// its step attempts: advance() returns kPending with the attempt's inputs in attempt(); the
/// caller fills its outputs (the same arithmetic, dopri5_attempt.hpp, for many cases at once)
/// and calls take_attempt(), then advance() again. Everything else — the step-size control,
/// the roots, the breakpoints — is this class's, in both modes.
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "dopri5_attempt.hpp"
#include "../integrator/integrator.hpp"
#include "../integrator/root_search.hpp"

namespace pcrf::detail {

/// One step attempt: what the integrator sets (t0, h, y0, k1) and what it takes back.
struct Dopri5Attempt {
  double t0 = 0.0, h = 0.0;
  double y0[2] = {0.0, 0.0}, k1[2] = {0.0, 0.0};
  Dopri5Stages<double> out{};
  bool ok = false;  ///< every stage succeeded, the error and solution are finite
  long evals = 0;   ///< right-hand-side calls made
};

class DormandPrinceIntegrator final : public OdeIntegrator {
 public:
  /// At most this many root functions.
  static constexpr int kMaxRoots = 8;

  /// `breakpoints`: no step crosses t = k·dt_s for k < count (0 count: none).
  /// \throws IntegratorError when the problem has more than kMaxRoots roots.
  DormandPrinceIntegrator(const SolverSettings& settings, OdeProblem& problem, SampleGrid breakpoints);

  void restart(double t0, const double* y0, const int* root_dirs, double t_stop, double h0) override;
  void set_stop_time(double t_stop) override { t_stop_ = t_stop; }
  Outcome advance(double tout, double& t, double* y, bool one_step) override;
  void interpolate(double t, double* y) override;
  void root_info(int* found) override;
  SolverCounts counts() override { return counts_; }
  const std::string& last_error() const override { return error_; }
  bool steps_between_samples() const override { return next_sample_.grid().count > 0; }

  /// Lockstep: step attempts are made by the caller (see above).
  void set_lockstep(bool on) { lockstep_ = on; }
  /// The pending attempt: its inputs set, its outputs for the caller to fill.
  Dopri5Attempt& attempt() { return attempt_; }
  /// Concludes the pending attempt from its outputs (accepted, or the next attempt made).
  void take_attempt();
  /// After take_attempt(): when the call of advance() that the caller would make next (with
  /// the tout and one_step of the last one, which returned kPending) would only step on to
  /// its next attempt — a rejected attempt, or no root in the step and tout and the stop
  /// time beyond it — does that and returns true (an attempt pending again, or a failed step
  /// that advance() reports); else false, nothing changed. The batch's shortcut past the
  /// case between two attempts.
  bool continue_alone();

  /// Work of the root search, for benchmarks: steps with a sign change to locate, roots returned.
  struct Tally {
    long root_searches = 0;
    long roots = 0;
  };
  const Tally& tally() const { return tally_; }

 private:
  using Vec = std::array<double, 2>;

  /// The attempt in attempt_ (one case): the right-hand side from the problem.
  void try_step();
  /// Takes one accepted step (with retries); false on failure (error_ set). In lockstep, true
  /// with an attempt pending.
  bool step();
  /// Attempts from h_trial_ until one is accepted (true), pending (true) or failure (false).
  bool attempt_until_accepted();
  /// Sets the next attempt's inputs from h_trial_; false on failure (error_ set).
  bool prepare_attempt();
  /// prepare_attempt's failure: too many attempts, or a step too small.
  [[gnu::cold, gnu::noinline]] bool fail_attempt();
  /// The attempt's outcome: accepted (true), or rejected with h_trial_ shrunk (false).
  bool conclude_attempt();
  void accept();
  /// The starting step of Hairer, Nørsett & Wanner §II.4.
  double initial_step();
  /// Whether some root function may cross between a and b (g_a, g_b its values there).
  bool root_candidate(const double* g_a, const double* g_b) const {
    bool candidate = false;
    for (int i = 0; i < nroots_; ++i) candidate = candidate || (g_a[i] != 0.0 && g_a[i] * g_b[i] <= 0.0);
    return candidate;
  }
  /// Looks for the earliest root crossing in (a, b] of the current step, from g_a at a
  /// (root_search.hpp). Fills root_time_, found_ and g_root_ and returns true when one exists.
  bool find_roots(double a, const double* g_a, double b, const double* g_b);
  /// Narrows [lo, hi] (values glo, ghi of opposite signs) around the root of function i to
  /// ttol: Newton on the interpolant for a state component, else the Illinois method
  /// (root_search.hpp: newton_in_bracket, illinois_in_bracket).
  void locate(int i, double& lo, double& glo, double& hi, double& ghi, double ttol);
  /// g at time t of the current step, from the dense output.
  bool roots_at(double t, double* g);
  void dense(double t, Vec& y) const;
  /// Component i of the Runge–Kutta dense output at t (within a step), and its time
  /// derivative: the polynomial c₀ + s c₁ + s s₁ c₂ + s² s₁ c₃ + s² s₁² c₄, s = (t − t₀)/h,
  /// s₁ = 1 − s.
  /// Defined here: they sit in the root search's inner loop.
  double dense_component(double t, int i) const {
    const double s = (t - t0_) / h_step_, s1 = 1.0 - s;
    const auto k = static_cast<std::size_t>(i);
    const auto& c = attempt_.out.cont;
    return c[0][k] + s * (c[1][k] + s1 * (c[2][k] + s * (c[3][k] + s1 * c[4][k])));
  }
  double dense_slope(double t, int i) const {
    const double s = (t - t0_) / h_step_, s1 = 1.0 - s;
    const auto k = static_cast<std::size_t>(i);
    const auto& c = attempt_.out.cont;
    return (c[1][k] + (1.0 - 2.0 * s) * c[2][k] + s * (2.0 - 3.0 * s) * c[3][k] + 2.0 * s * s1 * (s1 - s) * c[4][k]) /
           h_step_;
  }
  /// dense_component and dense_slope together.
  void dense_value_slope(double t, int i, double& v, double& slope) const {
    v = dense_component(t, i), slope = dense_slope(t, i);
  }
  /// The error weight atol_i + rtol·magnitude of component i.
  double weight(int i, double magnitude) const { return atol_[static_cast<std::size_t>(i)] + settings_.rtol * magnitude; }
  bool fail(const std::string& text);

  SolverSettings settings_;
  OdeProblem& problem_;
  NextSample next_sample_;  ///< the breakpoints, and the next after a step's start
  int nroots_;
  int velocity_root_;  ///< the root function that is y[1] (θ̇), located first; −1: none
  std::array<double, 2> atol_;  ///< atol_θ [rad], atol_ω [rad/s]
  std::array<int, kMaxRoots> dirs_{};
  double t_stop_ = 0.0;

  // The current step [t0_, t1_] and its dense output; the position tcur_ within it.
  double t0_ = 0.0, t1_ = 0.0, tcur_ = 0.0;
  Vec y0_{}, y1_{}, k1_{}, k7_{};
  double h_step_ = 0.0;        ///< t1_ − t0_
  bool have_step_ = false;
  std::array<double, kMaxRoots> g_cur_{};  ///< root functions at tcur_
  std::array<double, kMaxRoots> g_end_{};  ///< root functions at t1_
  std::array<double, kMaxRoots> g_root_{};  ///< root functions at root_time_

  double h_ = 0.0;        ///< the step the controller proposes next
  double log_err_old_ = 0.0;  ///< log of the previous accepted error norm (PI control)

  std::array<int, kMaxRoots> found_{};
  double root_time_ = 0.0;
  SolverCounts counts_;
  std::string error_;

  // The step being attempted: the breakpoint or stop time it may not cross, the step the
  // controller wants, the one tried (shortened to land on the limit: clamped). Once
  // accepted, its continuous extension is the dense output until the next step.
  Dopri5Attempt attempt_;
  double limit_ = 0.0, h_trial_ = 0.0, h_try_ = 0.0;
  bool clamped_ = false, rejected_ = false;
  int failures_ = 0;
  bool lockstep_ = false;

  bool pending_ = false;         ///< lockstep: an attempt awaits take_attempt()
  bool attempt_failed_ = false;  ///< lockstep: the step failed for good (error_ says why)
  double pending_tout_ = 0.0;    ///< lockstep: tout and one_step of the advance() that returned kPending
  bool pending_one_step_ = false;
  Tally tally_;
};

}  // namespace pcrf::detail
