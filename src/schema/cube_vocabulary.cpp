// The study's names in its cube (see cube_vocabulary.hpp).
#include "pcrf/schema/cube_vocabulary.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/metrics/curve_state.hpp"
#include "pcrf/metrics/unresolved.hpp"

namespace pcrf::schema {

const std::vector<CubeName>& cube_names() {
  static const std::vector<CubeName> names{
      {"RECORD", kRecord}, {"RECORD_SOURCE", kRecordSource}, {"SCALE", kScale}, {"INTENSITY", kIntensity},
      {"SCALE_FACTOR", kScaleFactor}, {"RETURN_PERIOD", kReturnPeriod}, {"RECORD_TITLE", kRecordTitle},
      {"IDA_POINT", kIdaPoint}, {"IDA_INTENSITY", kIdaIntensity}, {"COLLAPSE_INTENSITY", kCollapseIntensity},
      {"LAST_SAFE_INTENSITY", kLastSafeIntensity}, {"IDA_RUNS", kIdaRuns}, {"CURVE_STATE", kCurveState},
      {"UNRESOLVED_RUNS", kUnresolvedRuns}, {"UNSTABLE_FROM", kUnstableFrom}, {"UNSTABLE_TO", kUnstableTo},
      {"PULSE_SHAPE", kPulseShape}, {"PULSE_PERIOD", kPulsePeriod}, {"PULSE_LIKE", kPulseLike},
      {"PULSE_METHOD", kPulseMethod}, {"PULSE_AZIMUTH", kPulseAzimuth}, {"FREQUENCY_PARAMETER", kFrequencyParameter},
      {"UPLIFT_THRESHOLD", kUpliftThreshold}, {"OMEGA_OVER_P", kOmegaOverP}, {"CASE", kCase},
      {"CASE_LABEL", kCaseLabel}, {"VARIED_PARAMETER", kVariedParameter}, {"SALTELLI_BLOCK", kSaltelliBlock},
      {"SALTELLI_SAMPLE", kSaltelliSample}, {"INCIDENCE_DEG", kIncidenceDeg}, {"FRAME_AZIMUTH_DEG", kFrameAzimuthDeg},
      {"SCENE_MODEL", kSceneModel}, {"STUDY_NAME", kStudyName}, {"PLAN", kPlan}, {"PCRF_VERSION", kPcrfVersion},
      {"INTENSITY_HAZARD", kIntensityHazard}, {"TAIL_ATTRIBUTE", kTailAttribute},
      {"IDA_COLLAPSE_ATTRIBUTE", kIdaCollapseAttribute}, {"STATUS", cube::kStatusName},
      {"FINGERPRINT", cube::kFingerprintName}, {"SHARD", cube::kShardName}};
  return names;
}

std::string setting_attribute(std::string_view table, std::string_view key) {
  return std::string(table) + "_" + std::string(key);
}

std::string frame_attribute(std::string_view parameter) { return "frame_" + std::string(parameter); }

std::string base_attribute(std::string_view parameter) { return "base_" + std::string(parameter); }

const std::vector<PulseAxisKey>& pulse_axis_keys() {
  static const std::vector<PulseAxisKey> keys{{kPulsePeriod, "period_s", {}},
                                              {"pulse_amplitude_g", "amplitude_g", {}},
                                              {"pulse_cycles", "cycles", {PulseShape::kCycles}},
                                              {"pulse_gamma", "gamma", {PulseShape::kMavroeidis}},
                                              {"pulse_nu_deg", "nu_deg", {PulseShape::kMavroeidis}}};
  return keys;
}

std::vector<std::string> pulse_coordinates() {
  std::vector<std::string> names{kPulseShape};
  for (const auto& k : pulse_axis_keys()) names.emplace_back(k.axis_key);
  return names;
}

std::string info_heading(const cube::CubeLayout& layout) {
  return "study: " + layout.text_attribute(kStudyName) + " (plan " + layout.text_attribute(kPlan) + "), pcrf " +
         layout.text_attribute(kPcrfVersion) + ", fingerprint " + layout.text_attribute(cube::kFingerprintName);
}

std::vector<cube::Selector> stats_selectors(const cube::CubeLayout& layout, const std::string& by,
                                            std::vector<cube::Selector> selectors) {
  const cube::Coordinate* group_by = layout.find_coordinate(by);
  const bool sweep = layout.find_coordinate(kVariedParameter) != nullptr && group_by != nullptr &&
                     group_by->dimension == kCase && by != kVariedParameter && by != kCaseLabel && by != kCase;
  const bool varied_given = std::any_of(selectors.begin(), selectors.end(),
                                        [](const cube::Selector& s) { return s.coordinate == kVariedParameter; });
  if (sweep && !varied_given) selectors.push_back({kVariedParameter, by});
  return selectors;
}

std::vector<std::string> record_text_coordinates() { return {kRecordSource, kRecordTitle}; }

std::vector<std::string> expected_pooling() { return {kRecord}; }

std::vector<std::int8_t> collapse_statuses() {
  std::vector<std::int8_t> codes;
  for (CaseStatus s : all_final_statuses())
    if (is_collapse(s)) codes.push_back(static_cast<std::int8_t>(s));
  return codes;
}

std::vector<std::int8_t> unresolved_statuses() {
  std::vector<std::int8_t> codes;
  for (CaseStatus s : all_final_statuses())
    if (gives_no_verdict(s)) codes.push_back(static_cast<std::int8_t>(s));
  return codes;
}

std::int64_t unresolved_count(std::span<const std::int8_t> status) { return unresolved_count(cube::count_statuses(status)); }

std::int64_t unresolved_count(const cube::StatusCounts& counts) {
  std::int64_t n = 0;
  for (int code = -128; code < 128; ++code)
    if (cube::count_of(counts, static_cast<std::int8_t>(code)) > 0 && code != cube::kStatusNotRun &&
        is_unresolved(static_cast<CaseStatus>(code)))
      n += cube::count_of(counts, static_cast<std::int8_t>(code));
  return n;
}

double tail_s_of(const cube::CubeLayout& layout) {
  for (const auto& a : layout.attributes)
    if (a.name == kTailAttribute)
      if (const double* v = std::get_if<double>(&a.value)) return *v;
  return std::nan("");
}

std::string unresolved_note(std::int64_t count, const std::string& unit, const std::string& what, double tail_s) {
  if (count == 0) return {};
  return std::to_string(count) + " " + unit + " ended with the frame still rocking (rocking_at_end: the tail ended "
         "first): unresolved, " + what + "; " + tail_advice(tail_s);
}

std::string outside_model_note(const cube::StatusCounts& of_code, const std::string& unit, const std::string& what) {
  std::string counts;
  std::int64_t total = 0;
  for (CaseStatus s : all_final_statuses()) {
    if (!is_outside_model(s)) continue;
    const auto n = cube::count_of(of_code, static_cast<std::int8_t>(s));
    if (n == 0) continue;
    total += n;
    counts += (counts.empty() ? "" : ", ") + std::to_string(n) + " " + std::string(status_name(s));
  }
  if (total == 0) return {};
  return std::to_string(total) + " " + unit + " ended where the model no longer applies (" + counts + "): no verdict, " +
         what;
}

std::vector<std::pair<std::string, std::int64_t>> uncounted_collapses(const cube::StatusCounts& counts,
                                                                      const std::string& collapse) {
  std::vector<std::pair<std::string, std::int64_t>> result;
  const std::string listed = "," + collapse + ",";
  for (CaseStatus s : all_final_statuses()) {
    if (!is_collapse(s)) continue;
    const std::string name(status_name(s));
    if (listed.find("," + name + ",") != std::string::npos) continue;
    const auto n = cube::count_of(counts, static_cast<std::int8_t>(s));
    if (n > 0) result.emplace_back(name, n);
  }
  return result;
}

std::vector<std::string> uncounted_collapse_notes(const cube::StatusCounts& counts, const std::string& collapse) {
  std::vector<std::string> notes;
  for (const auto& [name, n] : uncounted_collapses(counts, collapse))
    notes.push_back(std::to_string(n) + (n == 1 ? " run" : " runs") + " ended in " + name +
                    ", which this study does not count as collapse ([ida] collapse = \"" + collapse +
                    "\"): its curves call them safe");
  return notes;
}

std::vector<std::string> verdict_notes(const std::vector<std::int8_t>& status, const std::optional<std::string>& ida_collapse,
                                       const std::string& treatment, double tail_s) {
  return verdict_notes(cube::count_statuses(status), ida_collapse, treatment, tail_s);
}

std::vector<std::string> verdict_notes(const cube::StatusCounts& status, const std::optional<std::string>& ida_collapse,
                                       const std::string& treatment, double tail_s) {
  std::vector<std::string> notes;
  const std::string unit = ida_collapse ? "runs" : "cases";
  const std::string ida_treatment = "never safe: each stops its curve's hunt, and a curve whose lowest stopping run is "
                                    "one is unresolved (no collapse intensity; bounded at its last safe run)";
  const std::string note = unresolved_note(unresolved_count(status), unit, ida_collapse ? ida_treatment : treatment, tail_s);
  if (!note.empty()) notes.push_back(note);
  if (auto line = outside_model_note(status, unit, ida_collapse ? ida_treatment : treatment); !line.empty())
    notes.push_back(std::move(line));
  if (ida_collapse)
    for (auto& line : uncounted_collapse_notes(status, *ida_collapse)) notes.push_back(std::move(line));
  return notes;
}

NotRun not_run(const cube::CubeReader& cube) {
  NotRun result;
  if (cube.layout().find_side_variable(kIdaRuns) != nullptr) {
    result.unit = "curves";
    for (double runs : cube.read_side(kIdaRuns)) {
      ++result.total;
      result.count += runs > 0.0 ? 0 : 1;  // NaN: no part ran it
    }
    return result;
  }
  result.unit = "cases";
  for (auto s : cube.read_status()) {
    ++result.total;
    result.count += s == cube::kStatusNotRun ? 1 : 0;
  }
  return result;
}

cube::Completion completion(const cube::CubeReader& cube) {
  const NotRun missing = not_run(cube);
  cube::Completion c{missing.total - missing.count, missing.total, missing.unit, ""};
  if (missing.unit == "curves") c.not_run_label = "no_run_slot";
  return c;
}

CurveStates curve_states(const cube::CubeReader& cube) {
  CurveStates states;
  if (cube.layout().find_side_variable(kCurveState) == nullptr) return states;
  for (double code : cube.read_side(kCurveState)) {
    ++states.total;
    if (code == static_cast<double>(CurveState::kBracketed)) ++states.bracketed;
    else if (code == static_cast<double>(CurveState::kCensored)) ++states.censored;
    else if (code == static_cast<double>(CurveState::kUnbracketed)) ++states.unbracketed;
    else if (code == static_cast<double>(CurveState::kUnresolved)) ++states.unresolved;
    else ++states.unfinished;  // NaN
  }
  return states;
}

std::string curve_states_text(const CurveStates& states) {
  if (states.total == 0) return "";
  std::string text = std::to_string(states.total) + " IDA curves: " + std::to_string(states.bracketed) +
                     " bracketed to the resolution, " + std::to_string(states.censored) +
                     " right-censored at max_intensity, " + std::to_string(states.unbracketed) +
                     " unbracketed (max_runs ran out)";
  if (states.unresolved > 0)
    text += ", " + std::to_string(states.unresolved) +
            " unresolved (a run without a verdict ended the hunt: no collapse intensity, safe only up to the last safe run)";
  if (states.unfinished > 0) text += ", " + std::to_string(states.unfinished) + " not finished";
  return text;
}

}  // namespace pcrf::schema
