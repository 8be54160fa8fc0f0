// Names of the eight dimensionless parameters (see parameters.hpp).
#include "pcrf/study/parameters.hpp"

namespace pcrf::study {

const std::array<ParameterInfo, kParameterCount>& all_parameters() {
  static const std::array<ParameterInfo, kParameterCount> parameters{{
      {"kappa", "beam to column mass ratio m_b / m_c", &FrameParameters::kappa},
      {"lambda", "span to height ratio L / h", &FrameParameters::lambda},
      {"tan_alpha", "column aspect ratio b / h", &FrameParameters::tan_alpha},
      {"lambda_h", "beam depth to column height ratio h_b / h", &FrameParameters::lambda_h},
      {"pi_sigma_b", "beam tendon prestress P_b0 / (m_c g)", &FrameParameters::pi_sigma_b},
      {"pi_sigma_c", "column tendon prestress P_c0 / (m_c g)", &FrameParameters::pi_sigma_c},
      {"pi_e_b", "beam tendon stiffness E A_bs / (m_c g)", &FrameParameters::pi_e_b},
      {"pi_e_c", "column tendon stiffness E A_cs / (m_c g)", &FrameParameters::pi_e_c},
  }};
  return parameters;
}

std::size_t parameter_index(std::string_view name) {
  const auto& parameters = all_parameters();
  for (std::size_t i = 0; i < parameters.size(); ++i)
    if (parameters[i].name == name) return i;
  return kParameterCount;
}

}  // namespace pcrf::study
