/// \file cube_vocabulary.hpp
/// \brief The names a study gives its cube (coordinates and attributes), written once and
/// used both where the cube is made (study_cube.cpp) and where it is queried (the CLI's
/// defaults for `pcrf cube`). The cube layer itself knows none of them.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/status_book.hpp"
#include "pcrf/record/pulses.hpp"

namespace pcrf::schema {

// Coordinates.
inline constexpr const char* kRecord = "record";
inline constexpr const char* kRecordSource = "record_source";
inline constexpr const char* kScale = "scale";
inline constexpr const char* kIntensity = "intensity";
inline constexpr const char* kScaleFactor = "scale_factor";
/// Hazard-consistent stripes: each intensity's return period on the site's hazard curve [yr].
inline constexpr const char* kReturnPeriod = "return_period_yr";
inline constexpr const char* kRecordTitle = "record_title";
inline constexpr const char* kIdaPoint = "ida_point";
inline constexpr const char* kIdaIntensity = "ida_intensity";
inline constexpr const char* kCollapseIntensity = "collapse_intensity";
inline constexpr const char* kLastSafeIntensity = "last_safe_intensity";
inline constexpr const char* kIdaRuns = "ida_runs";
inline constexpr const char* kCurveState = "curve_state";
inline constexpr const char* kUnresolvedRuns = "unresolved_runs";
inline constexpr const char* kUnstableFrom = "unstable_from_intensity";
inline constexpr const char* kUnstableTo = "unstable_to_intensity";
inline constexpr const char* kPulseShape = "pulse_shape";
inline constexpr const char* kPulsePeriod = "pulse_period_s";
inline constexpr const char* kPulseLike = "record_pulse_like";  ///< [outputs] record_pulses
inline constexpr const char* kPulseMethod = "record_pulse_method";
inline constexpr const char* kPulseAzimuth = "record_pulse_azimuth_deg";
inline constexpr const char* kFrequencyParameter = "frame_frequency_parameter_rad_s";
inline constexpr const char* kUpliftThreshold = "frame_uplift_threshold_g";
inline constexpr const char* kOmegaOverP = "omega_p_over_p";
inline constexpr const char* kCase = "case";
inline constexpr const char* kCaseLabel = "case_label";
inline constexpr const char* kVariedParameter = "varied_parameter";
inline constexpr const char* kSaltelliBlock = "saltelli_block";
inline constexpr const char* kSaltelliSample = "saltelli_sample";
inline constexpr const char* kIncidenceDeg = "incidence_deg";
inline constexpr const char* kFrameAzimuthDeg = "frame_azimuth_deg";
/// The scene model of each frame: a `case` coordinate where a list plan mixes models, else a
/// global attribute (when the study's model is not pcrf).
inline constexpr const char* kSceneModel = "scene_model";
// Global attributes.
inline constexpr const char* kStudyName = "study_name";
inline constexpr const char* kPlan = "plan";
inline constexpr const char* kPcrfVersion = "pcrf_version";
/// The hazard file of hazard-consistent stripes, as the study gives it.
inline constexpr const char* kIntensityHazard = "intensity_hazard";

/// A name of the cube's schema and the role code knows it by ("IDA_INTENSITY" for
/// kIdaIntensity): Python reads pcrf._names.IDA_INTENSITY, never "ida_intensity".
struct CubeName {
  std::string_view role;
  std::string_view name;
};
/// Every coordinate and global attribute named above, the cube's status variable
/// (cube::kStatusName) and the attributes of the tail and the IDA's collapse set: the names
/// post-processing, Python and figures read instead of spelling them.
const std::vector<CubeName>& cube_names();

/// The attribute holding a study setting: "TABLE_KEY" ("physics_tail_s", "intensity_period_s").
std::string setting_attribute(std::string_view table, std::string_view key);
/// The attribute of a frame parameter off the plan's axes: "frame_NAME" (its one value).
std::string frame_attribute(std::string_view parameter);
/// The attribute of a parameter on an axis: "base_NAME" (its value at the base point).
std::string base_attribute(std::string_view parameter);

/// A pulse parameter a study may put on its axes ([axes] pulse_period_s, …): the key,
/// "pulse_" + the pulse's own key (record/pulses.hpp), and the shapes that take it (empty:
/// every shape). Each axis a study gives is a coordinate of that name along `record`.
struct PulseAxisKey {
  std::string_view axis_key;
  std::string_view pulse_key;
  std::vector<PulseShape> only;
};
const std::vector<PulseAxisKey>& pulse_axis_keys();

/// Every coordinate a study of pulses may have along `record`: kPulseShape, then the pulse
/// axis keys (pcrf.open_cube(pulse_dimensions=True) unstacks `record` into those present).
std::vector<std::string> pulse_coordinates();

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
/// What `cube info` reports as complete: cases, or an IDA's curves (not_run), with the IDA
/// slots no run filled named "no_run_slot" rather than not_run (after a curve's end they are
/// empty by design). \throws cube::CubeError when the cube cannot be read.
cube::Completion completion(const cube::CubeReader& cube);
inline constexpr const char* kCollapses = "collapses";

/// How an IDA cube's curves ended, from its `curve_state` (CurveState codes, pcrf/metrics/curve_state.hpp): how many
/// are bracketed to the resolution, censored at max_intensity, unbracketed (max_runs ran out),
/// and not finished (not run, or still running). Empty (total 0) for other cubes and for IDA
/// cubes written before `curve_state`.
struct CurveStates {
  std::int64_t bracketed = 0, censored = 0, unbracketed = 0, unresolved = 0, unfinished = 0, total = 0;
};
/// \throws cube::CubeError when the cube cannot be read.
CurveStates curve_states(const cube::CubeReader& cube);
/// "132 IDA curves: 120 bracketed to the resolution, 10 right-censored at max_intensity,
/// 2 unbracketed (max_runs ran out)"; empty when the cube has no curve states.
std::string curve_states_text(const CurveStates& states);
/// The statuses of a case without a verdict (gives_no_verdict): a frame still moving
/// (rocking_at_end: its tail ended before the frame came to rest), or outside the model
/// (ground_free_fall, invalid_frame). Statistics count them apart, never as safe values.
std::vector<std::int8_t> unresolved_statuses();
/// Cases (IDA: runs) of `status` still rocking at their end (rocking_at_end).
std::int64_t unresolved_count(std::span<const std::int8_t> status);
/// The same of statuses counted by code (cube::count_statuses, or a writer's).
std::int64_t unresolved_count(const cube::StatusCounts& counts);
/// The attribute holding a study's physics.tail_s (inf: until rest).
inline constexpr const char* kTailAttribute = "physics_tail_s";
/// A cube's physics.tail_s [s] (inf: until rest; NaN: the cube does not say).
double tail_s_of(const cube::CubeLayout& layout);
/// "N cases ended still rocking …: unresolved, …" (how `what` treats them) and the setting
/// that helps (pcrf::tail_advice), or "" when none.
std::string unresolved_note(std::int64_t count, const std::string& unit, const std::string& what, double tail_s);
/// "N cases ended where the model no longer applies (2 ground_free_fall, …): no verdict, …"
/// (is_outside_model; `what`: how they are treated), or "" when none.
std::string outside_model_note(const cube::StatusCounts& counts, const std::string& unit, const std::string& what);

/// Collapse statuses that occur in `counts` but are not in `collapse` (an IDA's [ida]
/// collapse, comma-separated), with how many cases ended in each.
std::vector<std::pair<std::string, std::int64_t>> uncounted_collapses(const cube::StatusCounts& counts,
                                                                      const std::string& collapse);
/// One line per uncounted status: "413 runs ended in tendon_fracture, which this study does
/// not count as collapse ([ida] collapse = overturned)".
std::vector<std::string> uncounted_collapse_notes(const cube::StatusCounts& counts, const std::string& collapse);
/// What a run's or a cube's statuses say that its answers cannot show, one line each: the
/// unresolved cases and those outside the model (an IDA, `ida_collapse` set to its [ida]
/// collapse: "runs", which stop their curves as unresolved; else "cases", treated as
/// `treatment` says; `tail_s` picks the advice, tail_advice), and for an IDA each
/// collapse status that occurred but its collapse set leaves out. Empty when there is nothing
/// to say. The end of `pcrf study` and the `pcrf cube` commands print the same lines.
/// From statuses counted by code (a writer's, kept as they are stored: no pass over the cases).
std::vector<std::string> verdict_notes(const cube::StatusCounts& counts, const std::optional<std::string>& ida_collapse,
                                       const std::string& treatment, double tail_s);
/// The same of every case's status (one pass to count them).
std::vector<std::string> verdict_notes(const std::vector<std::int8_t>& status, const std::optional<std::string>& ida_collapse,
                                       const std::string& treatment, double tail_s);
/// The attribute holding an IDA cube's collapse set (the [ida] table's `collapse`).
inline constexpr const char* kIdaCollapseAttribute = "ida_collapse";

}  // namespace pcrf::schema
