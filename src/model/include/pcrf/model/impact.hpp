/// \file impact.hpp
/// \brief Coefficient of restitution r = θ̇₁⁺/θ̇₁⁻ of the rocking frame (Section 5).
///
/// Assumptions (the paper's): the impact is instantaneous, nothing slips, impulses act only
/// at the new pivots (feet A', D' and joint corners B', C'), tendon forces stay finite.
/// Unknowns: foot impulses (I_Ax, I_Ay, I_Dx, I_Dy) and θ̇₁⁺. Equations: linear momentum of
/// the whole frame (x, y), angular momentum of the whole frame about A', of the left
/// column about B', of the right column about C'. Body velocities before and after come
/// from the exact kinematics of the two branches, so no printed coefficient is used.
#pragma once

#include "pcrf/model/equation_of_motion.hpp"

namespace pcrf {

/// r from the five momentum equations, solved with Eigen (column-pivoting QR).
/// \throws std::runtime_error when the system is singular (degenerate frame).
double restitution_momentum(const EquationOfMotion& eom);

/// Sign convention of λ_L in Eq. (42)–(43).
enum class LambdaLSign {
  kCorrected,  ///< λ_L = −∂θ₂/∂θ₁ at 0 (MODEL.md erratum 3): equals the momentum balance
  kAsPrinted,  ///< λ_L = +∂θ₂/∂θ₁ at 0: kept only to show the erratum in a test
};

/// r from the closed form Eq. (42)–(43), with λ₁₃ = ∂θ₃/∂θ₁ at 0.
double restitution_closed_form(const EquationOfMotion& eom, LambdaLSign sign = LambdaLSign::kCorrected);

}  // namespace pcrf
