/// \file case_kernel.hpp
/// \brief The case kernel: one case of a rigid rocker (Housner's block, the Makris–Vassiliou
/// frame) or of the prestressed frame (its tabulated terms, EomTable) under one horizontal
/// record, start to end — rest scan, uplift, Dormand–Prince flights with their events,
/// impacts, the return to rest, the stops, the until-rest tail —
/// as one function over plain data, compiled as host C++ in every build and as CUDA device
/// code where nvcc is found (case_kernel.cu). Private to the solver.
///
/// One source, two compilers (as SUNDIALS' nvector/cuda and Eigen's arch/GPU do it: the
/// numerics are plain functions marked PCRF_HD, the integrators never learn of the GPU):
///  - the arithmetic of a step is the CPU engine's own, not a copy: the attempt
///    (dopri5/dopri5_attempt.hpp), the right-hand side (rigid_rocker_acceleration) and its
///    sin/cos (rocker_sincos), the root search (integrator/root_search.hpp), the prestressed
///    frame's table (EomTable::all_cells: the cells the CPU builds);
///  - the control around it — DormandPrinceIntegrator's restart, step-size control,
///    breakpoints and roots (dopri5/dormand_prince.cpp), CaseRun's state machine
///    (case/case_run.cpp), the record's interpolation (GroundMotion::accel_m_s2, which
///    ExcitationCursor repeats), the rest scan (first_exceedance) and the table's look-up
///    (EomTable::locate, power_series4 lane by lane) — is restated here
///    without exceptions, heap, strings, std::function or virtual calls, operation for
///    operation in the same order: the host build equals solve_case with integrator dopri5
///    bit for bit (tests/solver/case_kernel_test.cpp checks every metric and counter).
///    A change to one of those must be made here too; the test says where it was missed.
///  - the errors a step can meet are statuses (KernelError); the host turns them into the
///    CPU path's messages (kernel_group.cpp).
/// What the kernel does not take (another scene, integrator or excitation, a history, the
/// verdict check, a wall-time limit) the host refuses before it is called. A prestressed
/// frame whose stage falls where its table holds no cell (the CPU evaluates the exact terms
/// there: a long step across θ₁ = 0 overshooting by more than a cell) ends kLeftTable, and the
/// host refuses the case.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "pcrf/host_device.hpp"
#include "pcrf/model/eom_table.hpp"
#include "pcrf/model/rigid_rocker.hpp"
#include "../dopri5/dopri5_attempt.hpp"
#include "../integrator/root_search.hpp"

namespace pcrf::device {

// ---- math on both sides -------------------------------------------------------------------
// The C library's functions on the host (the CPU engine's), CUDA's on the device (log, exp and
// pow there are not glibc's bits: the device answers agree to rounding, not bit for bit).
PCRF_HD inline double kabs(double x) { return fabs(x); }
#if defined(__CUDA_ARCH__)
PCRF_HD inline bool kfinite(double x) { return isfinite(x); }
PCRF_HD inline bool knan(double x) { return isnan(x); }
#else
inline bool kfinite(double x) { return std::isfinite(x); }
inline bool knan(double x) { return std::isnan(x); }
#endif
PCRF_HD inline double kmin(double a, double b) { return b < a ? b : a; }  // std::min
PCRF_HD inline double kmax(double a, double b) { return a < b ? b : a; }  // std::max
PCRF_HD inline double kclamp(double v, double lo, double hi) { return v < lo ? lo : hi < v ? hi : v; }  // std::clamp
PCRF_HD inline double knan_value() { return std::numeric_limits<double>::quiet_NaN(); }
PCRF_HD inline double kinf() { return std::numeric_limits<double>::infinity(); }

/// dopri5_attempt's and rigid_rocker_acceleration's operations on one double (the CPU's
/// ScalarOps of dormand_prince.cpp and rigid_rocker.cpp).
struct KernelOps {
  using P = double;
  using M = bool;
  PCRF_HD static P select(M m, P a, P b) { return m ? a : b; }
  PCRF_HD static M finite(P v) { return kfinite(v); }
  PCRF_HD static P abs(P v) { return fabs(v); }
  PCRF_HD static P sqrt(P v) { return ::sqrt(v); }
  PCRF_HD static bool none(M m) { return !m; }
  PCRF_HD static void sincos(double x, double& s, double& c) { rocker_sincos<KernelOps>(x, s, c); }
};

// ---- the data ------------------------------------------------------------------------------

/// One horizontal record (GroundMotion's numbers): the samples stay where the caller keeps them.
struct KernelRecord {
  const double* samples_m_s2 = nullptr;
  std::size_t count = 0;     ///< ≥ 1
  double dt_s = 0.0;
  double inv_dt_per_s = 0.0;  ///< GroundMotion::inverse_dt_per_s
  double pga_m_s2 = 0.0;      ///< GroundMotion::pga_m_s2
};

/// The tables of the prestressed frames of a group (EomTable::all_cells of each, one after
/// another): EomTable::kCellValues coefficients and a tabulated flag per cell.
struct KernelTables {
  const double* coefficients = nullptr;
  const unsigned char* tabulated = nullptr;
};

/// The tables of a group's prestressed frames, appended frame by frame on the host
/// (KernelTables views them).
struct KernelTableStore {
  std::vector<double> coefficients;
  std::vector<unsigned char> tabulated;
  /// Valid until the next append.
  KernelTables view() const { return {coefficients.data(), tabulated.data()}; }
};

/// One case's numbers, set on the host from the prepared frame, the settings and the record.
struct KernelCase {
  /// The right-hand side: a rigid rocker's (rigid_rocker_acceleration), else the frame's
  /// table (EomTable::acceleration: cells table_first … table_first + table_cells − 1).
  bool rigid = true;
  std::size_t table_first = 0, table_cells = 0;
  double table_inv_cell_per_rad = 0.0;
  // The rocker (rigid_rocker_acceleration) and the terms at rest (Scene::rest()).
  double slenderness_rad = 0.0, moment_over_inertia_per_m = 0.0, gravity_m_s2 = 0.0;
  double rest_I = 0.0, rest_G = 0.0, rest_K = 0.0, rest_S = 0.0;
  double uplift_threshold_m_s2 = 0.0;
  double restitution = 0.0;
  double stop_rad = 0.0;       ///< StopAngles::stop_rad
  bool broken_at_rest = false;
  // Physics.
  double theta0_rad = 0.0, omega0_rad_s = 0.0;
  double zeno_time_s = 0.0, rest_rise_rad = 0.0;
  double t_end_s = 0.0;       ///< CaseEnd::t_end_s
  double record_end_s = 0.0;  ///< the record's duration
  bool until_rest = false;
  // Solver.
  double rtol = 0.0, atol_theta_rad = 0.0, atol_omega_rad_s = 0.0, max_step_s = 0.0;
  long max_steps = 0;
  bool omega_peak = false;
};

/// How a case ended, as CaseRun's finish() would say it (the host adds the message).
enum class KernelEnd : std::int8_t {
  kReachedEnd = 0,   ///< t_end reached: at rest, or rocking at the end
  kAtRestEnd = 1,    ///< at rest when the case ended (a rest-end finish)
  kStopped = 2,      ///< reached the stop angle (StopAngles::status says which)
  kBrokenAtRest = 3,
  kSolverFailure = 4,
  kLeftTable = 5,  ///< a prestressed frame reached a state its table does not hold: no answer
};

/// A failure's cause and its numbers, for the CPU path's message.
enum class KernelError : std::int8_t {
  kNone = 0,
  kRhsAtStart,           ///< "dopri5: the right-hand side failed at the start, t = <a> s"
  kNonFiniteDerivative,  ///< "dopri5: non-finite derivative"
  kTooManyFailures,      ///< "dopri5: <kMaxFailures> failed step attempts in a row at t = <a> s"
  kStepTooSmall,         ///< "dopri5: step size <b> s too small at t = <a> s"
  kMaxSteps,             ///< "more than max_steps steps"
  kNonFiniteState,       ///< "non-finite state at t = <a> s" (std::to_string)
};

/// What the kernel computes of a CaseResult.
struct KernelResult {
  KernelEnd end = KernelEnd::kReachedEnd;
  bool at_rest = true;  ///< at rest when the case ended (kReachedEnd: at rest or rocking)
  KernelError error = KernelError::kNone;
  double error_a = 0.0, error_b = 0.0;
  double t_uplift_s = 0.0, theta_max_rad = 0.0, t_theta_max_s = 0.0, omega_max_rad_s = 0.0, t_omega_max_s = 0.0;
  long impacts = 0;
  double t_end_s = 0.0;
  long steps = 0, rhs_evals = 0, root_evals = 0, reinits = 0;
};

// ---- the record ----------------------------------------------------------------------------

/// Sample k of a record: through the read-only data path on the device (the record is
/// read-only for the kernel's lifetime), a plain load on the host.
PCRF_HD inline double load_sample(const double* samples, std::size_t k) {
#if defined(__CUDA_ARCH__)
  return __ldg(samples + k);
#else
  return samples[k];
#endif
}

/// GroundMotion::accel_m_s2: linear between samples, the last sample at the end, zero after.
PCRF_HD inline double ground_at(const KernelRecord& r, double t_s) {
  if (!(t_s >= 0.0)) return t_s < 0.0 ? 0.0 : t_s;
  const std::size_t last = r.count - 1;
  const double t_end_s = static_cast<double>(last) * r.dt_s;
  if (t_s >= t_end_s) return t_s == t_end_s ? load_sample(r.samples_m_s2, last) : 0.0;
  auto k = static_cast<std::size_t>(t_s * r.inv_dt_per_s);  // GroundMotion::interval_of
  k -= static_cast<std::size_t>(static_cast<double>(k) * r.dt_s > t_s);
  k += static_cast<std::size_t>(static_cast<double>(k + 1) * r.dt_s <= t_s);
  const double frac = (t_s - static_cast<double>(k) * r.dt_s) * r.inv_dt_per_s;
  const double a0 = load_sample(r.samples_m_s2, k);
  return a0 + frac * (load_sample(r.samples_m_s2, k + 1) - a0);
}

/// first_exceedance (case_common.cpp) of the horizontal record: the first time ≥ t_from at
/// which |ü_g| exceeds the threshold; NaN when never before t_end.
PCRF_HD inline double first_exceedance(const KernelRecord& r, double t_from, double t_end, double threshold_m_s2) {
  if (r.pga_m_s2 < threshold_m_s2 * (1.0 - 1e-9)) return knan_value();
  if (kabs(ground_at(r, t_from)) > threshold_m_s2) return t_from;
  if (threshold_m_s2 < 0.0) return t_from;
  const double dt = r.dt_s;
  auto a = [&r](std::size_t k) { return load_sample(r.samples_m_s2, k); };
  auto crosses_level = [](double level, double a1) { return level > 0 ? a1 > level : a1 < level; };
  auto exceeds = [&](double a1) { return crosses_level(threshold_m_s2, a1) || crosses_level(-threshold_m_s2, a1); };
  auto i = static_cast<std::size_t>(kmax(0.0, floor(t_from / dt)));
  std::size_t end = i + 1;
  while (end < r.count && !exceeds(a(end))) ++end;
  if (end >= r.count) return knan_value();
  i = end - 1;
  const double t0 = static_cast<double>(i) * dt;
  if (t0 > t_end) return knan_value();
  const double a0 = a(i), a1 = a(i + 1);
  double best = knan_value();
  const double levels[2] = {threshold_m_s2, -threshold_m_s2};
  for (const double level : levels) {
    if (!crosses_level(level, a1)) continue;
    const double s = kclamp((level - a0) / (a1 - a0), 0.0, 1.0);
    const double tc = kmax(t0 + s * dt, t_from);
    if (knan(best) || tc < best) best = tc;
  }
  return best <= t_end ? best : knan_value();
}

/// NextSample (integrator.hpp): the record's samples after t, the last one found checked first.
struct KernelNextSample {
  double dt_s = 0.0;
  std::size_t count = 0;
  double last_k = 0.0, min_gap_s = 0.0, k = 0.0, tb = 0.0, t = 0.0;

  PCRF_HD void init(double dt, std::size_t n) {
    dt_s = dt, count = n;
    last_k = static_cast<double>(n) - 1.0;
    min_gap_s = 1e-9 * dt;
  }
  PCRF_HD double next_after(double t_s) const {  // SampleGrid::next_after
    if (count == 0 || !(dt_s > 0.0)) return kinf();
    double kk = kmax(floor(t_s / dt_s) + 1.0, 1.0);
    double b = kk * dt_s;
    while (b <= t_s || b - t_s < 1e-9 * dt_s) b = ++kk * dt_s;
    return kk <= static_cast<double>(count - 1) ? b : kinf();
  }
  PCRF_HD bool ahead(double b, double t_s) const { return b > t_s && !(b - t_s < min_gap_s); }
  PCRF_HD double remember(double t_s) {
    t = t_s;
    return k <= last_k ? tb : kinf();
  }
  PCRF_HD double after(double t_s) {
    if (k > 0.0 && t_s >= t) {
      if (ahead(tb, t_s)) return remember(t_s);
      const double k1 = k + 1.0, b = k1 * dt_s;
      if (ahead(b, t_s)) {
        k = k1, tb = b;
        return remember(t_s);
      }
    }
    tb = next_after(t_s);
    k = kfinite(tb) ? round(tb / dt_s) : 0.0;
    return remember(t_s);
  }
};

// ---- the case ------------------------------------------------------------------------------

/// Root indices (case_run.hpp's Root).
enum KernelRoot { kImpact = 0, kThetaPeak = 1, kOmegaPeak = 2, kLimit = 3, kRootCount = 4 };

/// One case: FlightProblem, DormandPrinceIntegrator (not in lockstep) and CaseRun in one.
class CaseKernel {
 public:
  PCRF_HD CaseKernel(const KernelCase& c, const KernelRecord& r, const KernelTables& tables)
      : c_(c), r_(r), tables_(tables) {
    next_sample_.init(r.dt_s, r.count);
    atol_[0] = c.atol_theta_rad, atol_[1] = c.atol_omega_rad_s;
  }

  /// The whole case (CaseRun::run without its history).
  PCRF_HD void run(KernelResult& out) {
    out = KernelResult{};
    out_ = &out;
    out.t_uplift_s = knan_value();
    out.t_theta_max_s = knan_value();
    out.t_omega_max_s = knan_value();
    out.theta_max_rad = 0.0;
    out.omega_max_rad_s = c_.omega_peak ? 0.0 : knan_value();
    if (c_.broken_at_rest) {
      finish(KernelEnd::kBrokenAtRest);
    } else if (c_.theta0_rad != 0.0 || c_.omega0_rad_s != 0.0) {
      start_displaced();
    }
    while (!done_) {
      if (at_rest_) {
        rest_until_uplift();
      } else {
        fly();
      }
    }
    if (left_table_) out.end = KernelEnd::kLeftTable;  // the CPU evaluates the exact terms there
    out.steps = steps_, out.rhs_evals = rhs_evals_, out.root_evals = root_evals_, out.reinits = reinits_;
  }

 private:
  // ---- the flight problem (FlightProblem) ----
  PCRF_HD bool acceleration(double t, const double* y, double& acc) {
    if (c_.rigid) {
      acc = rigid_rocker_acceleration<KernelOps>(c_.moment_over_inertia_per_m, c_.slenderness_rad, c_.gravity_m_s2, y[0],
                                                 side_ < 0, ground_at(r_, t), 0.0);
      return kfinite(acc);
    }
    double v[4];
    if (!table_ratios(y[0], v)) {
      left_table_ = true;  // the case is not answered (kLeftTable)
      return false;
    }
    const double s = side_ < 0 ? 1.0 : -1.0;  // detail::ratios_acceleration, no vertical component
    acc = v[0] * ground_at(r_, t) - s * (v[1] * y[1] * y[1] + (v[2] + v[3] * 0.0));
    return kfinite(acc);
  }
  /// EomTable::locate and power_series4: the ratios A, B, C, D at θ₁ on the current side;
  /// false where the table holds no tabulated cell (the CPU's exact terms).
  PCRF_HD bool table_ratios(double theta1, double* v) const {
    const double u = side_ < 0 ? -theta1 : theta1;
    const double w = u * c_.table_inv_cell_per_rad;
    if (!(w >= -1.0 && w < static_cast<double>(c_.table_cells))) return false;
    auto whole = static_cast<long>(w);
    whole -= static_cast<long>(w < static_cast<double>(whole));
    const long index = whole + 1;
    if (index < 0 || index >= static_cast<long>(c_.table_cells)) return false;
    const std::size_t cell = c_.table_first + static_cast<std::size_t>(index);
    if (!tables_.tabulated[cell]) return false;
    const double x = 2.0 * (w - static_cast<double>(whole)) - 1.0;
    const double* m = tables_.coefficients + cell * static_cast<std::size_t>(EomTable::kCellValues);
    const double x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
    for (int l = 0; l < 4; ++l) {  // power_series4's lanes, one at a time: the same operations
      auto c = [&](int k) { return load_sample(m, static_cast<std::size_t>(4 * k + l)); };
      const double q01 = c(0) + x * c(1), q23 = c(2) + x * c(3), q45 = c(4) + x * c(5), q67 = c(6) + x * c(7),
                   q89 = c(8) + x * c(9);
      v[l] = (q01 + x2 * q23) + x4 * (q45 + x2 * q67) + x8 * q89;
    }
    return true;
  }
  PCRF_HD int rhs(double t, const double* y, double* ydot) {
    double acc = 0;
    if (!acceleration(t, y, acc)) return 1;
    ydot[0] = y[1];
    ydot[1] = acc;
    return 0;
  }
  /// θ₁, θ̇₁, θ̈₁ (or 1), |θ₁| − θ_stop: root_value of each RootForm.
  PCRF_HD int roots(double t, const double* y, double* g) {
    double d[3] = {y[0], y[1], 0.0};
    if (c_.omega_peak && !acceleration(t, y, d[2])) return 1;
    g[kImpact] = d[0] - 0.0;
    g[kThetaPeak] = d[1] - 0.0;
    g[kOmegaPeak] = c_.omega_peak ? d[2] - 0.0 : 1.0;
    g[kLimit] = kabs(d[0]) - c_.stop_rad;
    return 0;
  }
  /// Scene::rest_acceleration without a vertical component.
  PCRF_HD double rest_acceleration(double ground_h, int side) const {
    const double s = side < 0 ? -1.0 : 1.0;
    return (c_.rest_S * ground_h + s * (c_.rest_G * (c_.gravity_m_s2 + 0.0) + c_.rest_K)) / c_.rest_I;
  }
  /// Scene::holds_closed: |ü_h| below the threshold (at ü_v = 0).
  PCRF_HD bool holds_closed(double t) const {
    return kabs(ground_at(r_, t)) < (c_.rest_G * (c_.gravity_m_s2 + 0.0) + c_.rest_K) / c_.rest_S;
  }

  // ---- the integrator (DormandPrinceIntegrator) ----
  PCRF_HD bool fail(KernelError e, double a = 0.0, double b = 0.0) {
    error_ = e, error_a_ = a, error_b_ = b;
    return false;
  }

  PCRF_HD void restart(double t0, const double* y0, double t_stop, double h0) {
    if (steps_ > 0 || rhs_evals_ > 0) ++reinits_;
    t0_ = t1_ = tcur_ = t0;
    y0_[0] = y1_[0] = y0[0];
    y0_[1] = y1_[1] = y0[1];
    t_stop_ = t_stop;
    have_step_ = false;
    log_err_old_ = log_err_floor();
    error_ = KernelError::kNone;
    for (int i = 0; i < kRootCount; ++i) found_[i] = 0;
    dirs_[0] = -side_, dirs_[1] = -side_, dirs_[2] = 0, dirs_[3] = 1;  // FlightProblem::directions
    ++rhs_evals_;
    if (rhs(t0, y0_, k1_) != 0) {
      fail(KernelError::kRhsAtStart, t0);
      k1_[0] = k1_[1] = knan_value();
    }
    k7_[0] = k1_[0], k7_[1] = k1_[1];
    if (h0 > 0.0) {
      h_ = h0;
    } else if (!(steps_ > 0 && h_ > 0.0)) {
      h_ = initial_step();
    }
    ++root_evals_;
    roots(t0, y0_, g_cur_.data());
    bool zero = false;
    for (int i = 0; i < kRootCount; ++i) zero = zero || g_cur_[i] == 0.0;
    if (zero && kfinite(k1_[0])) {
      const double dt = kmax(detail::root_tolerance(t0, h_), 0.1 * h_);
      const double y[2] = {y0_[0] + dt * k1_[0], y0_[1] + dt * k1_[1]};
      double g[kRootCount];
      ++root_evals_;
      roots(t0 + dt, y, g);
      for (int i = 0; i < kRootCount; ++i)
        if (g_cur_[i] == 0.0) g_cur_[i] = g[i];
    }
  }

  PCRF_HD static double log_err_floor() { return log(1e-4); }

  PCRF_HD double weight(int i, double magnitude) const { return atol_[i] + c_.rtol * magnitude; }

  PCRF_HD double initial_step() {
    double hmax = t_stop_ - t0_;
    if (c_.max_step_s > 0.0) hmax = kmin(hmax, c_.max_step_s);
    if (!(hmax > 0.0)) return 0.0;
    double dnf = 0.0, dny = 0.0;
    for (int i = 0; i < 2; ++i) {
      const double sk = weight(i, kabs(y0_[i]));
      dnf += (k1_[i] / sk) * (k1_[i] / sk);
      dny += (y0_[i] / sk) * (y0_[i] / sk);
    }
    double h = dnf <= 1e-10 || dny <= 1e-10 ? 1e-6 : ::sqrt(dny / dnf) * 0.01;
    h = kmin(h, hmax);
    const double y1[2] = {y0_[0] + h * k1_[0], y0_[1] + h * k1_[1]};
    double f1[2] = {0.0, 0.0};
    ++rhs_evals_;
    if (rhs(t0_ + h, y1, f1) != 0) return h;
    double der2 = 0.0;
    for (int i = 0; i < 2; ++i) {
      const double sk = weight(i, kabs(y0_[i]));
      der2 += ((f1[i] - k1_[i]) / sk) * ((f1[i] - k1_[i]) / sk);
    }
    der2 = ::sqrt(der2 / 2.0) / h;
    const double der12 = kmax(kabs(der2), ::sqrt(dnf / 2.0));
    const double h1 = der12 <= 1e-15 ? kmax(1e-6, kabs(h) * 1e-3) : pow(0.01 / der12, 0.2);
    return kmin(kmin(100.0 * h, h1), hmax);  // std::min({100 h, h1, hmax}): the first smallest
  }

  PCRF_HD void try_step() {
    const double t = t0_, h = h_try_;
    const double y0[2] = {y0_[0], y0_[1]}, k1[2] = {k1_[0], k1_[1]};
    const double atol[2] = {atol_[0], atol_[1]};
    long evals = 0;
    auto f = [&](double ts, const double* s, double* k, bool& alive) {
      ++evals;
      alive = rhs(ts, s, k) == 0;
    };
    attempt_ok_ = detail::dopri5_attempt<KernelOps>(t, h, y0, k1, atol, c_.rtol, f, out_stages_);
    attempt_evals_ = evals;
  }

  PCRF_HD bool step() {
    t0_ = tcur_;
    y0_[0] = y1_[0], y0_[1] = y1_[1];
    k1_[0] = k7_[0], k1_[1] = k7_[1];
    if (!kfinite(k1_[0]) || !kfinite(k1_[1]))
      return error_ == KernelError::kNone ? fail(KernelError::kNonFiniteDerivative) : false;
    limit_ = kmin(next_sample_.after(t0_), t_stop_);
    h_trial_ = h_;
    if (c_.max_step_s > 0.0) h_trial_ = kmin(h_trial_, c_.max_step_s);
    rejected_ = false;
    failures_ = 0;
    for (;;) {
      if (!prepare_attempt()) return false;
      try_step();
      if (conclude_attempt()) return true;
    }
  }

  PCRF_HD bool prepare_attempt() {
    if (failures_ > detail::kMaxFailures) return fail(KernelError::kTooManyFailures, t0_);
    clamped_ = t0_ + 1.01 * h_trial_ >= limit_;
    h_try_ = clamped_ ? limit_ - t0_ : h_trial_;
    if (!(h_try_ > 16.0 * detail::kEps * kabs(t0_)) || !(h_try_ > 0.0)) return fail(KernelError::kStepTooSmall, t0_, h_try_);
    return true;
  }

  PCRF_HD bool conclude_attempt() {
    rhs_evals_ += attempt_evals_;
    const double err = out_stages_.err;
    if (!attempt_ok_) {
      h_trial_ = 0.25 * h_try_;
    } else if (err > 1.0) {
      h_trial_ = h_try_ / kmin(1.0 / detail::kFacMin, pow(err, detail::kExpo) / detail::kSafety);
    } else {
      accept();
      return true;
    }
    rejected_ = true;
    ++failures_;
    return false;
  }

  PCRF_HD void accept() {
    const double err = out_stages_.err;
    const double log_err = log(kmax(err, 1e-300));
    if (clamped_ && detail::kFacMax * h_try_ <= h_trial_) {
      h_ = h_trial_;
    } else {
      double fac = exp(detail::kExpo * log_err - detail::kBeta * log_err_old_) / detail::kSafety;
      fac = kclamp(fac, 1.0 / detail::kFacMax, 1.0 / detail::kFacMin);
      double h_next = h_try_ / fac;
      if (rejected_) h_next = kmin(h_next, h_try_);
      h_ = clamped_ ? kmax(h_next, h_trial_) : h_next;
    }
    log_err_old_ = kmax(log_err, log_err_floor());
    t1_ = clamped_ ? limit_ : t0_ + h_try_;
    y1_[0] = out_stages_.y1[0], y1_[1] = out_stages_.y1[1];
    k7_[0] = out_stages_.k7[0], k7_[1] = out_stages_.k7[1];
    h_step_ = h_try_;
    cont_t0_ = t0_;
    have_step_ = true;
    ++steps_;
    ++root_evals_;
    roots(t1_, y1_, g_end_.data());
  }

  /// DormandPrinceIntegrator::dense_component.
  PCRF_HD double dense_component(double t, int i) const {
    const double s = (t - cont_t0_) / h_step_, s1 = 1.0 - s;
    const auto& c = out_stages_.cont;
    return c[0][i] + s * (c[1][i] + s1 * (c[2][i] + s * (c[3][i] + s1 * c[4][i])));
  }
  PCRF_HD double dense_slope(double t, int i) const {
    const double s = (t - cont_t0_) / h_step_, s1 = 1.0 - s;
    const auto& c = out_stages_.cont;
    return (c[1][i] + (1.0 - 2.0 * s) * c[2][i] + s * (2.0 - 3.0 * s) * c[3][i] + 2.0 * s * s1 * (s1 - s) * c[4][i]) /
           h_step_;
  }
  PCRF_HD void dense(double t, double* y) const {
    if (!have_step_) {
      y[0] = y1_[0], y[1] = y1_[1];
      return;
    }
    for (int i = 0; i < 2; ++i) y[i] = dense_component(t, i);
  }
  PCRF_HD bool roots_at(double t, double* g) {
    double y[2] = {0.0, 0.0};
    dense(t, y);
    ++root_evals_;
    return roots(t, y, g) == 0;
  }

  /// Root i's state component (OdeProblem::root_state_index of FlightProblem's forms): θ₁
  /// for the impact, θ̇₁ for the θ peak; −1 for the others.
  PCRF_HD static int root_state_index(int i) { return i == kImpact ? 0 : i == kThetaPeak ? 1 : -1; }

  PCRF_HD void locate(int i, double& lo, double& glo, double& hi, double& ghi, double ttol) {
    const int component = root_state_index(i);
    if (component >= 0) {
      detail::newton_in_bracket(
          [&](double t, double& v, double& slope, double&) { v = dense_component(t, component), slope = dense_slope(t, component); },
          lo, glo, hi, ghi, ttol);
    } else {
      detail::illinois_in_bracket<kMaxRoots>([this](double t, double* g) { return roots_at(t, g); }, i, lo, glo, hi, ghi,
                                             ttol);
    }
  }

  PCRF_HD bool find_roots(double a, const double* g_a, double b, const double* g_b) {
    auto at = [this](double t, double* g) { return this->roots_at(t, g); };
    auto loc = [this](int i, double& lo, double& glo, double& hi, double& ghi, double ttol) {
      this->locate(i, lo, glo, hi, ghi, ttol);
    };
    return detail::earliest_crossing(kRootCount, dirs_, kThetaPeak, a, g_a, b, g_b, detail::root_tolerance(b, h_step_), at,
                                     loc, root_time_, found_, g_root_);
  }

  enum class Outcome { kReachedTime, kRoot, kFailure };

  /// DormandPrinceIntegrator::advance, one_step false.
  PCRF_HD Outcome advance(double tout, double& t, double* y) {
    for (;;) {
      if (!have_step_ || tcur_ >= t1_) {
        if (t_stop_ - tcur_ <= 16.0 * detail::kEps * kmax(1.0, kabs(t_stop_))) tcur_ = kmax(tcur_, t_stop_);
        if (tcur_ >= t_stop_) {
          t = tcur_;
          y[0] = y1_[0], y[1] = y1_[1];
          return Outcome::kReachedTime;
        }
        if (steps_ > c_.max_steps) {
          fail(KernelError::kMaxSteps);
        } else {
          step();
        }
        if (error_ != KernelError::kNone) {
          t = tcur_;
          y[0] = y1_[0], y[1] = y1_[1];
          return Outcome::kFailure;
        }
      }
      if (find_roots(tcur_, g_cur_.data(), t1_, g_end_.data())) {
        double yr[2] = {0.0, 0.0};
        dense(root_time_, yr);
        tcur_ = root_time_;
        g_cur_ = g_root_;
        t = tcur_;
        y[0] = yr[0], y[1] = yr[1];
        return Outcome::kRoot;
      }
      if (tout < t1_) {
        double yo[2] = {0.0, 0.0};
        dense(tout, yo);
        tcur_ = tout;
        g_cur_ = g_end_;
        t = tout;
        y[0] = yo[0], y[1] = yo[1];
        return Outcome::kReachedTime;
      }
      tcur_ = t1_;
      g_cur_ = g_end_;
      if (tcur_ >= tout) {
        t = tcur_;
        y[0] = y1_[0], y[1] = y1_[1];
        return Outcome::kReachedTime;
      }
    }
  }

  // ---- the case (CaseRun) ----
  PCRF_HD double rest_end_s(double t_s) const {  // CaseEnd::rest_end_s
    return c_.until_rest ? kmin(kmax(t_s, c_.record_end_s), c_.t_end_s) : c_.t_end_s;
  }

  PCRF_HD void finish(KernelEnd end) {
    out_->end = end;
    out_->at_rest = at_rest_;
    out_->t_end_s = t_;
    done_ = true;
  }
  PCRF_HD void fail_case(KernelError e, double a = 0.0, double b = 0.0) {
    out_->error = e, out_->error_a = a, out_->error_b = b;
    finish(KernelEnd::kSolverFailure);
  }

  PCRF_HD void rest_until_uplift() {
    const double t_stop = rest_end_s(t_);
    const double t_open = t_ < t_stop ? first_exceedance(r_, t_, t_stop, c_.uplift_threshold_m_s2) : knan_value();
    if (knan(t_open)) {
      t_ = t_stop;
      finish(KernelEnd::kAtRestEnd);
      return;
    }
    t_ = t_open;
    if (knan(out_->t_uplift_s)) out_->t_uplift_s = t_open;
    side_ = ground_at(r_, t_open) > 0.0 ? -1 : +1;  // uplift_side
    const double y0[2] = {0.0, 0.0};
    at_rest_ = false;
    start_flight(t_open, y0);
  }

  PCRF_HD void start_displaced() {
    const double th = c_.theta0_rad, w = c_.omega0_rad_s;
    side_ = th < 0.0 || (th == 0.0 && w < 0.0) ? -1 : +1;  // initial_side
    const double y0[2] = {th, w};
    at_rest_ = false;
    out_->t_uplift_s = 0.0;
    note_theta(0.0, th);
    if (c_.omega_peak) note_omega(0.0, w);
    start_flight(0.0, y0);
  }

  PCRF_HD void start_flight(double t, const double* y) {
    double h0 = 0.0;
    if (y[0] == 0.0 && y[1] != 0.0) {
      const double a = kabs(rest_acceleration(ground_at(r_, t), side_));
      const double flight_s = 2.0 * kabs(y[1]) / a;
      if (kfinite(flight_s) && flight_s < 0.01) h0 = flight_s / 16.0;
    }
    restart(t, y, c_.t_end_s, h0);
  }

  PCRF_HD void fly() {
    double y[2];
    double t = t_;
    const double tout = kmin(c_.t_end_s, t_ + 1.0);  // the integrator stops at the samples itself
    const Outcome outcome = advance(tout, t, y);
    t_ = t;
    if (outcome == Outcome::kFailure) return fail_case(error_, error_a_, error_b_);
    if (!kfinite(y[0]) || !kfinite(y[1])) return fail_case(KernelError::kNonFiniteState, t);
    if (steps_ > c_.max_steps) return fail_case(KernelError::kMaxSteps);
    if (outcome == Outcome::kRoot && handle_roots(t, y)) return;
    note_theta(t, y[0]);
    if (c_.omega_peak) note_omega(t, y[1]);
    if (t >= c_.t_end_s) finish(KernelEnd::kReachedEnd);
  }

  PCRF_HD bool handle_roots(double t, double* y) {
    const int* found = found_.data();
    if (found[kThetaPeak] && !found[kLimit] && kabs(y[0]) >= c_.stop_rad) {
      stop_at(t, copysign(c_.stop_rad, y[0]), y[1]);
      return true;
    }
    if (found[kThetaPeak]) note_theta(t, y[0]);
    if (found[kOmegaPeak] && c_.omega_peak) note_omega(t, y[1]);
    if (found[kLimit]) {
      stop_at(t, y[0], y[1]);
      return true;
    }
    if (!found[kImpact]) return false;
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

  PCRF_HD void stop_at(double t, double theta, double omega) {
    note_theta(t, theta);
    if (c_.omega_peak) note_omega(t, omega);
    finish(KernelEnd::kStopped);
  }

  PCRF_HD void impact(double t, double* y) {
    const double omega_before = y[1];
    if (c_.omega_peak) note_omega(t, omega_before);
    ++out_->impacts;
    const double omega_after = c_.restitution * omega_before;
    side_ = -side_;
    if (returns_to_rest(t, omega_after)) {
      settle(t);
      return;
    }
    const double y0[2] = {0.0, omega_after};
    start_flight(t, y0);
  }

  PCRF_HD bool returns_to_rest(double t, double omega_after) const {
    if (!holds_closed(t) || c_.restitution >= 1.0) return false;
    const double a = ground_at(r_, t);
    const double a_min = kmin(kabs(rest_acceleration(a, -1)), kabs(rest_acceleration(a, +1)));
    const double v = kabs(omega_after);
    const double remaining_s = 2.0 * v / (a_min * (1.0 - c_.restitution));
    const double rise_rad = v * v / (2.0 * a_min);
    return remaining_s <= c_.zeno_time_s || rise_rad <= c_.rest_rise_rad;
  }

  PCRF_HD void settle(double t) {
    at_rest_ = true;
    t_ = t;
  }

  PCRF_HD void note_theta(double t, double theta) {
    if (kabs(theta) > out_->theta_max_rad) {
      out_->theta_max_rad = kabs(theta);
      out_->t_theta_max_s = t;
    }
  }
  PCRF_HD void note_omega(double t, double omega) {
    if (kabs(omega) > out_->omega_max_rad_s) {
      out_->omega_max_rad_s = kabs(omega);
      out_->t_omega_max_s = t;
    }
  }

  static constexpr std::size_t kMaxRoots = kRootCount;

  const KernelCase& c_;
  const KernelRecord& r_;
  const KernelTables& tables_;
  KernelResult* out_ = nullptr;
  bool left_table_ = false;
  // The case.
  bool at_rest_ = true, done_ = false;
  double t_ = 0.0;
  int side_ = -1;
  // The integrator.
  KernelNextSample next_sample_;
  double atol_[2] = {0.0, 0.0};
  std::array<int, kMaxRoots> dirs_{};
  double t_stop_ = 0.0;
  double t0_ = 0.0, t1_ = 0.0, tcur_ = 0.0, cont_t0_ = 0.0;
  double y0_[2] = {0.0, 0.0}, y1_[2] = {0.0, 0.0}, k1_[2] = {0.0, 0.0}, k7_[2] = {0.0, 0.0};
  double h_step_ = 0.0;
  bool have_step_ = false;
  std::array<double, kMaxRoots> g_cur_{}, g_end_{}, g_root_{};
  double h_ = 0.0, log_err_old_ = 0.0;
  std::array<int, kMaxRoots> found_{};
  double root_time_ = 0.0;
  long steps_ = 0, rhs_evals_ = 0, root_evals_ = 0, reinits_ = 0;
  KernelError error_ = KernelError::kNone;
  double error_a_ = 0.0, error_b_ = 0.0;
  detail::Dopri5Stages<double> out_stages_{};
  bool attempt_ok_ = false;
  long attempt_evals_ = 0;
  double limit_ = 0.0, h_trial_ = 0.0, h_try_ = 0.0;
  bool clamped_ = false, rejected_ = false;
  int failures_ = 0;
};

/// One case start to end: the kernel's entry, the same on host and device.
PCRF_HD inline void solve_kernel_case(const KernelCase& c, const KernelRecord& r, const KernelTables& tables,
                                      KernelResult& out) {
  CaseKernel(c, r, tables).run(out);
}

}  // namespace pcrf::device
