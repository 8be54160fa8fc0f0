// Guided hand-out of case indices (see work_queue.hpp).
#include "pcrf/parallel/work_queue.hpp"

#include <algorithm>

namespace pcrf::parallel {

WorkQueue::WorkQueue(std::vector<std::int64_t> shared, std::vector<std::int64_t> pinned,
                     int workers, std::size_t fixed_batch, std::size_t max_batch)
    : shared_(shared.begin(), shared.end()),
      pinned_(pinned.begin(), pinned.end()),
      workers_(std::max(workers, 1)),
      fixed_batch_(fixed_batch),
      max_batch_(std::max<std::size_t>(max_batch, 1)) {}

std::size_t WorkQueue::batch_size() const {
  if (fixed_batch_ > 0) return fixed_batch_;
  const std::size_t share = 4 * static_cast<std::size_t>(workers_);
  const std::size_t guided = (remaining() + share - 1) / share;
  return std::clamp<std::size_t>(guided, 1, max_batch_);
}

WorkBatch WorkQueue::take(bool in_process_worker) {
  std::size_t n = batch_size();
  WorkBatch batch;
  auto move_from = [&](std::deque<std::int64_t>& source) {
    while (n > 0 && !source.empty()) {
      batch.push_back({source.front(), 0.0});
      source.pop_front();
      --n;
    }
  };
  if (in_process_worker) move_from(pinned_);
  move_from(shared_);
  return batch;
}

}  // namespace pcrf::parallel
