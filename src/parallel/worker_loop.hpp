// The worker side of the scheduling protocol, independent of how messages travel.
// Used by MPI worker ranks and by the worker thread inside rank 0 alike.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <iterator>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pcrf/parallel/scheduler.hpp"

namespace pcrf::parallel::detail {

/// The master's answer "nothing is ready yet: report what you have and ask again" — one item
/// with this index. (An empty batch means "stop".)
inline constexpr std::int64_t kWaitIndex = -1;
inline WorkBatch wait_batch() { return {WorkItem{kWaitIndex, 0.0}}; }
inline bool is_wait(const WorkBatch& batch) { return batch.size() == 1 && batch.front().case_index == kWaitIndex; }

/// A batch that is one unit to seal whole (ScheduleOptions::seal) starts with one item of
/// this index, whose argument is the unit's number; its cases follow.
inline constexpr std::int64_t kUnitIndex = -2;
inline bool is_unit(const WorkBatch& batch) { return !batch.empty() && batch.front().case_index == kUnitIndex; }
/// A unit of consecutive cases (unit_range_batch): after the unit marker, one item of this
/// index whose argument is the number of cases, then one item, the first case.
inline constexpr std::int64_t kRangeIndex = -3;
inline bool is_range_unit(const WorkBatch& batch) {
  return batch.size() == 3 && batch[0].case_index == kUnitIndex && batch[1].case_index == kRangeIndex;
}
/// The number of cases of a range unit (0 for a count that is not one).
inline std::size_t range_count(const WorkBatch& batch) {
  const double count = batch[1].argument;
  return count >= 1.0 && count <= 9.0e15 ? static_cast<std::size_t>(count) : 0;
}
/// The cases a batch hands out (its unit marker, if any, is none).
inline std::size_t cases_in(const WorkBatch& batch) {
  return is_range_unit(batch) ? range_count(batch) : batch.size() - (is_unit(batch) ? 1 : 0);
}
/// A range unit as the unit it stands for: its marker, then each of its cases.
inline WorkBatch listed(const WorkBatch& range) {
  const std::size_t count = range_count(range);
  WorkBatch batch(count + 1);
  batch[0] = range[0];
  for (std::size_t k = 0; k < count; ++k) batch[k + 1] = {range[2].case_index + static_cast<std::int64_t>(k), 0.0};
  return batch;
}

/// How a worker talks to its master.
class MasterLink {
 public:
  virtual ~MasterLink() = default;
  /// Reports finished cases and sealed units, and asks for the next batch (answered by receive_batch).
  virtual void request(ResultBatch finished, SealedUnits sealed) = 0;
  /// Blocks until the master's answer to the oldest open request: work, "wait" (is_wait),
  /// or empty: stop.
  virtual WorkBatch receive_batch() = 0;
  /// Reports the last finished cases; the master expects nothing more from this worker.
  virtual void finish(ResultBatch finished, SealedUnits sealed) = 0;
};

/// The outcomes of `items`; an exception from `evaluate` marks every one of them.
inline ResultBatch evaluate_guarded(const CasesEvaluator& evaluate, std::span<const WorkItem> items,
                                    std::size_t row_width) {
  auto threw = [&](const std::string& what) {
    ResultBatch outcomes;
    for (const WorkItem& item : items)
      outcomes.push_back({item.case_index, kEvaluatorThrew,
                          std::vector<double>(row_width, std::numeric_limits<double>::quiet_NaN()), what});
    return outcomes;
  };
  try {
    ResultBatch outcomes = evaluate(items);
    if (outcomes.size() != items.size()) return threw("the evaluator returned " + std::to_string(outcomes.size()) +
                                                      " outcomes for " + std::to_string(items.size()) + " cases");
    return outcomes;
  } catch (const std::exception& e) {
    return threw(e.what());
  } catch (...) {
    return threw("unknown exception");
  }
}

/// How a unit computed by a UnitEvaluator ended: every case it chose run, stopped by the run's
/// stop (its cases run so far are reported one by one), or the evaluator threw (likewise, and
/// the worker goes on).
enum class UnitState { kWhole, kCut, kThrew };

/// Appends `outcomes` to `finished` (taking them whole when `finished` is empty).
inline void append(ResultBatch& finished, ResultBatch&& outcomes) {
  if (finished.empty() && finished.capacity() <= outcomes.capacity()) {
    finished = std::move(outcomes);
    return;
  }
  finished.insert(finished.end(), std::make_move_iterator(outcomes.begin()), std::make_move_iterator(outcomes.end()));
}

/// Computes one unit by `evaluate_unit`, its outcomes appended to `finished` as its cases run.
template <class Stopping>
UnitState run_unit(const UnitEvaluator& evaluate_unit, const WorkItem& marker, std::span<const WorkItem> cases,
                   const CasesEvaluator& evaluate, std::size_t row_width, ResultBatch& finished, Stopping stopping) {
  bool cut = false;
  const UnitCases run = [&](std::span<const WorkItem> items) -> std::optional<std::span<const CaseOutcome>> {
    if (cut || stopping()) {
      cut = true;
      return std::nullopt;
    }
    const std::size_t at = finished.size();
    append(finished, evaluate_guarded(evaluate, items, row_width));
    return std::span<const CaseOutcome>(finished.data() + at, finished.size() - at);
  };
  try {
    evaluate_unit(static_cast<std::int64_t>(marker.argument), cases, run);
  } catch (...) {
    return cut ? UnitState::kCut : UnitState::kThrew;
  }
  return cut ? UnitState::kCut : UnitState::kWhole;
}

/// Request, compute, report — with one request always in flight so that the next batch
/// is on its way while the current one is computed. When the master has nothing ready it
/// answers "wait": the worker then reports what it computed (an adaptive plan may need it to
/// make new work) and asks again. A batch is computed `together` cases per call of
/// `evaluate`. `stop` (optional) abandons the work between two calls without reporting (the
/// master is failing). `interrupt` (optional) ends the loop between two calls too, but
/// reports the cases done: a run stopped by a signal keeps them even when the rest of the
/// batch would outlast the time the launcher gives before SIGKILL.
/// A unit batch (is_unit) computed whole is handed to `seal`; what it makes is reported
/// instead of its outcomes, or, when `keep` keeps it (a remote worker's own file), only its
/// number and counts. A unit interrupted, or one `seal` declines (nullopt), is
/// reported case by case. With `evaluate_unit` (set), a unit is computed by it
/// (run_unit) instead of case by case.
inline void worker_loop(MasterLink& link, const CasesEvaluator& evaluate, std::size_t row_width,
                        std::size_t together, const std::atomic<bool>* stop = nullptr,
                        const std::atomic<int>* interrupt = nullptr, const Sealer* seal = nullptr,
                        const Keeper* keep = nullptr, const UnitEvaluator* evaluate_unit = nullptr) {
  auto stopping = [stop] { return stop != nullptr && stop->load(); };
  auto interrupted = [interrupt] { return interrupt != nullptr && interrupt->load() != 0; };
  link.request({}, {});
  WorkBatch batch = link.receive_batch();
  ResultBatch finished;
  SealedUnits sealed;
  while (!batch.empty()) {
    link.request(std::move(finished), std::move(sealed));  // prefetch the next batch (or, after "wait", report)
    finished.clear();
    sealed.clear();
    if (!is_wait(batch)) {
      if (is_range_unit(batch)) batch = listed(batch);
      const bool unit = is_unit(batch);
      const std::span<const WorkItem> items = std::span<const WorkItem>(batch).subspan(unit ? 1 : 0);
      const std::size_t before = finished.size();
      finished.reserve(before + items.size());  // one allocation: its outcomes are not moved again as it grows
      bool whole = true;  // the unit ran to its end (false: an evaluate_unit that threw)
      if (unit && evaluate_unit != nullptr && *evaluate_unit) {
        const UnitState state = run_unit(*evaluate_unit, batch.front(), items, evaluate, row_width, finished,
                                         [&] { return stopping() || interrupted(); });
        if (state == UnitState::kCut) {
          if (stopping()) return;
          (void)link.receive_batch();  // the prefetched answer: its cases stay not run
          link.finish(std::move(finished), std::move(sealed));
          return;
        }
        whole = state == UnitState::kWhole;
      } else {
        for (std::size_t first = 0; first < items.size(); first += together) {
          if (stopping()) return;
          if (interrupted()) {
            (void)link.receive_batch();  // the prefetched answer: its cases stay not run
            link.finish(std::move(finished), std::move(sealed));
            return;
          }
          append(finished, evaluate_guarded(evaluate, items.subspan(first, std::min(together, items.size() - first)), row_width));
        }
      }
      if (unit && whole && seal != nullptr && *seal) {
        const auto number = static_cast<std::int64_t>(batch.front().argument);
        const std::span<const CaseOutcome> outcomes(finished.data() + before, finished.size() - before);
        if (std::optional<std::vector<char>> bytes = (*seal)(number, outcomes)) {
          const auto cases = static_cast<std::int64_t>(outcomes.size());
          std::optional<std::int64_t> failed;
          if (keep != nullptr && *keep) failed = (*keep)(number, *bytes);
          if (failed) sealed.push_back({number, cases, {}, true, *failed});
          else sealed.push_back({number, cases, std::move(*bytes)});
          recycle_rows(std::span<CaseOutcome>(finished).subspan(before));  // the next unit's rows
          finished.resize(before);
        }
      }
    }
    batch = link.receive_batch();
  }
  link.finish(std::move(finished), std::move(sealed));
}

}  // namespace pcrf::parallel::detail
