// The worker side of the scheduling protocol, independent of how messages travel.
// Used by MPI worker ranks and by the worker thread inside rank 0 alike.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <vector>

#include "pcrf/parallel/scheduler.hpp"

namespace pcrf::parallel::detail {

/// How a worker talks to its master.
class MasterLink {
 public:
  virtual ~MasterLink() = default;
  /// Reports finished cases and asks for the next batch (answered by receive_batch).
  virtual void request(ResultBatch finished) = 0;
  /// Blocks until the master's answer to the oldest open request; empty: stop.
  virtual std::vector<std::int64_t> receive_batch() = 0;
  /// Reports the last finished cases; the master expects nothing more from this worker.
  virtual void finish(ResultBatch finished) = 0;
};

inline CaseOutcome evaluate_guarded(const CaseEvaluator& evaluate, std::int64_t index,
                                    std::size_t row_width) {
  try {
    return evaluate(index);
  } catch (const std::exception& e) {
    return {index, kEvaluatorThrew, std::vector<double>(row_width, std::numeric_limits<double>::quiet_NaN()),
            e.what()};
  } catch (...) {
    return {index, kEvaluatorThrew, std::vector<double>(row_width, std::numeric_limits<double>::quiet_NaN()),
            "unknown exception"};
  }
}

/// Request, compute, report — with one request always in flight so that the next batch
/// is on its way while the current one is computed. `stop` (optional) abandons the work
/// between two cases without reporting (the master is failing).
inline void worker_loop(MasterLink& link, const CaseEvaluator& evaluate, std::size_t row_width,
                        const std::atomic<bool>* stop = nullptr) {
  auto stopping = [stop] { return stop != nullptr && stop->load(); };
  link.request({});
  std::vector<std::int64_t> batch = link.receive_batch();
  ResultBatch finished;
  while (!batch.empty()) {
    link.request(std::move(finished));  // prefetch the next batch
    finished.clear();
    for (std::int64_t index : batch) {
      if (stopping()) return;
      finished.push_back(evaluate_guarded(evaluate, index, row_width));
    }
    batch = link.receive_batch();
  }
  link.finish(std::move(finished));
}

}  // namespace pcrf::parallel::detail
