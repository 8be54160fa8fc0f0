// `pcrf record FILE`: what a record is, its intensity measures and its header metadata, as
// one JSON object (api/record_measures.hpp).
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/record_flags.hpp"
#include "pcrf/api/record_measures.hpp"

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

}  // namespace

void add_record_command(CLI::App& app) {
  auto args = std::make_shared<RecordArguments>();
  auto* cmd = app.add_subcommand("record", "Intensity measures and header metadata of a record, as one JSON object");
  args->record.add_to(cmd, true, false);
  cmd->add_option("--periods-s,--period", args->request.periods_s, "oscillator period for Sa [s] (repeatable)");
  cmd->add_option("--damping", args->request.damping, "damping ratio of the oscillator [-]")->capture_default_str();
  // --pair adds the second horizontal's measures and RotD50/RotD100 of PGA, PGV and Sa.
  args->record.add_components_to(cmd, /*record_flags=*/true);
  cmd->callback([args] { describe(*args); });
}

}  // namespace pcrf::cli
