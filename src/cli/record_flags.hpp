/// \file record_flags.hpp
/// \brief The flags that name one ground motion (`pcrf run`, `pcrf record`): a file with its
/// format, units, dt and skipped rows, or a synthetic motion.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "pcrf/excitation/station_record.hpp"
#include "pcrf/record/ground_motion.hpp"
#include "pcrf/record/record_readers.hpp"

namespace pcrf::cli {

struct RecordFlags {
  std::string file;
  std::string format;  ///< empty: from the extension
  std::string units = "g";
  double dt_s = 0.0;
  std::size_t skip_rows = 0;
  std::size_t column = 0;
  std::string synthetic;

  /// Adds --record (unless `file_positional`, then FILE), --format, --units, --dt, --skip-rows
  /// and (with `synthetic_allowed`) --synthetic.
  void add_to(CLI::App* cmd, bool file_positional, bool synthetic_allowed);
  /// The file's spec. \throws UsageError for a bad format, unit or missing --dt.
  RecordFileSpec spec() const;
  /// The motion, unscaled. \throws UsageError with the reader's message.
  GroundMotion load() const;

  // The station's other components (files read like the first one).
  std::string file_h2;
  std::string file_up;
  std::optional<double> az1_deg;
  std::optional<double> az2_deg;
  /// Adds `h2_flag` (e.g. "--record-h2"), `up_flag` ("--record-up"), --azimuth-deg and
  /// --h2-azimuth-deg.
  void add_components_to(CLI::App* cmd, const std::string& h2_flag, const std::string& up_flag);
  /// Every component given, aligned (the notes of padding in `notes`), the azimuths given or
  /// read from the AT2 headers' component names. \throws UsageError: different dt, a
  /// vertical given as a horizontal or the other way round.
  StationRecord load_station(std::vector<std::string>& notes) const;
};

/// One line per record file of `flags` (first horizontal, --record-h2, --record-up) whose
/// measures no earthquake record has (record_plausibility), naming the file and the likely
/// --units: "a.txt: PGA 501 g is above 3 g: is this file in cm/s2 (PGA 0.511 g)? use --units cm/s2".
std::vector<std::string> implausible_records(const RecordFlags& flags, const StationRecord& station);

}  // namespace pcrf::cli
