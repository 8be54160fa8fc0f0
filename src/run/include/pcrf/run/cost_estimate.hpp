/// \file cost_estimate.hpp
/// \brief What a study will cost, measured before it runs (`pcrf study --check`): a sample
/// of its work, spread over the order the run hands it out, is run as the run would run it
/// and timed in CPU seconds of the thread that runs it, and the mean is scaled to the whole
/// study, with its standard error.
///
/// The unit of work is a case, or in an IDA a whole curve: every run its hunt-and-fill search
/// makes, at the intensities it reaches (the search is deterministic, so these are the runs
/// the study will make for that curve). Where the run solves a grid's or a plan's cases in
/// lockstep lanes (`[run] lanes`), a sampled case is solved with the cases of its excitation
/// that share its lane batch, and costs its share. The estimate is a sample mean, not a
/// bound: a study whose cost lies in a few cases the sample misses costs more.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pcrf/parallel/work_source.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/record_source.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;

struct CostEstimate {
  bool ida = false;                 ///< units are IDA curves (all their runs), not cases
  std::int64_t population = 0;      ///< units in the study: cases, or IDA curves
  std::vector<double> unit_cpu_s;   ///< CPU time of each sampled unit (in lanes: its share), in the order run [s]
  std::vector<parallel::WorkItem> runs;  ///< every case run, in order (an IDA's with their intensity; lane mates)
  std::vector<std::size_t> unit_runs;    ///< how many of `runs` each unit made, in order
  std::size_t lanes = 1;                 ///< lane batch width the sampled cases were solved in (1: alone)

  std::int64_t sampled() const { return static_cast<std::int64_t>(unit_cpu_s.size()); }
  /// population × the mean CPU time per sampled unit [CPU-seconds]; NaN when none was sampled.
  double total_cpu_s() const;
  /// Two standard errors of total_cpu_s (the sample's spread, with the finite-population
  /// correction: 0 when every unit was timed) [CPU-seconds]; NaN with fewer than two units.
  double two_standard_errors_cpu_s() const;
  /// One line: "cost estimate: about 2.1 CPU-hours (1.7 to 2.5 at two standard errors) …",
  /// how many units were timed, what each took, and what the estimate leaves out.
  std::string text() const;
};

/// The positions 0 … population − 1 a sample of `n` takes: the middle of each n-th of the
/// range, in an order whose every prefix is spread over the whole range too (the n-ths in
/// bit-reversed order), so a sample cut short by its budget is still spread.
std::vector<std::int64_t> sample_positions(std::int64_t population, std::int64_t n);

/// Runs up to `sample` units of the study at sample_positions over its hand-out order
/// (CaseSpace::handout_index, with their lane mates; an IDA: over its curves), one after
/// another in this thread,
/// stopping once `budget_cpu_s` CPU seconds have been spent (at least two units run when
/// the study has two). An IDA's curve runs every run its search makes, with the study's
/// collapse rule deciding each verdict.
CostEstimate estimate_cost(const Study& study, const CaseSpace& space, RecordCache& records, std::int64_t sample = 24,
                           double budget_cpu_s = 5.0);

}  // namespace pcrf::run
