/// \file cube_query.hpp
/// \brief Post-processing of a result cube: selecting cases by coordinate values, the
/// `info` summary, long CSV export, and median / 16th / 84th percentile statistics.
#pragma once

#include <cstddef>
#include <functional>
#include <ostream>
#include <optional>
#include <cstdint>
#include <utility>
#include <string>
#include <vector>

#include "pcrf/cube/cube_reader.hpp"

namespace pcrf::cube {

/// "NAME=VALUE" on a coordinate (a dimension or an auxiliary coordinate such as
/// varied_parameter). Numbers match within a relative 1e-9.
struct Selector {
  std::string coordinate;
  std::string value;
};
/// \throws CubeError when the text is not NAME=VALUE.
Selector parse_selector(const std::string& text);

/// One flag per case (linear order): true when every selector matches.
/// \throws CubeError naming an unknown coordinate or a value that is not on it.
std::vector<bool> select_cases(const CubeLayout& layout, const std::vector<Selector>& selectors);

/// How complete a cube is as the layer that made it counts: `done` of `total` `unit` (an IDA
/// counts curves: the slots after a curve's end are no runs left to do), and the name shown
/// for the not-run status in place of "not_run" (empty: "not_run").
struct Completion {
  std::int64_t done = 0, total = 0;
  std::string unit = "cases";
  std::string not_run_label;
};

/// Axes, metrics, completion, counts by status, the messages counted by kind (one line per
/// kind with its count and first case, not one per case); `heading` (a line naming what the
/// cube holds, from the layer that made it) after the file name, when not empty; the
/// completion as `completion` says (default: cases with a status of all cases).
void print_info(const CubeReader& cube, const std::string& heading, std::ostream& out,
                const std::optional<Completion>& completion = std::nullopt);

/// The same as one JSON object, for scripts: dimensions with their values, auxiliary
/// coordinates, metrics and side variables with units and long names, status counts,
/// completion, case count, history groups, global attributes, messages by kind.
void print_info_json(const CubeReader& cube, std::ostream& out, const std::optional<Completion>& completion = std::nullopt);

/// Messages of the same kind (the same text once its numbers are set aside: "non-finite
/// state at t = 3.2 s" and "… t = 4.1 s" are one kind): the first case's text, its case,
/// and how many cases have one. In order of first appearance.
struct MessageKind {
  std::string text;
  std::int64_t first_case = 0;
  std::int64_t count = 0;
};
std::vector<MessageKind> message_kinds(const std::vector<std::pair<std::int64_t, std::string>>& notes);

/// A CSV field: the text, quoted (with doubled quotes) when it holds a comma, quote or newline.
std::string csv_field(const std::string& text);

/// A table whose first row is the header: aligned columns for people, or CSV.
void print_table(const std::vector<std::vector<std::string>>& rows, bool csv, std::ostream& out);

/// A stored history group as CSV: a header of its column names, one row per time.
/// \throws CubeError naming the group when it does not exist.
void export_history_csv(const CubeReader& cube, const std::string& name, std::ostream& out);

/// One row per selected case, handed to `row` as its fields after a first call with the
/// header: every coordinate but those in `leave_out` (its value's label), the status (its
/// name), and the named metrics or side variables (all of both when `metrics` is empty; a side
/// variable repeats over the dimensions it lacks) as the shortest text of each number, empty for
/// NaN. \throws CubeError naming an unknown metric, coordinate or value.
void export_rows(const CubeReader& cube, const std::vector<std::string>& metrics, const std::vector<Selector>& selectors,
                 const std::function<void(const std::vector<std::string>&)>& row,
                 const std::vector<std::string>& leave_out = {});

/// export_rows() as CSV: a header, then one line per selected case.
void export_csv(const CubeReader& cube, const std::vector<std::string>& metrics,
                const std::vector<Selector>& selectors, std::ostream& out,
                const std::vector<std::string>& leave_out = {});

/// Summary of a metric over the cases that share one value of each coordinate grouped by.
struct GroupStats {
  std::vector<std::string> key;  ///< the group's value of each coordinate grouped by, in their order
  std::size_t cases = 0;    ///< selected cases in the group
  std::size_t set_apart = 0;  ///< cases whose status is set apart (e.g. collapses): not in the values
  std::size_t unresolved = 0;  ///< cases whose status is PoolReport::unresolved: in neither
  std::size_t values = 0;   ///< finite values of the metric among the other cases
  double median = 0.0;
  double p16 = 0.0;
  double p84 = 0.0;
};

/// Which dimensions group_stats() pools over without remark, and where it lists the others;
/// which statuses it counts apart instead of summarizing their values.
struct PoolReport {
  std::vector<std::string> expected;         ///< e.g. the record axis: pooling over it is the point
  std::vector<std::string>* pooled = nullptr;  ///< receives "NAME (N values)" for every other pooled axis
  std::vector<std::int8_t> set_apart;        ///< e.g. collapses, whose metrics stop at the collapse
  std::vector<std::int8_t> unresolved;       ///< e.g. frames still moving at the end: counted in a column of their own
};

/// Groups the selected cases by the values of the coordinates `by` (one group per
/// combination present, in the order of the coordinates' positions) and summarizes `metric`
/// across the rest. \throws CubeError for an unknown coordinate or metric, or no `by`.
std::vector<GroupStats> group_stats(const CubeReader& cube, const std::vector<std::string>& by, const std::string& metric,
                                    const std::vector<Selector>& selectors, const PoolReport& pool = {});

/// A metric reduced over one dimension before the statistics: every combination of the
/// other coordinates gives one value, the largest, smallest or median of its values along
/// `dimension` (e.g. over `incidence_deg`: the response of the worst orientation, max, is a
/// RotD100 and the median a RotD50, as Boore 2010 defines them for ground motions). A
/// combination counts as set apart (a collapse) when its reduced value would be one: any
/// member for max, every member for min, more than half for median. Otherwise it counts as
/// unresolved when any member is (PoolReport::unresolved: still moving at its end, it could
/// have become anything, a collapse included), and only the rest are reduced.
struct Reduction {
  std::string dimension;
  std::string how;  ///< "max", "min" or "median"
};

/// \throws CubeError unless `how` is max, min or median (one line: "reduce with max, min or median, not 'x'").
void check_reduction(const std::string& how);

/// The reduction of `values` by `how` (max, min or median; NaN and infinities left out; NaN when none
/// is left): the one reduction of `cube stats --reduce-over` and `cube fragility --reduce-over`.
double reduce_values(std::vector<double> values, const std::string& how);

/// A reduction of values of which some are known only from below (right-censored: an IDA curve that
/// did not collapse up to its last safe intensity). `value` is exact when no censored value can
/// change it, else the reduction is itself censored at `value` (a lower bound): the reduction with
/// the bounds in place and the one with the censored values raised without limit are compared.
struct CensoredReduction {
  double value = 0.0;  ///< NaN when there is neither an observed nor a censored value
  bool censored = false;
};
CensoredReduction reduce_censored(const std::vector<double>& observed, const std::vector<double>& censored_from,
                                  const std::string& how);

/// group_stats() of `metric` reduced over `reduction.dimension` first (one coordinate in `by`). `metric` may also be a
/// side variable over that dimension (an IDA's collapse_intensity); `cases` then counts its
/// combinations. \throws CubeError when `by` is the reduced dimension, the variable does not
/// run over it, or `how` is not max, min or median.
std::vector<GroupStats> group_stats_reduced(const CubeReader& cube, const std::vector<std::string>& by, const std::string& metric,
                                            const std::vector<Selector>& selectors, const Reduction& reduction,
                                            const PoolReport& pool = {});

}  // namespace pcrf::cube
