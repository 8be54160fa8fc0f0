// Mapping of a study onto its result cube (see study_cube.hpp).
#include "pcrf/study/study_cube.hpp"

#include <chrono>
#include <ctime>
#include <type_traits>
#include <variant>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/study/cube_vocabulary.hpp"
#include "pcrf/study/result_row.hpp"
#include "pcrf/version.hpp"

namespace pcrf::study {
namespace {

using cube::Attribute;
using cube::Coordinate;
namespace names = vocabulary;

Coordinate numbers(std::string name, std::string dimension, std::string units, std::string long_name,
                   std::vector<double> values) {
  return number_coordinate(std::move(name), std::move(dimension), std::move(units), std::move(long_name), std::move(values));
}

Coordinate texts(std::string name, std::string dimension, std::string long_name, std::vector<std::string> values) {
  return text_coordinate(std::move(name), std::move(dimension), std::move(long_name), std::move(values));
}

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

/// The record axis (names, sources, titles, and with an intensity axis each record's
/// unscaled intensity) and the second axis, `scale` or `intensity`.
void add_record_and_level(const Study& study, const CaseSpace& space, RecordCache& records,
                          cube::CubeLayout& layout) {
  auto& coords = layout.coordinates;
  coords.push_back(texts(names::kRecord, names::kRecord, "ground motion record", space.record_names()));
  std::vector<std::string> sources, titles;
  for (std::size_t r = 0; r < study.records.size(); ++r) {
    sources.push_back(study.records[r].describe());
    titles.push_back(records.title(r));
  }
  coords.push_back(texts(names::kRecordSource, names::kRecord, "where the record comes from", sources));
  coords.push_back(texts(names::kRecordTitle, names::kRecord, "the record's own title (AT2 header)", titles));
  if (!study.intensity) {
    coords.push_back(numbers(names::kScale, names::kScale, "1", "factor applied to the record's accelerations", space.levels()));
    return;
  }
  const IntensitySpec& im = *study.intensity;
  const std::string units(intensity_units(im.measure));
  const std::string long_name = intensity_long_name(im.measure, im.period_s, im.damping);
  std::vector<double> unscaled;
  for (std::size_t r = 0; r < study.records.size(); ++r) unscaled.push_back(records.intensity(r, im));
  coords.push_back(numbers("record_" + to_string(im.measure), names::kRecord, units, "unscaled record's " + long_name, unscaled));
  if (study.ida) return;  // the intensities are the runs' own (ida_intensity)
  coords.push_back(numbers(names::kIntensity, names::kIntensity, units, long_name, space.levels()));
  cube::SideVariable factor{names::kScaleFactor, "1", "factor applied to the record's accelerations to reach the intensity",
                            {names::kRecord, names::kIntensity}, {}};
  for (std::size_t r = 0; r < study.records.size(); ++r)
    for (double level : space.levels()) factor.values.push_back(records.scale_factor(r, level, study.intensity));
  layout.side_variables.push_back(std::move(factor));
}

/// One attribute "<table>_<key>" per setting: numbers as float64, integers and flags as
/// int64 (flags 0/1), choices as text.
template <class Target>
void add_settings(std::vector<Attribute>& attributes, const SettingTable<Target>& table, const Target& values) {
  for (const auto& setting : table.settings) {
    const std::string name = std::string(table.name) + "_" + std::string(setting.key);
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, bool>)
            attributes.push_back({name, static_cast<std::int64_t>(v ? 1 : 0)});
          else
            attributes.push_back({name, v});
        },
        setting.get(values));
  }
}

/// An IDA's extra axis and variables: `ida_point` (the runs of a curve, in the order run),
/// each run's intensity and scale factor, and per curve (every axis but ida_point) the
/// collapse intensity, the last safe intensity and the number of runs.
void add_ida_variables(const Study& study, const CaseSpace& space, cube::CubeLayout& layout) {
  std::vector<double> points(space.ida_runs());
  for (std::size_t k = 0; k < points.size(); ++k) points[k] = static_cast<double>(k);
  Coordinate axis = numbers(names::kIdaPoint, names::kIdaPoint, "", "run of the IDA curve, in the order run", points);
  axis.is_index = true;
  layout.coordinates.push_back(std::move(axis));
  const IntensitySpec& im = *study.intensity;
  const std::string units(intensity_units(im.measure));
  std::vector<std::string> curve_axes(space.dimension_names().begin(), space.dimension_names().end() - 1);
  layout.side_variables.push_back({names::kCollapseIntensity, units,
                                   "lowest intensity found to collapse (NaN: none up to max_intensity, right-censored)",
                                   curve_axes, {}});
  layout.side_variables.push_back({names::kLastSafeIntensity, units, "highest safe intensity below the collapse", curve_axes, {}});
  layout.side_variables.push_back({names::kIdaRuns, "1", "runs of the curve so far", curve_axes, {}});
  if (study.solver.verdict_check) {
    layout.side_variables.push_back({names::kUnstableFrom, units,
                                     "lowest intensity of the curve whose verdict failed the perturbation test (NaN: none)",
                                     curve_axes, {}});
    layout.side_variables.push_back({names::kUnstableTo, units,
                                     "highest intensity of the curve whose verdict failed the perturbation test (NaN: none)",
                                     curve_axes, {}});
  }
}

std::vector<Attribute> global_attributes(const Study& study, const std::string& fingerprint) {
  std::vector<Attribute> a{
      {"Conventions", std::string("CF-1.8")},
      {"title", "pcrf study " + study.name},
      {"source", std::string("pcrf ") + kVersion},
      {names::kPcrfVersion, std::string(kVersion)},
      {"date_created", utc_now()},
      {names::kStudyName, study.name},
      {"study_description", study.description},
      {"study_file", study.file},
      {"study_text", study.text},
      {cube::kFingerprintName, fingerprint},
      {names::kPlan, std::string(study.plan->name())},
  };
  if (study.intensity) add_settings(a, intensity_settings(), *study.intensity);
  if (study.ida) add_settings(a, ida_settings(), *study.ida);
  add_settings(a, physics_settings(), study.physics);
  add_settings(a, solver_settings(), study.solver);
  a.push_back({"frame_h_m", study.base.h_m});
  a.push_back({"frame_m_c_kg", study.base.m_c_kg});
  a.push_back({"gravity_m_s2", kGravity_m_s2});
  for (const auto& info : all_parameters()) a.push_back({"base_" + std::string(info.name), study.base.*info.member});
  return a;
}

}  // namespace

cube::CubeLayout make_cube_layout(const Study& study, const CaseSpace& space, RecordCache& records,
                                  const std::string& fingerprint) {
  cube::CubeLayout layout;
  for (std::size_t d = 0; d < space.shape().size(); ++d)
    layout.dimensions.push_back({space.dimension_names()[d], space.shape()[d]});
  add_record_and_level(study, space, records, layout);
  for (auto& c : space.plan().coordinates()) layout.coordinates.push_back(std::move(c));
  layout.metrics = ResultColumns(study).variables();
  if (study.ida) add_ida_variables(study, space, layout);
  for (CaseStatus status : all_final_statuses())
    layout.status_flags.push_back({static_cast<std::int8_t>(status), std::string(status_name(status))});
  layout.attributes = global_attributes(study, fingerprint);
  return layout;
}

cube::HistoryTable make_history_table(const std::string& label, std::int64_t case_index, const Study& study,
                                      const CaseSpace& space, const std::vector<HistorySample>& samples) {
  cube::HistoryTable table;
  table.name = label;
  for (const auto& c : history_columns()) {
    table.columns.push_back({std::string(c.name), std::string(c.units), std::string(c.long_name)});
    std::vector<double> values;
    values.reserve(samples.size());
    for (const auto& s : samples) values.push_back(s.*c.member);
    table.values.push_back(std::move(values));
  }
  const CaseSpec spec = space.case_at(case_index);
  table.attributes = {{"case_index", static_cast<std::int64_t>(case_index)},
                      {names::kRecord, study.records[spec.record].name},
                      {space.dimension_names()[1], spec.level}};
  for (const auto& info : all_parameters()) table.attributes.push_back({std::string(info.name), spec.parameters.*info.member});
  return table;
}

}  // namespace pcrf::study
