// Units (issue 38): a batch the work source marks as one unit is computed whole by one worker
// and comes back sealed, as the sealer made it, never case by case; a unit the sealer declines
// comes back case by case; the master's count of cases in flight holds either way.
#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <set>
#include <thread>

#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/parallel/scheduler.hpp"
#include "pcrf/parallel/work_queue.hpp"

namespace pcrf::parallel {
namespace {

/// Units 0..3 of 100 cases each (unit 3 declined by the sealer), then cases 400..449 one by one.
/// The units list their cases, or (`ranges`) give them as a range.
class Units final : public WorkSource {
 public:
  explicit Units(bool ranges = false) : ranges_(ranges) {}
  WorkBatch take(bool in_process) override {
    if (next_ < 4 && ranges_) {
      ++next_;
      return unit_range_batch(next_ - 1, 100 * (next_ - 1), 100);
    }
    if (next_ < 4) {
      std::vector<std::int64_t> cases;
      for (std::int64_t i = 0; i < 100; ++i) cases.push_back(100 * next_ + (99 - i));  // any order
      return unit_batch(next_++, cases);
    }
    return rest_.take(in_process);
  }
  bool exhausted() const override { return next_ == 4 && rest_.exhausted(); }

 private:
  bool ranges_;
  std::int64_t next_ = 0;
  WorkQueue rest_{[] {
    std::vector<std::int64_t> cases;
    for (std::int64_t i = 400; i < 450; ++i) cases.push_back(i);
    return cases;
  }(), {}, 1};
};

/// Runs Units to the end: each unit sealed has every one of its 100 cases once, and what comes
/// back one by one is unit 3 (declined) and the 50 cases after the units, each once.
void expect_units_sealed_and_declined_one_by_one(bool ranges) {
  MpiSession mpi;
  ASSERT_EQ(mpi.size(), 1);
  Units work(ranges);
  ScheduleOptions options;
  options.row_width = 1;
  options.seal = [](std::int64_t unit, std::span<const CaseOutcome> outcomes) -> std::optional<std::vector<char>> {
    if (unit == 3) return std::nullopt;
    std::set<std::int64_t> seen;
    for (const auto& o : outcomes) seen.insert(o.case_index);
    if (seen.size() != 100 || *seen.begin() != 100 * unit) return std::vector<char>{'b', 'a', 'd'};
    return std::vector<char>{'o', 'k', static_cast<char>('0' + unit)};
  };
  std::map<std::int64_t, std::string> sealed;
  options.on_sealed = [&](SealedUnits&& units) {
    for (auto& u : units) {
      EXPECT_EQ(u.cases, 100);
      sealed[u.unit] = std::string(u.bytes.begin(), u.bytes.end());
    }
  };
  std::set<std::int64_t> one_by_one;
  run_master(mpi.comm(), work, options,
             [](const WorkItem& item) { return CaseOutcome{item.case_index, 0, {static_cast<double>(item.case_index)}, ""}; },
             [&](ResultBatch&& batch) {
               for (const auto& o : batch) EXPECT_TRUE(one_by_one.insert(o.case_index).second) << o.case_index;
             },
             [] {});
  EXPECT_EQ(sealed, (std::map<std::int64_t, std::string>{{0, "ok0"}, {1, "ok1"}, {2, "ok2"}}));
  ASSERT_EQ(one_by_one.size(), 150u);  // unit 3, declined, and the 50 cases after the units
  EXPECT_EQ(*one_by_one.begin(), 300);
  EXPECT_EQ(*one_by_one.rbegin(), 449);
}

TEST(Scheduler, AUnitComesBackSealedByItsWorkerAndADeclinedOneCaseByCase) {
  expect_units_sealed_and_declined_one_by_one(false);
}

// A unit handed out as its range (three items, whatever its size) reaches the worker as each of
// its cases once, and the master's count of cases in flight holds (run_master returns).
TEST(Scheduler, ARangeUnitIsEveryCaseOfItsRangeOnce) { expect_units_sealed_and_declined_one_by_one(true); }

// A signal ends a unit half done: the cases done so far come back one by one, nothing sealed.
TEST(Scheduler, AnInterruptedUnitReportsItsCasesDoneOneByOne) {
  MpiSession mpi;
  Units work;
  std::atomic<int> interrupt{0};
  ScheduleOptions options;
  options.row_width = 1;
  options.interrupt = &interrupt;
  options.seal = [](std::int64_t, std::span<const CaseOutcome>) -> std::optional<std::vector<char>> {
    return std::vector<char>{'s'};
  };
  std::set<std::int64_t> sealed, one_by_one;
  options.on_sealed = [&](SealedUnits&& units) {
    for (auto& u : units) sealed.insert(u.unit);
  };
  run_master(mpi.comm(), work, options,
             [&](const WorkItem& item) {
               if (item.case_index == 150) interrupt = 1;
               return CaseOutcome{item.case_index, 0, {0.0}, ""};
             },
             [&](ResultBatch&& batch) {
               for (const auto& o : batch) one_by_one.insert(o.case_index);
             },
             [] {});
  EXPECT_EQ(sealed, std::set<std::int64_t>{0});
  ASSERT_FALSE(one_by_one.empty());
  EXPECT_EQ(*one_by_one.begin(), 150) << "unit 1 is computed from its last case to its first";
  EXPECT_EQ(*one_by_one.rbegin(), 199);
}

// Rank 0's worker thread keeps the units it seals when the options have a keeper (its part, at
// two ranks or more), called in that thread: the master hears each unit's number, case count
// and failures, never its bytes; a unit the keeper declines travels as before.
TEST(Scheduler, RankZerosWorkerThreadKeepsItsUnitsWhenGivenAKeeper) {
  MpiSession mpi;
  ASSERT_EQ(mpi.size(), 1);
  Units work;
  ScheduleOptions options;
  options.row_width = 1;
  options.seal = [](std::int64_t unit, std::span<const CaseOutcome>) -> std::optional<std::vector<char>> {
    return std::vector<char>{'u', static_cast<char>('0' + unit)};
  };
  const std::thread::id master = std::this_thread::get_id();
  std::atomic<bool> kept_in_master{false};
  options.keep = [&](std::int64_t unit, const std::vector<char>& bytes) -> std::optional<std::int64_t> {
    kept_in_master = kept_in_master || std::this_thread::get_id() == master;
    if (unit == 2) return std::nullopt;  // not kept: the bytes travel
    EXPECT_EQ(bytes, (std::vector<char>{'u', static_cast<char>('0' + unit)}));
    return unit + 10;                    // its failures, as the keeper counted them
  };
  std::map<std::int64_t, SealedUnit> sealed;
  options.on_sealed = [&](SealedUnits&& units) {
    for (auto& u : units) sealed[u.unit] = std::move(u);
  };
  run_master(mpi.comm(), work, options, [](const WorkItem& item) { return CaseOutcome{item.case_index, 0, {0.0}, ""}; },
             [](ResultBatch&&) {}, [] {});
  EXPECT_FALSE(kept_in_master) << "the keeper runs in the worker thread";
  ASSERT_EQ(sealed.size(), 4u);
  for (const std::int64_t unit : {0, 1, 3}) {
    EXPECT_TRUE(sealed[unit].kept) << unit;
    EXPECT_TRUE(sealed[unit].bytes.empty()) << unit;
    EXPECT_EQ(sealed[unit].failed, unit + 10);
    EXPECT_EQ(sealed[unit].cases, 100);
    EXPECT_EQ(sealed[unit].worker, 0) << "the master names the rank whose worker kept it (its own thread: 0)";
  }
  EXPECT_FALSE(sealed[2].kept);
  EXPECT_EQ(sealed[2].bytes, (std::vector<char>{'u', '2'}));
}

TEST(ResultBatch, AMessageCarriesOutcomesAndSealedUnits) {
  const ResultBatch batch{{4, 1, {1.5, 2.5}, "n"}};
  const SealedUnits units{{7, 100, {'x', 'y'}}, {8, 3, {}}};
  const auto [back, sealed] = unpack_message(pack_message(batch, units, 2), 2);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].row, batch[0].row);
  ASSERT_EQ(sealed.size(), 2u);
  EXPECT_EQ(sealed[0].unit, 7);
  EXPECT_EQ(sealed[0].cases, 100);
  EXPECT_EQ(sealed[0].bytes, units[0].bytes);
  EXPECT_TRUE(sealed[1].bytes.empty());
  auto cut = pack_message(batch, units, 2);
  cut.pop_back();
  EXPECT_THROW(unpack_message(cut, 2), std::runtime_error);
}

}  // namespace
}  // namespace pcrf::parallel
