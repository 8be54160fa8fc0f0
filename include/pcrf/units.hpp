/// \file units.hpp
/// \brief Physical constants shared by every layer (record units, the model, cube attributes).
#pragma once

namespace pcrf {

/// Standard gravity used by the model and by every unit conversion [m/s²].
/// The paper's Π values (e.g. Π_Ec = 4294.6) are reproduced with 9.81.
inline constexpr double kGravity_m_s2 = 9.81;

}  // namespace pcrf
