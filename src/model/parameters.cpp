// The frame parameters by name (see parameters.hpp).
#include "pcrf/model/parameters.hpp"

#include <cmath>

namespace pcrf {

const std::array<ParameterInfo, kParameterCount>& all_parameters() {
  using D = ParameterDomain;
  static const std::array<ParameterInfo, kParameterCount> parameters{{
      {"kappa", "beam to column mass ratio m_b / m_c", "1", D::kPositive, &FrameParameters::kappa},
      {"lambda", "span to height ratio L / h", "1", D::kPositive, &FrameParameters::lambda},
      {"tan_alpha", "column aspect ratio b / h", "1", D::kPositive, &FrameParameters::tan_alpha},
      {"lambda_h", "beam depth to column height ratio h_b / h", "1", D::kUnitOpen, &FrameParameters::lambda_h},
      {"pi_sigma_b", "beam tendon prestress P_b0 / (m_c g)", "1", D::kNonNegative, &FrameParameters::pi_sigma_b},
      {"pi_sigma_c", "column tendon prestress P_c0 / (m_c g)", "1", D::kNonNegative, &FrameParameters::pi_sigma_c},
      {"pi_e_b", "beam tendon stiffness E A_bs / (m_c g)", "1", D::kNonNegative, &FrameParameters::pi_e_b},
      {"pi_e_c", "column tendon stiffness E A_cs / (m_c g)", "1", D::kNonNegative, &FrameParameters::pi_e_c},
  }};
  return parameters;
}

const std::array<ParameterInfo, 2>& size_parameters() {
  static const std::array<ParameterInfo, 2> parameters{{
      {"h_m", "half column height h", "m", ParameterDomain::kPositive, &FrameParameters::h_m},
      {"m_c_kg", "column mass m_c", "kg", ParameterDomain::kPositive, &FrameParameters::m_c_kg},
  }};
  return parameters;
}

std::string parameter_problem(const ParameterInfo& parameter, double value) {
  if (!std::isfinite(value)) return "must be a finite number";
  switch (parameter.domain) {
    case ParameterDomain::kPositive: return value > 0.0 ? "" : "must be positive";
    case ParameterDomain::kNonNegative: return value >= 0.0 ? "" : "must not be negative";
    case ParameterDomain::kUnitOpen: return value > 0.0 && value < 1.0 ? "" : "must be between 0 and 1 (exclusive)";
  }
  return "";
}

}  // namespace pcrf
