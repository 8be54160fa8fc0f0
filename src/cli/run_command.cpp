// `pcrf run`: one case from the command line; the result record as JSON on stdout.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "cli/commands.hpp"
#include "cli/record_flags.hpp"
#include "cli/setting_flags.hpp"
#include "pcrf/io/output_file.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/model/parameters.hpp"
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
  FrameParameters frame;
  std::unique_ptr<SettingFlags<PhysicsOptions>> physics;
  std::unique_ptr<SettingFlags<SolverSettings>> solver;
  std::string history_file;
  double history_dt_s = 0.0;
  bool overwrite = false;  ///< replace an existing history file
};

/// The factor the record is scaled by: --scale, or --intensity over the record's measure.
double scale_factor(const RunOptions& o, const GroundMotion& motion) {
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
  if (spec.measure == IntensityMeasure::kSa)
    if (const auto problem = sa_period_problem(spec.period_s, motion.dt_s()); !problem.empty())
      throw UsageError("--period-s: " + problem + " (" + motion.name() + ")");
  if (const auto problem = measures_problem(motion); !problem.empty()) throw UsageError(motion.name() + ": " + problem);
  const double im = intensity_of(motion, spec);
  if (!(im > 0.0)) throw UsageError(motion.name() + ": its " + to_string(spec.measure) + " is 0: it cannot be scaled");
  return intensity_scale_factor(o.intensity, im);
}

GroundMotion load_motion(const RunOptions& o, double& factor) {
  const GroundMotion motion = o.record.load();
  factor = scale_factor(o, motion);
  try {
    return motion.scaled(factor);
  } catch (const std::invalid_argument& e) {  // a scale that overflows the record
    throw UsageError(e.what());
  }
}

/// Writes the history as CSV, one row per history row, a header of column names (their
/// units are in the names; README "pcrf run" lists them), by the one output rule
/// (io::OutputFile: never the record read, complete or not at all).
class CsvHistory {
 public:
  CsvHistory(const std::string& path, const std::string& record_file, bool overwrite)
      : file_(path, record_file.empty() ? std::vector<std::filesystem::path>{} : std::vector<std::filesystem::path>{record_file},
              overwrite),
        out_(file_.stream()) {
    const char* separator = "";
    for (const auto& c : history_columns()) {
      out_ << separator << c.name;
      separator = ",";
    }
    out_ << '\n';
  }
  void operator()(const HistorySample& s) {
    char value[32];
    const char* separator = "";
    for (const auto& c : history_columns()) {
      std::snprintf(value, sizeof value, "%.17g", s.*c.member);
      out_ << separator << value;
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
  const GroundMotion motion = load_motion(o, factor);
  const PhysicsOptions physics = o.physics->resolve();
  const SolverSettings solver = o.solver->resolve();
  Frame frame{};
  try {
    frame = make_frame(o.frame);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  std::unique_ptr<CsvHistory> csv;
  HistorySink sink;
  if (!o.history_file.empty()) {
    csv = std::make_unique<CsvHistory>(o.history_file, o.record.file, o.overwrite);
    sink = [&csv](const HistorySample& s) { (*csv)(s); };
  }
  CaseResult result;
  try {
    OutputRequest request;
    request.history_dt_s = o.history_dt_s;
    result = solve_case(frame, motion, physics, solver, request, sink);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (csv) csv->commit();
  JsonObject json;
  json.number("scale_factor", factor);
  add_to_json(json, result);
  std::cout << json.str() << std::endl;
}

/// --kappa … --pi-e-c and --h-m, --m-c-kg (older spelling --mc), from the parameter tables.
/// The older `--h` is gone: CLI11 2.4 refuses a one-letter long name beside `-h` (help).
void add_frame_flags(CLI::App* cmd, FrameParameters& frame) {
  const std::string group = "frame (default: the paper's basic model)";
  for (const auto& info : all_parameters())
    cmd->add_option(flag_name(info.name), frame.*info.member, std::string(info.long_name))
        ->capture_default_str()
        ->group(group);
  for (const auto& info : size_parameters()) {
    const std::string older = info.name == "m_c_kg" ? ",--mc" : "";
    cmd->add_option(flag_name(info.name) + older, frame.*info.member,
                    std::string(info.long_name) + " [" + std::string(info.units) + "]")
        ->capture_default_str()
        ->group(group);
  }
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Solve one case and print its result record as JSON");
  o->record.add_to(cmd, false, true);
  o->scale_flag = cmd->add_option("--scale", o->scale, "ground-motion scale factor [-]")->capture_default_str();
  o->intensity_flag = cmd->add_option("--intensity", o->intensity,
                                      "scale the record to this intensity of --measure (in its units: g or m/s)");
  o->measure = std::make_unique<SettingFlags<IntensitySpec>>(cmd, intensity_settings());
  add_frame_flags(cmd, o->frame);
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
