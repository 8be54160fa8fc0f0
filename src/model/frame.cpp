// Frame construction from dimensional values or from the dimensionless parameters.
#include "pcrf/model/frame.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "pcrf/units.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {
namespace {

// A study builds a frame per case: the message is formatted only when a check fails.
[[noreturn]] void impossible(const std::string& what) { throw UserError("impossible frame: " + what); }

void require(bool ok, const char* what) {
  if (!ok) impossible(what);
}

void require_finite_positive(double v, const char* name) {
  if (!(std::isfinite(v) && v > 0.0)) impossible(std::string(name) + " must be positive (got " + std::to_string(v) + ")");
}

void require_finite_non_negative(double v, const char* name) {
  if (!(std::isfinite(v) && v >= 0.0)) impossible(std::string(name) + " must be ≥ 0 (got " + std::to_string(v) + ")");
}

// Fills every derived field from the primary ones.
Frame complete(Frame f) {
  f.L_b = f.L - f.b;
  f.h_prime = f.h - f.h_b;
  f.I_c_G = f.m_c * (f.b * f.b + f.h * f.h) / 3.0;
  f.I_b_G = f.m_b * (f.L_b * f.L_b + f.h_b * f.h_b) / 3.0;
  f.len_c = 2.0 * f.h;
  f.len_b = 2.0 * f.L + 2.0 * f.b;
  f.k_c = f.EA_c / f.len_c;
  f.k_b = f.EA_b / f.len_b;
  // A tendon of no stiffness (Π_E = 0) with a force (Π_σ > 0) is the constant-force limit:
  // the equations use k e + P₀, and its strain counts from zero (no material, no fracture).
  f.e_c0 = f.k_c > 0.0 ? f.P_c0 / f.k_c : 0.0;
  f.e_b0 = f.k_b > 0.0 ? f.P_b0 / f.k_b : 0.0;
  return f;
}

void check(const Frame& f) {
  require_finite_positive(f.b, "column half-width b (tan_alpha)");
  require_finite_positive(f.h, "column half-height h");
  require_finite_positive(f.h_b, "beam half-depth h_b (lambda_h)");
  require_finite_positive(f.m_c, "column mass m_c");
  require_finite_non_negative(f.m_b, "beam mass m_b (kappa)");
  require_finite_non_negative(f.EA_c, "column tendon stiffness (pi_e_c)");
  require_finite_non_negative(f.EA_b, "beam tendon stiffness (pi_e_b)");
  require_finite_non_negative(f.P_c0, "column prestress (pi_sigma_c)");
  require_finite_non_negative(f.P_b0, "beam prestress (pi_sigma_b)");
  require(f.h_b < f.h, "beam depth 2h_b must be below the column height 2h (lambda_h < 1)");
  require(f.L > f.b, "columns overlap: L must exceed b (lambda > tan_alpha)");
}

}  // namespace

FrameParameters Frame::parameters() const {
  const double w = m_c * kGravity_m_s2;
  FrameParameters p;
  p.kappa = m_b / m_c;
  p.lambda = L / h;
  p.tan_alpha = b / h;
  p.lambda_h = h_b / h;
  p.pi_sigma_b = P_b0 / w;
  p.pi_sigma_c = P_c0 / w;
  p.pi_e_b = EA_b / w;
  p.pi_e_c = EA_c / w;
  p.h_m = h;
  p.m_c_kg = m_c;
  return p;
}

Frame make_frame(const FrameParameters& p) {
  const double w = p.m_c_kg * kGravity_m_s2;
  Frame f{};
  f.h = p.h_m;
  f.b = p.tan_alpha * p.h_m;
  f.h_b = p.lambda_h * p.h_m;
  f.L = p.lambda * p.h_m;
  f.m_c = p.m_c_kg;
  f.m_b = p.kappa * p.m_c_kg;
  f.EA_c = p.pi_e_c * w;
  f.EA_b = p.pi_e_b * w;
  f.P_c0 = p.pi_sigma_c * w;
  f.P_b0 = p.pi_sigma_b * w;
  check(f);
  return complete(f);
}

Frame make_frame(const FrameDimensions& d) {
  Frame f{};
  f.b = d.b_m;
  f.h = d.h_m;
  f.h_b = d.h_b_m;
  f.L = d.L_m;
  f.m_c = d.m_c_kg;
  f.m_b = d.m_b_kg;
  f.EA_c = d.E_Pa * d.A_cs_m2;
  f.EA_b = d.E_Pa * d.A_bs_m2;
  f.P_c0 = d.sigma_c0_Pa * d.A_cs_m2;
  f.P_b0 = d.sigma_b0_Pa * d.A_bs_m2;
  check(f);
  return complete(f);
}

Frame basic_frame() { return make_frame(FrameDimensions{}); }

}  // namespace pcrf
