/// \file curve_state.hpp
/// \brief How an IDA curve ended (the cube's `curve_state` codes): the result of one curve, as
/// a case's status is the result of one case. Here, below the scheduler and the IDA's search
/// (pcrf/ida/ida_search.hpp names it ida::CurveState), so that a report reads it without MPI.
#pragma once

#include <array>
#include <string>

#include "pcrf/setting.hpp"

namespace pcrf {

/// How a curve ended (its value is the cube's `curve_state` code: never renumber).
enum class CurveState {
  kBracketed = 0,   ///< collapse / last safe − 1 ≤ resolution
  kCensored = 1,    ///< safe at max_intensity: right-censored there
  kUnbracketed = 2, ///< max_runs ran out before either
  /// The lowest run that stopped the hunt gave no verdict (ida::RunVerdict::kNoVerdict): shown
  /// safe up to its last safe intensity at most, nothing known above.
  kUnresolved = 3,
};
inline constexpr std::array<EnumName<CurveState>, 4> kCurveStateNames{{{CurveState::kBracketed, "bracketed"},
                                                                       {CurveState::kCensored, "censored"},
                                                                       {CurveState::kUnbracketed, "unbracketed"},
                                                                       {CurveState::kUnresolved, "unresolved"}}};
inline std::string curve_state_name(CurveState state) { return name_of(kCurveStateNames, state); }

}  // namespace pcrf
