// Flags that name one ground motion (see record_flags.hpp).
#include "cli/record_flags.hpp"

#include "cli/commands.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/synthetic.hpp"

namespace pcrf::cli {

void RecordFlags::add_to(CLI::App* cmd, bool file_positional, bool synthetic_allowed) {
  const std::string group = "record";
  if (file_positional)
    cmd->add_option("FILE", file, "ground-motion file (.AT2, two-column or one-column text)")->required();
  else
    cmd->add_option("--record", file, "ground-motion file (.AT2, two-column or one-column text)")->group(group);
  cmd->add_option("--format", format, "record format: at2, two-column, one-column (default: from extension)")->group(group);
  cmd->add_option("--units", units, "acceleration units of a text record: g, m/s2, cm/s2")->capture_default_str()->group(group);
  cmd->add_option("--dt", dt_s, "sample interval of a one-column record [s]")->group(group);
  cmd->add_option("--skip-rows", skip_rows, "text records: lines to drop at the top (headers, an added leading sample)")
      ->group(group);
  cmd->add_option("--column", column,
                  "one-column records: read the K-th field of every row (a file of series side by side)")
      ->group(group);
  if (synthetic_allowed)
    cmd->add_option("--synthetic", synthetic,
                    "synthetic motion, e.g. 'sine:amplitude_g=1.5,period_s=0.5,cycles=2' or "
                    "'stochastic:seed=3,pga_g=1.2,duration_s=20'")
        ->group(group);
}

RecordFileSpec RecordFlags::spec() const {
  RecordFileSpec spec;
  spec.path = file;
  try {
    spec.format = format.empty() ? guess_record_format(spec.path) : parse_record_format(format);
    spec.unit = parse_accel_unit(units);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  spec.dt_s = dt_s;
  spec.skip_rows = skip_rows;
  spec.column = column;
  if (column > 0 && spec.format != RecordFormat::kOneColumn) throw UsageError("--column applies to one-column records only");
  if (spec.format == RecordFormat::kOneColumn && !(dt_s > 0)) throw UsageError("--dt is required (and > 0) for a one-column record");
  return spec;
}

GroundMotion RecordFlags::load() const {
  if (file.empty() == synthetic.empty()) throw UsageError("give exactly one of --record FILE or --synthetic SPEC");
  try {
    if (!synthetic.empty()) return make_synthetic(synthetic);
    return read_record(spec());
  } catch (const RecordError& e) {
    throw UsageError(e.what());
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

void RecordFlags::add_components_to(CLI::App* cmd, const std::string& h2_flag, const std::string& up_flag) {
  const std::string group = "record";
  cmd->add_option(h2_flag, file_h2, "the station's other horizontal component (read like the first)")->group(group);
  cmd->add_option(up_flag, file_up, "the station's vertical component, positive up (read like the first)")->group(group);
  cmd->add_option("--azimuth-deg", az1_deg, "azimuth of the first component [deg from north] (default: its header)")
      ->group(group);
  cmd->add_option("--h2-azimuth-deg", az2_deg,
                  "azimuth of the second horizontal component [deg from north] (default: its header)")
      ->group(group);
}

namespace {

/// The component name an AT2 header states ("230", "UP"); empty for other files.
std::string component_of(const RecordFileSpec& spec) {
  try {
    return spec.format == RecordFormat::kAt2 ? read_metadata(spec).component : std::string();
  } catch (const RecordError& e) {
    throw UsageError(e.what());
  }
}

}  // namespace

std::vector<std::string> implausible_records(const RecordFlags& flags, const StationRecord& station) {
  std::vector<std::string> lines;
  const AccelUnit unit = flags.spec().unit;
  auto check = [&](const std::string& file, const GroundMotion& motion) {
    const bool at2 = (flags.format.empty() ? guess_record_format(file) : parse_record_format(flags.format)) == RecordFormat::kAt2;
    const auto p = record_plausibility(motion, at2 ? AccelUnit::kG : unit);
    if (p.problem.empty()) return;
    std::string line = file + ": " + p.problem + ": " + p.hint;
    if (p.likely_unit) line += at2 ? " (an .AT2 file is read in g)" : " use --units " + to_string(*p.likely_unit);
    lines.push_back(line);
  };
  if (flags.file.empty()) return lines;  // a synthetic motion is what it was asked to be
  check(flags.file, station.h1);
  if (station.h2 && !flags.file_h2.empty()) check(flags.file_h2, *station.h2);
  if (station.up && !flags.file_up.empty()) check(flags.file_up, *station.up);
  return lines;
}

StationRecord RecordFlags::load_station(std::vector<std::string>& notes) const {
  auto other = [this](const std::string& path) {
    RecordFlags flags = *this;
    flags.file = path;
    flags.synthetic.clear();
    return flags;
  };
  auto part = [](const RecordFlags& flags) {
    const std::string component = flags.file.empty() ? std::string() : component_of(flags.spec());
    return StationComponent{flags.load(), component, flags.file.empty() ? flags.synthetic : flags.file};
  };
  std::optional<StationComponent> h2, up;
  if (!file_h2.empty()) h2 = part(other(file_h2));
  if (!file_up.empty()) up = part(other(file_up));
  try {
    return make_station(part(*this), az1_deg, std::move(h2), az2_deg, std::move(up), notes);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace pcrf::cli
