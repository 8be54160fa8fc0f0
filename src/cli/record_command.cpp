// `pcrf record FILE`: what a record is, its intensity measures and its header metadata, as
// one JSON object (api/record_measures.hpp). `pcrf record pulse FILE [--h2 FILE2]`: whether
// it is pulse-like and its T_p (api/record_pulse.hpp).
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/record_flags.hpp"
#include "pcrf/api/record_measures.hpp"
#include "pcrf/api/record_pulse.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::cli {
namespace {

struct RecordArguments {
  RecordFlags record;  ///< with the station's other components (--pair, --up)
  api::MeasureRequest request;
};

void describe(const RecordArguments& args) {
  api::check_measure_request(args.request);
  std::vector<std::string> notes;
  const StationRecord station = args.record.load_station(notes);
  for (const auto& note : notes) std::cerr << "pcrf record: note: " << note << '\n';
  for (const auto& line : api::implausible_records(args.record, station)) std::cerr << "pcrf record: warning: " << line << '\n';
  std::cout << api::record_measures(station, args.record, args.request).str() << std::endl;
}

struct PulseArguments {
  RecordFlags record;  ///< the first horizontal, and with --h2 the second
  bool series = false;
};

void identify_pulse(const PulseArguments& args) {
  std::vector<std::string> notes;
  const StationRecord station = args.record.load_station(notes);
  for (const auto& note : notes) std::cerr << "pcrf record pulse: note: " << note << '\n';
  std::cout << api::pulse_json(api::classify_station_pulse(station), args.series).str() << std::endl;
}

void add_pulse_command(CLI::App* record) {
  auto args = std::make_shared<PulseArguments>();
  auto* cmd = record->add_subcommand(
      "pulse", "Whether a record is pulse-like, and its pulse period T_p (Baker 2007; Shahi & Baker 2014 with --h2)");
  args->record.add_to(cmd, true, false);
  cmd->add_option("--h2", args->record.component_files[0],
                  "the station's other horizontal: classify every orientation (Shahi & Baker 2014)");
  cmd->add_option("--azimuth-deg", args->record.az1_deg, "azimuth of the first component [deg from north] (default: its header)");
  cmd->add_option("--h2-azimuth-deg", args->record.az2_deg,
                  "azimuth of the second horizontal [deg from north] (default: its header)");
  cmd->add_flag("--series", args->series, "add the velocity, the extracted pulse and the residual [cm/s]");
  cmd->callback([args] { identify_pulse(*args); });
}

}  // namespace

void add_record_command(CLI::App& app) {
  auto args = std::make_shared<RecordArguments>();
  auto* cmd = app.add_subcommand("record", "Intensity measures and header metadata of a record, as one JSON object");
  args->record.add_to(cmd, true, false);
  // FILE is needed unless a subcommand (pulse) is given: checked in the callback.
  cmd->get_option("FILE")->required(false);
  cmd->add_option("--periods-s,--period", args->request.periods_s, "oscillator period for Sa [s] (repeatable)");
  cmd->add_option("--damping", args->request.damping, "damping ratio of the oscillator [-]")->capture_default_str();
  // --pair adds the second horizontal's measures and RotD50/RotD100 of PGA, PGV and Sa.
  args->record.add_components_to(cmd, /*record_flags=*/true);
  add_pulse_command(cmd);
  add_record_library_commands(cmd);
  cmd->require_subcommand(0, 1);
  cmd->callback([args, cmd] {
    if (!cmd->get_subcommands().empty()) return;
    if (args->record.file.empty()) throw UserError("a record file is required: pcrf record FILE (see pcrf record --help)");
    describe(*args);
  });
}

}  // namespace pcrf::cli
