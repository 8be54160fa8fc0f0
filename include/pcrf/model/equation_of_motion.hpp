/// \file equation_of_motion.hpp
/// \brief The rocking frame's equation of motion (31), energy and tendon strains.
///
///     I(θ₁) θ̈₁ + J(θ₁) θ̇₁² + G(θ₁) (g + ü_v) + K(θ₁) = S(θ₁) ü_h
///
/// with ü_h the ground's horizontal acceleration in the frame's plane and ü_v its vertical
/// acceleration, positive up (docs/vertical_excitation.md: in the frame that moves with the
/// ground, the vertical acceleration adds to gravity); without vertical shaking this is the
/// paper's Eq. (31) with ü_g = ü_h.
///
/// derived from T = ½ I θ̇₁², V = V_F + V_T (MODEL.md): I = Σ m|∂p/∂θ₁|² + I^G (∂φ/∂θ₁)²,
/// J = ½ dI/dθ₁, G = Σ m ∂y/∂θ₁ (so G g = ∂V_F/∂θ₁), K = ∂V_T/∂θ₁, S = −Σ m ∂x/∂θ₁.
/// Every term is built from the exact four-bar kinematics, never from the printed
/// formulas (see MODEL.md errata).
///
/// Sides: the motion lives on one of two branches, side = −1 (θ₁ ≤ 0, counter-clockwise
/// sway) or side = +1 (θ₁ ≥ 0, the mirror image). The dynamics are odd:
/// I₊(θ) = I₋(−θ), S₊(θ) = S₋(−θ), J₊(θ) = −J₋(−θ), G₊(θ) = −G₋(−θ), K₊(θ) = −K₋(−θ),
/// so one branch of formulas serves both. The side, not the sign of θ₁, selects the
/// branch, so an integrator that overshoots θ₁ = 0 sees smooth dynamics.
#pragma once

#include "pcrf/ground_acceleration.hpp"
#include "pcrf/model/four_bar.hpp"
#include "pcrf/model/frame.hpp"

namespace pcrf {

/// The coefficients of Eq. (31) at one configuration.
struct EomTerms {
  double I = 0;  ///< generalized inertia [kg m²]
  double J = 0;  ///< ½ dI/dθ₁ [kg m²]
  double G = 0;  ///< gravity term [kg m] (multiplied by g)
  double K = 0;  ///< tendon term [N m]
  double S = 0;  ///< ground-inertia term [kg m]
};

/// Tendon elongations beyond the initial ones and total strains at one configuration.
struct TendonState {
  double e_column_left_m = 0, e_column_right_m = 0, e_beam_m = 0;  ///< added elongation [m]
  double strain_column_left = 0, strain_column_right = 0, strain_beam = 0;  ///< (e + e₀)/length [-]
  double strain_column_max() const;
};

class EquationOfMotion {
 public:
  explicit EquationOfMotion(const Frame& frame);

  const Frame& frame() const { return frame_; }
  const FourBar& linkage() const { return four_bar_; }

  /// Terms on `side` (−1 or +1) at θ₁. Returns false where the linkage cannot close.
  bool terms(double theta1, int side, EomTerms& out) const;

  /// θ̈₁ [rad/s²] for state (θ₁, θ̇₁) on `side` under the ground acceleration `ground`.
  /// Returns false where the linkage cannot close.
  bool acceleration(double theta1, double omega1, GroundAcceleration ground, int side,
                    double& theta1_ddot) const;

  /// T + V [J] (V_F from the ground line, V_T including the initial elongations).
  double energy(double theta1, double omega1, int side) const;

  /// Tendon state at θ₁ on `side`; left and right refer to the physical columns.
  TendonState tendons(double theta1, int side) const;

  /// Largest strains reached while |θ₁| sweeps [0, abs_theta_rad] (each tendon's own
  /// maximum; at abs_theta_rad itself where elongations grow monotonically).
  TendonState peak_tendon_strains(double abs_theta_rad) const;

  /// Configuration of the frame (θ₂, θ₃ of the physical beam and the column that is
  /// not the reference), mirrored on side +1.
  bool configuration(double theta1, int side, double& theta2, double& theta3) const;

  /// λ_g = G(0)/S(0), the paper's uplift coefficient (prestress ignored) [-].
  double lambda_g() const { return lambda_g_; }
  /// The terms of Eq. (31) at rest (θ₁ = 0⁻).
  const EomTerms& rest_terms() const { return rest_; }
  /// Horizontal ground acceleration that opens the closed frame, prestress included, without
  /// vertical shaking [m/s²].
  double uplift_threshold_m_s2() const { return uplift_threshold_m_s2_; }
  /// The same under a vertical ground acceleration ü_v (positive up):
  /// (G(0)(g + ü_v) + K(0)) / S(0) [m/s²], affine in ü_v; it reaches zero where the ground
  /// falls fast enough to unload the joints.
  double uplift_threshold_m_s2(double vertical_m_s2) const;

  /// θ̈₁ at θ₁ = 0, θ̇₁ = 0 on `side` [rad/s²]: the net generalized force at rest over I(0).
  /// Its sign says whether the force opens the joints into that side (side·θ̈ > 0) or holds
  /// them closed. Every rest, uplift and return-to-rest decision derives from it.
  double rest_acceleration(GroundAcceleration ground, int side) const;

  /// True while the net force at rest holds the joints closed on both sides:
  /// |ü_h| below uplift_threshold_m_s2(ü_v).
  bool holds_closed(GroundAcceleration ground) const;

  /// The linkage's closing limit |θ₁| [rad] (1.6002 for the basic model).
  double closing_limit_rad() const { return -four_bar_.closing_limit_rad(); }

  /// |θ₁| at which a case ends as overturned: 95 % of the closing limit [rad]. Near the
  /// limit the linkage's Jacobian degenerates (dθ₃/dθ₁ → ∞), the equation of motion
  /// stiffens without bound and no integrator step can reach the limit itself; a frame
  /// rotated that far (≈ 87° for the basic model) is lost in any practical sense.
  double overturn_angle_rad() const { return 0.95 * closing_limit_rad(); }

  /// Smallest |θ₁| at which a tendon's total strain reaches `fracture_strain`; +∞ when
  /// no tendon does before the closing limit [rad].
  double fracture_angle_rad(double fracture_strain) const;
  /// True when a tendon's strain at rest already reaches `fracture_strain` (prestrained
  /// beyond fracture): fracture_angle_rad() is 0. Needs no scan.
  bool broken_at_rest(double fracture_strain) const;

 private:
  bool negative_branch_terms(double phi, EomTerms& out, Configuration& c) const;
  /// Largest tendon strain at |θ₁| minus `fracture_strain` (tendons without stiffness left out).
  double strain_excess(double theta_abs_rad, double fracture_strain) const;

  Frame frame_;
  FourBar four_bar_;
  EomTerms rest_;  ///< terms at θ₁ = 0⁻
  double lambda_g_;
  double uplift_threshold_m_s2_;
};

}  // namespace pcrf
