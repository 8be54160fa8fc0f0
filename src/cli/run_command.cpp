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
#include "pcrf/api/one_case.hpp"
#include "pcrf/io/output_file.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/user_error.hpp"

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

/// What the frame feels: the station's components at the frame's incidence, scaled by
/// --scale or to --intensity of the in-plane horizontal motion.
ScaledExcitation load_excitation(const RunOptions& o) {
  std::vector<std::string> notes;
  const StationRecord station = o.record.load_station(notes);
  for (const auto& note : notes) std::cerr << "pcrf run: note: " << note << '\n';
  for (const auto& line : api::implausible_records(o.record, station)) std::cerr << "pcrf run: warning: " << line << '\n';
  if (o.incidence_deg)
    if (const auto problem = radians_problem({*o.incidence_deg}); !problem.empty())
      std::cerr << "pcrf run: warning: " << UserError("incidence_deg", problem, {"incidence_deg"}).message(Dialect::kFlag) << '\n';
  api::Scaling scaling;
  scaling.scale = o.scale;
  scaling.scale_given = o.scale_flag->count() > 0;
  if (o.intensity_flag->count() > 0) scaling.intensity = o.intensity;
  scaling.measure = o.measure->given();
  return api::scaled_excitation(station, o.incidence_deg, scaling);
}

/// Writes the history as CSV, one row per history row, a header of column names (their
/// units are in the names; docs/commands/run.md lists them), by the one output rule
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
  const ScaledExcitation scaled = load_excitation(o);
  const PhysicsOptions physics = o.physics->resolve();
  const SolverSettings solver = o.solver->resolve();
  std::unique_ptr<Scene> scene = o.scene.scene();
  std::unique_ptr<CsvHistory> csv;
  HistorySink sink;
  if (!o.history_file.empty()) {
    std::vector<std::filesystem::path> records;  // the files read: every component's
    if (!o.record.file.empty()) records.emplace_back(o.record.file);
    for (const std::string& file : o.record.component_files)
      if (!file.empty()) records.emplace_back(file);
    csv = std::make_unique<CsvHistory>(o.history_file, records, o.overwrite);
    sink = [&csv](const HistorySample& s) { (*csv)(s); };
  }
  const CaseResult result =
      api::solve_one_case(std::move(scene), physics, scaled.view(), solver, o.history_dt_s, sink);
  if (csv) csv->commit();
  std::cout << api::case_json(scaled.factor(), result, physics).str() << std::endl;
  if (const auto note = api::verdict_note(result, physics); !note.empty()) std::cerr << "pcrf run: note: " << note << '\n';
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Solve one case and print its result record as JSON");
  o->record.add_to(cmd, false, true);
  o->record.add_components_to(cmd, /*record_flags=*/false);
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
