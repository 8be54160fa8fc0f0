// Lockstep batches of cases under one excitation (see include/pcrf/solver/batch_solver.hpp).
//
// Each lane is a case: the state machine of rocking_solver.cpp's CaseRun over the
// integrator of dormand_prince.cpp, made resumable at one point, "a step attempt is
// ready". The driver runs every lane up to that point, makes all the attempts with one
// vector kernel (attempt_kernel.hpp), and hands each lane its result. Everything else a
// lane does (the step-size control, the root search on its dense output, impacts, rest,
// the end of its case) is scalar, in the order and arithmetic of the one-case solver, so
// the answers are the same (tests/solver/batch_solver_test.cpp).
#include "pcrf/solver/batch_solver.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "../case_common.hpp"
#include "../integrators.hpp"
#include "../prepared_frame.hpp"
#include "dopri5_tableau.hpp"
#include "lane_arrays.hpp"
#include "pcrf/model/rigid_rocker.hpp"
#include "pcrf/number_text.hpp"

namespace pcrf {
namespace detail::batch {
namespace {

/// Root indices (as rocking_solver.cpp's).
enum Root { kImpact = 0, kThetaPeak = 1, kOmegaPeak = 2, kLimit = 3, kRootCount = 4 };

const double kLogErrFloor = std::log(1e-4);  // err_old ≥ 1e-4 in the PI control

/// Time tolerance of a located root, as SUNDIALS' (100 ulp of the time and step).
double root_tolerance(double t, double h) { return 100.0 * kEps * (std::abs(t) + std::abs(h)); }

using Vec = std::array<double, 2>;

enum class Advance { kReachedTime, kRoot, kFailure, kPending };

class Driver;

/// One lane: a case in progress, with its integrator's state.
class Lane {
 public:
  Lane(Driver& driver, int index) : d_(driver), l_(index) {}

  /// Starts case `c`; false when the case is done at once (at rest throughout).
  void start(std::size_t c, PreparedFrame& frame);
  bool busy() const { return busy_; }
  std::size_t case_index() const { return case_; }
  /// Runs the case until an attempt is ready (true) or the case has ended (false).
  bool progress();
  /// Takes the kernel's attempt; then progress().
  bool take_attempt();
  CaseResult finish_case();

 private:
  friend class Driver;
  // ---- the integrator (DormandPrinceIntegrator's arithmetic) ----
  void restart(double t0, const Vec& y0, const std::array<int, kRootCount>& dirs, double t_stop, double h0);
  double initial_step();
  Advance advance(double tout, double& t, Vec& y);
  bool begin_step();
  bool prepare_attempt();
  void accept(double err);
  bool find_roots(double a, const double* g_a, double b, const double* g_b);
  void locate_on_interpolant(int component, double& lo, double& glo, double& hi, double& ghi, double ttol) const;
  bool roots_at(double t, double* g);
  double dense_component(double t, int i) const {
    const double s = (t - t0_) / h_step_, s1 = 1.0 - s;
    const auto k = static_cast<std::size_t>(i);
    return cont_[0][k] + s * (cont_[1][k] + s1 * (cont_[2][k] + s * (cont_[3][k] + s1 * cont_[4][k])));
  }
  double dense_slope(double t, int i) const {
    const double s = (t - t0_) / h_step_, s1 = 1.0 - s;
    const auto k = static_cast<std::size_t>(i);
    return (cont_[1][k] + (1.0 - 2.0 * s) * cont_[2][k] + s * (2.0 - 3.0 * s) * cont_[3][k] +
            2.0 * s * s1 * (s1 - s) * cont_[4][k]) /
           h_step_;
  }
  void dense(double t, Vec& y) const;
  double weight(int i, double magnitude) const;
  void fail(std::string text) { error_ = std::move(text); }

  // ---- the flight problem (rocking_solver.cpp's FlightProblem) ----
  bool acceleration(double t, double theta, double omega, double& acc);
  int rhs(double t, const Vec& y, Vec& ydot);
  int roots(double t, const Vec& y, double* g);
  std::array<int, kRootCount> directions() const { return {-side_, -side_, 0, 1}; }

  // ---- the case (rocking_solver.cpp's CaseRun) ----
  void rest_until_uplift();
  void start_displaced();
  bool fly();  ///< false: an attempt is pending
  bool handle_roots(double t, const Vec& y);
  void impact(double t, const Vec& y);
  bool returns_to_rest(double t, double omega_after) const;
  bool holds_closed(double t) const;
  void settle(double t);
  void start_flight(double t, const Vec& y);
  void note_theta(double t, double theta);
  void note_omega(double t, double omega);
  void finish(CaseStatus status, std::string message = {});
  bool over_time() const;

  Driver& d_;
  int l_;  ///< lane index in the arrays
  bool busy_ = false;
  std::size_t case_ = 0;
  PreparedFrame* frame_ = nullptr;
  const Scene* scene_ = nullptr;
  const EomTable* table_ = nullptr;
  StopAngles stop_{};
  std::optional<CaseEnd> end_;
  double t_end_ = 0.0;
  double restitution_ = 0.0;
  std::chrono::steady_clock::time_point start_;

  // Case progress.
  bool at_rest_ = true, done_ = false;
  double t_ = 0.0;
  Vec last_y_{};
  int side_ = -1;
  CaseResult result_;

  // Integrator.
  double t_stop_ = 0.0, t0_ = 0.0, t1_ = 0.0, tcur_ = 0.0;
  Vec y0_{}, y1_{}, k1_{}, k7_{};
  std::array<Vec, 5> cont_{};
  double h_step_ = 0.0;
  bool have_step_ = false;
  std::array<int, kRootCount> dirs_{};
  std::array<double, kRootCount> g_cur_{}, g_end_{};
  double h_ = 0.0, log_err_old_ = 0.0;
  std::array<int, kRootCount> found_{};
  double root_time_ = 0.0;
  SolverCounts counts_;
  std::string error_;
  // The step being attempted.
  bool stepping_ = false;       ///< an attempt is in the arrays
  bool attempt_failed_ = false; ///< the step failed for good (error_ says why)
  double limit_ = 0.0, h_trial_ = 0.0, h_try_ = 0.0;
  bool clamped_ = false, rejected_ = false;
  int failures_ = 0;
};

/// The batch: lanes, arrays, the kernel, the queue of cases.
class Driver final : public LaneCallbacks {
 public:
  Driver(std::span<PreparedFrame* const> frames, const Excitation& excitation, const SolverSettings& solver,
         const OutputRequest& request, const BatchOptions& options, std::vector<CaseResult>& results,
         BatchStats& stats);
  void run();

  void ground(int lane, double t_s, double& horizontal_m_s2, double& vertical_m_s2) override;
  bool acceleration(int lane, double t_s, double theta_rad, double omega_rad_s, double& acc_rad_s2) override {
    return lanes_[static_cast<std::size_t>(lane)].acceleration(t_s, theta_rad, omega_rad_s, acc_rad_s2);
  }

 private:
  friend class Lane;
  /// Gives lane l the next case that needs integration; false when none is left.
  bool refill(Lane& lane);
  void set_block_parameters(int lane, const Scene& scene);
  static bool all_rigid_rockers(std::span<PreparedFrame* const> frames);

  std::span<PreparedFrame* const> frames_;
  Excitation excitation_;
  SolverSettings solver_;
  OutputRequest request_;
  SampleGrid samples_;
  std::vector<CaseResult>& results_;
  BatchStats& stats_;
  LaneArrays arrays_;
  bool block_;
  AttemptKernel kernel_;
  std::vector<Lane> lanes_;
  std::size_t next_case_ = 0;
};

// ---------------------------------------------------------------------------------------
// The flight problem.

void Driver::ground(int lane, double t_s, double& horizontal_m_s2, double& vertical_m_s2) {
  // ExcitationCursor::at and ::enter over the lane's entries of the arrays.
  LaneArrays& a = arrays_;
  const auto l = static_cast<std::size_t>(lane);
  bool inside = t_s >= a.lo[l] && t_s < a.hi[l];
  if (!inside) {
    const GroundMotion& h = excitation_.horizontal();
    const bool enters = t_s >= 0.0 && t_s < h.duration_s() &&
                        !(excitation_.has_vertical() && excitation_.vertical()->dt_s() != h.dt_s());
    if (!enters) {
      const GroundAcceleration g = excitation_.at(t_s);
      horizontal_m_s2 = g.horizontal_m_s2, vertical_m_s2 = g.vertical_m_s2;
      return;
    }
    const std::size_t k = h.interval_of(t_s);
    const double dt = h.dt_s();
    a.lo[l] = static_cast<double>(k) * dt;
    a.hi[l] = static_cast<double>(k + 1) * dt;
    a.inv_dt[l] = h.inverse_dt_per_s();
    const auto& s = h.samples_m_s2();
    a.h0[l] = s[k], a.dh[l] = s[k + 1] - s[k];
    if (const GroundMotion* v = excitation_.vertical()) {
      const auto& b = v->samples_m_s2();
      a.v0[l] = b[k], a.dv[l] = b[k + 1] - b[k];
    }
  }
  const double frac = (t_s - a.lo[l]) * a.inv_dt[l];
  horizontal_m_s2 = a.h0[l] + frac * a.dh[l];
  vertical_m_s2 = a.v0[l] + frac * a.dv[l];
}

bool Lane::acceleration(double t, double theta, double omega, double& acc) {
  if (!busy_) {  // an idle lane in a kernel call: any finite number
    acc = 0.0;
    return true;
  }
  GroundAcceleration g;
  d_.ground(l_, t, g.horizontal_m_s2, g.vertical_m_s2);
  return table_->acceleration(theta, omega, g, side_, acc) && std::isfinite(acc);
}

int Lane::rhs(double t, const Vec& y, Vec& ydot) {
  double acc = 0;
  if (!acceleration(t, y[0], y[1], acc)) return 1;
  ydot[0] = y[1];
  ydot[1] = acc;
  return 0;
}

int Lane::roots(double t, const Vec& y, double* g) {
  g[kImpact] = y[0];
  g[kThetaPeak] = y[1];
  g[kOmegaPeak] = 1.0;  // inactive unless requested
  if (d_.request_.omega_peak && !acceleration(t, y[0], y[1], g[kOmegaPeak])) return 1;
  g[kLimit] = std::abs(y[0]) - stop_.stop_rad();
  return 0;
}

// ---------------------------------------------------------------------------------------
// The integrator.

double Lane::weight(int i, double magnitude) const {
  return (i == 0 ? d_.solver_.atol_theta_rad : d_.solver_.atol_omega_rad_s) + d_.solver_.rtol * magnitude;
}

void Lane::restart(double t0, const Vec& y0, const std::array<int, kRootCount>& dirs, double t_stop, double h0) {
  if (counts_.steps > 0 || counts_.rhs_evals > 0) ++counts_.reinits;
  t0_ = t1_ = tcur_ = t0;
  y0_ = y1_ = y0;
  t_stop_ = t_stop;
  have_step_ = false;
  stepping_ = attempt_failed_ = false;
  log_err_old_ = kLogErrFloor;
  error_.clear();
  found_.fill(0);
  dirs_ = dirs;
  ++counts_.rhs_evals;
  if (rhs(t0, y0_, k1_) != 0) {
    fail("dopri5: the right-hand side failed at the start, t = " + number_text(t0) + " s");
    k1_ = {std::nan(""), std::nan("")};
  }
  k7_ = k1_;
  if (h0 > 0.0) {
    h_ = h0;
  } else if (!(counts_.steps > 0 && h_ > 0.0)) {
    h_ = initial_step();
  }
  ++counts_.root_evals;
  roots(t0, y0_, g_cur_.data());
  bool zero = false;
  for (double g : g_cur_) zero = zero || g == 0.0;
  if (zero && std::isfinite(k1_[0])) {
    const double dt = std::max(root_tolerance(t0, h_), 0.1 * h_);
    const Vec y = {y0_[0] + dt * k1_[0], y0_[1] + dt * k1_[1]};
    std::array<double, kRootCount> g{};
    ++counts_.root_evals;
    roots(t0 + dt, y, g.data());
    for (std::size_t k = 0; k < kRootCount; ++k)
      if (g_cur_[k] == 0.0) g_cur_[k] = g[k];
  }
}

double Lane::initial_step() {
  double hmax = t_stop_ - t0_;
  if (d_.solver_.max_step_s > 0.0) hmax = std::min(hmax, d_.solver_.max_step_s);
  if (!(hmax > 0.0)) return 0.0;
  double dnf = 0.0, dny = 0.0;
  for (int i = 0; i < 2; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double sk = weight(i, std::abs(y0_[k]));
    dnf += (k1_[k] / sk) * (k1_[k] / sk);
    dny += (y0_[k] / sk) * (y0_[k] / sk);
  }
  double h = dnf <= 1e-10 || dny <= 1e-10 ? 1e-6 : std::sqrt(dny / dnf) * 0.01;
  h = std::min(h, hmax);
  const Vec y1 = {y0_[0] + h * k1_[0], y0_[1] + h * k1_[1]};
  Vec f1{};
  ++counts_.rhs_evals;
  if (rhs(t0_ + h, y1, f1) != 0) return h;
  double der2 = 0.0;
  for (int i = 0; i < 2; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double sk = weight(i, std::abs(y0_[k]));
    der2 += ((f1[k] - k1_[k]) / sk) * ((f1[k] - k1_[k]) / sk);
  }
  der2 = std::sqrt(der2 / 2.0) / h;
  const double der12 = std::max(std::abs(der2), std::sqrt(dnf / 2.0));
  const double h1 = der12 <= 1e-15 ? std::max(1e-6, std::abs(h) * 1e-3) : std::pow(0.01 / der12, 0.2);
  return std::min({100.0 * h, h1, hmax});
}

bool Lane::begin_step() {
  t0_ = tcur_;
  y0_ = y1_;
  k1_ = k7_;
  if (!std::isfinite(k1_[0]) || !std::isfinite(k1_[1])) {
    fail(error_.empty() ? "dopri5: non-finite derivative" : error_);
    return false;
  }
  limit_ = std::min(d_.samples_.next_after(t0_), t_stop_);
  h_trial_ = h_;
  if (d_.solver_.max_step_s > 0.0) h_trial_ = std::min(h_trial_, d_.solver_.max_step_s);
  rejected_ = false;
  failures_ = 0;
  return prepare_attempt();
}

bool Lane::prepare_attempt() {
  if (failures_ > kMaxFailures) {
    fail("dopri5: " + std::to_string(kMaxFailures) + " failed step attempts in a row at t = " + number_text(t0_) +
         " s");
    return false;
  }
  clamped_ = t0_ + 1.01 * h_trial_ >= limit_;
  h_try_ = clamped_ ? limit_ - t0_ : h_trial_;
  if (!(h_try_ > 16.0 * kEps * std::abs(t0_)) || !(h_try_ > 0.0)) {
    fail("dopri5: step size " + number_text(h_try_) + " s too small at t = " + number_text(t0_) + " s");
    return false;
  }
  LaneArrays& a = d_.arrays_;
  const auto l = static_cast<std::size_t>(l_);
  a.t0[l] = t0_, a.h[l] = h_try_;
  a.theta0[l] = y0_[0], a.omega0[l] = y0_[1];
  a.k1_theta[l] = k1_[0], a.k1_omega[l] = k1_[1];
  a.side[l] = side_;
  stepping_ = true;
  return true;
}

void Lane::accept(double err) {
  const LaneArrays& a = d_.arrays_;
  const auto l = static_cast<std::size_t>(l_);
  const double log_err = std::log(std::max(err, 1e-300));
  if (clamped_ && kFacMax * h_try_ <= h_trial_) {
    h_ = h_trial_;
  } else {
    double fac = std::exp(kExpo * log_err - kBeta * log_err_old_) / kSafety;
    fac = std::clamp(fac, 1.0 / kFacMax, 1.0 / kFacMin);
    double h_next = h_try_ / fac;
    if (rejected_) h_next = std::min(h_next, h_try_);
    h_ = clamped_ ? std::max(h_next, h_trial_) : h_next;
  }
  log_err_old_ = std::max(log_err, kLogErrFloor);
  t1_ = clamped_ ? limit_ : t0_ + h_try_;
  y1_ = {a.theta1[l], a.omega1[l]};
  k7_ = {a.k7_theta[l], a.k7_omega[l]};
  for (std::size_t j = 0; j < 5; ++j) cont_[j] = {a.cont[j][0][l], a.cont[j][1][l]};
  h_step_ = h_try_;
  have_step_ = true;
  ++counts_.steps;
  ++counts_.root_evals;
  // The θ̈₁ root at the step's end is the last stage's when that stage was there (as the
  // flight problem's memory of its last evaluation gives it).
  if (d_.request_.omega_peak && t1_ == t0_ + 1.0 * h_try_) {
    g_end_[kImpact] = y1_[0];
    g_end_[kThetaPeak] = y1_[1];
    g_end_[kOmegaPeak] = k7_[1];
    g_end_[kLimit] = std::abs(y1_[0]) - stop_.stop_rad();
  } else {
    roots(t1_, y1_, g_end_.data());
  }
}

bool Lane::take_attempt() {
  const LaneArrays& a = d_.arrays_;
  const auto l = static_cast<std::size_t>(l_);
  stepping_ = false;
  counts_.rhs_evals += static_cast<long>(a.evals[l]);
  const double err = a.err[l];
  if (a.ok[l] == 0.0 || err > 1.0) {
    ++d_.stats_.rejected;
    // The mechanism does not exist at a stage (or the norm is not finite): shrink. Else the
    // error test failed: the controller's shrink.
    h_trial_ = a.ok[l] == 0.0 ? 0.25 * h_try_ : h_try_ / std::min(1.0 / kFacMin, std::pow(err, kExpo) / kSafety);
    rejected_ = true;
    ++failures_;
    if (prepare_attempt()) return true;
    attempt_failed_ = true;
  } else {
    ++d_.stats_.accepted;
    accept(err);
  }
  return progress();
}

void Lane::dense(double t, Vec& y) const {
  if (!have_step_) {
    y = y1_;
    return;
  }
  for (int i = 0; i < 2; ++i) y[static_cast<std::size_t>(i)] = dense_component(t, i);
}

void Lane::locate_on_interpolant(int component, double& lo, double& glo, double& hi, double& ghi,
                                 double ttol) const {
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
    const double newton = t - v / slope;
    if (std::abs(newton - t) < 0.5 * ttol) {
      t = below ? t + 0.5 * ttol : t - 0.5 * ttol;
    } else if (newton > lo && newton < hi) {
      t = newton;
    } else {
      t = 0.5 * (lo + hi);
    }
  }
}

bool Lane::roots_at(double t, double* g) {
  Vec y{};
  dense(t, y);
  ++counts_.root_evals;
  return roots(t, y, g) == 0;
}

bool Lane::find_roots(double a, const double* g_a, double b, const double* g_b) {
  bool candidate = false;
  for (int i = 0; i < kRootCount; ++i) candidate = candidate || (g_a[i] != 0.0 && g_a[i] * g_b[i] <= 0.0);
  if (!candidate) return false;
  ++d_.stats_.root_searches;
  const double ttol = root_tolerance(b, h_step_);
  double earliest = std::numeric_limits<double>::infinity();
  std::array<double, kRootCount> when;  // NOLINT: filled below for every root
  std::array<double, kRootCount> g;     // NOLINT: filled by roots_at before use
  bool any = false;
  for (int i = 0; i < kRootCount; ++i) {
    const auto k = static_cast<std::size_t>(i);
    when[k] = std::numeric_limits<double>::infinity();
    const double ga = g_a[i], gb = g_b[i];
    if (ga == 0.0 || ga * gb > 0.0) continue;
    if (dirs_[k] != 0 && dirs_[k] * ga > 0.0) continue;
    double lo = a, glo = ga, hi = b, ghi = gb;
    const int component = i == kImpact ? 0 : i == kThetaPeak ? 1 : -1;
    if (component >= 0) {
      locate_on_interpolant(component, lo, glo, hi, ghi, ttol);
      when[k] = hi;
      earliest = std::min(earliest, hi);
      any = true;
      continue;
    }
    int last = 0;
    for (int it = 0; it < 200 && hi - lo > ttol && ghi != 0.0; ++it) {
      double t = hi - ghi * (hi - lo) / (ghi - glo);
      const double margin = 0.5 * ttol;
      t = std::clamp(t, lo + margin, hi - margin);
      if (!roots_at(t, g.data())) break;
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
    when[k] = hi;
    earliest = std::min(earliest, hi);
    any = true;
  }
  if (!any) return false;
  found_.fill(0);
  for (std::size_t k = 0; k < kRootCount; ++k)
    if (when[k] <= earliest + ttol) found_[k] = 1;
  root_time_ = earliest;
  return true;
}

Advance Lane::advance(double tout, double& t, Vec& y) {
  if (stepping_) return Advance::kPending;
  if (attempt_failed_) {
    attempt_failed_ = false;
    t = tcur_;
    y = y1_;
    return Advance::kFailure;
  }
  for (;;) {
    if (!have_step_ || tcur_ >= t1_) {
      if (t_stop_ - tcur_ <= 16.0 * kEps * std::max(1.0, std::abs(t_stop_))) tcur_ = std::max(tcur_, t_stop_);
      if (tcur_ >= t_stop_) {
        t = tcur_;
        y = y1_;
        return Advance::kReachedTime;
      }
      if (counts_.steps > d_.solver_.max_steps) {
        fail("more than max_steps steps");
      } else if (begin_step()) {
        return Advance::kPending;
      }
      t = tcur_;
      y = y1_;
      return Advance::kFailure;
    }
    if (find_roots(tcur_, g_cur_.data(), t1_, g_end_.data())) {
      Vec yr{};
      dense(root_time_, yr);
      tcur_ = root_time_;
      roots_at(tcur_, g_cur_.data());
      t = tcur_;
      y = yr;
      return Advance::kRoot;
    }
    if (tout < t1_) {
      Vec yo{};
      dense(tout, yo);
      tcur_ = tout;
      g_cur_ = g_end_;
      t = tout;
      y = yo;
      return Advance::kReachedTime;
    }
    tcur_ = t1_;
    g_cur_ = g_end_;
    if (tcur_ >= tout) {
      t = tcur_;
      y = y1_;
      return Advance::kReachedTime;
    }
  }
}

// ---------------------------------------------------------------------------------------
// The case.

/// rocking_solver.cpp's rest_throughout: a case whose frame rests through the whole record.
std::optional<CaseResult> rest_throughout(PreparedFrame& frame, const Excitation& excitation,
                                          const OutputRequest& request) {
  const PhysicsOptions& physics = frame.physics();
  if (frame.broken_at_rest() || physics.theta0_rad != 0.0 || physics.omega0_rad_s != 0.0) return std::nullopt;
  const CaseEnd end(excitation, frame.scene().gravity_m_s2(), physics);
  if (end.free_fall) return std::nullopt;
  const double t_end = end.rest_end_s(0.0);
  if (!std::isnan(first_opening(excitation, frame.scene(), 0.0, t_end))) return std::nullopt;
  CaseResult result = initial_result(frame.scene(), excitation, frame.restitution(), request.omega_peak);
  result.status = CaseStatus::kAtRest;
  result.t_end_s = t_end;
  return result;
}

void Lane::start(std::size_t c, PreparedFrame& frame) {
  busy_ = true;
  case_ = c;
  frame_ = &frame;
  scene_ = &frame.scene();
  start_ = std::chrono::steady_clock::now();
  restitution_ = frame.restitution();
  stop_ = frame.stop_angles();
  table_ = &frame.table();
  end_.emplace(d_.excitation_, scene_->gravity_m_s2(), frame.physics());
  t_end_ = end_->t_end_s;
  at_rest_ = true, done_ = false;
  t_ = 0.0;
  last_y_ = {0.0, 0.0};
  side_ = -1;
  stepping_ = attempt_failed_ = false;
  have_step_ = false;
  t0_ = t1_ = tcur_ = 0.0;
  y0_ = y1_ = k1_ = k7_ = {0.0, 0.0};
  h_ = 0.0;
  counts_ = {};
  error_.clear();
  d_.set_block_parameters(l_, *scene_);
  result_ = initial_result(*scene_, d_.excitation_, restitution_, d_.request_.omega_peak);
  if (stop_.broken_at_rest()) {
    finish(CaseStatus::kTendonFracture, kBrokenAtRestMessage);
  } else if (frame.physics().theta0_rad != 0.0 || frame.physics().omega0_rad_s != 0.0) {
    start_displaced();
  }
}

bool Lane::progress() {
  while (!done_) {
    if (at_rest_) {
      rest_until_uplift();
    } else if (!fly()) {
      return true;
    }
  }
  return false;
}

CaseResult Lane::finish_case() {
  busy_ = false;
  result_.counts = counts_;
  set_peak_strains(*scene_, result_);
  result_.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return std::move(result_);
}

void Lane::rest_until_uplift() {
  const double t_stop = end_->rest_end_s(t_);
  const double t_open = t_ < t_stop ? first_opening(d_.excitation_, *scene_, t_, t_stop) : std::nan("");
  if (std::isnan(t_open)) {
    t_ = t_stop;
    finish(end_->status(CaseStatus::kAtRest), end_->message());
    return;
  }
  t_ = t_open;
  if (std::isnan(result_.t_uplift_s)) result_.t_uplift_s = t_open;
  side_ = uplift_side(d_.excitation_.at(t_open).horizontal_m_s2);
  at_rest_ = false;
  start_flight(t_open, {0.0, 0.0});
}

void Lane::start_displaced() {
  const PhysicsOptions& physics = frame_->physics();
  const double th = physics.theta0_rad, w = physics.omega0_rad_s;
  side_ = initial_side(th, w);
  at_rest_ = false;
  result_.t_uplift_s = 0.0;
  note_theta(0.0, th);
  if (d_.request_.omega_peak) note_omega(0.0, w);
  start_flight(0.0, {th, w});
}

void Lane::start_flight(double t, const Vec& y) {
  ++d_.stats_.flights;
  double h0 = 0.0;
  if (y[0] == 0.0 && y[1] != 0.0) {
    const double a = std::abs(scene_->rest_acceleration(d_.excitation_.at(t), side_));
    const double flight_s = 2.0 * std::abs(y[1]) / a;
    if (std::isfinite(flight_s) && flight_s < 0.01) h0 = flight_s / 16.0;
  }
  restart(t, y, directions(), t_end_, h0);
}

bool Lane::fly() {
  Vec y{};
  double t = t_;
  const double tout = std::min(t_end_, t_ + 1.0);
  const Advance outcome = advance(tout, t, y);
  if (outcome == Advance::kPending) return false;
  t_ = t;
  last_y_ = y;
  if (outcome == Advance::kFailure) {
    finish(CaseStatus::kSolverFailure, error_);
    return true;
  }
  if (!std::isfinite(y[0]) || !std::isfinite(y[1])) {
    finish(CaseStatus::kSolverFailure, "non-finite state at t = " + std::to_string(t) + " s");
    return true;
  }
  if (counts_.steps > d_.solver_.max_steps) {
    finish(CaseStatus::kSolverFailure, "more than max_steps steps");
    return true;
  }
  if (outcome == Advance::kRoot) {
    ++d_.stats_.events;
    if (handle_roots(t, y)) return true;
  }
  note_theta(t, y[0]);
  if (d_.request_.omega_peak) note_omega(t, y[1]);
  if (t >= t_end_) {
    finish(end_->status(CaseStatus::kRockingAtEnd), end_->message());
  } else if (over_time()) {
    finish(CaseStatus::kTimeLimit, "wall-time limit reached at t = " + std::to_string(t) + " s");
  }
  return true;
}

bool Lane::handle_roots(double t, const Vec& y) {
  if (found_[kThetaPeak]) note_theta(t, y[0]);
  if (found_[kOmegaPeak] && d_.request_.omega_peak) note_omega(t, y[1]);
  if (found_[kLimit]) {
    note_theta(t, y[0]);
    finish(stop_.status(), stop_.message());
    return true;
  }
  if (!found_[kImpact]) return false;
  if (side_ * y[1] < 0.0) {
    impact(t, y);
    return true;
  }
  if (holds_closed(t)) {
    settle(t);
    return true;
  }
  return false;
}

void Lane::impact(double t, const Vec& y) {
  const double omega_before = y[1];
  if (d_.request_.omega_peak) note_omega(t, omega_before);
  ++result_.impacts;
  const double omega_after = restitution_ * omega_before;
  side_ = -side_;
  if (returns_to_rest(t, omega_after)) {
    settle(t);
    return;
  }
  start_flight(t, {0.0, omega_after});
}

bool Lane::returns_to_rest(double t, double omega_after) const {
  if (!holds_closed(t) || restitution_ >= 1.0) return false;
  const GroundAcceleration a = d_.excitation_.at(t);
  const double a_min =
      std::min(std::abs(scene_->rest_acceleration(a, -1)), std::abs(scene_->rest_acceleration(a, +1)));
  const double v = std::abs(omega_after);
  const double remaining_s = 2.0 * v / (a_min * (1.0 - restitution_));
  const double rise_rad = v * v / (2.0 * a_min);
  return remaining_s <= frame_->physics().zeno_time_s || rise_rad <= 10.0 * d_.solver_.atol_theta_rad;
}

bool Lane::holds_closed(double t) const { return scene_->holds_closed(d_.excitation_.at(t)); }

void Lane::settle(double t) {
  at_rest_ = true;
  t_ = t;
}

void Lane::note_theta(double t, double theta) {
  if (std::abs(theta) > result_.theta_max_rad) {
    result_.theta_max_rad = std::abs(theta);
    result_.t_theta_max_s = t;
  }
}

void Lane::note_omega(double t, double omega) {
  if (std::abs(omega) > result_.omega_max_rad_s) {
    result_.omega_max_rad_s = std::abs(omega);
    result_.t_omega_max_s = t;
  }
}

void Lane::finish(CaseStatus status, std::string message) {
  if (status == CaseStatus::kRockingAtEnd && at_rest_) status = CaseStatus::kAtRest;
  result_.status = status;
  result_.message = std::move(message);
  result_.t_end_s = t_;
  done_ = true;
}

bool Lane::over_time() const {
  if (d_.solver_.wall_time_limit_s <= 0.0) return false;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() >
         d_.solver_.wall_time_limit_s;
}

// ---------------------------------------------------------------------------------------
// The driver.

bool Driver::all_rigid_rockers(std::span<PreparedFrame* const> frames) {
  return std::all_of(frames.begin(), frames.end(),
                     [](PreparedFrame* f) { return dynamic_cast<const RigidRocker*>(&f->scene()) != nullptr; });
}

int capacity_for(int lanes, int register_lanes) {
  return (lanes + register_lanes - 1) / register_lanes * register_lanes;
}

AttemptKernel kernel_of(const KernelSet& set, const std::string& trig) {
  if (trig.empty() || trig == "libm") return set.libm_trig;
  if (trig == "xsimd") return set.xsimd_trig;
  if (trig == "sleef") {
    if (set.sleef_trig == nullptr) throw std::invalid_argument("batch trig 'sleef': not built with SLEEF");
    return set.sleef_trig;
  }
  throw std::invalid_argument("unknown batch trig '" + trig + "' (expected libm, sleef or xsimd)");
}

Driver::Driver(std::span<PreparedFrame* const> frames, const Excitation& excitation, const SolverSettings& solver,
               const OutputRequest& request, const BatchOptions& options, std::vector<CaseResult>& results,
               BatchStats& stats)
    : frames_(frames),
      excitation_(excitation),
      solver_(solver),
      request_(request),
      samples_{excitation.dt_s(), excitation.horizontal().size()},
      results_(results),
      stats_(stats),
      arrays_(capacity_for(options.lanes, choose_kernels(options.lanes, options.kernels).register_lanes)),
      block_(all_rigid_rockers(frames)) {
  const KernelSet set = choose_kernels(options.lanes, options.kernels);
  kernel_ = kernel_of(set, options.trig);
  stats_.kernels = set.name;
  stats_.trig = options.trig.empty() || set.register_lanes == 1 ? "libm" : options.trig;
  stats_.lanes = arrays_.capacity();
  arrays_.rtol = solver.rtol;
  arrays_.atol_theta = solver.atol_theta_rad;
  arrays_.atol_omega = solver.atol_omega_rad_s;
  lanes_.reserve(static_cast<std::size_t>(arrays_.capacity()));
  for (int l = 0; l < arrays_.capacity(); ++l) lanes_.emplace_back(*this, l);
}

void Driver::set_block_parameters(int lane, const Scene& scene) {
  const auto* rocker = dynamic_cast<const RigidRocker*>(&scene);
  if (rocker == nullptr) return;
  const RockerParameters& p = rocker->parameters();
  // As RigidRocker's constructor computes them.
  const double inertia_m2 = p.size_m * p.size_m * (4.0 / 3.0 + 4.0 * p.beam_mass_ratio);
  const auto l = static_cast<std::size_t>(lane);
  arrays_.alpha[l] = p.slenderness_rad;
  arrays_.moment_over_inertia[l] = (1.0 + 2.0 * p.beam_mass_ratio) * p.size_m / inertia_m2;
  arrays_.gravity[l] = p.gravity_m_s2;
}

bool Driver::refill(Lane& lane) {
  while (next_case_ < frames_.size()) {
    const std::size_t c = next_case_++;
    PreparedFrame& frame = *frames_[c];
    detail::validate(solver_, frame.physics());
    check_initial_state(frame.scene(), frame.physics());
    const auto start = std::chrono::steady_clock::now();
    ++stats_.cases;
    if (auto rest = rest_throughout(frame, excitation_, request_)) {
      ++stats_.rest_cases;
      results_[c] = std::move(*rest);
      results_[c].wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      continue;
    }
    lane.start(c, frame);
    if (lane.progress()) return true;
    results_[c] = lane.finish_case();
  }
  return false;
}

void Driver::run() {
  // Every lane up to its first attempt.
  int pending = 0;
  for (Lane& lane : lanes_) pending += refill(lane) ? 1 : 0;
  while (pending > 0) {
    kernel_(arrays_, *this, block_);
    ++stats_.kernel_calls;
    stats_.busy_lane_attempts += pending;
    pending = 0;
    for (Lane& lane : lanes_) {
      if (!lane.stepping_) continue;
      bool more = lane.take_attempt();
      if (!more) {
        results_[lane.case_index()] = lane.finish_case();
        more = refill(lane);
      }
      pending += more ? 1 : 0;
    }
  }
}

}  // namespace
}  // namespace detail::batch

bool batch_integrates(const SolverSettings& solver) {
  return solver.integrator == Integrator::kDormandPrince5 && !solver.verdict_check;
}

std::vector<CaseResult> solve_batch(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                                    const SolverSettings& solver, const OutputRequest& request,
                                    const BatchOptions& options, BatchStats* stats) {
  if (options.lanes < 1 || options.lanes > 64)
    throw std::invalid_argument("batch lanes: must lie in 1 … 64, got " + std::to_string(options.lanes));
  std::vector<CaseResult> results(frames.size());
  BatchStats local;
  BatchStats& s = stats != nullptr ? *stats : local;
  s = {};
  if (!batch_integrates(solver)) {
    s.scalar_cases = static_cast<long>(frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) results[i] = solve_case(*frames[i], excitation, solver, request);
    return results;
  }
  detail::batch::Driver(frames, excitation, solver, request, options, results, s).run();
  return results;
}

}  // namespace pcrf
