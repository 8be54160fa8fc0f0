/// \file unresolved.hpp
/// \brief What resolves a case still rocking at its end (rocking_at_end, is_unresolved): the
/// tail setting to lengthen. Here, below the solver, so that what reads a cube (the schema's
/// verdict notes, reports) names it without linking the solver.
#pragma once

#include <limits>
#include <string>

namespace pcrf {

/// tail_s = "until-rest": the free vibration after the record goes on until the frame rests.
inline constexpr double kTailUntilRest = std::numeric_limits<double>::infinity();

/// The setting that resolves a case still rocking at its end (rocking_at_end) for a tail of
/// `tail_s` [s]: "a longer physics.tail_s …" when the tail is fixed, "… physics.max_tail_s …"
/// when it runs until rest (kTailUntilRest); both when NaN (not known).
std::string tail_advice(double tail_s);

}  // namespace pcrf
