/// \file parameters.hpp
/// \brief The frame parameters by name, as study files, `pcrf run` flags and cubes spell
/// them: the eight dimensionless parameters of the paper's Section 7 (kappa, lambda,
/// tan_alpha, lambda_h, pi_sigma_b, pi_sigma_c, pi_e_b, pi_e_c) and the two that set the
/// frame's size (h_m, m_c_kg). Each is described once here, with its domain.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "pcrf/model/frame.hpp"

namespace pcrf {

/// The values a parameter admits on its own (combinations are checked by make_frame()).
enum class ParameterDomain {
  kPositive,     ///< > 0
  kNonNegative,  ///< ≥ 0 (a Π of 0: no prestress, or a constant-force tendon)
  kUnitOpen,     ///< in (0, 1)
};

/// One frame parameter.
struct ParameterInfo {
  std::string_view name;       ///< study key and cube coordinate name, e.g. "pi_e_c"
  std::string_view long_name;  ///< e.g. "column tendon stiffness E A_cs / (m_c g)"
  std::string_view units;      ///< UDUNITS: "1" for the dimensionless ones, "m", "kg"
  ParameterDomain domain;
  double FrameParameters::*member;
};

inline constexpr std::size_t kParameterCount = 8;

/// The eight dimensionless parameters in their fixed order (the order of the grid's axes).
const std::array<ParameterInfo, kParameterCount>& all_parameters();

/// The two dimensional parameters, h_m and m_c_kg: a study's base point sets them for
/// every case; they are not axes.
const std::array<ParameterInfo, 2>& size_parameters();


/// Why `value` is outside the parameter's domain ("must be positive"); empty when inside.
std::string parameter_problem(const ParameterInfo& parameter, double value);

}  // namespace pcrf
