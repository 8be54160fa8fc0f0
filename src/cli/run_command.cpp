// `pcrf run`: one case from the command line; the result record as JSON on stdout.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "cli/commands.hpp"
#include "cli/frame_flags.hpp"
#include "cli/record_flags.hpp"
#include "cli/setting_flags.hpp"
#include "pcrf/io/output_file.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace pcrf::cli {
namespace {

struct RunOptions {
  RecordFlags record;
  double scale = 1.0;
  CLI::Option* scale_flag = nullptr;
  double intensity = 0.0;  ///< with --measure: the target intensity, in the measure's units
  CLI::Option* intensity_flag = nullptr;
  std::unique_ptr<SettingFlags<IntensitySpec>> measure;
  SceneFlags scene;
  std::unique_ptr<SettingFlags<PhysicsOptions>> physics;
  std::unique_ptr<SettingFlags<SolverSettings>> solver;
  std::string history_file;
  double history_dt_s = 0.0;
  bool overwrite = false;  ///< replace an existing history file
  std::optional<double> incidence_deg;  ///< the frame's plane [deg from north]; needs both horizontals
};

/// The factor the record is scaled by: --scale, or --intensity over the record's measure.
double scale_factor(const RunOptions& o, const StationRecord& station) {
  const GroundMotion& motion = station.h1;
  const auto measure_flags = o.measure->given();
  const bool by_intensity = o.intensity_flag->count() > 0;
  if (!by_intensity) {
    if (!measure_flags.empty()) throw UsageError("--measure, --period-s and --damping go with --intensity VALUE");
    return o.scale;
  }
  if (o.scale_flag->count() > 0) throw UsageError("give either --scale or --intensity, not both");
  if (!(o.intensity > 0.0)) throw UsageError("--intensity must be positive");
  const IntensitySpec spec = o.measure->resolve();
  if (const auto problem = intensity_spec_problem(spec); !problem.empty()) throw UsageError("--period-s: " + problem);
  if (spec.normalise != SetNormalisation::kNone)
    throw UsageError("--normalise applies to a study's record set, not to one record: scale it with --scale");
  if (component_measure(spec.measure) == IntensityMeasure::kSa)
    if (const auto problem = sa_period_problem(spec.period_s, motion.dt_s()); !problem.empty())
      throw UsageError("--period-s: " + problem + " (" + motion.name() + ")");
  if (const auto problem = measures_problem(motion); !problem.empty()) throw UsageError(motion.name() + ": " + problem);
  const double im = station_intensity(station, o.incidence_deg, spec);
  if (!(im > 0.0)) throw UsageError(motion.name() + ": its " + to_string(spec.measure) + " is 0: it cannot be scaled");
  return intensity_scale_factor(o.intensity, im);
}

/// What the frame feels: the station's components at the frame's incidence, scaled by
/// --scale or to --intensity of the in-plane horizontal motion.
std::unique_ptr<FrameExcitation> load_excitation(const RunOptions& o, double& factor) {
  std::vector<std::string> notes;
  const StationRecord station = o.record.load_station(notes);
  for (const auto& note : notes) std::cerr << "pcrf run: note: " << note << '\n';
  for (const auto& line : implausible_records(o.record, station)) std::cerr << "pcrf run: warning: " << line << '\n';
  try {
    factor = scale_factor(o, station);
    return std::make_unique<FrameExcitation>(station, o.incidence_deg, factor);
  } catch (const std::invalid_argument& e) {  // an incidence without a pair, a scale that overflows
    throw UsageError(e.what());
  }
}

/// Writes the history as CSV, one row per history row, a header of column names (their
/// units are in the names; README "pcrf run" lists them), by the one output rule
/// (io::OutputFile: never the record read, complete or not at all).
class CsvHistory {
 public:
  CsvHistory(const std::string& path, const std::vector<std::filesystem::path>& records, bool overwrite)
      : file_(path, records, overwrite),
        out_(file_.stream()) {
    const char* separator = "";
    for (const auto& c : history_columns()) {
      out_ << separator << c.name;
      separator = ",";
    }
    out_ << '\n';
  }
  void operator()(const HistorySample& s) {
    const char* separator = "";
    for (const auto& c : history_columns()) {
      out_ << separator << number_text(s.*c.member);
      separator = ",";
    }
    out_ << '\n';
  }
  void commit() { file_.commit(); }

 private:
  io::OutputFile file_;
  std::ostream& out_;
};

void run(const RunOptions& o) {
  double factor = 1.0;
  const auto excitation = load_excitation(o, factor);
  const PhysicsOptions physics = o.physics->resolve();
  const SolverSettings solver = o.solver->resolve();
  std::unique_ptr<Scene> scene = o.scene.scene();
  std::unique_ptr<CsvHistory> csv;
  HistorySink sink;
  if (!o.history_file.empty()) {
    std::vector<std::filesystem::path> records;  // the files read: every component's
    for (const std::string* file : {&o.record.file, &o.record.file_h2, &o.record.file_up})
      if (!file->empty()) records.emplace_back(*file);
    csv = std::make_unique<CsvHistory>(o.history_file, records, o.overwrite);
    sink = [&csv](const HistorySample& s) { (*csv)(s); };
  }
  CaseResult result;
  try {
    OutputRequest request;
    request.history_dt_s = o.history_dt_s;
    const auto prepared = prepare_scene(std::move(scene), physics);
    result = solve_case(*prepared, excitation->view(), solver, request, sink);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (csv) csv->commit();
  JsonObject json;
  json.number("scale_factor", factor);
  add_to_json(json, result);
  std::cout << json.str() << std::endl;
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Solve one case and print its result record as JSON");
  o->record.add_to(cmd, false, true);
  o->record.add_components_to(cmd, "--record-h2", "--record-up");
  cmd->add_option("--incidence-deg", o->incidence_deg,
                  "azimuth of the frame's plane [deg from north]: the pair is projected on it (needs --record-h2)")
      ->group("record");
  o->scale_flag = cmd->add_option("--scale", o->scale, "ground-motion scale factor [-]")->capture_default_str();
  o->intensity_flag = cmd->add_option("--intensity", o->intensity,
                                      "scale the record to this intensity of --measure (in its units: g or m/s)");
  o->measure = std::make_unique<SettingFlags<IntensitySpec>>(cmd, intensity_settings());
  o->scene.add_to(cmd);
  o->physics = std::make_unique<SettingFlags<PhysicsOptions>>(cmd, physics_settings());
  o->solver = std::make_unique<SettingFlags<SolverSettings>>(cmd, solver_settings());
  auto* history = cmd->add_option("--history", o->history_file, "write the time history to this CSV file");
  cmd->add_option("--history-dt-s", o->history_dt_s,
                  "history output interval [s] (default: the record's dt); events are always added")
      ->needs(history)
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--overwrite", o->overwrite, "replace an existing --history file")->needs(history);
  cmd->callback([o]() { run(*o); });
}

}  // namespace pcrf::cli
