/// \file work_source.hpp
/// \brief Where the master's cases come from: a fixed list (WorkQueue) or a plan that makes
/// new cases as results come back (the adaptive IDA). The scheduler draws from this one
/// interface and knows nothing of what a case is.
#pragma once

#include <cstdint>
#include <vector>

#include "pcrf/parallel/result_batch.hpp"

namespace pcrf::parallel {

/// One case to compute: its index, and a number the evaluator receives with it (an
/// adaptive plan's choice, e.g. an intensity; 0 for a fixed list).
struct WorkItem {
  std::int64_t case_index = -1;
  double argument = 0.0;
};
using WorkBatch = std::vector<WorkItem>;

/// A batch a worker computes whole and seals (ScheduleOptions::seal): a marker item, then its
/// cases. The marker's argument is the unit's number, which comes back with what was sealed.
WorkBatch unit_batch(std::int64_t unit, const std::vector<std::int64_t>& cases);
/// The same for a unit whose cases are the `count` consecutive ones from `first`: three items
/// however many cases, so that handing it out costs the master nothing a case (the worker
/// lists them).
WorkBatch unit_range_batch(std::int64_t unit, std::int64_t first, std::int64_t count);

class WorkSource {
 public:
  virtual ~WorkSource() = default;
  /// The next batch for a worker (the in-process worker, or a remote one): empty when
  /// nothing is ready now.
  virtual WorkBatch take(bool in_process_worker) = 0;
  /// A case came back (master thread, before the outcome handler sees it).
  virtual void completed(const CaseOutcome& outcome) { (void)outcome; }
  /// True when take() will never return anything again (and nothing is still to come back
  /// that could make new cases).
  virtual bool exhausted() const = 0;
};

}  // namespace pcrf::parallel
