/// \file frame.hpp
/// \brief Geometry, masses and tendons of a one-storey, one-span rocking frame.
///
/// Two ways to make a frame: from its dimensional values (FrameDimensions, the paper's
/// Table 1 as corrected in MODEL.md) or from the eight dimensionless parameters of the
/// paper's Section 7 plus the half column height h and the column mass m_c
/// (FrameParameters). Both produce a Frame, which holds every derived length and constant
/// the equations of motion use. Lengths in m, masses in kg, forces in N.
#pragma once

#include <string>

#include "pcrf/units.hpp"

namespace pcrf {

/// The eight dimensionless parameters plus the scale (h, m_c). Defaults: basic model.
struct FrameParameters {
  double kappa = 1.8;         ///< κ = m_b / m_c
  double lambda = 2.0;        ///< λ = L / h (2L: distance between column centrelines)
  double tan_alpha = 0.2;     ///< tan α = b / h (2b: column width)
  double lambda_h = 0.2;      ///< λ_h = h_b / h (2h_b: beam depth)
  double pi_sigma_b = 105000.0 / (2592.0 * 9.81);   ///< Π_σb = P_b0 /(m_c g) ≈ 4.13
  double pi_sigma_c = 168000.0 / (2592.0 * 9.81);   ///< Π_σc = P_c0 /(m_c g) ≈ 6.61
  double pi_e_b = 1.95e11 * 3.5e-4 / (2592.0 * 9.81); ///< Π_Eb = E A_bs /(m_c g) ≈ 2684.1
  double pi_e_c = 1.95e11 * 5.6e-4 / (2592.0 * 9.81); ///< Π_Ec = E A_cs /(m_c g) ≈ 4294.6
  double h_m = 1.5;           ///< half column height h [m]
  double m_c_kg = 2592.0;     ///< column mass m_c [kg]
};

/// Dimensional description (the paper's Table 1, corrected). Defaults: basic model.
struct FrameDimensions {
  double L_m = 3.0;             ///< half distance between column centrelines [m]
  double b_m = 0.3;             ///< half column width [m]
  double h_m = 1.5;             ///< half column height [m]
  double h_b_m = 0.3;           ///< half beam depth [m]
  double m_c_kg = 2592.0;       ///< column mass [kg]
  double m_b_kg = 4665.6;       ///< beam mass [kg]
  double A_cs_m2 = 5.6e-4;      ///< column tendon area [m²]
  double A_bs_m2 = 3.5e-4;      ///< beam tendon area [m²]
  double sigma_c0_Pa = 3e8;     ///< initial column tendon stress [Pa]
  double sigma_b0_Pa = 3e8;     ///< initial beam tendon stress [Pa]
  double E_Pa = 1.95e11;        ///< tendon Young's modulus [Pa]
};

/// A frame with every derived quantity the model needs.
struct Frame {
  // Primary.
  double b, h, h_b, L;          ///< [m]
  double m_c, m_b;              ///< [kg]
  double EA_c, EA_b;            ///< axial stiffness × length: E·A [N]
  double P_c0, P_b0;            ///< initial tendon forces [N]
  // Derived (see MODEL.md "Geometry").
  double L_b;                   ///< L − b, half beam length [m]
  double h_prime;               ///< h − h_b [m]
  double I_c_G, I_b_G;          ///< centroidal moments of inertia [kg m²]
  double k_c, k_b;              ///< tendon stiffnesses E A / length [N/m]
  double e_c0, e_b0;            ///< initial tendon elongations P₀/k [m]; 0 when k = 0
  double len_c, len_b;          ///< tendon lengths 2h and 2L + 2b [m]
  /// Gravity the frame stands in [m/s²]. The ground's vertical acceleration adds to it
  /// (equation_of_motion.hpp); the Π values are always defined with the standard g.
  double gravity_m_s2 = kGravity_m_s2;

  /// Dimensionless parameters of this frame.
  FrameParameters parameters() const;
};

/// Builds a frame from dimensionless parameters.
/// \throws std::invalid_argument naming the parameter when the geometry is impossible
///         (non-positive size, λ_h ≥ 1, λ ≤ tan α (columns overlap), negative Π).
///         Π_E = 0 with Π_σ > 0 is allowed: a constant-force tendon.
Frame make_frame(const FrameParameters& p);

/// Builds a frame from dimensional values (same checks).
Frame make_frame(const FrameDimensions& d);

/// The paper's basic model.
Frame basic_frame();

}  // namespace pcrf
