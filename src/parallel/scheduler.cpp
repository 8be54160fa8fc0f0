// Master–worker scheduling over MPI (see scheduler.hpp). Message protocol:
//   worker → master  kTagRequest  pack_message: finished cases and sealed (or kept) units, asks for a batch
//   worker → master  kTagFinish   pack_message, the worker's last message
//   master → worker  kTagBatch    WorkItems (index, argument) as bytes; empty means "stop",
//                                 one item of index kWaitIndex "nothing ready: report and ask again",
//                                 a first item of index kUnitIndex "compute these whole and seal them"
//                                 (then the cases, or an item of index kRangeIndex: consecutive ones)
#include "pcrf/parallel/scheduler.hpp"

#include <algorithm>
#include <chrono>
#include <list>
#include <optional>
#include <stdexcept>
#include <thread>

#include "parallel/local_channel.hpp"
#include "pcrf/parallel/work_queue.hpp"

namespace pcrf::parallel {
namespace {

using detail::Incoming;
using detail::LocalChannel;

constexpr int kTagRequest = 101;
constexpr int kTagFinish = 102;
constexpr int kTagBatch = 103;

/// Cases a worker computes per evaluator call (at least 1).
std::size_t together(const ScheduleOptions& options) { return std::max<std::size_t>(options.evaluate_together, 1); }

/// Short sleep used while waiting for a message that is not there yet.
void nap() { std::this_thread::sleep_for(std::chrono::microseconds(100)); }

/// A worker rank's link to rank 0.
class MpiMasterLink final : public detail::MasterLink {
 public:
  MpiMasterLink(MPI_Comm comm, std::size_t row_width) : comm_(comm), row_width_(row_width) {}
  ~MpiMasterLink() override { wait_send(); }

  void request(ResultBatch finished, SealedUnits sealed) override { send(kTagRequest, finished, sealed); }
  void finish(ResultBatch finished, SealedUnits sealed) override {
    send(kTagFinish, finished, sealed);
    wait_send();
  }
  WorkBatch receive_batch() override {
    MPI_Status status;
    for (int arrived = 0;;) {  // poll with naps rather than spin in MPI_Probe
      MPI_Iprobe(0, kTagBatch, comm_, &arrived, &status);
      if (arrived) break;
      nap();
    }
    int bytes = 0;
    MPI_Get_count(&status, MPI_BYTE, &bytes);
    WorkBatch batch(static_cast<std::size_t>(bytes) / sizeof(WorkItem));
    MPI_Recv(batch.data(), bytes, MPI_BYTE, 0, kTagBatch, comm_, MPI_STATUS_IGNORE);
    return batch;
  }

 private:
  void send(int tag, const ResultBatch& finished, const SealedUnits& sealed) {
    wait_send();
    buffer_ = pack_message(finished, sealed, row_width_);
    MPI_Isend(buffer_.data(), static_cast<int>(buffer_.size()), MPI_BYTE, 0, tag, comm_, &pending_);
  }
  void wait_send() {
    if (pending_ != MPI_REQUEST_NULL) MPI_Wait(&pending_, MPI_STATUS_IGNORE);
  }

  MPI_Comm comm_;
  std::size_t row_width_;
  std::vector<char> buffer_;
  MPI_Request pending_ = MPI_REQUEST_NULL;
};

/// The master's side of the MPI workers: non-blocking receive and send.
class MpiWorkers {
 public:
  MpiWorkers(MPI_Comm comm, std::size_t row_width) : comm_(comm), row_width_(row_width) {}

  std::optional<Incoming> poll() {
    reap_sends();
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, comm_, &arrived, &status);
    if (!arrived) return std::nullopt;
    if (status.MPI_TAG != kTagRequest && status.MPI_TAG != kTagFinish)
      throw std::runtime_error("scheduler: unexpected message tag " + std::to_string(status.MPI_TAG) +
                               " from rank " + std::to_string(status.MPI_SOURCE));
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    std::vector<char> bytes(static_cast<std::size_t>(count));
    MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, comm_,
             MPI_STATUS_IGNORE);
    auto [results, sealed] = unpack_message(bytes, row_width_);
    return Incoming{status.MPI_SOURCE, status.MPI_TAG == kTagFinish, std::move(results), std::move(sealed)};
  }

  /// Non-blocking: a worker posts its receive only after its current batch, and the
  /// master must not wait for that.
  void reply(int rank, WorkBatch batch) {
    sends_.push_back({MPI_REQUEST_NULL, std::move(batch)});
    auto& send = sends_.back();
    MPI_Isend(send.buffer.data(), static_cast<int>(send.buffer.size() * sizeof(WorkItem)), MPI_BYTE, rank,
              kTagBatch, comm_, &send.request);
  }

  void wait_all() {
    for (auto& send : sends_) MPI_Wait(&send.request, MPI_STATUS_IGNORE);
    sends_.clear();
  }

 private:
  struct PendingSend {
    MPI_Request request;
    WorkBatch buffer;
  };
  void reap_sends() {
    for (auto it = sends_.begin(); it != sends_.end();) {
      int done = 0;
      MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
      it = done ? sends_.erase(it) : std::next(it);
    }
  }

  MPI_Comm comm_;
  std::size_t row_width_;
  std::list<PendingSend> sends_;  // list: buffers must not move while in flight
};

/// The master's event loop over both kinds of worker.
class Master {
 public:
  Master(MPI_Comm comm, WorkSource& work, const ScheduleOptions& options, int ranks)
      : options_(options), work_(work), remote_(comm, options.row_width), active_workers_(ranks),
        in_flight_(static_cast<std::size_t>(ranks), 0), units_out_(static_cast<std::size_t>(ranks)) {}

  void run(const CasesEvaluator& evaluate, const OutcomeHandler& on_outcomes,
           const IdleHandler& on_idle) {
    std::thread local_worker([&] {
      detail::worker_loop(local_, evaluate, options_.row_width, together(options_), local_.stop_flag(),
                          options_.interrupt, &options_.seal, &options_.keep, &options_.evaluate_unit);
    });
    try {
      loop(on_outcomes, on_idle);
    } catch (...) {
      local_.stop();
      local_worker.join();
      throw;
    }
    local_worker.join();
    remote_.wait_all();
  }

 private:
  void loop(const OutcomeHandler& on_outcomes, const IdleHandler& on_idle) {
    while (active_workers_ > 0) {
      bool busy = false;
      while (auto message = remote_.poll()) busy = handle(std::move(*message), on_outcomes);
      while (auto message = local_.poll()) busy = handle(std::move(*message), on_outcomes);
      serve_held();
      on_idle();
      if (!busy) local_.wait(options_.poll_interval_s);
    }
  }

  bool handle(Incoming message, const OutcomeHandler& on_outcomes) {
    const auto worker = static_cast<std::size_t>(message.worker);
    in_flight_[worker] -= std::min(in_flight_[worker], message.results.size());
    for (const auto& unit : message.sealed) in_flight_[worker] -= std::min(in_flight_[worker], handed_back(worker, unit));
    for (const auto& outcome : message.results) work_.completed(outcome);
    if (!message.results.empty()) on_outcomes(std::move(message.results));
    if (!message.sealed.empty()) {
      if (!options_.on_sealed) throw std::logic_error("scheduler: a worker sealed units and nobody takes them");
      for (auto& unit : message.sealed) unit.worker = message.worker;
      options_.on_sealed(std::move(message.sealed));
    }
    if (message.finished) {
      --active_workers_;
      return true;
    }
    if (!serve(message.worker)) {
      // Nothing ready. A worker that still holds cases is told to report them (they may be
      // what the source waits for); one that holds nothing waits here for work.
      if (in_flight_[worker] > 0)
        reply(message.worker, detail::wait_batch());
      else
        held_.push_back(message.worker);
    }
    return true;
  }

  /// Answers a worker with work, or "stop" once the source is exhausted; false if neither.
  bool serve(int worker) {
    WorkBatch batch = work_.take(worker == 0);
    if (batch.empty() && !work_.exhausted()) return false;
    const std::size_t cases = detail::cases_in(batch);
    in_flight_[static_cast<std::size_t>(worker)] += cases;
    if (options_.evaluate_unit && detail::is_unit(batch))
      units_out_[static_cast<std::size_t>(worker)].push_back({static_cast<std::int64_t>(batch.front().argument), cases});
    reply(worker, std::move(batch));
    return true;
  }

  /// The cases a sealed unit gives back to its worker's count in flight: those it was handed
  /// (a unit evaluator may run fewer of them, ScheduleOptions::evaluate_unit), else those it holds.
  std::size_t handed_back(std::size_t worker, const SealedUnit& unit) {
    auto& out = units_out_[worker];
    const auto it = std::find_if(out.begin(), out.end(), [&](const auto& u) { return u.first == unit.unit; });
    if (it == out.end()) return static_cast<std::size_t>(unit.cases);
    const std::size_t cases = it->second;
    out.erase(it);
    return cases;
  }

  void serve_held() {
    for (auto it = held_.begin(); it != held_.end();) it = serve(*it) ? held_.erase(it) : std::next(it);
  }

  void reply(int worker, WorkBatch batch) {
    if (worker == 0)
      local_.reply(std::move(batch));
    else
      remote_.reply(worker, std::move(batch));
  }

  ScheduleOptions options_;
  WorkSource& work_;
  LocalChannel local_;
  MpiWorkers remote_;
  int active_workers_;
  std::vector<std::size_t> in_flight_;  ///< cases handed to each worker and not back yet
  /// Units handed to each worker that a unit evaluator computes (number, cases handed): at
  /// most two a worker (the one it computes and the one it prefetched).
  std::vector<std::vector<std::pair<std::int64_t, std::size_t>>> units_out_;
  std::list<int> held_;                 ///< workers waiting for work to appear
};

}  // namespace

int worker_count(MPI_Comm comm) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  return ranks;
}

void run_master(MPI_Comm comm, WorkSource& work, const ScheduleOptions& options,
                const CasesEvaluator& evaluate, const OutcomeHandler& on_outcomes,
                const IdleHandler& on_idle) {
  Master master(comm, work, options, worker_count(comm));
  master.run(evaluate, on_outcomes, on_idle);
}

void run_master(MPI_Comm comm, WorkSource& work, const ScheduleOptions& options,
                const CaseEvaluator& evaluate, const OutcomeHandler& on_outcomes,
                const IdleHandler& on_idle) {
  ScheduleOptions one = options;
  one.evaluate_together = 1;
  run_master(comm, work, one, one_by_one(evaluate), on_outcomes, on_idle);
}

void run_worker(MPI_Comm comm, const ScheduleOptions& options, const CasesEvaluator& evaluate) {
  MpiMasterLink link(comm, options.row_width);
  detail::worker_loop(link, evaluate, options.row_width, together(options), nullptr, options.interrupt, &options.seal,
                      &options.keep, &options.evaluate_unit);
}

void run_worker(MPI_Comm comm, const ScheduleOptions& options, const CaseEvaluator& evaluate) {
  ScheduleOptions one = options;
  one.evaluate_together = 1;
  run_worker(comm, one, one_by_one(evaluate));
}

CasesEvaluator one_by_one(CaseEvaluator evaluate) {
  return [evaluate = std::move(evaluate)](std::span<const WorkItem> items) {
    ResultBatch outcomes;
    for (const WorkItem& item : items) outcomes.push_back(evaluate(item));
    return outcomes;
  };
}

}  // namespace pcrf::parallel
