// One ground motion as a user names it (see record_input.hpp).
#include "pcrf/api/record_input.hpp"

#include "pcrf/api/input_error.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/synthetic.hpp"

namespace pcrf::api {

RecordFileSpec RecordInput::spec() const {
  RecordFileSpec spec;
  spec.path = file;
  try {
    spec.format = format.empty() ? guess_record_format(spec.path) : parse_record_format(format);
    spec.unit = parse_accel_unit(units);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  spec.dt_s = dt_s;
  spec.skip_rows = skip_rows;
  spec.column = column;
  if (column > 0 && spec.format != RecordFormat::kOneColumn) throw InputError("--column applies to one-column records only");
  if (spec.format == RecordFormat::kOneColumn && !(dt_s > 0)) throw InputError("--dt is required (and > 0) for a one-column record");
  return spec;
}

GroundMotion RecordInput::load() const {
  if (file.empty() == synthetic.empty()) throw InputError("give exactly one of --record FILE or --synthetic SPEC");
  try {
    if (!synthetic.empty()) return make_synthetic(synthetic);
    return read_record(spec());
  } catch (const RecordError& e) {
    throw InputError(e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
}

RecordInput RecordInput::component(const std::string& path) const {
  RecordInput input = *this;
  input.file = path;
  input.synthetic.clear();
  return input;
}

RecordMetadata record_metadata(const RecordFileSpec& spec) {
  try {
    return read_metadata(spec);
  } catch (const RecordError& e) {
    throw InputError(e.what());
  }
}

namespace {

/// The component name an AT2 header states ("230", "UP"); empty for other files.
std::string component_of(const RecordFileSpec& spec) {
  return spec.format == RecordFormat::kAt2 ? record_metadata(spec).component : std::string();
}

}  // namespace

StationRecord RecordInput::load_station(std::vector<std::string>& notes) const {
  StationRecord station{load(), az1_deg, std::nullopt, az2_deg, std::nullopt};
  auto stated_azimuth = [](const RecordFileSpec& spec, const char* role) -> std::optional<double> {
    const std::string component = component_of(spec);
    if (is_vertical_component(component))
      throw InputError(spec.path.string() + ": its header names a vertical component ('" + component + "'), given as " + role);
    return azimuth_of_component(component);
  };
  if (!file.empty() && !station.az1_deg) station.az1_deg = stated_azimuth(spec(), "the first horizontal");
  if (!file_h2.empty()) {
    const RecordInput h2 = component(file_h2);
    station.h2 = h2.load();
    if (!station.az2_deg) station.az2_deg = stated_azimuth(h2.spec(), "the second horizontal");
  }
  if (!file_up.empty()) {
    const RecordInput up = component(file_up);
    const std::string component = component_of(up.spec());
    if (!component.empty() && azimuth_of_component(component))
      throw InputError(file_up + ": its header names a horizontal component ('" + component + "'), given as the vertical");
    station.up = up.load();
  }
  try {
    notes = station.align();
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  return station;
}

}  // namespace pcrf::api
