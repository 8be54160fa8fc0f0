/// \file lane_arrays.hpp
/// \brief What the batch driver and the vector kernels share: the lanes' numbers in
/// structure-of-arrays form (one array a quantity, one entry a lane), and the table of
/// kernels one instruction set provides. Private to the solver.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace pcrf::detail::batch {

class LaneArrays;

/// The scalar side of a lane that a kernel calls back for what it does not vectorise: the
/// ground acceleration at a time outside the lane's current record interval, and the
/// right-hand side of a scene the kernel does not know (evaluated lane by lane).
class LaneCallbacks {
 public:
  virtual ~LaneCallbacks() = default;
  /// Ground acceleration at t for lane l, as ExcitationCursor::at (moving the lane's cursor),
  /// for a t in neither of the lane's intervals.
  virtual void ground(int lane, double t_s, double& horizontal_m_s2, double& vertical_m_s2) = 0;
  /// θ̈₁ of lane l at (t, θ₁, θ̇₁) from its scene; false where the flight problem's
  /// right-hand side fails (the mechanism does not exist, or a non-finite value).
  virtual bool acceleration(int lane, double t_s, double theta_rad, double omega_rad_s, double& acc_rad_s2) = 0;
};

/// One step attempt of Dormand–Prince 5(4) for every lane of the batch, from the inputs of
/// LaneArrays to its outputs. `block`: the lanes are rigid rockers whose terms the kernel
/// evaluates itself (LaneArrays' block parameters); else the callbacks give θ̈₁.
using AttemptKernel = void (*)(LaneArrays& lanes, LaneCallbacks& callbacks, bool block);

/// Kernels of one instruction set.
struct KernelSet {
  const char* name = "";      ///< "scalar", "sse2", "avx2", "avx512f", "neon64"
  int register_lanes = 1;     ///< doubles in one register
  AttemptKernel exact_trig = nullptr;   ///< the one-case sin/cos (rocker_sincos) a register at a time
  AttemptKernel scalar_trig = nullptr;  ///< rocker_sincos lane by lane (exact too)
  AttemptKernel xsimd_trig = nullptr;   ///< sin/cos of xsimd (not exact)
  AttemptKernel sleef_trig = nullptr;   ///< SLEEF's fastest 1-ulp sin/cos (not exact; null where not built)
  /// exact_trig's sin and cos of n arguments [rad] (for tests).
  void (*sincos)(const double* x_rad, double* sin_x, double* cos_x, std::size_t n) = nullptr;
};

/// The structure of arrays. Capacity: the batch's lane count rounded up to whole registers.
class LaneArrays {
 public:
  explicit LaneArrays(int capacity) : capacity_(capacity) {
    for (auto* v : all()) v->assign(static_cast<std::size_t>(capacity), 0.0);
    for (auto& row : cont)
      for (auto& v : row) v.assign(static_cast<std::size_t>(capacity), 0.0);
    for (std::size_t l = 0; l < static_cast<std::size_t>(capacity); ++l) {
      side[l] = -1.0, hi[l] = -1.0, nhi[l] = -1.0;  // inert padding: no NaN
    }
  }
  int capacity() const { return capacity_; }

  // The tolerances (SolverSettings), the same for every lane.
  double rtol = 0.0, atol_theta = 0.0, atol_omega = 0.0;
  // Inputs of an attempt.
  std::vector<double> t0, h, theta0, omega0, k1_theta, k1_omega;
  // Outputs: the 5th-order solution, the last stage (FSAL), the error norm, success (1/0),
  // the right-hand-side calls made, and the continuous extension's coefficients.
  std::vector<double> theta1, omega1, k7_theta, k7_omega, err, ok, evals;
  std::vector<double> cont[5][2];
  // The flight: side (−1/+1). Rigid-rocker terms: α [rad], (1 + 2γ)R/I [1/m], g [m/s²].
  std::vector<double> side, alpha, moment_over_inertia, gravity;
  // The record cursor of each lane (ExcitationCursor's fields): the interval [lo, hi), 1/dt,
  // the samples at lo and their differences; and the interval after it, [nlo, nhi) (empty
  // past the record's end), where a step's last stages land.
  std::vector<double> lo, hi, inv_dt, h0, dh, v0, dv;
  std::vector<double> nlo, nhi, nh0, ndh, nv0, ndv;

 private:
  std::vector<std::vector<double>*> all() {
    return {&t0,     &h,        &theta0,   &omega0, &k1_theta, &k1_omega, &theta1, &omega1, &k7_theta,
            &k7_omega, &err,    &ok,       &evals,  &side,     &alpha,    &moment_over_inertia, &gravity,
            &lo,     &hi,       &inv_dt,   &h0,     &dh,       &v0,       &dv,       &nlo,     &nhi,
            &nh0,    &ndh,      &nv0,      &ndv};
  }
  int capacity_;
};

/// The kernel sets built into this binary, each with the check that this CPU runs it.
KernelSet scalar_kernels();
KernelSet sse2_kernels();
KernelSet avx2_kernels();
KernelSet avx512_kernels();
KernelSet neon64_kernels();

/// The widest kernel set this CPU runs whose register holds at most `lanes` doubles
/// (scalar for one lane); `name` non-empty forces that set (\throws std::invalid_argument
/// when unknown or not runnable here).
KernelSet choose_kernels(int lanes, const std::string& name);

}  // namespace pcrf::detail::batch
