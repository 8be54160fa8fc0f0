// Dormand–Prince 5(4) with dense output, breakpoints and events (see dormand_prince.hpp).
#include "dormand_prince.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pcrf/number_text.hpp"

namespace pcrf::detail {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The tableau (Dormand & Prince 1980, Table 2; Hairer, Nørsett & Wanner, Table II.5.2).
constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                 a65 = -5103.0 / 18656;
constexpr double a71 = 35.0 / 384, a73 = 500.0 / 1113, a74 = 125.0 / 192, a75 = -2187.0 / 6784, a76 = 11.0 / 84;
// The 5th-order solution minus the embedded 4th-order one.
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200, e6 = 22.0 / 525,
                 e7 = -1.0 / 40;
// Shampine's continuous extension (Hairer, Nørsett & Wanner, DOPRI5's CONTD5).
constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                 d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                 d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;

// Step-size control (Hairer, Nørsett & Wanner §IV.2, DOPRI5's defaults).
constexpr double kBeta = 0.04;                // PI control
constexpr double kExpo = 0.2 - kBeta * 0.75;  // 1/5 − 0.75 β
constexpr double kSafety = 0.9;
constexpr double kFacMin = 0.2, kFacMax = 10.0;  // bounds of h_new/h
constexpr int kMaxFailures = 50;
const double kLogErrFloor = std::log(1e-4);      // err_old ≥ 1e-4 in the PI control                 // consecutive rejected or failed attempts

/// Time tolerance of a located root, as SUNDIALS' (100 ulp of the time and step).
double root_tolerance(double t, double h) { return 100.0 * kEps * (std::abs(t) + std::abs(h)); }

}  // namespace

DormandPrinceIntegrator::DormandPrinceIntegrator(const SolverSettings& settings, OdeProblem& problem,
                                                 SampleGrid breakpoints)
    : settings_(settings),
      problem_(problem),
      grid_(breakpoints),
      nroots_(problem.root_count()),
      atol_{settings.atol_theta_rad, settings.atol_omega_rad_s} {
  if (nroots_ < 0 || nroots_ > kMaxRoots) throw IntegratorError("dopri5: too many root functions");
}

void DormandPrinceIntegrator::restart(double t0, const double* y0, const int* root_dirs, double t_stop, double h0) {
  if (counts_.steps > 0 || counts_.rhs_evals > 0) ++counts_.reinits;
  t0_ = t1_ = tcur_ = t0;
  y0_ = y1_ = {y0[0], y0[1]};
  t_stop_ = t_stop;
  have_step_ = false;
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

bool DormandPrinceIntegrator::try_step(double h, Vec& y1, Vec& k7, double& err) {
  const double t = t0_;
  const Vec& y = y0_;
  const Vec& k1 = k1_;
  Vec s{};
  auto f = [&](double c, Vec& k) {
    ++counts_.rhs_evals;
    return problem_.rhs(t + c * h, s.data(), k.data()) == 0;
  };
  for (int i = 0; i < 2; ++i) s[i] = y[i] + h * a21 * k1[i];
  if (!f(c2, k2_)) return false;
  for (int i = 0; i < 2; ++i) s[i] = y[i] + h * (a31 * k1[i] + a32 * k2_[i]);
  if (!f(c3, k3_)) return false;
  for (int i = 0; i < 2; ++i) s[i] = y[i] + h * (a41 * k1[i] + a42 * k2_[i] + a43 * k3_[i]);
  if (!f(c4, k4_)) return false;
  for (int i = 0; i < 2; ++i) s[i] = y[i] + h * (a51 * k1[i] + a52 * k2_[i] + a53 * k3_[i] + a54 * k4_[i]);
  if (!f(c5, k5_)) return false;
  for (int i = 0; i < 2; ++i)
    s[i] = y[i] + h * (a61 * k1[i] + a62 * k2_[i] + a63 * k3_[i] + a64 * k4_[i] + a65 * k5_[i]);
  if (!f(1.0, k6_)) return false;
  for (int i = 0; i < 2; ++i) y1[i] = y[i] + h * (a71 * k1[i] + a73 * k3_[i] + a74 * k4_[i] + a75 * k5_[i] + a76 * k6_[i]);
  s = y1;
  if (!f(1.0, k7)) return false;
  double sum = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double e = h * (e1 * k1[i] + e3 * k3_[i] + e4 * k4_[i] + e5 * k5_[i] + e6 * k6_[i] + e7 * k7[i]);
    const double sk = weight(i, std::max(std::abs(y[i]), std::abs(y1[i])));
    sum += (e / sk) * (e / sk);
  }
  err = std::sqrt(sum / 2.0);
  return std::isfinite(err) && std::isfinite(y1[0]) && std::isfinite(y1[1]);
}

bool DormandPrinceIntegrator::step() {
  t0_ = tcur_;
  y0_ = y1_;
  k1_ = k7_;
  if (!std::isfinite(k1_[0]) || !std::isfinite(k1_[1])) return fail(error_.empty() ? "dopri5: non-finite derivative" : error_);
  const double limit = std::min(grid_.next_after(t0_), t_stop_);
  double h = h_;
  if (settings_.max_step_s > 0.0) h = std::min(h, settings_.max_step_s);
  bool rejected = false;
  for (int failures = 0;; ++failures) {
    if (failures > kMaxFailures)
      return fail("dopri5: " + std::to_string(kMaxFailures) + " failed step attempts in a row at t = " + number_text(t0_) + " s");
    // Land on the breakpoint (or stop time) when the step would reach it or nearly so.
    const bool clamped = t0_ + 1.01 * h >= limit;
    const double h_try = clamped ? limit - t0_ : h;
    if (!(h_try > 16.0 * kEps * std::abs(t0_)) || !(h_try > 0.0))
      return fail("dopri5: step size " + number_text(h_try) + " s too small at t = " + number_text(t0_) + " s");
    Vec y1{}, k7{};
    double err = 0.0;
    if (!try_step(h_try, y1, k7, err)) {  // the mechanism does not exist at a stage: shrink
      h = 0.25 * h_try;
      rejected = true;
      continue;
    }
    if (err > 1.0) {
      h = h_try / std::min(1.0 / kFacMin, std::pow(err, kExpo) / kSafety);
      rejected = true;
      continue;
    }
    // Accepted. A step cut short by a breakpoint says little about the step the solution
    // allows: the one the controller proposed before it is kept unless the PI control of
    // this step proposes a longer one, which it cannot when even its largest growth
    // (kFacMax) stays below (no pow() then: most steps of a record end at a sample).
    const double log_err = std::log(std::max(err, 1e-300));
    if (clamped && kFacMax * h_try <= h) {
      h_ = h;
    } else {
      // err^α / err_old^β, with one exp instead of two pow().
      double fac = std::exp(kExpo * log_err - kBeta * log_err_old_) / kSafety;
      fac = std::clamp(fac, 1.0 / kFacMax, 1.0 / kFacMin);
      double h_next = h_try / fac;
      if (rejected) h_next = std::min(h_next, h_try);
      h_ = clamped ? std::max(h_next, h) : h_next;
    }
    log_err_old_ = std::max(log_err, kLogErrFloor);
    const double h1 = h_try;
    t1_ = clamped ? limit : t0_ + h1;
    y1_ = y1;
    k7_ = k7;
    // The continuous extension's coefficients.
    for (int i = 0; i < 2; ++i) {
      const double ydiff = y1[i] - y0_[i], bspl = h1 * k1_[i] - ydiff;
      cont_[0][i] = y0_[i];
      cont_[1][i] = ydiff;
      cont_[2][i] = bspl;
      cont_[3][i] = ydiff - h1 * k7[i] - bspl;
      cont_[4][i] = h1 * (d1 * k1_[i] + d3 * k3_[i] + d4 * k4_[i] + d5 * k5_[i] + d6 * k6_[i] + d7 * k7[i]);
    }
    h_step_ = h1;
    have_step_ = true;
    ++counts_.steps;
    ++counts_.root_evals;
    problem_.roots(t1_, y1_.data(), g_end_.data());
    return true;
  }
}

void DormandPrinceIntegrator::dense(double t, Vec& y) const {
  if (!have_step_) {
    y = y1_;
    return;
  }
  for (int i = 0; i < 2; ++i) y[i] = dense_component(t, i);
}

void DormandPrinceIntegrator::locate_on_interpolant(int component, double& lo, double& glo, double& hi, double& ghi,
                                                    double ttol) const {
  // Newton on the interpolant's polynomial, kept inside the bracket (bisection where it
  // would leave it); once its steps fall below the tolerance, one probe just across the
  // root closes the bracket. Two to four probes where Illinois takes eight.
  double t = hi - ghi * (hi - lo) / (ghi - glo);
  for (int it = 0; it < 100 && hi - lo > ttol && ghi != 0.0; ++it) {
    t = std::clamp(t, lo + 0.25 * ttol, hi - 0.25 * ttol);
    const double v = dense_component(t, component), slope = dense_slope(t, component);
    if (v == 0.0) {
      hi = t, ghi = 0.0;
      break;
    }
    const bool below = (v > 0.0) == (glo > 0.0);
    if (below) {
      lo = t, glo = v;
    } else {
      hi = t, ghi = v;
    }
    const double newton = t - v / slope;  // ±inf or NaN for a zero slope: bisection below
    if (std::abs(newton - t) < 0.5 * ttol) {
      t = below ? t + 0.5 * ttol : t - 0.5 * ttol;
    } else if (newton > lo && newton < hi) {
      t = newton;
    } else {
      t = 0.5 * (lo + hi);
    }
  }
}

bool DormandPrinceIntegrator::roots_at(double t, double* g) {
  Vec y{};
  dense(t, y);
  ++counts_.root_evals;
  return problem_.roots(t, y.data(), g) == 0;
}

bool DormandPrinceIntegrator::illinois(int i, double& lo, double& glo, double& hi, double& ghi, double ttol) {
  // Regula falsi that halves the stale end's value when an end repeats.
  std::array<double, kMaxRoots> g;  // NOLINT: filled by roots_at before use
  const auto k = static_cast<std::size_t>(i);
  int last = 0;
  for (int it = 0; it < 200 && hi - lo > ttol && ghi != 0.0; ++it) {
    double t = hi - ghi * (hi - lo) / (ghi - glo);
    const double margin = 0.5 * ttol;
    t = std::clamp(t, lo + margin, hi - margin);
    if (!roots_at(t, g.data())) return false;
    const double gt = g[k];
    if (gt == 0.0) {
      hi = t;
      ghi = 0.0;
    } else if ((gt > 0.0) == (glo > 0.0)) {
      lo = t, glo = gt;
      if (last == -1) ghi *= 0.5;
      last = -1;
    } else {
      hi = t, ghi = gt;
      if (last == 1) glo *= 0.5;
      last = 1;
    }
  }
  return true;
}

void DormandPrinceIntegrator::locate(int i, double& lo, double& glo, double& hi, double& ghi, double ttol) {
  // A root that is a state component: Newton on the interpolant, no call of the problem.
  const int component = problem_.root_state_index(i);
  if (component >= 0) {
    locate_on_interpolant(component, lo, glo, hi, ghi, ttol);
  } else {
    illinois(i, lo, glo, hi, ghi, ttol);
  }
}

bool DormandPrinceIntegrator::find_roots(double a, const double* g_a, double b, const double* g_b) {
  bool candidate = false;  // most steps cross nothing: leave at once
  for (int i = 0; i < nroots_; ++i) candidate = candidate || (g_a[i] != 0.0 && g_a[i] * g_b[i] <= 0.0);
  if (!candidate) return false;
  const double ttol = root_tolerance(b, h_step_);
  double earliest = std::numeric_limits<double>::infinity();
  std::array<double, kMaxRoots> when;  // NOLINT: filled below for every root
  std::array<double, kMaxRoots> g;     // NOLINT: filled by roots_at before use
  bool any = false;
  for (int i = 0; i < nroots_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    when[k] = std::numeric_limits<double>::infinity();
    const double ga = g_a[i], gb = g_b[i];
    if (ga == 0.0 || ga * gb > 0.0) continue;     // inactive, or no sign change
    if (dirs_[k] != 0 && dirs_[k] * ga > 0.0) continue;  // crosses against its direction
    double lo = a, glo = ga, hi = b, ghi = gb;
    locate(i, lo, glo, hi, ghi, ttol);
    when[k] = hi;
    earliest = std::min(earliest, hi);
    any = true;
  }
  if (!any) return false;
  // A function with the same sign at both ends of the step may still cross before the
  // earliest root and back: the stop angle exceeded at a θ peak inside the step, where
  // |θ₁| is largest. At the earliest root, any function whose sign differs from its sign at
  // `a` crossed before it: locate that crossing, and check again at the new earliest.
  bool current = false;  // g holds the functions at `earliest`
  for (int pass = 0; pass < nroots_; ++pass) {
    if (!roots_at(earliest, g.data())) break;
    current = true;
    bool moved = false;
    for (int i = 0; i < nroots_; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double ga = g_a[i], gm = g[k];
      if (when[k] <= earliest || ga == 0.0 || !(ga * gm < 0.0)) continue;
      if (dirs_[k] != 0 && dirs_[k] * ga > 0.0) continue;
      double lo = a, glo = ga, hi = earliest, ghi = gm;
      locate(i, lo, glo, hi, ghi, ttol);
      when[k] = hi;
      if (hi < earliest) earliest = hi, moved = true, current = false;
    }
    if (!moved) break;
  }
  // The functions at the root, for the search that resumes there (advance()).
  if (current) {
    g_root_ = g;
  } else if (!roots_at(earliest, g_root_.data())) {
    std::fill(g_root_.begin(), g_root_.end(), 0.0);
  }
  std::fill(found_.begin(), found_.end(), 0);
  for (int i = 0; i < nroots_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (when[k] <= earliest + ttol) found_[k] = 1;
  }
  root_time_ = earliest;
  return true;
}

OdeIntegrator::Outcome DormandPrinceIntegrator::advance(double tout, double& t, double* y, bool one_step) {
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
