// Up-front checks of a study (see study_check.hpp).
#include "pcrf/study/study_check.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "pcrf/number_text.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/study/fingerprint.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::study {
namespace {

void check_records(const Study& study, RecordCache& records, std::vector<std::string>& notes,
                   std::vector<std::string>& warnings) {
  for (std::size_t r = 0; r < study.records.size(); ++r) {
    const auto& source = study.records[r];
    try {
      records.get(r);  // loaded once, here, so that a bad record fails up front
      for (const auto& note : records.notes(r)) notes.push_back("record \"" + source.name + "\": " + note);
    } catch (const std::exception& e) {
      throw UserError(source.declared_at + ": records: cannot load record \"" + source.name + "\" (" +
                       source.describe() + "): " + e.what());
    }
    if (const auto problem = measures_problem(records.get(r)); !problem.empty())
      throw UserError(source.declared_at + ": records: record \"" + source.name + "\": " + problem);
    std::vector<std::string> found;
    if (auto warning = record_warning(study, r, records.get(r)); !warning.empty()) found.push_back(std::move(warning));
    for (const auto& line : records.warnings(r))
      found.push_back(source.declared_at + ": records: record \"" + source.name + "\": " + line);
    for (auto& warning : found) {
      if (study.run.warnings_as_errors) throw UserError(warning + " ([run] warnings_as_errors)");
      warnings.push_back(std::move(warning));
    }
    if (!study.intensity) continue;
    if (component_measure(study.intensity->measure) == IntensityMeasure::kSa)
      if (const auto problem = sa_period_problem(study.intensity->period_s, records.get(r).dt_s()); !problem.empty()) {
        const auto line = study.setting_lines.find("intensity.period_s");
        throw UserError((line != study.setting_lines.end() ? line->second : study.file) + ": intensity.period_s: " + problem +
                         " (record \"" + source.name + "\")");
      }
    double im = 0.0;
    try {
      im = records.intensity(r, *study.intensity);
    } catch (const std::invalid_argument& e) {
      if (study.intensity->normalise != SetNormalisation::kNone) {  // normalise = "p695" over records that are not pairs
        const auto line = study.setting_lines.find("intensity.normalise");
        throw UserError((line != study.setting_lines.end() ? line->second : study.file) + ": intensity.normalise: " + e.what());
      }
      throw UserError(source.declared_at + ": records: record \"" + source.name + "\": " + e.what());
    }
    if (!(im > 0.0) || !std::isfinite(im))
      throw UserError(source.declared_at + ": records: record \"" + source.name + "\" has " +
                       to_string(study.intensity->measure) + " = " + number_text(im) +
                       ": it cannot be scaled to an intensity");
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
/// Each frame is built once.
void check_frames(const Study& study, const CaseSpace& space, CheckedStudy& checked) {
  const auto frames = space.frames();
  const std::int64_t cases_per_frame = space.size() / static_cast<std::int64_t>(frames.size());
  for (const auto& spec : frames) {
    const Scene* frame = nullptr;
    std::shared_ptr<PreparedFrame> prepared;  // owns *frame
    try {
      auto made = spec.make();
      frame = made.get();
      prepared = prepare_scene(std::move(made), study.physics);
    } catch (const std::invalid_argument& e) {  // impossible geometry, or outside the model's domain
      if (checked.invalid_frames++ == 0) checked.first_invalid = describe(study, spec) + ": " + e.what();
      checked.invalid_cases += cases_per_frame;
      continue;
    }
    try {
      check_initial_state(*frame, study.physics);
    } catch (const std::invalid_argument& e) {
      const auto line = study.setting_lines.find("physics.theta0_rad");
      throw UserError((line != study.setting_lines.end() ? line->second : study.file) + ": physics." + e.what() +
                       " (frame " + describe(study, spec) + ")");
    }
  }
}

/// Incidences that all look like radians (radians_warning): a warning, or an error with
/// warnings_as_errors.
void check_incidence(const Study& study, std::vector<std::string>& warnings) {
  const auto line = study.setting_lines.find("axes.incidence_deg");
  if (line == study.setting_lines.end()) return;
  auto warning = radians_warning(line->second + ": axes.incidence_deg", study.incidence_deg);
  if (warning.empty()) return;
  if (study.run.warnings_as_errors) throw UserError(warning + " ([run] warnings_as_errors)");
  warnings.push_back(std::move(warning));
}

}  // namespace

std::string record_warning(const Study& study, std::size_t r, const GroundMotion& motion) {
  const auto& source = study.records[r];
  if (!source.file) return {};
  const bool at2 = source.file->format == RecordFormat::kAt2;
  const auto p = record_plausibility(motion, at2 ? AccelUnit::kG : source.file->unit);
  if (p.problem.empty()) return {};
  std::string line = source.declared_at + ": records: record \"" + source.name + "\" (" + source.describe() +
                     "): " + p.problem + ": " + p.hint;
  if (p.likely_unit) line += at2 ? " (an .AT2 file is read in g)" : " give units = \"" + to_string(*p.likely_unit) + "\"";
  return line;
}

CheckedStudy check_study(const Study& study, const CaseSpace& space, RecordCache& records, FrameCheck frames) {
  CheckedStudy checked;
  check_records(study, records, checked.notes, checked.warnings);
  check_incidence(study, checked.warnings);
  // A displaced start must lie below every frame's overturning angle: an input error, found
  // before the run. Otherwise the worker that runs a frame's cases builds it, once per case.
  if (frames == FrameCheck::kEveryFrame || study.physics.theta0_rad != 0.0) {
    check_frames(study, space, checked);
    checked.frames_checked = true;
  }
  for (const auto& h : study.histories) {
    const std::int64_t index = space.resolve(h);
    for (std::size_t k = 0; k < checked.history_cases.size(); ++k)
      if (checked.history_cases[k] == index)
        throw UserError(h.declared_at + ": outputs.histories \"" + h.label + "\": names the same case as \"" +
                         study.histories[k].label + "\"");
    checked.history_cases.push_back(index);
  }
  checked.fingerprint = study_fingerprint(study, space, records);
  return checked;
}

}  // namespace pcrf::study
