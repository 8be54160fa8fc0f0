// A unit computed by a unit evaluator (ScheduleOptions::evaluate_unit, issue 38: an IDA's curves
// searched whole by the worker of their chunk): the worker runs the cases the evaluator chooses,
// with the arguments it chooses, each after the outcome of the one before; the sealer gets
// exactly those and the unit comes back with their count; a stop inside the unit reports the
// cases run so far one by one; an evaluator that throws loses none of the cases it ran.
#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/parallel/scheduler.hpp"

namespace pcrf::parallel {
namespace {

/// Units 0..5 of 10 consecutive cases each (as ranges), nothing else.
class Ranges final : public WorkSource {
 public:
  WorkBatch take(bool) override {
    if (next_ == kUnits) return {};
    ++next_;
    return unit_range_batch(next_ - 1, 10 * (next_ - 1), 10);
  }
  bool exhausted() const override { return next_ == kUnits; }
  static constexpr std::int64_t kUnits = 6;

 private:
  std::int64_t next_ = 0;
};

/// A chain in each unit: case first + k runs with argument k + 1 while the last outcome's value
/// (its argument squared, as the evaluator below makes it) is below 10: 1, 4, 9, 16 -> four runs.
UnitEvaluator chain(std::atomic<int>* stop_at_unit_two = nullptr, std::atomic<int>* interrupt = nullptr) {
  return [=](std::int64_t unit, std::span<const WorkItem> cases, const UnitCases& run) {
    EXPECT_EQ(cases.size(), 10u);
    EXPECT_EQ(cases.front().case_index, 10 * unit);
    double last = 0.0;
    for (std::size_t k = 0; k < cases.size() && last < 10.0; ++k) {
      if (stop_at_unit_two != nullptr && unit == 2 && k == 2) *interrupt = 1;
      const WorkItem item{cases[k].case_index, static_cast<double>(k + 1)};
      const auto outcome = run(std::span<const WorkItem>(&item, 1));
      if (!outcome) return;
      EXPECT_EQ(outcome->size(), 1u);
      last = outcome->front().row[0];
    }
  };
}

CaseOutcome square(const WorkItem& item) {
  return CaseOutcome{item.case_index, 0, {item.argument * item.argument}, ""};
}

/// A sealer that says which cases it was given, in order: "10:1,11:4,..." (case:value).
Sealer listing() {
  return [](std::int64_t, std::span<const CaseOutcome> outcomes) -> std::optional<std::vector<char>> {
    std::string text;
    for (const auto& o : outcomes) text += std::to_string(o.case_index) + ":" + std::to_string(static_cast<int>(o.row[0])) + ",";
    return std::vector<char>(text.begin(), text.end());
  };
}

/// Runs `work` on rank 0 alone: the units that came back sealed, and the cases reported one
/// by one (their rows' first values).
std::pair<std::set<std::int64_t>, std::map<std::int64_t, double>> run_units(const MpiSession& mpi, Ranges& work,
                                                                          ScheduleOptions options) {
  std::set<std::int64_t> sealed;
  options.on_sealed = [&](SealedUnits&& units) {
    for (auto& u : units) sealed.insert(u.unit);
  };
  std::map<std::int64_t, double> one_by_one;
  run_master(mpi.comm(), work, options, square,
             [&](ResultBatch&& batch) {
               for (const auto& o : batch) one_by_one[o.case_index] = o.row[0];
             },
             [] {});
  return {sealed, one_by_one};
}

TEST(UnitEvaluator, AUnitRunsTheCasesItsEvaluatorChoosesEachAfterTheOneBefore) {
  MpiSession mpi;
  Ranges work;
  ScheduleOptions options;
  options.row_width = 1;
  options.seal = listing();
  options.evaluate_unit = chain();
  std::map<std::int64_t, std::string> sealed;
  std::map<std::int64_t, std::int64_t> cases;
  options.on_sealed = [&](SealedUnits&& units) {
    for (auto& u : units) {
      sealed[u.unit] = std::string(u.bytes.begin(), u.bytes.end());
      cases[u.unit] = u.cases;
    }
  };
  std::size_t one_by_one = 0;
  run_master(mpi.comm(), work, options, square, [&](ResultBatch&& batch) { one_by_one += batch.size(); }, [] {});
  EXPECT_EQ(one_by_one, 0u);
  ASSERT_EQ(sealed.size(), static_cast<std::size_t>(Ranges::kUnits));
  for (std::int64_t u = 0; u < Ranges::kUnits; ++u) {
    const std::int64_t f = 10 * u;
    EXPECT_EQ(sealed[u], std::to_string(f) + ":1," + std::to_string(f + 1) + ":4," + std::to_string(f + 2) + ":9," +
                             std::to_string(f + 3) + ":16,");
    EXPECT_EQ(cases[u], 4) << "the cases it ran, not the 10 it was handed";
  }
}

TEST(UnitEvaluator, AStopInsideAUnitReportsTheCasesItRanOneByOne) {
  MpiSession mpi;
  Ranges work;
  std::atomic<int> interrupt{0};
  ScheduleOptions options;
  options.row_width = 1;
  options.interrupt = &interrupt;
  options.seal = listing();
  options.evaluate_unit = chain(&interrupt, &interrupt);
  const auto [sealed, one_by_one] = run_units(mpi, work, options);
  EXPECT_EQ(sealed, (std::set<std::int64_t>{0, 1}));
  // Unit 2 stopped before its third run: its first two, as they ran, and nothing after.
  EXPECT_EQ(one_by_one, (std::map<std::int64_t, double>{{20, 1.0}, {21, 4.0}}));
}

TEST(UnitEvaluator, AnEvaluatorThatThrowsLosesNoneOfTheCasesItRan) {
  MpiSession mpi;
  Ranges work;
  ScheduleOptions options;
  options.row_width = 1;
  options.seal = listing();
  const UnitEvaluator runs = chain();
  options.evaluate_unit = [runs](std::int64_t unit, std::span<const WorkItem> cases, const UnitCases& run) {
    if (unit != 3) return runs(unit, cases, run);
    const WorkItem item{cases.front().case_index, 7.0};
    (void)run(std::span<const WorkItem>(&item, 1));
    throw std::runtime_error("the evaluator's own failure");
  };
  const auto [sealed, one_by_one] = run_units(mpi, work, options);
  EXPECT_EQ(sealed, (std::set<std::int64_t>{0, 1, 2, 4, 5})) << "the worker goes on after the unit that threw";
  EXPECT_EQ(one_by_one, (std::map<std::int64_t, double>{{30, 49.0}}));
}

}  // namespace
}  // namespace pcrf::parallel
