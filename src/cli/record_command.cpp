// `pcrf record FILE`: what a record is, its intensity measures and its header metadata, as
// one JSON object.
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <vector>

#include "cli/commands.hpp"
#include "cli/record_flags.hpp"
#include "pcrf/json.hpp"
#include "pcrf/record/intensity.hpp"

namespace pcrf::cli {
namespace {

struct RecordArguments {
  RecordFlags record;
  std::vector<double> periods_s;
  double damping = 0.05;
};

void describe(const RecordArguments& args) {
  if (!(args.damping >= 0.0 && args.damping < 1.0)) throw UsageError("--damping must be in [0, 1)");
  for (double t : args.periods_s)
    if (const auto problem = sa_period_problem(t, 0.0); !problem.empty()) throw UsageError("--period: " + problem);
  const GroundMotion motion = args.record.load();
  if (const auto problem = measures_problem(motion); !problem.empty()) throw UsageError(motion.name() + ": " + problem);
  for (double t : args.periods_s)
    if (const auto problem = sa_period_problem(t, motion.dt_s()); !problem.empty())
      throw UsageError("--period: " + problem + " (" + motion.name() + ")");
  RecordMetadata meta;
  try {
    meta = read_metadata(args.record.spec());
  } catch (const RecordError& e) {
    throw UsageError(e.what());
  }
  const auto peak = peak_acceleration(motion);
  std::vector<double> sa_g;
  for (double t : args.periods_s) sa_g.push_back(spectral_acceleration_g(motion, t, args.damping));
  JsonObject json;
  json.text("name", motion.name())
      .integer("npts", static_cast<long long>(motion.size()))
      .number("dt_s", motion.dt_s())
      .number("duration_s", motion.duration_s())
      .number("pga_g", peak.pga_g)
      .number("t_pga_s", peak.t_pga_s)
      .number("pgv_m_s", peak_velocity_m_s(motion))
      .number("pgd_m", peak_displacement_m(motion))
      .number("arias_intensity_m_s", arias_intensity_m_s(motion))
      .number("significant_duration_s", significant_duration_s(motion))
      .number("damping", args.damping)
      .numbers("periods_s", args.periods_s)
      .numbers("sa_g", sa_g);
  for (const auto& [key, value] : {std::pair{"title", meta.title}, std::pair{"event", meta.event},
                                   std::pair{"station", meta.station}, std::pair{"component", meta.component},
                                   std::pair{"rsn", meta.rsn}})
    if (!value.empty()) json.text(key, value);
  std::cout << json.str() << std::endl;
}

}  // namespace

void add_record_command(CLI::App& app) {
  auto args = std::make_shared<RecordArguments>();
  auto* cmd = app.add_subcommand("record", "Intensity measures and header metadata of a record, as one JSON object");
  args->record.add_to(cmd, true, false);
  cmd->add_option("--period", args->periods_s, "oscillator period for Sa [s] (repeatable)");
  cmd->add_option("--damping", args->damping, "damping ratio of the oscillator [-]")->capture_default_str();
  cmd->callback([args] { describe(*args); });
}

}  // namespace pcrf::cli
