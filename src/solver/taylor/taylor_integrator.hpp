/// \file taylor_integrator.hpp
/// \brief Taylor steps: the integrator `taylor` for a problem that expands its solution as a
/// series (the rigid rockers), stepping between record samples, events located on the
/// series. Private to the solver.
///
/// Method:
///  - a step is the problem's Taylor series of y[0] (OdeProblem::taylor) to a fixed order n,
///    the forcing linear over the record interval (for a rigid rocker: one sincos and about
///    n² products, the recurrences of A. Jorba & M. Zou, "A software package for the
///    numerical integration of ODEs by means of high-order Taylor methods", Exp. Math. 14
///    (2005) 99–117, §3);
///  - the step goes to the next breakpoint (record sample) when the series' last two terms
///    there, in the weighted norm of dopri5 (atol_i + rtol·|y_i|), are within the tolerance;
///    otherwise to where they would be, the estimate of Jorba & Zou §3.2 (without their e⁻²
///    safety: the terms, not the radius, are bounded). No rejected attempts and no step-size
///    history: each step is sized by its own series;
///  - the order grows slowly with the tolerance, n = ⌈−log₁₀(rtol)/3⌉ + 4 (6 at rtol 1e-4, 7
///    at 1e-7): most steps end at a record sample, where a lower order than Jorba & Zou's
///    ⌈−ln(rtol)/2⌉ + 1 (which minimises the work per unit time of free steps) already meets
///    the tolerance;
///  - the series is the dense output, and every root function is a closed form of it
///    (OdeProblem::root_form: θ₁, θ̇₁, θ̈₁, |θ₁| − θ_stop): the functions at a step's end, and
///    each probe of a root search, are one Horner pass over the series, with no call of the
///    problem. Crossings are found as by dopri5 (root_search.hpp) and located, to 100 ulp of
///    the time, by the steps of the series' local quadratic (model_step: value, slope and
///    curvature from one Horner pass; cubic convergence, and no slow approach to a root where
///    the slope vanishes, as a flight's θ̇ where the ground is near the uplift threshold). The
///    first probe is the quadratic's root at the bracket's start when the derivatives there
///    are known without an evaluation (the step's start: the coefficients; an earlier root
///    of the step: its probe), so a search takes two probes, three near a double root;
///  - a peak root (θ̇ or θ̈) whose magnitude cannot reach its floor over a step (set_peak_floor:
///    the running maximum, when the caller keeps no history) is left out of that step's
///    search: the series bounds |θ| or |θ̇| by Σ k!/(k − m)! |a_k| h^(k−m).
///
/// The breakpoints are part of the integrator: no step crosses one (the series holds within
/// one record interval), so the integrator runs sample to sample without returning to its
/// caller. No heap allocation after construction.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "../integrator/integrator.hpp"

namespace pcrf::detail {

class TaylorIntegrator final : public OdeIntegrator {
 public:
  /// At most this many root functions.
  static constexpr int kMaxRoots = 8;
  /// The highest order (the series' order at rtol = ε is 10).
  static constexpr int kOrderMax = 12;

  /// `breakpoints`: no step crosses t = k·dt_s for k < count.
  /// \throws IntegratorError when the problem has no series, more than kMaxRoots roots, or a
  /// root function that is not a closed form of the series (OdeProblem::root_form).
  TaylorIntegrator(const SolverSettings& settings, OdeProblem& problem, SampleGrid breakpoints);

  /// `h0` is not used: every step is sized by its own series.
  void restart(double t0, const double* y0, const int* root_dirs, double t_stop, double h0) override;
  void set_stop_time(double t_stop) override;
  Outcome advance(double tout, double& t, double* y, bool one_step) override;
  void interpolate(double t, double* y) override;
  void root_info(int* found) override;
  SolverCounts counts() override { return counts_; }
  const std::string& last_error() const override { return error_; }
  bool steps_between_samples() const override { return next_sample_.grid().count > 0; }
  bool takes_first_step() const override { return false; }
  /// Crossings of a θ̇ or θ̈ root (RootForm derivative 1 or 2, not absolute) are passed over in
  /// a step where the series bounds |θ| or |θ̇| below `floor` (peak_bound); for other roots the
  /// floor is ignored.
  void set_peak_floor(int root, double floor) override;

  /// The series' order.
  int order() const { return order_; }
  /// The order that follows a relative tolerance (see above), within [3, order_max].
  static int order_for(double rtol, int order_max);

 private:
  /// y[0]'s series and its derivatives 0 … D at τ = t − t0_ (d[k] = dᵏy[0]/dtᵏ).
  template <int D>
  void at(double tau, double* d) const {
    switch (order_) {
      case 5: horner<5, D>(tau, d); break;
      case 6: horner<6, D>(tau, d); break;
      case 7: horner<7, D>(tau, d); break;
      case 8: horner<8, D>(tau, d); break;
      default: horner<kOrderMax, D>(tau, d); break;  // the coefficients above the order are zero
    }
  }
  /// Horner's scheme with derivatives over N + 1 coefficients, unrolled (the presets' orders
  /// have their own): it runs at every step's end and root probe.
  template <int N, int D>
  void horner(double tau, double* d) const {
    double p[D + 1];
    p[0] = a_[N];
    for (int j = 1; j <= D; ++j) p[j] = 0.0;
#pragma GCC unroll 16
    for (int k = N - 1; k >= 0; --k) {
#pragma GCC unroll 4
      for (int j = D; j >= 1; --j) p[j] = p[j] * tau + p[j - 1];
      p[0] = p[0] * tau + a_[static_cast<std::size_t>(k)];
    }
    double factorial = 1.0;
    d[0] = p[0];
    for (int j = 1; j <= D; ++j) factorial *= j, d[j] = p[j] * factorial;
  }

  /// One step from tcur_ (the series, its size, the state and root functions at its end);
  /// false on failure (error_ set).
  bool step();
  /// Whether the series' truncation estimate over [0, h] is within the tolerance (in the
  /// weighted norm); if not, `h_fit`: the step at which it would be.
  bool within_tolerance(double h, double& h_fit);
  /// The step at which the truncation estimate would be within the tolerance (out of line:
  /// rarely needed).
  [[gnu::noinline]] double fitting_step(double h, double an1, double an, double w0, double w1) const;
  /// The stop time, and the slack within which a time a few ulp short of it is taken as it.
  void set_stop(double t_stop) {
    t_stop_ = t_stop;
    stop_slack_ = 16.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_stop));
  }
  /// The root functions from d = (θ, θ̇, θ̈) at one time: root_value on the forms as the
  /// constructor unpacked them (a constant g_i = c reads 0 − (−c)), a branch fewer per
  /// function (2 % of the block's instructions under ER1).
  void roots_of(const double* d, double* g) const {
    if (nroots_ == 4) return roots_of_n<4>(d, g);  // the rockers' (case_run.hpp): unrolled
    roots_of_n<0>(d, g);
  }
  /// roots_of over N functions (0: nroots_).
  template <int N>
  void roots_of_n(const double* d, double* g) const {
    const double e[4] = {d[0], d[1], d[2], 0.0};
    const int n = N > 0 ? N : nroots_;
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const auto bits = std::bit_cast<std::uint64_t>(e[index_[k]]) & keep_bits_[k];  // |v| by its sign bit
      g[i] = std::bit_cast<double>(bits) - offset_[k];
    }
  }
  /// The root functions at t within the step (from the last probes of a search when t is one
  /// of them: the root a search reports is its last or next-to-last probe).
  void roots_at(double t, double* g) {
    double d[3];
    if (!state_at(t, d)) ++counts_.root_evals;
    roots_of(d, g);
  }
  /// (θ, θ̇, θ̈) at t within the step, from the probe cache when t is one of its times (true)
  /// or from the series (false).
  bool state_at(double t, double* d) const {
    if (const Probe* p = probe_at(t)) {
      d[0] = p->d[0], d[1] = p->d[1], d[2] = p->d[2];
      return true;
    }
    at<2>(t - t0_, d);
    return false;
  }
  /// θ⁽ʲ⁾ at the step's start: the series' coefficient a_j times j! (j ≤ 4), no evaluation.
  double start_derivative(int j) const {
    constexpr double kFactorials[5] = {1.0, 1.0, 2.0, 6.0, 24.0};
    return kFactorials[j] * a_[static_cast<std::size_t>(j)];
  }
  /// Whether any root function changes sign, or is zero, between tcur_ and t1_ (the check
  /// of crosses() without the directions).
  bool may_cross() const {
    if (nroots_ == 4) {  // the rockers': two products of pairs (GCC vector extension)
      using Pair = double __attribute__((vector_size(16)));
      const auto at = [](const std::array<double, kMaxRoots>& g, std::size_t k) { return Pair{g[k], g[k + 1]}; };
      const auto m = (at(g_cur_, 0) * at(g_end_, 0) <= 0.0) | (at(g_cur_, 2) * at(g_end_, 2) <= 0.0);
      return (m[0] | m[1]) != 0;
    }
    bool any = false;
    for (int i = 0; i < nroots_; ++i) any |= g_cur_[static_cast<std::size_t>(i)] * g_end_[static_cast<std::size_t>(i)] <= 0.0;
    return any;
  }
  /// Narrows [lo, hi] (values glo, ghi of opposite signs) around the root of function i to
  /// ttol, by the steps of the series' local quadratic (model_step).
  void locate(int i, double& lo, double& glo, double& hi, double& ghi, double ttol);
  template <int D>
  void locate_derivative(int i, double& lo, double& glo, double& hi, double& ghi, double ttol);
  /// The earliest crossing in (tcur_, t1_]: root_time_, found_, g_root_; false when none.
  bool find_root();
  /// An upper bound of |θ⁽ᵐ⁾| over the step [t0_, t1_]: Σ_k k!/(k − m)! |a_k| h^(k−m).
  double peak_bound(int m) const;
  /// The state y at t, reported as `outcome`.
  Outcome report(Outcome outcome, double t_at, const double* y_at, double& t, double* y) const {
    t = t_at;
    y[0] = y_at[0], y[1] = y_at[1];
    return outcome;
  }
  bool fail(const std::string& text);
  /// A step too small (`series` false) or a series not finite at t0_ (out of line: the message
  /// is built only then).
  [[gnu::noinline, gnu::cold]] bool fail_step(double h, bool series);

  SolverSettings settings_;
  OdeProblem& problem_;
  int nroots_;
  int order_;
  // The problem's root forms (OdeProblem::root_form), unpacked: g_i = (|d| if absolute_ else
  // d) − offset_ with d the index_-th derivative of θ (3: a zero, for a constant −offset_).
  std::array<int, kMaxRoots> index_{};
  std::array<bool, kMaxRoots> absolute_{};
  std::array<std::uint64_t, kMaxRoots> keep_bits_{};  ///< all bits, or all but the sign for absolute_
  std::array<double, kMaxRoots> offset_{};
  int velocity_root_;  ///< the root function that is θ̇, located first; −1: none
  std::array<double, 2> atol_;  ///< atol_θ [rad], atol_ω [rad/s]
  std::array<int, kMaxRoots> dirs_{};
  /// set_peak_floor's floors (−∞: none); any_floor_: one is finite.
  std::array<double, kMaxRoots> floors_;
  bool any_floor_ = false;
  double t_stop_ = 0.0, stop_slack_ = 0.0;

  // The current step [t0_, t1_], its series in τ = t − t0_ (zero above order_); the position
  // tcur_ within it.
  double t0_ = 0.0, t1_ = 0.0, tcur_ = 0.0, h_step_ = 0.0;
  double y0_[2] = {0.0, 0.0}, y1_[2] = {0.0, 0.0};  ///< the state at t0_ and t1_
  bool have_step_ = false;
  std::array<double, kOrderMax + 1> a_{};
  /// 2h^(n−1), 2hⁿ, 2(n−1)h^(n−2), 2n·h^(n−1) of a step of one record interval, h_powers_of_:
  /// the last two terms of θ and θ̇ over |a_(n−1)| and |a_n|, twice (each against half its
  /// weight).
  double h_powers_[4] = {1.0, 1.0, 1.0, 1.0};
  double h_powers_of_ = 0.0;
  std::array<double, kMaxRoots> g_cur_{}, g_end_{}, g_root_{};  ///< at tcur_, t1_, root_time_
  /// The last two probes of a root search: θ and its first `count` − 1 derivatives (3 or 4)
  /// at t within the current step (count 0: none).
  struct Probe {
    double t = 0.0;
    double d[4] = {0.0, 0.0, 0.0, 0.0};
    int count = 0;
  };
  /// The probe at t, or null.
  const Probe* probe_at(double t) const {
    for (const Probe& p : probes_)
      if (p.t == t && p.count > 0) return &p;
    return nullptr;
  }
  std::array<Probe, 2> probes_{};
  NextSample next_sample_;  ///< the breakpoints, and the next after a step's start
  std::array<int, kMaxRoots> found_{};
  double root_time_ = 0.0;
  SolverCounts counts_;
  std::string error_;
};

}  // namespace pcrf::detail
