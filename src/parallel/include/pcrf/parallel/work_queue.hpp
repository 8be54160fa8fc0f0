/// \file work_queue.hpp
/// \brief The master's list of cases still to hand out, and how big each hand-out is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include "pcrf/parallel/work_source.hpp"

namespace pcrf::parallel {

/// Cases not yet handed out. Pinned cases go only to the worker that runs inside the
/// master's process (they produce output that never crosses MPI, e.g. time histories).
///
/// Batch sizes are guided: a hand-out is 1/(4·workers) of what is left, clamped to
/// [1, max_batch], so early batches amortize messages and the last ones balance the tail
/// (case costs differ by orders of magnitude). A fixed size can be forced instead.
class WorkQueue final : public WorkSource {
 public:
  /// \param shared  cases any worker may run, in the order to run them
  /// \param pinned  cases for the in-process worker only
  /// \param workers number of workers that will ask (≥ 1)
  /// \param fixed_batch 0: guided sizes; otherwise every batch has this size (or what's left)
  /// \param max_batch upper bound of a guided batch
  WorkQueue(std::vector<std::int64_t> shared, std::vector<std::int64_t> pinned, int workers,
            std::size_t fixed_batch = 0, std::size_t max_batch = 64);

  /// The shared cases one window at a time, so that the list is never held whole: `next`
  /// returns the following window in the order to run it (empty: none left), and
  /// `shared_total` is how many cases all windows hold together (for the guided sizes).
  using NextWindow = std::function<std::vector<std::int64_t>()>;
  WorkQueue(NextWindow next, std::int64_t shared_total, std::vector<std::int64_t> pinned, int workers,
            std::size_t fixed_batch = 0, std::size_t max_batch = 64);

  /// Next batch for a worker; empty when nothing is left for it.
  WorkBatch take(bool in_process_worker) override;
  bool exhausted() const override { return shared_.empty() && pinned_.empty(); }

  /// Cases not yet handed out.
  std::size_t remaining() const;

  /// The group of a case: a batch then holds consecutive cases of one group only (a worker
  /// computes a group's cases faster together; what a group is, the caller knows). Unset:
  /// batches take cases regardless.
  using GroupOf = std::function<std::int64_t(std::int64_t case_index)>;
  void group_by(GroupOf group_of) { group_of_ = std::move(group_of); }

 private:
  std::size_t batch_size() const;
  /// Loads windows until there are shared cases or none is left.
  void refill();

  NextWindow next_window_;
  GroupOf group_of_;
  std::size_t shared_left_ = 0;  ///< in shared_ and in the windows still to come
  std::deque<std::int64_t> shared_;
  std::deque<std::int64_t> pinned_;
  int workers_;
  std::size_t fixed_batch_;
  std::size_t max_batch_;
};

}  // namespace pcrf::parallel
