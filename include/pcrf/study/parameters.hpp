/// \file parameters.hpp
/// \brief The eight dimensionless frame parameters by name, as study files and cubes
/// spell them (kappa, lambda, tan_alpha, lambda_h, pi_sigma_b, pi_sigma_c, pi_e_b, pi_e_c).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "pcrf/model/frame.hpp"

namespace pcrf::study {

/// One of the paper's eight Section 7 parameters.
struct ParameterInfo {
  std::string_view name;         ///< study key and cube coordinate name, e.g. "pi_e_c"
  std::string_view long_name;    ///< e.g. "column tendon stiffness E A_cs / (m_c g)"
  double FrameParameters::*member;
};

inline constexpr std::size_t kParameterCount = 8;

/// The eight parameters in their fixed order (the order of the grid's axes).
const std::array<ParameterInfo, kParameterCount>& all_parameters();

/// Index of a parameter in all_parameters(), or kParameterCount when unknown.
std::size_t parameter_index(std::string_view name);

}  // namespace pcrf::study
