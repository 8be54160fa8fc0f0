/// \file record_readers.hpp
/// \brief Readers for ground-motion files: PEER NGA `.AT2`, two-column and one-column text.
///
/// Every reader returns a GroundMotion in m/s². Errors throw UserError (at the file and line) whose
/// message names the file and, where it applies, the line: "file.AT2:4: cannot read
/// NPTS/DT header".
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "pcrf/record/ground_motion.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {

/// Units of acceleration values in a text file.
enum class AccelUnit { kG, kMeterPerSecond2, kCentimeterPerSecond2 };

/// Parses "g", "m/s2" (also "m/s^2", "mps2"), "cm/s2" (also "cm/s^2", "gal"); case and
/// surrounding blanks are ignored.
/// \throws UserError naming the bad text.
AccelUnit parse_accel_unit(const std::string& text);

/// "g", "m/s2" or "cm/s2": the spelling parse_accel_unit takes and messages suggest.
std::string to_string(AccelUnit unit);

/// Factor that converts a value in `unit` to m/s² (g → pcrf::kGravity_m_s2).
/// \throws UserError for a value outside the enumeration.
double to_m_s2(AccelUnit unit);

/// File layouts the engine reads.
enum class RecordFormat { kAt2, kTwoColumn, kOneColumn };

/// Parses "at2", "two-column", "one-column" (case ignored). \throws UserError.
RecordFormat parse_record_format(const std::string& text);

/// PEER NGA `.AT2`: four header lines, the fourth giving NPTS and DT in either form
/// `NPTS=  7374, DT=   .0050 SEC` or `11000  0.0050  NPTS, DT`; then values in g,
/// any number per line. CRLF or LF; a partial last line is fine. Extra values beyond
/// NPTS are an error, as are fewer values than NPTS and non-numeric data. Numbers may be
/// written Fortran-style (".0050", "-.47E-02", "1.0D-03"). Line 3 is checked only where it
/// speaks: "VELOCITY"/"DISPLACEMENT", or "UNITS OF" followed by anything but G, is an
/// error. The record's name is the file stem.
GroundMotion read_at2(const std::filesystem::path& file);

/// Two columns: time [s] and acceleration in `unit`, whitespace or comma separated.
/// Lines starting with '#' and blank lines are skipped. The time step must be uniform
/// (relative spread below 1e-6). If the first time is not 0, samples are kept as they are
/// and t = i·dt still applies (documented shift). '#' starts a comment anywhere on a line;
/// every data row needs exactly two fields; an empty field (",,", a leading or trailing comma)
/// is an error. At least two rows are needed; dt is the mean step (t_last − t_first)/(n − 1),
/// and each step must lie within 1e-6 (relative) of the first one.
/// `skip_rows` lines at the top are dropped first (headers, or the extra leading sample some
/// converters add); line numbers in messages stay those of the file.
GroundMotion read_two_column(const std::filesystem::path& file, AccelUnit unit, std::size_t skip_rows = 0);

/// One value a line (or several per line), acceleration in `unit`, sampled every dt_s.
/// Same comment and separator rules as read_two_column. A dt_s that is not positive and
/// finite, or a file without values, is a UserError (at the file and line).
/// `column` = 0 reads every value in reading order. `column` = k ≥ 1 reads the k-th field of
/// every row, for a file that holds several series side by side (e.g. N-S and E-W, no time
/// column); then every row needs at least k fields, and the record's name is the file stem
/// followed by "_col" and k.
GroundMotion read_one_column(const std::filesystem::path& file, double dt_s, AccelUnit unit,
                             std::size_t skip_rows = 0, std::size_t column = 0);

/// Where a record comes from, as a study file or the command line names it.
struct RecordFileSpec {
  std::filesystem::path path;
  RecordFormat format = RecordFormat::kAt2;
  AccelUnit unit = AccelUnit::kG;  ///< ignored for .AT2 (always g)
  double dt_s = 0.0;               ///< one-column only
  std::size_t skip_rows = 0;       ///< text formats: lines dropped at the top of the file
  std::size_t column = 0;          ///< one-column only: 0 every value, k ≥ 1 the k-th field of a row
};

/// What is wrong with a record of `samples` samples every `dt_s` seconds ("" when nothing):
/// fewer than 2 samples, or a dt outside 10 µs–1 s (a unit or header error). The readers
/// refuse such a file with it; an array given in Python is refused with it too.
std::string sampling_problem(double dt_s, std::size_t samples);

/// Reads a record by its spec; its name is record_name(spec).
GroundMotion read_record(const RecordFileSpec& spec);

/// The name a record read by `spec` carries: the file stem, with "_colK" for column K.
std::string record_name(const RecordFileSpec& spec);

/// What a record file says about itself. AT2 files: `title` is header line 2 ("Imperial
/// Valley-06, 10/15/1979, El Centro Array #11, 230"), split at its commas into event, (date,)
/// station and component. Any file: `rsn` from a name like "RSN174_…". Empty where unknown.
struct RecordMetadata {
  std::string title;
  std::string event;
  std::string station;
  std::string component;
  std::string rsn;
};
/// \throws UserError (at the file and line) when an AT2 file cannot be read.
RecordMetadata read_metadata(const RecordFileSpec& spec);

/// A component file (`label`, for messages) and what its header says.
struct ComponentHeader {
  std::string label;
  RecordMetadata metadata;
};

/// One line when the headers of two components of one station name different events or
/// stations, naming both files with their event and station; "" when they name the same
/// (case and spacing aside) or either header names none (a text file).
std::string different_station(const ComponentHeader& a, const ComponentHeader& b);

/// A record file read once: its motion (read_record) and what it says about itself
/// (read_metadata). \throws UserError (at the file and line) as read_record.
struct RecordFile {
  GroundMotion motion;
  RecordMetadata metadata;
};
RecordFile read_record_file(const RecordFileSpec& spec);

/// Guesses the format from the extension: ".at2" (any case) → AT2, else two-column.
RecordFormat guess_record_format(const std::filesystem::path& file);

}  // namespace pcrf
