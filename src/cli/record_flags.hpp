/// \file record_flags.hpp
/// \brief The flags that name one ground motion (`pcrf run`, `pcrf record`): a file with its
/// format, units, dt and skipped rows, or a synthetic motion, and the station's other
/// components. What they name is an api::RecordInput, loaded and checked there.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "pcrf/api/record_input.hpp"

namespace pcrf::cli {

struct RecordFlags : api::RecordInput {
  /// Adds --record (unless `file_positional`, then FILE), --format, --units, --dt, --skip-rows
  /// and (with `synthetic_allowed`) --synthetic.
  void add_to(CLI::App* cmd, bool file_positional, bool synthetic_allowed);
  /// Adds a flag for each of the station's other components (kStationComponents): `pcrf
  /// run`'s (the keyword's flag_name, "--record-h2"), or with `record_flags` `pcrf record`'s
  /// ("--pair"); then --azimuth-deg and --h2-azimuth-deg.
  void add_components_to(CLI::App* cmd, bool record_flags);
};


}  // namespace pcrf::cli
