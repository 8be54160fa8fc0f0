// Taylor steps with breakpoints and events (see taylor_integrator.hpp).
#include "taylor_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../dopri5/dopri5_tableau.hpp"
#include "pcrf/number_text.hpp"
#include "../integrator/root_search.hpp"

namespace pcrf::detail {

TaylorIntegrator::TaylorIntegrator(const SolverSettings& settings, OdeProblem& problem, SampleGrid breakpoints)
    : settings_(settings),
      problem_(problem),
      nroots_(problem.root_count()),
      order_(order_for(settings.rtol, std::min(problem.taylor_order_max(), kOrderMax))),
      velocity_root_(problem.root_of_state(1)),
      atol_{settings.atol_theta_rad, settings.atol_omega_rad_s},
      next_sample_(breakpoints) {
  floors_.fill(-std::numeric_limits<double>::infinity());
  if (problem.taylor_order_max() < 3) throw IntegratorError("taylor: the problem has no Taylor series");
  if (nroots_ < 0 || nroots_ > kMaxRoots) throw IntegratorError("taylor: too many root functions");
  for (int i = 0; i < nroots_; ++i) {
    const RootForm f = problem.root_form(i);
    if (f.derivative != RootForm::kConstant && (f.derivative < 0 || f.derivative > 2))
      throw IntegratorError("taylor: root function " + std::to_string(i) + " is not a closed form of the series");
    const auto k = static_cast<std::size_t>(i);
    const bool constant = f.derivative == RootForm::kConstant;
    index_[k] = constant ? 3 : f.derivative;
    absolute_[k] = f.absolute && !constant;
    keep_bits_[k] = absolute_[k] ? ~(std::uint64_t{1} << 63) : ~std::uint64_t{0};
    offset_[k] = constant ? -f.offset : f.offset;
  }
}

int TaylorIntegrator::order_for(double rtol, int order_max) {
  const double n = std::ceil(-std::log10(std::max(rtol, kEps)) / 3.0) + 4.0;
  return static_cast<int>(std::clamp(n, 3.0, static_cast<double>(order_max)));
}

void TaylorIntegrator::restart(double t0, const double* y0, const int* root_dirs, double t_stop, double /*h0*/) {
  if (counts_.steps > 0 || counts_.rhs_evals > 0) ++counts_.reinits;
  t0_ = t1_ = tcur_ = t0;
  y1_[0] = y0[0], y1_[1] = y0[1];
  set_stop(t_stop);
  have_step_ = false;
  error_.clear();
  found_.fill(0);
  for (int i = 0; i < nroots_; ++i) dirs_[static_cast<std::size_t>(i)] = root_dirs[i];
  // The first step now: its series gives the root functions at the start. One that is zero
  // there is judged a little later (as SUNDIALS and dopri5 do): a flight leaving θ₁ = 0 takes
  // the sign it moves into, and a function still zero stays inactive until it moves away.
  if (!step()) return;  // advance() reports the failure
  const double d[4] = {start_derivative(0), start_derivative(1), start_derivative(2), start_derivative(3)};
  roots_of(d, g_cur_.data());
  // A zero θ⁽ʲ⁾ − c a tolerance later: θ⁽ʲ⁺¹⁾ times it, when that is not zero (the series'
  // value there but for rounding); else, and for |θ| − c, the series' value.
  const double tau = root_tolerance(t0, h_step_);
  bool evaluate = false;
  for (int i = 0; i < nroots_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (g_cur_[k] != 0.0) continue;
    const double later = index_[k] <= 2 && !absolute_[k] ? d[index_[k] + 1] * tau : 0.0;
    if (later != 0.0) {
      g_cur_[k] = later;
    } else {
      evaluate = true;
    }
  }
  if (evaluate) {
    std::array<double, kMaxRoots> g{};
    roots_at(t0 + tau, g.data());
    for (int i = 0; i < nroots_; ++i) {
      auto k = static_cast<std::size_t>(i);
      if (g_cur_[k] == 0.0) g_cur_[k] = g[k];
    }
  }
}

void TaylorIntegrator::set_stop_time(double t_stop) {
  set_stop(t_stop);
  if (!have_step_ || t1_ <= t_stop_) return;
  // The step goes beyond the new stop time: the next one starts again from tcur_.
  double d[2];
  at<1>(tcur_ - t0_, d);
  y1_[0] = d[0], y1_[1] = d[1];
  t1_ = tcur_;
}

inline bool TaylorIntegrator::within_tolerance(double h, double& h_fit) {
  // The last two terms of θ (a_{n−1} h^{n−1}, a_n h^n) and of θ̇ ((n−1) a_{n−1} h^{n−2},
  // n a_n h^{n−1}), each against half its component's weight. Most steps are one record
  // interval long: their powers of h are kept, and serve a step within a millionth of it
  // (k·dt − (k − 1)·dt differs from dt by rounding), an estimate changed by 1e-5 at most.
  const int n = order_;
  double fresh[4];
  const double* powers_of_h = h_powers_;
  if (!(std::abs(h - h_powers_of_) <= 1e-6 * h)) {
    double h_n2 = 2.0;  // 2h^(n−2)
    for (int p = 0; p < n - 2; ++p) h_n2 *= h;
    const bool interval = std::abs(h - next_sample_.grid().dt_s) <= 1e-6 * h;
    double* to = interval ? h_powers_ : fresh;
    to[0] = h_n2 * h, to[1] = h_n2 * h * h, to[2] = (n - 1) * h_n2, to[3] = n * (h_n2 * h);
    if (interval) h_powers_of_ = h;
    powers_of_h = to;
  }
  const double an1 = std::abs(a_[static_cast<std::size_t>(n - 1)]), an = std::abs(a_[static_cast<std::size_t>(n)]);
  const double w0 = atol_[0] + settings_.rtol * std::abs(y0_[0]), w1 = atol_[1] + settings_.rtol * std::abs(y0_[1]);
  if (std::max(an1 * powers_of_h[0], an * powers_of_h[1]) <= w0 && std::max(an1 * powers_of_h[2], an * powers_of_h[3]) <= w1)
    return true;
  h_fit = fitting_step(h, an1, an, w0, w1);
  return false;
}

double TaylorIntegrator::fitting_step(double h, double an1, double an, double w0, double w1) const {
  const int n = order_;
  const double terms[4] = {an1, an, (n - 1) * an1, n * an};
  const double weights[4] = {w0, w0, w1, w1};
  const int powers[4] = {n - 1, n, n - 2, n - 1};
  double h_fit = h;
  for (int i = 0; i < 4; ++i)
    if (terms[i] > 0.0) h_fit = std::min(h_fit, std::pow(0.5 * weights[i] / terms[i], 1.0 / powers[i]));
  return h_fit;
}

bool TaylorIntegrator::step() {
  t0_ = tcur_;
  y0_[0] = y1_[0], y0_[1] = y1_[1];
  const double limit = std::min(next_sample_.after(t0_), t_stop_);
  double h = limit - t0_;
  bool clamped = true;
  if (settings_.max_step_s > 0.0 && h > settings_.max_step_s) h = settings_.max_step_s, clamped = false;
  bool fresh = false;  // a_ holds the series for a step of h
  for (int attempt = 0;; ++attempt) {
    if (attempt > kMaxFailures || !(h > 16.0 * kEps * std::abs(t0_)) || !(h > 0.0)) return fail_step(h, false);
    if (!fresh) {
      ++counts_.rhs_evals;
      if (!problem_.taylor(t0_, y0_, h, order_, a_.data(), fresh)) return fail_step(h, true);
    }
    double h_fit = h;
    if (within_tolerance(h, h_fit)) break;
    // Within a record interval the series holds for any shorter step: h_fit is within the
    // tolerance at once. Under a chord it is the chord's: new coefficients for the new h.
    h = std::min(h_fit, 0.9 * h);
    clamped = false;
  }
  h_step_ = h;
  t1_ = clamped ? limit : t0_ + h;
  probes_[0].count = probes_[1].count = 0;
  double d[3];
  at<2>(h, d);
  y1_[0] = d[0], y1_[1] = d[1];
  have_step_ = true;
  ++counts_.steps;
  ++counts_.root_evals;
  roots_of(d, g_end_.data());
  return true;
}

template <int D>
void TaylorIntegrator::locate_derivative(int i, double& lo, double& glo, double& hi, double& ghi, double ttol) {
  const auto k = static_cast<std::size_t>(i);
  const bool absolute = absolute_[k];
  const double offset = offset_[k];
  // The first probe is the root of the series' quadratic at lo when its derivatives there are
  // known without an evaluation: at the step's start (the coefficients), or at a probe of the
  // search before (a root found earlier in the step); else the secant's.
  double t_first = std::numeric_limits<double>::quiet_NaN();
  double m[3];  // the function's value, slope and curvature at lo
  bool known = false;
  if (lo == t0_) {
    for (int j = 0; j < 3; ++j) m[j] = start_derivative(D + j);
    known = true;
  } else if constexpr (D + 3 <= 4) {
    if (const Probe* p = probe_at(lo); p != nullptr && p->count >= D + 3) {
      for (int j = 0; j < 3; ++j) m[j] = p->d[D + j];
      known = true;
    }
  }
  if (known) {
    const bool flip = absolute && m[0] < 0.0;
    const double v = (flip ? -m[0] : m[0]) - offset, slope = flip ? -m[1] : m[1], curvature = flip ? -m[2] : m[2];
    // A function zero at lo itself (θ₁ at the impact the flight left): the quadratic's other
    // root, the flight's landing.
    t_first = lo + (v == 0.0 && curvature != 0.0 ? -2.0 * slope / curvature : model_step(v, slope, curvature));
  }
  int next = 0;
  newton_in_bracket(
      [&](double t, double& v, double& slope, double& curvature) {
        double d[D + 3];
        at<D + 2>(t - t0_, d);
        ++counts_.root_evals;
        const bool flip = absolute && d[D] < 0.0;
        v = (flip ? -d[D] : d[D]) - offset;
        slope = flip ? -d[D + 1] : d[D + 1];
        curvature = flip ? -d[D + 2] : d[D + 2];
        Probe& p = probes_[static_cast<std::size_t>(next)];
        next ^= 1;
        p.t = t, p.count = D + 3 < 4 ? D + 3 : 4;
        for (int j = 0; j < p.count; ++j) p.d[j] = d[j];
      },
      lo, glo, hi, ghi, ttol, t_first);
}

void TaylorIntegrator::locate(int i, double& lo, double& glo, double& hi, double& ghi, double ttol) {
  switch (index_[static_cast<std::size_t>(i)]) {
    case 0: locate_derivative<0>(i, lo, glo, hi, ghi, ttol); break;
    case 1: locate_derivative<1>(i, lo, glo, hi, ghi, ttol); break;
    default: locate_derivative<2>(i, lo, glo, hi, ghi, ttol); break;  // a constant never crosses
  }
}

void TaylorIntegrator::set_peak_floor(int root, double floor) {
  if (root < 0 || root >= nroots_) return;
  const auto k = static_cast<std::size_t>(root);
  if (index_[k] < 1 || index_[k] > 2 || absolute_[k]) return;
  floors_[k] = floor;
  any_floor_ = any_floor_ || floor > -std::numeric_limits<double>::infinity();
}

double TaylorIntegrator::peak_bound(int m) const {
  double bound = 0.0, h_power = 1.0;
  for (int k = m; k <= order_; ++k) {
    double falling = 1.0;  // k!/(k − m)!
    for (int j = 0; j < m; ++j) falling *= k - j;
    bound += falling * std::abs(a_[static_cast<std::size_t>(k)]) * h_power;
    h_power *= h_step_;
  }
  return bound;
}

bool TaylorIntegrator::find_root() {
  // A peak root whose magnitude the series keeps below its floor over the step cannot raise
  // the running maximum: it is left out of this step's search (a zero start value never
  // crosses).
  const double* g_start = g_cur_.data();
  std::array<double, kMaxRoots> searched;  // NOLINT: filled below before use
  if (any_floor_) {
    searched = g_cur_;
    for (int i = 0; i < nroots_; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (floors_[k] > -std::numeric_limits<double>::infinity() && crosses(g_cur_[k], g_end_[k], dirs_[k]) &&
          peak_bound(index_[k] - 1) * (1.0 + 1e-12) < floors_[k])
        searched[k] = 0.0;
    }
    g_start = searched.data();
  }
  auto roots_at = [this](double t, double* g) {
    this->roots_at(t, g);
    return true;
  };
  auto locate = [this](int i, double& lo, double& glo, double& hi, double& ghi, double ttol) {
    this->locate(i, lo, glo, hi, ghi, ttol);
  };
  return earliest_crossing(nroots_, dirs_, velocity_root_, tcur_, g_start, t1_, g_end_.data(),
                           root_tolerance(t1_, h_step_), roots_at, locate, root_time_, found_, g_root_);
}

OdeIntegrator::Outcome TaylorIntegrator::advance(double tout, double& t, double* y, bool one_step) {
  if (!error_.empty()) return report(Outcome::kFailure, tcur_, y1_, t, y);
  for (;;) {
    if (!have_step_ || tcur_ >= t1_) {
      // A root may leave the state a few ulp short of the stop time: no step that short
      // exists, so the state is taken as the stop time's.
      if (t_stop_ - tcur_ <= stop_slack_) tcur_ = std::max(tcur_, t_stop_);
      if (tcur_ >= t_stop_) return report(Outcome::kReachedTime, tcur_, y1_, t, y);
      if (counts_.steps > settings_.max_steps) {
        fail("more than max_steps steps");
        return report(Outcome::kFailure, tcur_, y1_, t, y);
      }
      if (!step()) return report(Outcome::kFailure, tcur_, y1_, t, y);
    }
    if (may_cross() && find_root()) {
      double d[3];
      state_at(root_time_, d);
      tcur_ = root_time_;
      g_cur_ = g_root_;
      return report(Outcome::kRoot, tcur_, d, t, y);
    }
    if (tout < t1_) {  // tout inside the step: the state there; the step goes on
      double d[2];
      at<1>(tout - t0_, d);
      tcur_ = tout;
      g_cur_ = g_end_;  // no root in between: the signs are those at the step's end
      return report(Outcome::kReachedTime, tout, d, t, y);
    }
    tcur_ = t1_;
    g_cur_ = g_end_;
    if (tcur_ >= tout || one_step) return report(Outcome::kReachedTime, tcur_, y1_, t, y);
  }
}

void TaylorIntegrator::interpolate(double t, double* y) {
  if (!have_step_) {
    y[0] = y1_[0], y[1] = y1_[1];
    return;
  }
  double d[2];
  at<1>(t - t0_, d);
  y[0] = d[0], y[1] = d[1];
}

void TaylorIntegrator::root_info(int* found) {
  for (int i = 0; i < nroots_; ++i) found[i] = found_[static_cast<std::size_t>(i)];
}

bool TaylorIntegrator::fail_step(double h, bool series) {
  if (series) return fail("taylor: the series is not finite at t = " + number_text(t0_) + " s");
  return fail("taylor: step size " + number_text(h) + " s too small at t = " + number_text(t0_) + " s");
}

bool TaylorIntegrator::fail(const std::string& text) {
  error_ = text;
  return false;
}

}  // namespace pcrf::detail
