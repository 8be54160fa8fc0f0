/// \file cost_estimate.hpp
/// \brief What a study will cost, measured before it runs (`pcrf study --check`): a sample
/// of its cases, spread evenly over the order the run hands them out, is run and timed as
/// the run would run them, and the mean time per case is scaled to the whole study.
#pragma once

#include <cstdint>
#include <string>

#include "pcrf/study/case_space.hpp"
#include "pcrf/study/record_source.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;

struct CostEstimate {
  std::int64_t sampled = 0;     ///< cases run and timed
  double sampled_s = 0.0;       ///< their wall time [s]
  double cases = 0.0;           ///< cases the estimate covers (an IDA: curves × max_runs, an upper bound)
  double total_core_s = 0.0;    ///< cases × the mean time per sampled case [core-seconds]
  bool upper_bound = false;     ///< an IDA's: every curve running max_runs
  /// One line: "about 2.1 core-hours (… min on 8 workers): 16 of 20 000 cases, spread evenly
  /// over the study, ran in 1.7 s (0.11 s each) …".
  std::string text() const;
};

/// Runs up to `sample` cases of the study spread evenly over its hand-out order
/// (CaseSpace::handout_index), one after another in this thread, stopping early once
/// `budget_s` seconds have passed (at least one case runs). An IDA's cases are the first
/// run of sampled curves, at [ida] start; its estimate is an upper bound (every curve
/// running max_runs). Slow frames and fast ones are both in the sample, but a study whose
/// cost lies in a few cases is estimated roughly: the text says how many were timed.
CostEstimate estimate_cost(const Study& study, const CaseSpace& space, RecordCache& records, std::int64_t sample = 24,
                           double budget_s = 5.0);

}  // namespace pcrf::run
