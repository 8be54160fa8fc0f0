/// \file cube_vocabulary.hpp
/// \brief The names a study gives its cube (coordinates and attributes), written once and
/// used both where the cube is made (study_cube.cpp) and where it is queried (the CLI's
/// defaults for `pcrf cube`). The cube layer itself knows none of them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"

namespace pcrf::study::vocabulary {

// Coordinates.
inline constexpr const char* kRecord = "record";
inline constexpr const char* kRecordSource = "record_source";
inline constexpr const char* kScale = "scale";
inline constexpr const char* kIntensity = "intensity";
inline constexpr const char* kScaleFactor = "scale_factor";
inline constexpr const char* kRecordTitle = "record_title";
inline constexpr const char* kIdaPoint = "ida_point";
inline constexpr const char* kIdaIntensity = "ida_intensity";
inline constexpr const char* kCollapseIntensity = "collapse_intensity";
inline constexpr const char* kLastSafeIntensity = "last_safe_intensity";
inline constexpr const char* kIdaRuns = "ida_runs";
inline constexpr const char* kUnstableFrom = "unstable_from_intensity";
inline constexpr const char* kUnstableTo = "unstable_to_intensity";
inline constexpr const char* kCase = "case";
inline constexpr const char* kCaseLabel = "case_label";
inline constexpr const char* kVariedParameter = "varied_parameter";
inline constexpr const char* kSaltelliBlock = "saltelli_block";
inline constexpr const char* kSaltelliSample = "saltelli_sample";
// Global attributes.
inline constexpr const char* kStudyName = "study_name";
inline constexpr const char* kPlan = "plan";
inline constexpr const char* kPcrfVersion = "pcrf_version";

/// "study: NAME (plan P), pcrf V, fingerprint F", for `pcrf cube info`.
std::string info_heading(const cube::CubeLayout& layout);

/// The selectors `pcrf cube stats --by BY` uses: in a one-at-a-time cube, grouping by a
/// parameter keeps that parameter's sweep only (varied_parameter = BY), unless the user
/// selected a sweep already.
std::vector<cube::Selector> stats_selectors(const cube::CubeLayout& layout, const std::string& by,
                                            std::vector<cube::Selector> selectors);

/// The long texts of each record (where it comes from, its own title): `pcrf cube export
/// --no-record-text` leaves them out.
std::vector<std::string> record_text_coordinates();

/// Axes that statistics pool over by design (records): not reported as pooled.
std::vector<std::string> expected_pooling();

/// The statuses that are collapses (tendon fracture, overturned): their metrics stop at the
/// collapse, so statistics count them apart (`collapses`) rather than mixing them in.
std::vector<std::int8_t> collapse_statuses();

/// What of a cube was never run (a run stopped early, a merge of some shards only): cases
/// with no status, or in an IDA cube curves with no run (the points after a curve's end are
/// not run by design and not counted).
struct NotRun {
  std::int64_t count = 0;
  std::int64_t total = 0;
  std::string unit;  ///< "cases" or "curves"
};
/// \throws cube::CubeError when the cube cannot be read.
NotRun not_run(const cube::CubeReader& cube);
inline constexpr const char* kCollapses = "collapses";

}  // namespace pcrf::study::vocabulary
