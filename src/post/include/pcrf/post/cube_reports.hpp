/// \file cube_reports.hpp
/// \brief One function per cube command (`pcrf cube stats|fragility|sensitivity|p695`):
/// reads the cube, computes, and returns a Report (table.hpp) without printing. The command
/// line writes it as text, CSV or JSON; the Python module turns its tables into DataFrames.
///
/// Tables and fields (the JSON's keys; `columns` in the JSON describes every column):
/// - stats: fields file, metric, metric_units, by; table `groups` (stats_columns()).
/// - fragility: fields file, intensity_units, mce (and reduced_over, reduction when reduced); tables `frames` (fragility_columns())
///   and `points` (fragility_point_columns()).
/// - sensitivity: fields file, metric, by_record; table `indices` (sensitivity_columns()).
/// - p695: fields file, sdc, period_s, mu_t, ratings, group_mean_acmr, group_acmr10, group,
///   measure_problem; table `frames` (p695_columns()).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/post/cube_p695.hpp"
#include "pcrf/post/table.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::post {

/// A cube that cannot be read, as what it is to the user: bad input of its file ("FILE:
/// problem"). The command line and Python report every cube they open so.
UserError unreadable_cube(const std::string& file, const cube::CubeError& error);

/// How a reduction reduces when only its dimension is given: each command's worst. For a
/// response (stats of θ_max) the worst orientation is its maximum; for a capacity (the
/// fragility's collapse intensity) its minimum.
inline constexpr const char* kStatsReduction = "max";
inline constexpr const char* kFragilityReduction = "min";

struct StatsRequest {
  std::vector<std::string> by;  ///< coordinates to group by (at least one)
  std::string metric;
  std::vector<cube::Selector> where;
  /// When `reduction.dimension` is set, the metric is first reduced over it (group_stats_reduced:
  /// e.g. the worst incidence); `by` then names one coordinate.
  cube::Reduction reduction;
};
/// Median and 16th/84th percentiles of the metric across records per group; collapses are
/// counted apart. Warnings: the axes pooled over besides the records ("also pooled over …").
/// \throws cube::CubeError for an unknown coordinate, metric or value.
Report stats_report(const cube::CubeReader& cube, const StatsRequest& request);

struct FragilityRequest {
  std::vector<cube::Selector> where;
  std::optional<double> mce;  ///< MCE intensity: adds the collapse margin ratio column `cmr`
};
/// The lognormal collapse fragility of each frame and the data fitted (cube_fragility.hpp);
/// with `reduction` (an IDA cube), of each record's collapse intensity reduced over a
/// dimension first (fields reduced_over and reduction then name it).
Report fragility_report(const cube::CubeReader& cube, const FragilityRequest& request,
                        const cube::Reduction& reduction = {});

struct SensitivityRequest {
  std::string metric;  ///< a metric, or "collapse"
  std::vector<cube::Selector> where;
  bool by_record = false;
};
/// Sobol' indices of each parameter (cube_sensitivity.hpp). Warnings: base samples left out.
Report sensitivity_report(const cube::CubeReader& cube, const SensitivityRequest& request);

/// FEMA P-695 per frame and the group's verdict (cube_p695.hpp). Warning: the measure problem.
/// \throws UserError as cube_p695().
Report p695_report(const cube::CubeReader& cube, const std::vector<cube::Selector>& where, const P695Inputs& inputs);
/// The same from an assessment already made (the text report needs it too).
Report p695_report(const P695Report& result, const P695Inputs& inputs, const std::string& file);

/// \throws UserError at `mce` when it cannot be a fragility's MCE intensity (not positive).
void check_mce(const std::optional<double>& mce);

/// The reduction that --reduce-over `over` and --reduce `how` ask for (`how` empty:
/// `default_how`); none when `over` is empty. \throws UserError for a `how`
/// without `over` ("goes with --reduce-over DIMENSION") or other than max, min or median.
cube::Reduction reduction_of(const std::string& over, const std::string& how, const std::string& default_how);

/// The P-695 inputs from their text forms (the command line's --sdc, --period-s, --mu-t,
/// --ratings "B,B,C", empty: B,B,B by default, which the report then says; --s-ct counted or
/// lognormal), checked. \throws UserError naming the input.
P695Inputs p695_inputs(const std::string& sdc, double period_s, double mu_t, const std::string& ratings,
                       const std::string& s_ct = "counted");

/// The columns of each table, for --help and the README (units of cube-dependent columns
/// are left empty here: the JSON's `columns` carries them).
std::vector<Column> stats_columns(const std::vector<std::string>& by = {"BY"});
std::vector<Column> fragility_columns(bool with_mce = true);
std::vector<Column> fragility_point_columns();
std::vector<Column> sensitivity_columns();
std::vector<Column> p695_columns();

}  // namespace pcrf::post
