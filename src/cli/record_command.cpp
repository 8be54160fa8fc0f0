// `pcrf record FILE`: what a record is, its intensity measures and its header metadata, as
// one JSON object.
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/record_flags.hpp"
#include "pcrf/json.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/rotd.hpp"

namespace pcrf::cli {
namespace {

struct RecordArguments {
  RecordFlags record;
  std::vector<double> periods_s;
  double damping = 0.05;
  std::string pair_file;            ///< the second horizontal component, for RotD
  std::optional<double> az1_deg;    ///< azimuths, when the headers do not state them
  std::optional<double> az2_deg;
};

RecordMetadata metadata_of(const RecordFileSpec& spec) {
  try {
    return read_metadata(spec);
  } catch (const RecordError& e) {
    throw UsageError(e.what());
  }
}

/// The measures of one component, and what its file says about itself.
/// \throws UsageError for values that overflow the measures or a period below 2·dt.
JsonObject measures(const GroundMotion& motion, const RecordMetadata& meta, const RecordArguments& args) {
  if (const auto problem = measures_problem(motion); !problem.empty()) throw UsageError(motion.name() + ": " + problem);
  for (double t : args.periods_s)
    if (const auto problem = sa_period_problem(t, motion.dt_s()); !problem.empty())
      throw UsageError("--period: " + problem + " (" + motion.name() + ")");
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
  return json;
}

/// A component's azimuth: given, or stated by its header's component name.
double azimuth(const std::optional<double>& given, const RecordMetadata& meta, const GroundMotion& motion,
               const char* flag) {
  if (given) return *given;
  if (const auto stated = azimuth_of_component(meta.component)) return *stated;
  throw UsageError("the azimuth of '" + motion.name() + "' is not stated by its header (component '" + meta.component +
                   "'): give " + flag);
}

/// RotD50 and RotD100 of PGA, PGV and Sa at each period, added to `json` with the
/// measure names a study uses ("pga_rotd50_g", …) and the azimuths used.
void add_rotd(JsonObject& json, const HorizontalPair& pair, const RecordArguments& args) {
  auto both = [&](IntensityMeasure m, double period_s) { return rotd(pair, {m, period_s, args.damping}); };
  const RotD pga = both(IntensityMeasure::kPga, 0.0), pgv = both(IntensityMeasure::kPgv, 0.0);
  std::vector<double> sa50, sa100;
  for (double t : args.periods_s) {
    const RotD sa = both(IntensityMeasure::kSa, t);
    sa50.push_back(sa.rotd50);
    sa100.push_back(sa.rotd100);
  }
  json.numbers("azimuths_deg", {pair.az1_deg, pair.az2_deg})
      .number("pga_rotd50_g", pga.rotd50)
      .number("pga_rotd100_g", pga.rotd100)
      .number("pgv_rotd50_m_s", pgv.rotd50)
      .number("pgv_rotd100_m_s", pgv.rotd100)
      .numbers("sa_rotd50_g", sa50)
      .numbers("sa_rotd100_g", sa100);
}

void describe(const RecordArguments& args) {
  if (!(args.damping >= 0.0 && args.damping < 1.0)) throw UsageError("--damping must be in [0, 1)");
  for (double t : args.periods_s)
    if (const auto problem = sa_period_problem(t, 0.0); !problem.empty()) throw UsageError("--period: " + problem);
  if (args.pair_file.empty() && (args.az1_deg || args.az2_deg))
    throw UsageError("--azimuth-deg and --pair-azimuth-deg go with --pair");
  const GroundMotion motion = args.record.load();
  const RecordMetadata meta = metadata_of(args.record.spec());
  JsonObject json = measures(motion, meta, args);
  if (!args.pair_file.empty()) {
    RecordFlags second = args.record;
    second.file = args.pair_file;
    const GroundMotion other = second.load();
    const RecordMetadata other_meta = metadata_of(second.spec());
    const HorizontalPair pair{motion, azimuth(args.az1_deg, meta, motion, "--azimuth-deg"), other,
                              azimuth(args.az2_deg, other_meta, other, "--pair-azimuth-deg")};
    try {
      add_rotd(json, pair, args);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    json.object("pair", measures(other, other_meta, args));
  }
  std::cout << json.str() << std::endl;
}

}  // namespace

void add_record_command(CLI::App& app) {
  auto args = std::make_shared<RecordArguments>();
  auto* cmd = app.add_subcommand("record", "Intensity measures and header metadata of a record, as one JSON object");
  args->record.add_to(cmd, true, false);
  cmd->add_option("--period", args->periods_s, "oscillator period for Sa [s] (repeatable)");
  cmd->add_option("--damping", args->damping, "damping ratio of the oscillator [-]")->capture_default_str();
  cmd->add_option("--pair", args->pair_file,
                  "the station's other horizontal component: adds its measures and RotD50/RotD100 of PGA, PGV and Sa");
  cmd->add_option("--azimuth-deg", args->az1_deg, "azimuth of FILE's component [deg from north] (default: its header)");
  cmd->add_option("--pair-azimuth-deg", args->az2_deg,
                  "azimuth of the --pair component [deg from north] (default: its header)");
  cmd->callback([args] { describe(*args); });
}

}  // namespace pcrf::cli
