/// \file four_bar.hpp
/// \brief Exact kinematics of the rocking frame as a four-bar linkage A–B–C–D.
///
/// Branch θ₁ ≤ 0 (counter-clockwise sway, clockwise angles positive): the left column
/// AB rocks about its outer foot A = (0,0), the beam BC turns about the joint corner
/// B = (2b, 2h'), the right column CD rocks about its inner foot D = (2L, 0). Given θ₁,
/// loop closure B(θ₁) + Rot(θ₂)·u = D + Rot(θ₃)·w (u = (2L_b, 2h_b), w = (0, 2h)) fixes
/// θ₂ and θ₃; C comes from intersecting the circles |C − B| = 2R_b and |C − D| = 2h.
/// The derivatives dθ/dθ₁ and d²θ/dθ₁² come from differentiating the loop-closure
/// equations implicitly (exact, no finite differences).
///
/// The branch θ₁ > 0 is the mirror image and is handled by the equation of motion, not
/// here. The formulas are analytic through θ₁ = 0, so evaluating this branch a little
/// above zero (an integrator overshooting an impact) is smooth and harmless.
#pragma once

#include <cmath>
#include <optional>

#include "pcrf/model/frame.hpp"

namespace pcrf {

/// A planar vector [m] (or its derivative with respect to θ₁).
struct Vec2 {
  double x = 0.0, y = 0.0;
};

/// Position and angle of one rigid body and their first two θ₁-derivatives.
struct BodyMotion {
  Vec2 p, dp, ddp;              ///< centre of mass: position, ∂/∂θ₁, ∂²/∂θ₁²
  double phi = 0, dphi = 0, ddphi = 0;  ///< rotation (clockwise positive) and derivatives
};

/// The configuration of the θ₁ ≤ 0 branch at one angle.
struct Configuration {
  double theta1 = 0, theta2 = 0, theta3 = 0;   ///< [rad]
  double d_theta2 = 0, d_theta3 = 0;           ///< dθ₂/dθ₁, dθ₃/dθ₁
  double dd_theta2 = 0, dd_theta3 = 0;         ///< d²θ₂/dθ₁², d²θ₃/dθ₁²
  BodyMotion left, beam, right;                ///< left column, beam, right column
  /// Determinant of the loop-closure Jacobian ∂(closure)/∂(θ₂, θ₃) [m²]; it vanishes
  /// where beam and right column align (a toggle: the mechanism locks or snaps through).
  double jacobian = 0;
};

class FourBar {
 public:
  explicit FourBar(const Frame& frame);

  /// Solves the linkage at θ₁ (θ₁ ≤ 0 branch). Returns false when the mechanism cannot
  /// close at that angle (the circles do not meet or the linkage is at a toggle). The rest
  /// configuration (θ₁ = +0) is solved once, by the constructor, and copied: building a
  /// frame and a case at rest ask for it four times (the terms and restitution at rest, the
  /// initial tendon strains twice), a quarter of a non-lifting case.
  bool solve(double theta1, Configuration& out) const {
    if (theta1 == 0.0 && !std::signbit(theta1)) {  // +0 only: −0 may round differently
      if (rest_closes_) out = rest_;
      return rest_closes_;
    }
    return solve_at(theta1, out);
  }

  /// The most negative θ₁ reached before the linkage stops closing or passes a toggle
  /// (Jacobian sign change), found on first use by a scan and bisection (−1.6002 rad for the
  /// basic model) [rad]. A frame that never lifts never needs it.
  double closing_limit_rad() const {
    if (!closing_limit_rad_) closing_limit_rad_ = find_closing_limit();
    return *closing_limit_rad_;
  }

 private:
  double find_closing_limit() const;
  bool solve_at(double theta1, Configuration& out) const;

  Frame f_;
  double r_beam_;   ///< 2R_b [m]
  double r_right_;  ///< 2h [m]
  Configuration rest_{};      ///< solve_at(+0)
  bool rest_closes_ = false;  ///< what solve_at(+0) returned
  mutable std::optional<double> closing_limit_rad_;  ///< not thread-safe: one FourBar per thread
};

}  // namespace pcrf
