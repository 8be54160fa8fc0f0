// The scheduler's parts: result messages, guided batches, and a whole master run on one
// rank (MPI singleton) where every case must come back exactly once.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <map>
#include <set>
#include <span>
#include <stdexcept>
#include <thread>

#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/parallel/result_batch.hpp"
#include "pcrf/parallel/scheduler.hpp"
#include "pcrf/parallel/work_queue.hpp"

namespace pcrf::parallel {
namespace {

TEST(ResultBatch, PacksAndUnpacksRowsAndNotes) {
  const ResultBatch batch = {{7, 0, {1.0, NAN, -2.5}, ""}, {42, 3, {0.0, 3.0, 1e300}, "tendon, \"fracture\"\n"}};
  const auto back = unpack_results(pack_results(batch, 3), 3);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].case_index, 42);
  EXPECT_EQ(back[1].note, batch[1].note);
  EXPECT_EQ(back[0].status, 0);
  EXPECT_EQ(back[1].status, 3);
  EXPECT_TRUE(std::isnan(back[0].row[1]));
  EXPECT_EQ(back[1].row[2], 1e300);
  EXPECT_THROW(unpack_results(pack_results(batch, 3), 4), std::runtime_error);
  EXPECT_THROW(pack_results(batch, 2), std::invalid_argument);
}

// A worker's rows: given back after a unit is sealed, reused by its next cases, each filled
// anew whatever it held; a thread's pool keeps at most kPooledRows; other threads' are theirs.
TEST(ResultBatch, RowsGivenBackAreReusedFilledAnewAndThePoolIsBounded) {
  std::thread([] {
    const auto fresh = pooled_row(5, NAN);
    ASSERT_EQ(fresh.size(), 5u);
    EXPECT_TRUE(std::all_of(fresh.begin(), fresh.end(), [](double v) { return std::isnan(v); }));
    ResultBatch batch(kPooledRows + 10);
    std::set<const double*> buffers;
    for (auto& outcome : batch) {
      outcome.row.assign(17, 1.0);
      buffers.insert(outcome.row.data());
    }
    buffers.erase(batch[3].row.data());
    std::vector<double>().swap(batch[3].row);  // nothing to reuse
    recycle_rows(batch);
    std::size_t given = 0;
    for (const auto& outcome : batch) given += outcome.row.empty() ? 1 : 0;
    EXPECT_EQ(given, kPooledRows + 1) << "the pool takes kPooledRows, and the row that had none stays empty";
    std::size_t reused = 0;
    std::vector<std::vector<double>> rows;
    for (std::size_t k = 0; k < kPooledRows + 5; ++k) {
      rows.push_back(pooled_row(3, 2.5));
      ASSERT_EQ(rows.back(), std::vector<double>(3, 2.5));
      reused += buffers.count(rows.back().data());
    }
    EXPECT_EQ(reused, kPooledRows);
    std::thread([] { EXPECT_EQ(pooled_row(2, 0.0), std::vector<double>(2, 0.0)); }).join();
  }).join();
}

TEST(WorkQueue, GuidedBatchesShrinkAndPinnedCasesStayLocal) {
  std::vector<std::int64_t> shared(1000);
  for (std::size_t i = 0; i < shared.size(); ++i) shared[i] = static_cast<std::int64_t>(i);
  WorkQueue queue(shared, {5000, 5001}, 2, 0, 64);
  EXPECT_EQ(queue.take(false).size(), 64u);  // capped
  auto local = queue.take(true);
  EXPECT_EQ(local[0].case_index, 5000);
  EXPECT_EQ(local[1].case_index, 5001);
  std::size_t last = 64, taken = 64 + local.size() - 2;
  while (queue.remaining() > 0) {
    const auto batch = queue.take(false);
    EXPECT_LE(batch.size(), last);
    last = batch.size();
    taken += batch.size();
  }
  EXPECT_EQ(last, 1u);  // the tail is handed out one by one
  EXPECT_EQ(taken, 1000u);
  EXPECT_TRUE(queue.take(true).empty());
}

TEST(WorkQueue, WindowsAreHandedOutInOrderWithoutHoldingTheWholeList) {
  // 10 windows of 100 cases (one of them empty), asked for one at a time.
  int asked = 0;
  auto next = [&asked, window = 0]() mutable {
    std::vector<std::int64_t> cases;
    while (cases.empty() && window < 10) {
      if (window != 4)
        for (int k = 0; k < 100; ++k) cases.push_back(window * 100 + k);
      ++window;
    }
    ++asked;
    return cases;
  };
  WorkQueue queue(next, 900, {7777}, 2, 0, 64);
  EXPECT_EQ(asked, 1);  // only the first window is loaded up front
  EXPECT_EQ(queue.remaining(), 901u);
  std::vector<std::int64_t> order;
  while (!queue.exhausted()) {
    const std::size_t left = queue.remaining();
    const auto batch = queue.take(order.empty());
    ASSERT_FALSE(batch.empty());
    // Guided by everything left, not by the window: 1/(4·2) of it, at most 64.
    EXPECT_EQ(batch.size(), std::min<std::size_t>({64, (left + 7) / 8, left})) << order.size();
    for (const auto& item : batch) order.push_back(item.case_index);
  }
  EXPECT_EQ(order.front(), 7777);
  order.erase(order.begin());
  ASSERT_EQ(order.size(), 900u);
  EXPECT_TRUE(std::is_sorted(order.begin(), order.end()));  // window after window
  EXPECT_EQ(std::adjacent_find(order.begin(), order.end()), order.end());
  EXPECT_TRUE(queue.take(false).empty());
}

TEST(Scheduler, OneRankRunsEveryCaseOnceThroughTheWorkerThread) {
  MpiSession mpi;
  ASSERT_EQ(mpi.size(), 1);
  std::vector<std::int64_t> shared;
  for (std::int64_t i = 0; i < 300; ++i) shared.push_back(i);
  WorkQueue work(shared, {300, 301}, 1);
  const auto master_thread = std::this_thread::get_id();
  std::set<std::thread::id> workers;
  auto evaluate = [&](const WorkItem& item) {
    const std::int64_t index = item.case_index;
    workers.insert(std::this_thread::get_id());
    if (index == 17) throw std::runtime_error("boom");  // must not stop the study
    return CaseOutcome{index, 1, {static_cast<double>(index), 2.0 * static_cast<double>(index)}, ""};
  };
  std::map<std::int64_t, CaseOutcome> received;
  int idle_calls = 0;
  ScheduleOptions options;
  options.row_width = 2;
  run_master(mpi.comm(), work, options, evaluate,
             [&](ResultBatch&& batch) {
               EXPECT_EQ(std::this_thread::get_id(), master_thread);
               for (auto& o : batch) EXPECT_TRUE(received.emplace(o.case_index, o).second) << o.case_index;
             },
             [&] { ++idle_calls; });
  ASSERT_EQ(received.size(), 302u);
  EXPECT_EQ(received[299].row[1], 598.0);
  EXPECT_TRUE(std::isnan(received[17].row[0]));
  EXPECT_EQ(received[17].status, kEvaluatorThrew);
  EXPECT_EQ(received[299].status, 1);
  EXPECT_EQ(received[17].note, "boom");
  EXPECT_GT(idle_calls, 0);
  ASSERT_EQ(workers.size(), 1u);
  EXPECT_NE(*workers.begin(), master_thread);
}

TEST(WorkQueue, GroupedBatchesNeverMixTwoGroupsAndStillShrinkAtTheEnd) {
  // Groups of 100 consecutive cases (what a study's excitation is, the queue does not know).
  std::vector<std::int64_t> shared(1000);
  for (std::size_t i = 0; i < shared.size(); ++i) shared[i] = static_cast<std::int64_t>(i);
  WorkQueue queue(shared, {}, 2, 0, 64);
  queue.group_by([](std::int64_t i) { return i / 100; });
  std::vector<std::int64_t> order;
  std::size_t largest = 0, last = 0;
  while (!queue.exhausted()) {
    const std::size_t left = queue.remaining();
    const auto batch = queue.take(false);
    ASSERT_FALSE(batch.empty());
    EXPECT_LE(batch.size(), std::min<std::size_t>({64, (left + 7) / 8, left}));  // never above the guided size
    EXPECT_EQ(batch.front().case_index / 100, batch.back().case_index / 100) << "two groups in one batch";
    largest = std::max(largest, batch.size());
    last = batch.size();
    for (const auto& item : batch) order.push_back(item.case_index);
  }
  EXPECT_EQ(largest, 64u);
  EXPECT_EQ(last, 1u);  // the tail still one by one: dynamic balance at the end
  ASSERT_EQ(order.size(), 1000u);
  EXPECT_TRUE(std::is_sorted(order.begin(), order.end()));
  EXPECT_EQ(std::adjacent_find(order.begin(), order.end()), order.end());
}

TEST(Scheduler, ACasesEvaluatorGetsAtMostItsShareOfABatchPerCall) {
  MpiSession mpi;
  ASSERT_EQ(mpi.size(), 1);
  std::vector<std::int64_t> shared;
  for (std::int64_t i = 0; i < 300; ++i) shared.push_back(i);
  WorkQueue work(shared, {}, 1, 20);  // batches of 20
  std::vector<std::size_t> calls;
  auto evaluate = [&](std::span<const WorkItem> items) {
    calls.push_back(items.size());
    ResultBatch outcomes;
    for (const WorkItem& item : items) {
      if (item.case_index == 42) throw std::runtime_error("boom");  // the call's every case fails
      outcomes.push_back({item.case_index, 1, {static_cast<double>(item.case_index)}, ""});
    }
    return outcomes;
  };
  ScheduleOptions options;
  options.row_width = 1;
  options.evaluate_together = 8;
  std::map<std::int64_t, CaseOutcome> received;
  run_master(mpi.comm(), work, options, evaluate,
             [&](ResultBatch&& batch) {
               for (auto& o : batch) EXPECT_TRUE(received.emplace(o.case_index, o).second) << o.case_index;
             },
             [] {});
  ASSERT_EQ(received.size(), 300u);
  EXPECT_EQ(calls.size(), 15u * 3u);  // 20 = 8 + 8 + 4
  EXPECT_EQ(*std::max_element(calls.begin(), calls.end()), 8u);
  for (std::int64_t i = 40; i < 48; ++i) EXPECT_EQ(received[i].status, kEvaluatorThrew) << i;  // 42's call: 40 … 47
  EXPECT_EQ(received[48].status, 1);
  EXPECT_EQ(received[42].note, "boom");
}

/// Chains of cases: case k of a chain exists only once case k − 1 has come back, the way
/// an adaptive plan makes its next run. Every step must run once, in order, with the
/// argument its chain chose.
class ChainSource final : public WorkSource {
 public:
  ChainSource(int chains, int length) : length_(length), next_(static_cast<std::size_t>(chains), 0), ready_() {
    for (int c = 0; c < chains; ++c) ready_.push_back(c);
  }
  WorkBatch take(bool) override {
    WorkBatch batch;
    if (!ready_.empty()) {
      const int c = ready_.front();
      ready_.erase(ready_.begin());
      batch.push_back({c * 1000 + next_[static_cast<std::size_t>(c)], 0.5 * c + next_[static_cast<std::size_t>(c)]});
    }
    return batch;
  }
  void completed(const CaseOutcome& outcome) override {
    const auto c = static_cast<std::size_t>(outcome.case_index / 1000);
    EXPECT_EQ(outcome.case_index % 1000, next_[c]) << "out of order";
    if (++next_[c] < length_) ready_.push_back(static_cast<int>(c));
    else ++done_;
  }
  bool exhausted() const override { return done_ == static_cast<int>(next_.size()); }

 private:
  int length_;
  std::vector<int> next_;
  std::vector<int> ready_;
  int done_ = 0;
};

TEST(Scheduler, AnAdaptiveSourceGetsEachResultBeforeItsNextCase) {
  MpiSession mpi;
  ChainSource chains(5, 20);
  ScheduleOptions options;
  options.row_width = 1;
  std::map<std::int64_t, double> arguments;
  run_master(mpi.comm(), chains, options,
             [](const WorkItem& item) { return CaseOutcome{item.case_index, 0, {item.argument}, ""}; },
             [&](ResultBatch&& batch) {
               for (auto& o : batch) EXPECT_TRUE(arguments.emplace(o.case_index, o.row[0]).second);
             },
             [] {});
  ASSERT_EQ(arguments.size(), 100u);
  EXPECT_EQ(arguments[3019], 0.5 * 3 + 19);
  EXPECT_TRUE(chains.exhausted());
}

}  // namespace
}  // namespace pcrf::parallel
