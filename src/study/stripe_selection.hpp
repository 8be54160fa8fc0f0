/// \file stripe_selection.hpp
/// \brief The [selection] table of a study: records selected per hazard-consistent stripe
/// from a library to each return period's target spectrum (Study::StripeSelection).
#pragma once

#include <string>
#include <string_view>

#include "pcrf/study/study.hpp"
#include "study/toml_fields.hpp"

namespace pcrf::study {

inline constexpr std::string_view kSelectionTable = "selection";

/// Largest relative difference allowed between a target's conditioning level exp(mean_ln_sa(T*))
/// and its stripe's intensity on the hazard curve, and between a selected record's intensity
/// once scaled and the stripe's. A check that two input files agree (a target written with a
/// few digits, another program's interpolation of the same curve), not a model parameter.
inline constexpr double kConditioningRelativeTolerance = 0.01;

/// A number for a selection message, to four significant digits ("0.2", not "0.19999999999999996").
std::string selection_number_text(double value);

/// Reads [selection] (after [intensity] and [axes]), runs the selection of every stripe, and
/// sets Study::selection and Study::records. Nothing when the table is absent.
/// \throws UserError naming the study's key and line, and the library's or target's own file,
/// line and key where the problem is in one of them.
void read_selection(const detail::Fields& top, Study& s);

}  // namespace pcrf::study
