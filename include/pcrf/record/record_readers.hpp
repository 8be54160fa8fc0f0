/// \file record_readers.hpp
/// \brief Readers for ground-motion files: PEER NGA `.AT2`, two-column and one-column text.
///
/// Every reader returns a GroundMotion in m/s². Errors throw RecordError whose
/// message names the file and, where it applies, the line: "file.AT2:4: cannot read
/// NPTS/DT header".
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "pcrf/record/ground_motion.hpp"

namespace pcrf {

/// A ground-motion file could not be read; what() names the file and line.
class RecordError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Units of acceleration values in a text file.
enum class AccelUnit { kG, kMeterPerSecond2, kCentimeterPerSecond2 };

/// Parses "g", "m/s2" (also "m/s^2", "mps2"), "cm/s2" (also "cm/s^2", "gal").
/// \throws std::invalid_argument naming the bad text.
AccelUnit parse_accel_unit(const std::string& text);

/// Factor that converts a value in `unit` to m/s².
double to_m_s2(AccelUnit unit);

/// File layouts the engine reads.
enum class RecordFormat { kAt2, kTwoColumn, kOneColumn };

/// Parses "at2", "two-column", "one-column". \throws std::invalid_argument.
RecordFormat parse_record_format(const std::string& text);

/// PEER NGA `.AT2`: four header lines, the fourth giving NPTS and DT in either form
/// `NPTS=  7374, DT=   .0050 SEC` or `11000  0.0050  NPTS, DT`; then values in g,
/// any number per line. CRLF or LF; a partial last line is fine. Extra values beyond
/// NPTS are an error, as are fewer values than NPTS and non-numeric data.
GroundMotion read_at2(const std::filesystem::path& file);

/// Two columns: time [s] and acceleration in `unit`, whitespace or comma separated.
/// Lines starting with '#' and blank lines are skipped. The time step must be uniform
/// (relative spread below 1e-6). If the first time is not 0, samples are kept as they are
/// and t = i·dt still applies (documented shift).
GroundMotion read_two_column(const std::filesystem::path& file, AccelUnit unit);

/// One value a line (or several per line), acceleration in `unit`, sampled every dt_s.
GroundMotion read_one_column(const std::filesystem::path& file, double dt_s, AccelUnit unit);

/// Where a record comes from, as a study file or the command line names it.
struct RecordFileSpec {
  std::filesystem::path path;
  RecordFormat format = RecordFormat::kAt2;
  AccelUnit unit = AccelUnit::kG;  ///< ignored for .AT2 (always g)
  double dt_s = 0.0;               ///< one-column only
};

/// Reads a record by its spec; the record's name is the file stem.
GroundMotion read_record(const RecordFileSpec& spec);

/// Guesses the format from the extension: ".at2" (any case) → AT2, else two-column.
RecordFormat guess_record_format(const std::filesystem::path& file);

}  // namespace pcrf
