// Guided hand-out of case indices (see work_queue.hpp).
#include "pcrf/parallel/work_queue.hpp"

#include <algorithm>

#include "parallel/worker_loop.hpp"

namespace pcrf::parallel {

WorkBatch unit_batch(std::int64_t unit, const std::vector<std::int64_t>& cases) {
  WorkBatch batch;
  batch.reserve(cases.size() + 1);
  batch.push_back({detail::kUnitIndex, static_cast<double>(unit)});
  for (const std::int64_t c : cases) batch.push_back({c, 0.0});
  return batch;
}

WorkBatch unit_range_batch(std::int64_t unit, std::int64_t first, std::int64_t count) {
  return {{detail::kUnitIndex, static_cast<double>(unit)}, {detail::kRangeIndex, static_cast<double>(count)}, {first, 0.0}};
}

WorkQueue::WorkQueue(std::vector<std::int64_t> shared, std::vector<std::int64_t> pinned,
                     int workers, std::size_t fixed_batch, std::size_t max_batch)
    : shared_left_(shared.size()),
      shared_(shared.begin(), shared.end()),
      pinned_(pinned.begin(), pinned.end()),
      workers_(std::max(workers, 1)),
      fixed_batch_(fixed_batch),
      max_batch_(std::max<std::size_t>(max_batch, 1)) {}

WorkQueue::WorkQueue(NextWindow next, std::int64_t shared_total, std::vector<std::int64_t> pinned, int workers,
                     std::size_t fixed_batch, std::size_t max_batch)
    : WorkQueue(std::vector<std::int64_t>{}, std::move(pinned), workers, fixed_batch, max_batch) {
  next_window_ = std::move(next);
  shared_left_ = static_cast<std::size_t>(std::max<std::int64_t>(shared_total, 0));
  refill();
}

void WorkQueue::refill() {
  while (shared_.empty() && next_window_) {
    auto window = next_window_();
    if (window.empty()) next_window_ = nullptr;
    shared_.assign(window.begin(), window.end());
  }
}

std::size_t WorkQueue::remaining() const { return std::max(shared_left_, shared_.size()) + pinned_.size(); }

std::size_t WorkQueue::batch_size() const {
  if (fixed_batch_ > 0) return fixed_batch_;
  const std::size_t share = 4 * static_cast<std::size_t>(workers_);
  const std::size_t guided = (remaining() + share - 1) / share;
  return std::clamp<std::size_t>(guided, 1, max_batch_);
}

WorkBatch WorkQueue::take(bool in_process_worker) {
  std::size_t n = batch_size();
  WorkBatch batch;
  std::int64_t group = 0;
  auto same_group = [&](std::int64_t index) {
    if (!group_of_) return true;
    if (batch.empty()) group = group_of_(index);
    return group_of_(index) == group;
  };
  auto move_from = [&](std::deque<std::int64_t>& source) {
    while (n > 0 && !source.empty()) {
      if (!same_group(source.front())) {
        n = 0;  // the batch ends with its group
        return;
      }
      batch.push_back({source.front(), 0.0});
      source.pop_front();
      --n;
    }
  };
  if (in_process_worker) move_from(pinned_);
  while (n > 0 && !shared_.empty()) {
    const std::size_t before = batch.size();
    move_from(shared_);
    const std::size_t taken = batch.size() - before;
    shared_left_ = shared_left_ > taken ? shared_left_ - taken : 0;
    refill();  // whenever windows remain, shared_ is not empty: exhausted() is exact
  }
  return batch;
}

}  // namespace pcrf::parallel
