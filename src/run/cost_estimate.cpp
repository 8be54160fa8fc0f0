// A study's cost, measured on a sample of its work (see cost_estimate.hpp).
#include "pcrf/run/cost_estimate.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <span>

#include "pcrf/ida/ida_search.hpp"
#include "pcrf/run/case_runner.hpp"
#include "pcrf/run/ida_work.hpp"
#include "pcrf/solver/case_group.hpp"
#include "pcrf/thread_cpu.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;
namespace {

/// An amount of CPU time in the unit that reads best, e.g. "2.1 CPU-hours".
std::string cpu_amount(double seconds) {
  const bool hours = seconds >= 7200.0, minutes = !hours && seconds >= 120.0;
  char text[64];
  std::snprintf(text, sizeof text, "%.2g CPU-%s", hours ? seconds / 3600.0 : minutes ? seconds / 60.0 : seconds,
                hours ? "hours" : minutes ? "minutes" : "seconds");
  return text;
}

/// The value of `bits` bits read backwards.
std::int64_t reversed(std::int64_t value, int bits) {
  std::int64_t out = 0;
  for (int b = 0; b < bits; ++b) out |= ((value >> b) & 1) << (bits - 1 - b);
  return out;
}

/// The cases a run solves together with case `index` in lockstep lanes: up to `lanes` cases of
/// its excitation (the same record, level and incidence; other frames), adjacent in storage
/// order as the run's blocks of one excitation take them. `index` alone without lanes.
std::vector<parallel::WorkItem> lane_group(const CaseSpace& space, std::int64_t index, std::size_t lanes) {
  std::vector<parallel::WorkItem> group{{index, 0.0}};
  const std::int64_t excitation = space.excitation_of(index);
  for (std::int64_t j = index + 1; group.size() < lanes && j < space.size() && space.excitation_of(j) == excitation; ++j)
    group.push_back({j, 0.0});
  for (std::int64_t j = index - 1; group.size() < lanes && j >= 0 && space.excitation_of(j) == excitation; --j)
    group.push_back({j, 0.0});
  return group;
}

}  // namespace

double CostEstimate::total_cpu_s() const {
  if (unit_cpu_s.empty()) return std::nan("");
  const double mean = std::accumulate(unit_cpu_s.begin(), unit_cpu_s.end(), 0.0) / static_cast<double>(sampled());
  return static_cast<double>(population) * mean;
}

double CostEstimate::two_standard_errors_cpu_s() const {
  const auto k = static_cast<double>(sampled());
  if (k < 2.0) return std::nan("");
  const double mean = std::accumulate(unit_cpu_s.begin(), unit_cpu_s.end(), 0.0) / k;
  double squares = 0.0;
  for (const double x : unit_cpu_s) squares += (x - mean) * (x - mean);
  const double variance = squares / (k - 1.0);
  const double n = static_cast<double>(population);
  // Units sampled without replacement: the finite-population correction (1 − k/N).
  const double error_of_mean = std::sqrt(variance / k * std::max(0.0, 1.0 - k / n));
  return 2.0 * n * error_of_mean;
}

std::string CostEstimate::text() const {
  if (unit_cpu_s.empty()) return "no case could be timed: no cost estimate";
  const double total = total_cpu_s(), spread = two_standard_errors_cpu_s();
  const auto [lo, hi] = std::minmax_element(unit_cpu_s.begin(), unit_cpu_s.end());
  const char* unit = ida ? "IDA curves" : "cases";
  std::string range;
  if (sampled() == population)
    range = std::string("every one of the study's ") + unit + " timed";
  else if (std::isnan(spread))
    range = std::string("spread unknown: one ") + (ida ? "IDA curve" : "case") + " timed";
  else
    range = cpu_amount(std::max(0.0, total - spread)) + " to " + cpu_amount(total + spread) +
            " at two standard errors of the sample mean";
  char line[1024];
  std::snprintf(line, sizeof line,
                "cost estimate: about %s (%s; divide by the worker count): %lld sampled %s of %lld%s, spread over "
                "the study's hand-out order, took %.3g to %.3g s of CPU each (mean %.3g s)%s",
                cpu_amount(total).c_str(), range.c_str(), static_cast<long long>(sampled()), unit,
                static_cast<long long>(population),
                ida ? (" (run whole: " + std::to_string(runs.size()) + " runs at the intensities their searches reach)").c_str()
                : lanes > 1 ? (" (each solved in lanes with up to " + std::to_string(lanes - 1) +
                               " more cases of its excitation, as the run does: its share)").c_str()
                            : "",
                *lo, *hi, total / static_cast<double>(population),
                sampled() == population ? ""
                : ida ? "; a sample mean, not a bound: rare costly curves it misses are not in it"
                      : "; a sample mean, not a bound: rare costly cases it misses are not in it");
  return line;
}

std::vector<std::int64_t> sample_positions(std::int64_t population, std::int64_t n) {
  n = std::clamp<std::int64_t>(n, 0, population);
  int bits = 0;
  while ((std::int64_t{1} << bits) < n) ++bits;
  std::vector<std::int64_t> positions;
  for (std::int64_t k = 0; k < (std::int64_t{1} << bits); ++k) {
    const std::int64_t slot = reversed(k, bits);  // n-ths in bit-reversed order: halves, quarters, …
    if (slot < n) positions.push_back(slot * population / n + population / (2 * n));  // the middle of the slot-th n-th
  }
  return positions;
}

CostEstimate estimate_cost(const Study& study, const CaseSpace& space, RecordCache& records, std::int64_t sample,
                           double budget_cpu_s) {
  const CaseRunner runner(study, space, records);
  CostEstimate estimate;
  estimate.ida = space.ida_runs() > 0;
  estimate.population = estimate.ida ? space.curves() : space.size();
  const auto collapse = estimate.ida ? collapse_test(study) : ida::IdaCurves::CollapseTest{};
  // As the run solves them: a grid's or a plan's cases in lanes where it does (study_run.cpp's
  // in_lanes), each case then costing its share of its lane batch.
  const std::size_t lanes = !estimate.ida && study.run.lanes > 1 && lanes_take(study.solver) ? study.run.lanes : 1;
  estimate.lanes = lanes;
  const double begin_s = thread_cpu_s();
  for (const std::int64_t position : sample_positions(estimate.population, sample)) {
    const double unit_begin_s = thread_cpu_s();
    const std::size_t runs_before = estimate.runs.size();
    double share = 1.0;
    if (!estimate.ida) {
      const auto group = lane_group(space, space.handout_index(position), lanes);
      if (group.size() == 1) (void)runner.run(group.front());
      else (void)runner.run(std::span<const parallel::WorkItem>(group));
      estimate.runs.insert(estimate.runs.end(), group.begin(), group.end());
      share = 1.0 / static_cast<double>(group.size());
    } else {
      // A curve whole, as IdaCurves makes its runs: run k of curve c is case c · max_runs + k.
      ida::IdaSearch search(study.ida->search());
      for (std::optional<double> x = search.next(); x; x = search.next()) {
        const parallel::WorkItem item{position * static_cast<std::int64_t>(space.ida_runs()) + search.runs(), *x};
        search.add(*x, collapse(runner.run(item)));
        estimate.runs.push_back(item);
      }
    }
    estimate.unit_cpu_s.push_back(share * (thread_cpu_s() - unit_begin_s));
    estimate.unit_runs.push_back(estimate.runs.size() - runs_before);
    if (estimate.sampled() >= 2 && thread_cpu_s() - begin_s > budget_cpu_s) break;
  }
  return estimate;
}

}  // namespace pcrf::run
