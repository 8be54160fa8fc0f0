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
  /// Adds `h2_flag` (e.g. "--record-h2"), `up_flag` ("--record-up"), --azimuth-deg and
  /// --h2-azimuth-deg.
  void add_components_to(CLI::App* cmd, const std::string& h2_flag, const std::string& up_flag);
};


}  // namespace pcrf::cli
