// `pcrf run`: one case from the command line; the result record as JSON on stdout.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "cli/commands.hpp"
#include "cli/setting_flags.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace pcrf::cli {
namespace {

struct RunOptions {
  std::string record_file;
  std::string format;  // empty: from the extension
  std::string units = "g";
  double dt_s = 0.0;
  std::string synthetic;
  double scale = 1.0;
  FrameParameters frame;
  std::unique_ptr<SettingFlags<PhysicsOptions>> physics;
  std::unique_ptr<SettingFlags<SolverSettings>> solver;
  std::string history_file;
};

GroundMotion load_motion(const RunOptions& o) {
  if (o.record_file.empty() == o.synthetic.empty())
    throw UsageError("give exactly one of --record FILE or --synthetic SPEC");
  try {
    if (!o.synthetic.empty()) return make_synthetic(o.synthetic).scaled(o.scale);
    RecordFileSpec spec;
    spec.path = o.record_file;
    spec.format = o.format.empty() ? guess_record_format(spec.path) : parse_record_format(o.format);
    spec.unit = parse_accel_unit(o.units);
    spec.dt_s = o.dt_s;
    if (spec.format == RecordFormat::kOneColumn && !(o.dt_s > 0))
      throw UsageError("--dt is required (and > 0) for a one-column record");
    return read_record(spec).scaled(o.scale);
  } catch (const RecordError& e) {
    throw UsageError(e.what());
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

/// Writes the history as CSV, one row per sample, header with units.
class CsvHistory {
 public:
  explicit CsvHistory(const std::string& path) : out_(path) {
    if (!out_) throw UsageError(path + ": cannot create the history file: " + std::strerror(errno));
    out_ << "t_s,theta1_rad,omega1_rad_s,theta2_rad,theta3_rad,strain_column_left,"
            "strain_column_right,strain_beam,ground_accel_m_s2\n";
  }
  void operator()(const HistorySample& s) {
    char line[512];
    std::snprintf(line, sizeof line, "%.10g,%.12g,%.12g,%.12g,%.12g,%.10g,%.10g,%.10g,%.10g\n", s.t_s,
                  s.theta1_rad, s.omega1_rad_s, s.theta2_rad, s.theta3_rad, s.strain_column_left,
                  s.strain_column_right, s.strain_beam, s.ground_accel_m_s2);
    out_ << line;
  }

 private:
  std::ofstream out_;
};

void run(const RunOptions& o) {
  const GroundMotion motion = load_motion(o);
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
    csv = std::make_unique<CsvHistory>(o.history_file);
    sink = [&csv](const HistorySample& s) { (*csv)(s); };
  }
  CaseResult result;
  try {
    result = solve_case(frame, motion, physics, solver, OutputRequest{}, sink);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  std::cout << to_json(result) << std::endl;
}

/// --kappa … --pi-e-c and --h-m, --m-c-kg (older spellings --h, --mc), from the parameter tables.
void add_frame_flags(CLI::App* cmd, FrameParameters& frame) {
  const std::string group = "frame (default: the paper's basic model)";
  for (const auto& info : all_parameters())
    cmd->add_option(flag_name(info.name), frame.*info.member, std::string(info.long_name))
        ->capture_default_str()
        ->group(group);
  for (const auto& info : size_parameters()) {
    const std::string older = info.name == "h_m" ? ",--h" : ",--mc";
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
  cmd->add_option("--record", o->record_file, "ground-motion file (.AT2, two-column or one-column text)");
  cmd->add_option("--format", o->format, "record format: at2, two-column, one-column (default: from extension)");
  cmd->add_option("--units", o->units, "acceleration units of a text record: g, m/s2, cm/s2")->capture_default_str();
  cmd->add_option("--dt", o->dt_s, "sample interval of a one-column record [s]");
  cmd->add_option("--synthetic", o->synthetic,
                  "synthetic motion, e.g. 'sine:amplitude_g=1.5,period_s=0.5,cycles=2' or "
                  "'stochastic:seed=3,pga_g=1.2,duration_s=20'");
  cmd->add_option("--scale", o->scale, "ground-motion scale factor [-]")->capture_default_str();
  add_frame_flags(cmd, o->frame);
  o->physics = std::make_unique<SettingFlags<PhysicsOptions>>(cmd, physics_settings());
  o->solver = std::make_unique<SettingFlags<SolverSettings>>(cmd, solver_settings());
  cmd->add_option("--history", o->history_file, "write the time history to this CSV file");
  cmd->callback([o]() { run(*o); });
}

}  // namespace pcrf::cli
