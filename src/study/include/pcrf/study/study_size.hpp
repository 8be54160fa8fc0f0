/// \file study_size.hpp
/// \brief How big a study is, counted from the study file alone, before any plan is drawn or
/// any case list is made: a study too large for rank 0 is refused with one line naming the
/// key that makes it so, never by an allocation failing later.
#pragma once

#include <cstddef>
#include <string>

#include "pcrf/study/study.hpp"

namespace pcrf::study {

/// Results rank 0 holds between checkpoints at most [bytes]: one is written when they reach it.
inline constexpr std::size_t kPendingResultsBytes = std::size_t{256} << 20;

/// Counts in double: a product of axes or a sample count can exceed any integer type.
struct StudySize {
  double frames = 0.0;  ///< parameter points (grid combinations, listed cases, samples, …)
  double cases = 0.0;   ///< frames × records × levels (IDA: × max_runs)
};

StudySize study_size(const Study& study);

/// The plan's frames are counted from its dimensions (a sampled plan draws nothing before
/// its frames are asked for, one at a time). Rank 0 holds what the plan holds per frame
/// (Plan::bytes_per_frame: nothing for a grid or a sampled plan), the status of every case
/// (one byte) and at most 256 MiB of results between checkpoints.
/// \throws UserError at the key that makes the study too large
/// (plan.samples, ida.max_runs or axes) and the memory it would need, when that exceeds 80 %
/// of this machine's.
void check_study_size(const Study& study);

}  // namespace pcrf::study
