// The study's names in its cube (see cube_vocabulary.hpp).
#include "pcrf/study/cube_vocabulary.hpp"

#include <algorithm>

#include "pcrf/metrics/case_result.hpp"

namespace pcrf::study::vocabulary {

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

}  // namespace pcrf::study::vocabulary
