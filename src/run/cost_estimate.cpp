// A study's cost, measured on a sample of its cases (see cost_estimate.hpp).
#include "pcrf/run/cost_estimate.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "pcrf/run/case_runner.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;

std::string CostEstimate::text() const {
  if (sampled == 0) return "no case could be timed: no cost estimate";
  const double per_case_s = sampled_s / static_cast<double>(sampled);
  const bool hours = total_core_s >= 7200.0, minutes = !hours && total_core_s >= 120.0;
  const double amount = hours ? total_core_s / 3600.0 : minutes ? total_core_s / 60.0 : total_core_s;
  char line[400];
  std::snprintf(line, sizeof line,
                "cost estimate: about %.2g core-%s (divide by the worker count): "
                "%lld sampled cases, spread evenly over the study's hand-out order, ran in %.3g s (%.3g s each), "
                "times %.0f %s",
                amount, hours ? "hours" : minutes ? "minutes" : "seconds", static_cast<long long>(sampled), sampled_s, per_case_s, cases,
                upper_bound ? "runs (an upper bound: every IDA curve running max_runs, each timed at [ida] start)"
                            : "cases");
  return line;
}

CostEstimate estimate_cost(const Study& study, const CaseSpace& space, RecordCache& records, std::int64_t sample,
                           double budget_s) {
  using Clock = std::chrono::steady_clock;
  const CaseRunner runner(study, space, records);
  const bool ida = space.ida_runs() > 0;
  const std::int64_t population = ida ? space.curves() : space.size();
  const std::int64_t n = std::clamp<std::int64_t>(sample, 1, population);
  CostEstimate estimate;
  const auto begin = Clock::now();
  for (std::int64_t k = 0; k < n; ++k) {
    const std::int64_t position = k * population / n + population / (2 * n);  // the middle of each n-th
    parallel::WorkItem item;
    item.case_index = ida ? position * static_cast<std::int64_t>(space.ida_runs()) : space.handout_index(position);
    item.argument = ida ? study.ida->start : 0.0;
    (void)runner.run(item);
    ++estimate.sampled;
    if (std::chrono::duration<double>(Clock::now() - begin).count() > budget_s) break;
  }
  estimate.sampled_s = std::chrono::duration<double>(Clock::now() - begin).count();
  estimate.upper_bound = ida;
  estimate.cases = ida ? static_cast<double>(space.curves()) * static_cast<double>(study.ida->max_runs)
                       : static_cast<double>(space.size());
  estimate.total_core_s = estimate.cases * estimate.sampled_s / static_cast<double>(estimate.sampled);
  return estimate;
}

}  // namespace pcrf::run
