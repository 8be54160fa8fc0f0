/// \file record_input.hpp
/// \brief One ground motion as a user names it (`pcrf run`, `pcrf record`, `pcrf.run`): a
/// file with its format, units, dt and skipped rows, or a synthetic motion; and the station's
/// other components (the second horizontal, the vertical) read like the first.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pcrf/excitation/station_record.hpp"
#include "pcrf/record/ground_motion.hpp"
#include "pcrf/record/record_readers.hpp"

namespace pcrf::api {

struct RecordInput {
  std::string file;
  std::string format;  ///< empty: from the extension
  std::string units = "g";
  double dt_s = 0.0;
  std::size_t skip_rows = 0;
  std::size_t column = 0;
  std::string synthetic;

  /// The file's spec. \throws UserError for a bad format, unit or missing --dt.
  RecordFileSpec spec() const;
  /// The motion, unscaled. \throws UserError with the reader's message.
  GroundMotion load() const;

  /// The file of each of the station's other components (kStationComponents; empty: none),
  /// read like the first one.
  PerComponent<std::string> component_files;
  std::optional<double> az1_deg;
  std::optional<double> az2_deg;
  /// Every component given, aligned (the notes of padding in `notes`), the azimuths given or
  /// read from the AT2 headers' component names. \throws UserError: different dt, a
  /// vertical given as a horizontal or the other way round.
  StationRecord load_station(std::vector<std::string>& notes) const;
  /// The same input naming another file (of the same format and units) as its first component.
  RecordInput component(const std::string& path) const;
};

/// One line per record file of `input` (the first horizontal, then the others) whose measures no
/// earthquake record has (record_plausibility), naming the file and the likely units: "a.txt:
/// PGA 501 g is above 3 g: is it in cm/s2 (PGA 0.511 g)? use --units cm/s2"; and one line
/// when the AT2 headers of the components name different events or stations
/// (different_station). Empty for a synthetic motion.
std::vector<std::string> implausible_records(const RecordInput& input, const StationRecord& station);

/// The same checks for components given as arrays in g (Python's ground_accel_g): one line
/// per component whose measures no earthquake record has, named as the station names it.
std::vector<std::string> implausible_arrays(const StationRecord& station);

/// What a file's header says about the record (title, component, …). \throws UserError.
RecordMetadata record_metadata(const RecordFileSpec& spec);

}  // namespace pcrf::api
