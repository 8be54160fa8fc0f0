/// \file rigid_rocker.hpp
/// \brief The canonical rocking scenes: Housner's rigid block (1963) and the free-standing
/// rocking frame of Makris & Vassiliou (2013), columns capped by a freely supported beam.
///
/// Rectangular columns of slenderness α (tan α = b/h) and half-diagonal R rock on their
/// corners; the beam, γ times the columns' mass, translates with the columns' top corners
/// (at 2R from the pivot along the diagonal). With one column of mass m (the mass cancels from
/// the motion: the scene uses m = 1 kg), on the branch θ ≤ 0:
///
///     I = m R² (4/3 + 4γ),  J = 0,  G = −m R (1 + 2γ) sin(α + θ),  K = 0,
///     S = −m R (1 + 2γ) cos(α + θ),
///
/// i.e. θ̈ = (p̂²/g) [(g + ü_v) sin(α + θ) − ü_h cos(α + θ)] with p̂² = (3g/4R)(1 + 2γ)/(1 + 3γ):
/// the frame rocks like a block of size R̂ = R(1 + 3γ)/(1 + 2γ).
/// γ = 0 is Housner's block, p² = 3g/(4R), uplift at |ü_h| = g tan α.
///
/// The coefficient of restitution, from angular momentum about the new pivots with the
/// beam's impulse at the columns' tops (docs/rocking_canon.md), is
///
///     r = [1 − (3/2) sin²α + 3γ cos 2α] / (1 + 3γ),
///
/// Housner's 1 − (3/2) sin²α for the block; a value may be given instead.
///
/// Passing |θ| = α does not overturn a block: the ground can still bring it back. A case ends
/// as overturned when the block has fallen over, |θ| = π/2.
#pragma once

#include <optional>

#include "pcrf/host_device.hpp"
#include "pcrf/model/rocker_sincos.hpp"
#include "pcrf/model/scene.hpp"
#include "pcrf/units.hpp"

namespace pcrf {

struct RockerParameters {
  double slenderness_rad = 0.25;       ///< α, in (0, π/2) [rad]
  double size_m = 1.0;                 ///< R, the columns' half-diagonal [m]
  double beam_mass_ratio = 0.0;        ///< γ ≥ 0: beam mass over the columns' (0: the block)
  std::optional<double> restitution;   ///< r in [0, 1]; empty: from momentum (see above)
  double gravity_m_s2 = kGravity_m_s2; ///< the gravity it stands in [m/s²]
};

/// θ̈₁ of a rigid rocker, eq. (31) with I, J = K = 0 and the G, S above:
///
///     θ̈₁ = ((1 + 2γ) R / I) (σ sin(α + φ) (g + ü_v) − cos(α + φ) ü_h),
///
/// φ = θ₁ and σ = 1 on side −1 (`left`), φ = −θ₁ and σ = −1 on side +1: the odd mirror flips
/// the sign of the gravity term only, exactly. Written once over a number type T — double
/// (RigidRocker::acceleration) or a SIMD pack of cases (the batch kernels) — whose `Ops`
/// give select(mask, a, b) and sincos(x, sin, cos): rocker_sincos (rocker_sincos.hpp), the
/// same bits for both, unless a batch asks for another.
template <class Ops, class T, class Mask>
PCRF_HD T rigid_rocker_acceleration(const T& moment_over_inertia_per_m, const T& slenderness_rad, const T& gravity_m_s2,
                            const T& theta1, const Mask& left, const T& ground_h_m_s2, const T& ground_v_m_s2) {
  const T phi = Ops::select(left, theta1, -theta1);
  T sin_a, cos_a;
  Ops::sincos(slenderness_rad + phi, sin_a, cos_a);
  const T sigma = Ops::select(left, T(1.0), T(-1.0));
  return moment_over_inertia_per_m * (sigma * sin_a * (gravity_m_s2 + ground_v_m_s2) - cos_a * ground_h_m_s2);
}

class RigidRocker final : public Scene {
 public:
  /// \throws UserError naming the parameter: α outside (0, π/2), R ≤ 0, γ < 0,
  /// a restitution outside [0, 1], a gravity ≤ 0.
  explicit RigidRocker(const RockerParameters& parameters);

  const RockerParameters& parameters() const { return p_; }
  /// (1 + 2γ) R / I [1/m], the factor of rigid_rocker_acceleration.
  double moment_over_inertia_per_m() const { return moment_over_inertia_per_m_; }

  bool terms(double theta1, int side, EomTerms& out) const override;
  /// Eq. (31) with I, J = K = 0, G and S of a rigid rocker: one sincos.
  bool acceleration(double theta1, double omega1, GroundAcceleration ground, int side,
                    double& theta1_ddot) const override;
  int taylor_order_max() const override { return kTaylorOrderMax; }
  /// The series of rigid_rocker_acceleration, by the recurrences of sin and cos (automatic
  /// differentiation; e.g. A. Jorba & M. Zou, Exp. Math. 14 (2005) 99–117, §3): with
  /// x = α + φ = α + σθ₁ (σ = 1 on side −1, −1 on side +1), S = sin x, C = cos x,
  ///
  ///     S_k = (1/k) Σ_{j=1..k} j x_j C_{k−j},   C_k = −(1/k) Σ_{j=1..k} j x_j S_{k−j},
  ///     F_k = σ [(g + v0) S_k + v1 S_{k−1}] − [h0 C_k + h1 C_{k−1}],
  ///     a_{k+2} = ((1 + 2γ) R / I) F_k / ((k + 1)(k + 2)),
  ///
  /// one sincos and about order² products.
  bool taylor_series(double theta1, double omega1, const GroundLine& ground, int side, int order,
                     double* a) const override;
  TaylorKernel taylor_kernel(int side, int order) const override;
  std::optional<RockerCoefficients> rocker_coefficients() const override {
    return RockerCoefficients{p_.slenderness_rad, moment_over_inertia_per_m_, p_.gravity_m_s2};
  }
  static constexpr int kTaylorOrderMax = 24;
  double gravity_m_s2() const override { return p_.gravity_m_s2; }
  double restitution() const override { return restitution_; }
  /// π/2: fallen on its side.
  double overturn_angle_rad() const override;
  double closing_limit_rad() const override;
  double energy(double theta1, double omega1, int side) const override;

  /// The momentum formula above, whatever `restitution` was given.
  static double restitution_from_momentum(double slenderness_rad, double beam_mass_ratio);

 private:
  RockerParameters p_;
  double restitution_;
  double inertia_m2_;          ///< I = R²(4/3 + 4γ) per unit column mass [m²]
  double moment_over_inertia_per_m_;  ///< (1 + 2γ) R / I [1/m]
  double sin_alpha_ = 0.0, cos_alpha_ = 0.0;  ///< of the slenderness: the series' sin/cos at θ₁ = 0 (every impact)
};

}  // namespace pcrf
