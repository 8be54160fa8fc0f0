// `pcrf run`: one case from the command line; the result record as JSON on stdout.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "cli/commands.hpp"
#include "pcrf/model/frame.hpp"
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
  std::string criterion = "physical";
  std::string integrator;  // empty: the preset's
  SolverSettings solver;  // explicit values, applied over the preset where given
  std::vector<const CLI::Option*> solver_flags;  // which of them the user gave
  PhysicsOptions physics;
  std::string history_file;
  std::string preset = "balanced";
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
    if (!out_) throw UsageError("cannot write history file '" + path + "'");
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

/// The preset, then every solver option the user gave explicitly.
SolverSettings settings_from(const RunOptions& o) {
  SolverSettings s = preset_settings(o.preset);
  auto given = [&](const char* name) {
    for (const CLI::Option* opt : o.solver_flags)
      if (opt->check_name(name) && opt->count() > 0) return true;
    return false;
  };
  if (!o.integrator.empty()) s.integrator = parse_integrator(o.integrator);
  if (given("--rtol")) s.rtol = o.solver.rtol;
  if (given("--atol-theta")) s.atol_theta_rad = o.solver.atol_theta_rad;
  if (given("--atol-omega")) s.atol_omega_rad_s = o.solver.atol_omega_rad_s;
  if (given("--max-step")) s.max_step_s = o.solver.max_step_s;
  if (given("--fixed-step")) s.fixed_step_s = o.solver.fixed_step_s;
  if (given("--stop-at-samples")) s.stop_at_samples = o.solver.stop_at_samples;
  if (given("--time-limit")) s.wall_time_limit_s = o.solver.wall_time_limit_s;
  return s;
}

void run(const RunOptions& o) {
  const GroundMotion motion = load_motion(o);
  Frame frame{};
  PhysicsOptions physics = o.physics;
  SolverSettings solver;
  try {
    frame = make_frame(o.frame);
    physics.uplift = parse_uplift_criterion(o.criterion);
    solver = settings_from(o);
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
  FrameParameters& f = o->frame;
  cmd->add_option("--kappa", f.kappa, "κ = m_b/m_c [-]")->capture_default_str();
  cmd->add_option("--lambda", f.lambda, "λ = L/h [-]")->capture_default_str();
  cmd->add_option("--tan-alpha", f.tan_alpha, "tan α = b/h [-]")->capture_default_str();
  cmd->add_option("--lambda-h", f.lambda_h, "λ_h = h_b/h [-]")->capture_default_str();
  cmd->add_option("--pi-sigma-b", f.pi_sigma_b, "Π_σb = P_b0/(m_c g) [-]")->capture_default_str();
  cmd->add_option("--pi-sigma-c", f.pi_sigma_c, "Π_σc = P_c0/(m_c g) [-]")->capture_default_str();
  cmd->add_option("--pi-e-b", f.pi_e_b, "Π_Eb = E A_bs/(m_c g) [-]")->capture_default_str();
  cmd->add_option("--pi-e-c", f.pi_e_c, "Π_Ec = E A_cs/(m_c g) [-]")->capture_default_str();
  cmd->add_option("--h", f.h_m, "half column height h [m]")->capture_default_str();
  cmd->add_option("--mc", f.m_c_kg, "column mass m_c [kg]")->capture_default_str();
  cmd->add_option("--criterion", o->criterion, "uplift criterion: physical or paper")->capture_default_str();
  cmd->add_option("--fracture-strain", o->physics.fracture_strain, "tendon fracture strain [-]")->capture_default_str();
  cmd->add_option("--tail", o->physics.tail_s, "free vibration after the record [s]")->capture_default_str();
  cmd->add_option("--zeno-time", o->physics.zeno_time_s, "return-to-rest time scale [s]")->capture_default_str();
  cmd->add_option("--preset", o->preset, "accuracy preset: fast, balanced, reference (explicit solver options override it)")
      ->capture_default_str();
  cmd->add_option("--integrator", o->integrator, "arkode-erk5, arkode-erk8, cvode-adams, cvode-bdf, fixed-rk4");
  auto& flags = o->solver_flags;
  flags.push_back(cmd->add_option("--rtol", o->solver.rtol, "relative tolerance [-]"));
  flags.push_back(cmd->add_option("--atol-theta", o->solver.atol_theta_rad, "absolute tolerance on θ₁ [rad]"));
  flags.push_back(cmd->add_option("--atol-omega", o->solver.atol_omega_rad_s, "absolute tolerance on θ̇₁ [rad/s]"));
  flags.push_back(cmd->add_option("--max-step", o->solver.max_step_s, "largest step [s], 0 = no limit"));
  flags.push_back(cmd->add_option("--fixed-step", o->solver.fixed_step_s, "step of fixed-rk4 [s], 0 = the record's dt"));
  flags.push_back(cmd->add_option("--stop-at-samples", o->solver.stop_at_samples,
                                  "stop the integrator at every record sample (kinks of the interpolated record)"));
  flags.push_back(cmd->add_option("--time-limit", o->solver.wall_time_limit_s, "wall-time limit of the case [s], 0 = none"));
  cmd->add_option("--history", o->history_file, "write the time history to this CSV file");
  cmd->callback([o]() { run(*o); });
}

}  // namespace pcrf::cli
