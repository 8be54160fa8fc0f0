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
#include "pcrf/model/scene.hpp"

namespace pcrf {

/// The prestressed rocking frame as a scene (scene.hpp).
class EquationOfMotion final : public Scene {
 public:
  explicit EquationOfMotion(const Frame& frame);

  const Frame& frame() const { return frame_; }
  const FourBar& linkage() const { return four_bar_; }

  /// Terms on `side` (−1 or +1) at θ₁. Returns false where the linkage cannot close.
  bool terms(double theta1, int side, EomTerms& out) const override;
  double gravity_m_s2() const override { return frame_.gravity_m_s2; }
  /// From the five momentum equations of MODEL.md (impact.hpp), computed once.
  double restitution() const override { return restitution_; }

  /// T + V [J] (V_F from the ground line, V_T including the initial elongations).
  double energy(double theta1, double omega1, int side) const override;

  /// Tendon state at θ₁ on `side`; left and right refer to the physical columns.
  TendonState tendons(double theta1, int side) const override;

  /// Largest strains reached while |θ₁| sweeps [0, abs_theta_rad] (each tendon's own
  /// maximum; at abs_theta_rad itself where elongations grow monotonically).
  TendonState peak_tendon_strains(double abs_theta_rad) const override;

  /// Configuration of the frame (θ₂, θ₃ of the physical beam and the column that is
  /// not the reference), mirrored on side +1.
  bool configuration(double theta1, int side, double& theta2, double& theta3) const override;

  /// The linkage's closing limit |θ₁| [rad] (1.6002 for the basic model).
  double closing_limit_rad() const override { return -four_bar_.closing_limit_rad(); }

  /// |θ₁| at which a case ends as overturned: 95 % of the closing limit [rad]. Near the
  /// limit the linkage's Jacobian degenerates (dθ₃/dθ₁ → ∞), the equation of motion
  /// stiffens without bound and no integrator step can reach the limit itself; a frame
  /// rotated that far (≈ 87° for the basic model) is lost in any practical sense.
  double overturn_angle_rad() const override { return 0.95 * closing_limit_rad(); }

  /// Smallest |θ₁| at which a tendon's total strain reaches `fracture_strain`; +∞ when
  /// no tendon does before the closing limit [rad].
  double fracture_angle_rad(double fracture_strain) const override;
  /// True when a tendon's strain at rest already reaches `fracture_strain` (prestrained
  /// beyond fracture): fracture_angle_rad() is 0. Needs no scan.
  bool broken_at_rest(double fracture_strain) const override;
  /// A loop closure and some sixteen transcendental functions per evaluation.
  bool worth_tabulating() const override { return true; }

 private:
  bool negative_branch_terms(double phi, EomTerms& out, Configuration& c) const;
  /// Largest tendon strain at |θ₁| minus `fracture_strain` (tendons without stiffness left out).
  double strain_excess(double theta_abs_rad, double fracture_strain) const;

  Frame frame_;
  FourBar four_bar_;
  double restitution_;
};

}  // namespace pcrf
