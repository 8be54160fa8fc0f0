// One ground motion as a user names it (see record_input.hpp).
#include "pcrf/api/record_input.hpp"

#include "pcrf/user_error.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/synthetic.hpp"

namespace pcrf::api {

RecordFileSpec RecordInput::spec() const {
  RecordFileSpec spec;
  spec.path = file;
  spec.format = format.empty() ? guess_record_format(spec.path) : parse_record_format(format);
  spec.unit = parse_accel_unit(units);
  spec.dt_s = dt_s;
  spec.skip_rows = skip_rows;
  spec.column = column;
  if (column > 0 && spec.format != RecordFormat::kOneColumn) throw UserError("column", "applies to one-column records only");
  if (spec.format == RecordFormat::kOneColumn && !(dt_s > 0)) throw UserError("dt_s", "is required (and > 0) for a one-column record");
  return spec;
}

GroundMotion RecordInput::load() const {
  if (file.empty() == synthetic.empty())
    throw UserError(Where{}, "give exactly one of {} FILE or {} SPEC", {"record", "synthetic"});
  if (!synthetic.empty()) return make_synthetic(synthetic);
  return read_record(spec());
}

RecordInput RecordInput::component(const std::string& path) const {
  RecordInput input = *this;
  input.file = path;
  input.synthetic.clear();
  return input;
}

RecordMetadata record_metadata(const RecordFileSpec& spec) {
  return read_metadata(spec);
}

namespace {

/// The component name an AT2 header states ("230", "UP"); empty for other files.
std::string component_of(const RecordFileSpec& spec) {
  return spec.format == RecordFormat::kAt2 ? record_metadata(spec).component : std::string();
}

}  // namespace

StationRecord RecordInput::load_station(std::vector<std::string>& notes) const {
  // The checks of the components' names and azimuths are the study's too (make_station).
  auto part = [](const RecordInput& input) {
    const std::string component = input.file.empty() ? std::string() : component_of(input.spec());
    GroundMotion motion = input.load();
    // Values no measure can take name the file they came from (the motion's name is its stem).
    if (const auto problem = measures_problem(motion); !problem.empty())
      throw input.file.empty() ? UserError("synthetic", problem) : UserError(Where{{}, input.file, 0}, problem);
    return StationComponent{std::move(motion), component, input.file.empty() ? input.synthetic : input.file};
  };
  StationParts parts{part(*this), az1_deg, std::nullopt, az2_deg, std::nullopt};
  const auto members = component_members<StationParts>();
  for (std::size_t i = 0; i < kComponentCount; ++i)
    if (!component_files[i].empty()) parts.*members[i] = part(component(component_files[i]));
  return make_station(std::move(parts), notes);
}

std::vector<std::string> implausible_records(const RecordInput& input, const StationRecord& station) {
  std::vector<std::string> lines;
  const AccelUnit unit = input.spec().unit;
  auto check = [&](const std::string& file, const GroundMotion& motion) {
    const bool at2 = (input.format.empty() ? guess_record_format(file) : parse_record_format(input.format)) == RecordFormat::kAt2;
    const auto p = record_plausibility(motion, at2 ? AccelUnit::kG : unit);
    if (p.problem.empty()) return;
    std::string line = file + ": " + p.problem + ": " + p.hint;
    if (p.likely_unit) line += at2 ? " (an .AT2 file is read in g)" : " use --units " + to_string(*p.likely_unit);
    lines.push_back(line);
  };
  if (input.file.empty()) return lines;  // a synthetic motion is what it was asked to be
  check(input.file, station.h1);
  const auto members = component_members<StationRecord>();
  for (std::size_t i = 0; i < kComponentCount; ++i)
    if (station.*members[i] && !input.component_files[i].empty()) check(input.component_files[i], *(station.*members[i]));
  const auto header = [&](const std::string& file) {
    const RecordInput part = input.component(file);
    return ComponentHeader{file, record_metadata(part.spec())};
  };
  for (const std::string& other : input.component_files)
    if (!other.empty())
      if (auto line = different_station(header(input.file), header(other)); !line.empty()) lines.push_back(std::move(line));
  return lines;
}

std::vector<std::string> implausible_arrays(const StationRecord& station) {
  std::vector<std::string> lines;
  auto check = [&](const GroundMotion& motion) {
    const auto p = record_plausibility(motion, AccelUnit::kG);
    if (p.problem.empty()) return;
    std::string line = motion.name() + ": " + p.problem + ": " + p.hint;
    if (p.likely_unit) line += " (the array is read in g: convert it to g)";
    lines.push_back(line);
  };
  check(station.h1);
  for (const auto member : component_members<StationRecord>())
    if (station.*member) check(*(station.*member));
  return lines;
}

}  // namespace pcrf::api
