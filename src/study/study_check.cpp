// Up-front checks of a study (see study_check.hpp).
#include "pcrf/study/study_check.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "pcrf/hazard/hazard_file.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/study/fingerprint.hpp"
#include "pcrf/study/plan.hpp"
#include "study/stripe_selection.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::study {
namespace {

/// A warning (a UserError not thrown) into `warnings`, rendered as the study spells it; with
/// [run] warnings_as_errors it is thrown instead.
void warn(const Study& study, const UserError& warning, std::vector<std::string>& warnings) {
  if (study.run.warnings_as_errors) throw warning.followed_by(" ([run] warnings_as_errors)");
  warnings.push_back(warning.message(Dialect::kStudy));
}

/// "record \"NAME\": " before a problem of a study's record.
std::string record_text(const RecordSource& source) { return "record \"" + source.name + "\": "; }

/// The record of least intensity (an [intensity] study): the one scaled the most.
struct WeakestRecord {
  double im = std::numeric_limits<double>::infinity();
  std::string name;
};

void check_records(const Study& study, RecordCache& records, std::vector<std::string>& notes,
                   std::vector<std::string>& warnings, WeakestRecord& weakest) {
  for (std::size_t r = 0; r < study.records.size(); ++r) {
    const auto& source = study.records[r];
    try {
      records.get(r);  // loaded once, here, so that a bad record fails up front
      for (const auto& note : records.notes(r)) notes.push_back("record \"" + source.name + "\": " + note);
    } catch (const std::exception& e) {  // the study's key and line of the record, which the reader cannot know
      throw UserError(source.declared_at, "cannot load record \"" + source.name + "\" (" + source.describe() + "): " + e.what());
    }
    if (const auto problem = measures_problem(records.get(r)); !problem.empty())
      throw UserError(source.declared_at, record_text(source) + problem);
    if (auto problem = record_warning(study, r, records.get(r)); !problem.empty())
      warn(study, UserError(source.declared_at, std::move(problem)), warnings);
    for (const auto& line : records.warnings(r)) warn(study, UserError(source.declared_at, record_text(source) + line), warnings);
    if (!study.intensity) continue;
    if (component_measure(study.intensity->measure) == IntensityMeasure::kSa)
      if (const auto problem = sa_period_problem(study.intensity->period_s, records.get(r).dt_s()); !problem.empty())
        throw UserError(study.where("intensity.period_s"), problem + " (record \"" + source.name + "\")");
    double im = 0.0;
    try {
      im = records.intensity(r, *study.intensity);
    } catch (const std::invalid_argument& e) {  // the study's key and line, which the measure cannot know
      if (study.intensity->normalise != SetNormalisation::kNone)  // normalise = "p695" over records that are not pairs
        throw UserError(study.where("intensity.normalise"), e.what());
      throw UserError(source.declared_at, record_text(source) + e.what());
    }
    if (!(im > 0.0) || !std::isfinite(im))
      throw UserError(source.declared_at, "record \"" + source.name + "\" has " + to_string(study.intensity->measure) +
                                              " = " + number_text(im) + ": it cannot be scaled to an intensity");
    if (im < weakest.im) weakest = {im, source.name};
  }
}

/// Hazard-consistent stripes: the curve's own warnings (post::hazard_warnings), and a
/// warning when its intensities ask a record for a scale factor above
/// hazard::kMaxHazardScaleFactor (a curve in other units than its header's, or records that
/// are not the site's).
void check_hazard_stripes(const Study& study, const WeakestRecord& weakest, std::vector<std::string>& warnings) {
  if (!study.hazard_stripes) return;
  for (const UserError& w : study.hazard_stripes->warnings) warn(study, w, warnings);
  if (study.selection) return;  // the selection's factors, within its scale limits, are what run
  if (study.levels.empty() || !(weakest.im > 0.0) || !std::isfinite(weakest.im)) return;
  const double strongest = *std::max_element(study.levels.begin(), study.levels.end());
  const double factor = strongest / weakest.im;
  if (factor <= hazard::kMaxHazardScaleFactor) return;
  char text[64];
  std::snprintf(text, sizeof text, "%.4g", factor);
  const auto where = study.given_at.find("intensity.return_periods_yr");
  warn(study,
       UserError(where == study.given_at.end() ? Where{{}, study.file, 0} : where->second,
                 "the hazard curve " + study.hazard_stripes->hazard + " asks record \"" + weakest.name + "\" (" +
                     to_string(study.intensity->measure) + " " + number_text(weakest.im) + ") for a scale factor of " +
                     text + " at " + number_text(strongest) + ", above " + number_text(hazard::kMaxHazardScaleFactor) +
                     ": are the curve's intensities in the units its header names?"),
       warnings);
}

/// [selection]: every selected record, scaled by its selection factor, has the stripe's
/// intensity by the study's own measure (within kConditioningRelativeTolerance): the library's
/// Sa (interpolated to the target's conditioning period) and the engine's measure of the
/// record agree, so that the cube's `intensity` is what each case feels and cube risk's rate
/// is the study's.
void check_selection(const Study& study, RecordCache& records) {
  if (!study.selection) return;
  const auto& stripes = study.selection->stripes;
  for (std::size_t k = 0; k < stripes.size(); ++k)
    for (std::size_t slot = 0; slot < stripes[k].records.size(); ++slot) {
      const std::size_t r = stripes[k].records[slot];
      const double scaled = stripes[k].scales[slot] * records.intensity(r, *study.intensity);
      const double level = study.levels.at(k);
      if (std::abs(scaled / level - 1.0) <= kConditioningRelativeTolerance) continue;
      throw UserError(study.where("selection.targets"),
                      "record \"" + study.records[r].name + "\" of the stripe at " + selection_number_text(level) + " (target " +
                          stripes[k].target + ") scaled by " + number_text(stripes[k].scales[slot]) + " has " +
                          to_string(study.intensity->measure) + " " + selection_number_text(scaled) +
                          ", not the stripe's intensity: compute the library at the study's period_s (" +
                          number_text(study.intensity->period_s) + " s among its periods) and damping, from the same records");
    }
}

std::string describe(const Study& study, const SceneSpec& frame) {
  std::ostringstream out;
  if (frame.model != study.model) out << "model " << frame.model->name << ": ";
  const auto& parameters = frame.model->parameters;
  for (std::size_t k = 0; k < parameters.size(); ++k)
    if (parameters[k].axis) out << (out.tellp() == 0 ? "" : ", ") << parameters[k].name << '=' << frame.values[k];
  return out.str();
}

/// Counts the frames the model cannot represent, and checks the initial state of the rest.
/// Each frame is built once, one at a time.
void check_frames(const Study& study, const CaseSpace& space, CheckedStudy& checked) {
  const std::int64_t cases_per_frame = space.size() / space.distinct_frames();
  space.for_each_frame([&](const SceneSpec& spec) {
    const Scene* frame = nullptr;
    std::shared_ptr<PreparedFrame> prepared;  // owns *frame
    try {
      auto made = spec.make();
      frame = made.get();
      prepared = prepare_scene(std::move(made), study.physics);
    } catch (const std::invalid_argument& e) {  // impossible geometry, or outside the model's domain
      if (checked.invalid_frames++ == 0) checked.first_invalid = describe(study, spec) + ": " + e.what();
      checked.invalid_cases += cases_per_frame;
      return;
    }
    try {
      check_initial_state(*frame, study.physics);
    } catch (const UserError& e) {  // the study's file and line, and which frame
      throw UserError(study.where("physics." + last_key_name(e.where().keys)), e.problem(Dialect::kStudy) +
                                                                               " (frame " + describe(study, spec) + ")");
    }
  });
}

/// Incidences that all look like radians (radians_problem): a warning, or an error with
/// warnings_as_errors.
void check_incidence(const Study& study, std::vector<std::string>& warnings) {
  const auto given = study.given_at.find("axes.incidence_deg");
  if (given == study.given_at.end()) return;
  if (auto problem = radians_problem(study.incidence_deg); !problem.empty())
    warn(study, UserError(given->second, std::move(problem), {"incidence_deg"}), warnings);
}

}  // namespace

std::string record_warning(const Study& study, std::size_t r, const GroundMotion& motion) {
  const auto& source = study.records[r];
  if (!source.file) return {};
  const bool at2 = source.file->format == RecordFormat::kAt2;
  const auto p = record_plausibility(motion, at2 ? AccelUnit::kG : source.file->unit);
  if (p.problem.empty()) return {};
  std::string line = "record \"" + source.name + "\" (" + source.describe() + "): " + p.problem + ": " + p.hint;
  if (p.likely_unit) line += at2 ? " (an .AT2 file is read in g)" : " give units = \"" + to_string(*p.likely_unit) + "\"";
  return line;
}

CheckedStudy check_study(const Study& study, const CaseSpace& space, RecordCache& records, FrameCheck frames) {
  CheckedStudy checked;
  WeakestRecord weakest;
  check_records(study, records, checked.notes, checked.warnings, weakest);
  check_hazard_stripes(study, weakest, checked.warnings);
  check_selection(study, records);
  check_incidence(study, checked.warnings);
  // A displaced start must lie below every frame's overturning angle: an input error, found
  // before the run. Otherwise the worker that runs a frame's cases builds it, once per case.
  if (frames == FrameCheck::kEveryFrame || study.physics.theta0_rad != 0.0) {
    check_frames(study, space, checked);
    checked.frames_checked = true;
  }
  for (const auto& h : study.histories) {
    const std::int64_t index = space.resolve(h);
    // The history's rows bounded up front (solve_case checks it again when the case runs).
    const GroundMotion& motion = records.get(space.case_at(index).record);
    try {
      check_history_interval(longest_case_s(motion.duration_s(), study.physics), h.dt_s, motion.dt_s());
    } catch (const UserError& e) {
      fail_history(h, "dt_s: " + e.problem(Dialect::kStudy));
    }
    for (std::size_t k = 0; k < checked.history_cases.size(); ++k)
      if (checked.history_cases[k] == index)
        fail_history(h, "names the same case as \"" + study.histories[k].label + "\"");
    checked.history_cases.push_back(index);
  }
  checked.fingerprint = study_fingerprint(study, space, records);
  return checked;
}

}  // namespace pcrf::study
