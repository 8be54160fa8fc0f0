/// \file scene.hpp
/// \brief What every rocking scene gives the solver: one rocking coordinate θ₁ and the terms
/// of its equation of motion, its impacts' restitution, and the angles where it stops.
///
/// A scene is a mechanism with one degree of freedom that rocks on a rigid ground:
///
///     I(θ₁) θ̈₁ + J(θ₁) θ̇₁² + G(θ₁) (g + ü_v) + K(θ₁) = S(θ₁) ü_h        (31')
///
/// on the branch θ₁ ≤ 0 (side −1), and its mirror image on θ₁ ≥ 0 (side +1: J, G, K change
/// sign, I and S do not). An impact at θ₁ = 0 multiplies θ̇₁ by the restitution and flips the
/// side. The scenes are the prestressed rocking frame (EquationOfMotion), Housner's rigid
/// block and the Makris–Vassiliou rocking frame (rigid_rocker.hpp). The solver knows none of
/// them by name: everything it decides (uplift, rest, the return to rest, impacts, stops)
/// derives from this interface.
#pragma once

#include <array>
#include <limits>
#include <optional>

#include "pcrf/ground_acceleration.hpp"

namespace pcrf {

/// The coefficients of Eq. (31') at one configuration.
struct EomTerms {
  double I = 0;  ///< generalized inertia [kg m²]
  double J = 0;  ///< ½ dI/dθ₁ [kg m²]
  double G = 0;  ///< gravity term [kg m] (multiplied by g + ü_v)
  double K = 0;  ///< tendon (spring) term [N m]
  double S = 0;  ///< ground-inertia term [kg m]
};

/// Tendon elongations beyond the initial ones and total strains at one configuration; NaN
/// for a scene without tendons.
struct TendonState {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  double e_column_left_m = kNone, e_column_right_m = kNone, e_beam_m = kNone;  ///< added elongation [m]
  double strain_column_left = kNone, strain_column_right = kNone, strain_beam = kNone;  ///< (e + e₀)/length [-]
  double strain_column_max() const;
};

/// A scene's taylor_series for one side and order as a plain function and the constants it
/// reads, for a caller that computes one series per step: series(constants, θ₁, θ̇₁, ground,
/// a) is taylor_series(θ₁, θ̇₁, ground, side, order, a), without its two dispatches.
struct TaylorKernel {
  using Series = bool (*)(const double* constants, double theta1, double omega1, const GroundLine& ground, double* a);
  Series series = nullptr;  ///< null: the scene has no series of that order
  std::array<double, 6> constants{};
};

/// A rigid rocker's right-hand side in three numbers (rigid_rocker_acceleration): what a scene
/// that is one offers to a caller evaluating it for many cases at once (the CPU lanes' kernels).
struct RockerCoefficients {
  double slenderness_rad = 0.0;            ///< α
  double moment_over_inertia_per_m = 0.0;  ///< (1 + 2γ) R / I [1/m]
  double gravity_m_s2 = 0.0;
};

class Scene {
 public:
  virtual ~Scene() = default;

  /// Terms on `side` (−1 or +1) at θ₁. Returns false where the mechanism does not exist.
  virtual bool terms(double theta1, int side, EomTerms& out) const = 0;
  /// Gravity the scene stands in [m/s²].
  virtual double gravity_m_s2() const = 0;
  /// Coefficient of restitution r = θ̇₁⁺/θ̇₁⁻ at an impact [-].
  virtual double restitution() const = 0;
  /// |θ₁| at which a case ends as overturned [rad].
  virtual double overturn_angle_rad() const = 0;
  /// |θ₁| beyond which the mechanism does not exist (messages) [rad].
  virtual double closing_limit_rad() const = 0;
  /// T + V [J] at (θ₁, θ̇₁) on `side`, gravity from its rest line.
  virtual double energy(double theta1, double omega1, int side) const = 0;

  /// Smallest |θ₁| at which a tendon's strain reaches `fracture_strain`: +∞ without tendons.
  virtual double fracture_angle_rad(double fracture_strain) const;
  /// True when a tendon is broken at rest (fracture_angle_rad() is 0).
  virtual bool broken_at_rest(double fracture_strain) const;
  /// Tendon state at θ₁ on `side` (NaN without tendons).
  virtual TendonState tendons(double theta1, int side) const;
  /// Largest strains while |θ₁| sweeps [0, abs_theta_rad] (NaN without tendons).
  virtual TendonState peak_tendon_strains(double abs_theta_rad) const;
  /// The angles of the scene's other bodies at θ₁ (the frame's beam and second column);
  /// NaN for a scene of one body. Returns false where the mechanism does not exist.
  virtual bool configuration(double theta1, int side, double& theta2, double& theta3) const;
  /// True when the terms are costly enough to be worth tabulating (eom_table.hpp).
  virtual bool worth_tabulating() const { return false; }

  // ---- derived from the terms at rest (θ₁ = 0⁻) -------------------------------------
  /// λ_g = G(0)/S(0), the paper's uplift coefficient (prestress ignored) [-].
  double lambda_g() const { return lambda_g_; }
  /// Horizontal ground acceleration that opens the scene at rest, without vertical shaking [m/s²].
  double uplift_threshold_m_s2() const { return uplift_threshold_m_s2_; }
  /// The same under a vertical ground acceleration ü_v (positive up):
  /// (G(0)(g + ü_v) + K(0)) / S(0) [m/s²].
  double uplift_threshold_m_s2(double vertical_m_s2) const;
  /// θ̈₁ at θ₁ = 0, θ̇₁ = 0 on `side` [rad/s²]: the net generalized force at rest over I(0).
  /// Its sign says whether the force opens the scene into that side (side·θ̈ > 0) or holds it
  /// closed. Every rest, uplift and return-to-rest decision derives from it.
  double rest_acceleration(GroundAcceleration ground, int side) const;
  /// The terms at rest, θ₁ = 0⁻ (I, G, K, S: what rest_acceleration and the threshold are
  /// made of; the case kernel of src/solver/device/ repeats their arithmetic).
  const EomTerms& rest() const { return rest_; }
  /// True while the net force at rest holds the scene closed on both sides.
  bool holds_closed(GroundAcceleration ground) const;
  /// θ̈₁ [rad/s²] for state (θ₁, θ̇₁) on `side` under `ground`, from the exact terms:
  /// (S ü_h − J θ̇₁² − G (g + ü_v) − K) / I. A scene whose terms reduce to fewer operations
  /// overrides it (the right-hand side of an untabulated scene calls it at every stage).
  /// Returns false where the mechanism does not exist.
  virtual bool acceleration(double theta1, double omega1, GroundAcceleration ground, int side,
                            double& theta1_ddot) const;

  /// Highest order of taylor_series(); 0: the scene has none (the solver then steps with
  /// Runge–Kutta stages instead).
  virtual int taylor_order_max() const { return 0; }
  /// The Taylor coefficients a₀…a_order of θ₁(t₀ + τ) = Σ a_k τ^k on `side`, from (θ₁, θ̇₁)
  /// at t₀, under a ground linear in τ (θ̇₁'s are k·a_k). False when the scene has none, the
  /// order exceeds taylor_order_max(), or a coefficient is not finite.
  virtual bool taylor_series(double /*theta1*/, double /*omega1*/, const GroundLine& /*ground*/, int /*side*/,
                             int /*order*/, double* /*a*/) const {
    return false;
  }
  /// taylor_series on `side` to `order` as a kernel (see TaylorKernel); a null one when the
  /// scene has none.
  virtual TaylorKernel taylor_kernel(int /*side*/, int /*order*/) const { return {}; }
  /// The scene's right-hand side as a rigid rocker's coefficients, where it is one; nullopt
  /// for any other (its acceleration() is then the one form of its right-hand side).
  virtual std::optional<RockerCoefficients> rocker_coefficients() const { return std::nullopt; }

 protected:
  /// Derived classes call this once their terms can be evaluated.
  /// \throws std::invalid_argument when the mechanism does not exist at rest.
  void settle_rest();
 private:
  EomTerms rest_;
  double lambda_g_ = 0.0;
  double uplift_threshold_m_s2_ = 0.0;
};

}  // namespace pcrf
