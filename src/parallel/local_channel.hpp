// In-process link between the master thread of rank 0 and the worker thread beside it.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>

#include "parallel/worker_loop.hpp"

namespace pcrf::parallel::detail {

/// A message from a worker to the master.
struct Incoming {
  int worker = 0;         ///< MPI rank; 0 for the in-process worker
  bool finished = false;  ///< true: the worker's last message
  ResultBatch results;
  SealedUnits sealed;
};

/// Two queues under one mutex: requests (worker → master) and batches (master → worker).
class LocalChannel final : public MasterLink {
 public:
  // Worker side.
  void request(ResultBatch finished, SealedUnits sealed) override {
    push({0, false, std::move(finished), std::move(sealed)});
  }
  void finish(ResultBatch finished, SealedUnits sealed) override {
    push({0, true, std::move(finished), std::move(sealed)});
  }
  WorkBatch receive_batch() override {
    std::unique_lock lock(mutex_);
    batch_ready_.wait(lock, [this] { return !batches_.empty() || stop_; });
    if (batches_.empty()) return {};
    auto batch = std::move(batches_.front());
    batches_.pop_front();
    return batch;
  }

  // Master side.
  std::optional<Incoming> poll() {
    std::lock_guard lock(mutex_);
    if (requests_.empty()) return std::nullopt;
    Incoming message = std::move(requests_.front());
    requests_.pop_front();
    return message;
  }
  void reply(WorkBatch batch) {
    {
      std::lock_guard lock(mutex_);
      batches_.push_back(std::move(batch));
    }
    batch_ready_.notify_one();
  }
  /// Sleeps until the worker sends something or `seconds` pass.
  void wait(double seconds) {
    std::unique_lock lock(mutex_);
    request_ready_.wait_for(lock, std::chrono::duration<double>(seconds),
                            [this] { return !requests_.empty(); });
  }
  /// Makes the worker give up (master failing).
  void stop() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    stop_flag_.store(true);
    batch_ready_.notify_all();
  }
  const std::atomic<bool>* stop_flag() const { return &stop_flag_; }

 private:
  void push(Incoming message) {
    {
      std::lock_guard lock(mutex_);
      requests_.push_back(std::move(message));
    }
    request_ready_.notify_one();
  }

  std::mutex mutex_;
  std::condition_variable request_ready_, batch_ready_;
  std::deque<Incoming> requests_;
  std::deque<WorkBatch> batches_;
  bool stop_ = false;
  std::atomic<bool> stop_flag_{false};
};

}  // namespace pcrf::parallel::detail
