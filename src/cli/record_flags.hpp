/// \file record_flags.hpp
/// \brief The flags that name one ground motion (`pcrf run`, `pcrf record`): a file with its
/// format, units, dt and skipped rows, or a synthetic motion.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

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
};

}  // namespace pcrf::cli
