/// \file record_readers.cpp
/// \brief Readers for ground-motion files: PEER NGA `.AT2`, two-column and one-column text.
///
/// Every problem with a file becomes a UserError "path:LINE: problem" (or "path: problem"
/// when no single line is to blame). Nothing is guessed or silently repaired: a value that
/// does not parse, a count that does not match NPTS or an uneven time step stops the read.

#include "pcrf/record/record_readers.hpp"

#include "pcrf/user_error.hpp"

#include <array>

#include "pcrf/setting.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "pcrf/byte_order_mark.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/printable.hpp"

namespace pcrf {

namespace {

// ---- small text helpers -----------------------------------------------------------------

[[noreturn]] void fail_at(const std::filesystem::path& file, std::size_t line_number,
                          const std::string& problem) {
  throw UserError(Where{{}, file.string(), static_cast<int>(line_number)}, problem);
}

[[noreturn]] void fail_file(const std::filesystem::path& file, const std::string& problem) {
  throw UserError(Where{{}, file.string(), 0}, problem);
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::string to_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string to_upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

/// A token as it appears in a message: quoted, cut short and with unprintable bytes
/// escaped, so that a binary file stays readable.
std::string quote_token(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  // Built by append: GCC 12 reports a false -Wrestrict for "'" + std::string(...).
  std::string out(1, '\'');
  out.append(printable(token.substr(0, kMaxShown)));
  if (token.size() > kMaxShown) out.append("...");
  out.push_back('\'');
  return out;
}

/// Parses a whole token as a finite double. Accepts what Fortran writes: ".0050",
/// "-.4722856E-02", "7.6753400E-05", a leading '+', and a 'D' exponent ("1.0D-03").
bool parse_finite_double(std::string_view token, double& value) {
  // from_chars takes no '+' sign; drop one, but only before a digit or '.', so "+-1" still fails.
  if (token.size() >= 2 && token.front() == '+' &&
      (std::isdigit(static_cast<unsigned char>(token[1])) || token[1] == '.')) {
    token.remove_prefix(1);
  }
  char buffer[64];
  if (token.empty() || token.size() >= sizeof buffer) return false;
  std::size_t n = 0;
  for (char c : token) buffer[n++] = (c == 'D' || c == 'd') ? 'E' : c;
  const char* end = buffer + n;
  // from_chars also takes "inf" and "nan"; a record holds finite numbers only.
  const auto [ptr, ec] = std::from_chars(buffer, end, value, std::chars_format::general);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

/// Parses a whole token as a signed integer.
bool parse_integer(std::string_view token, long long& value) {
  if (token.size() >= 2 && token.front() == '+' &&
      std::isdigit(static_cast<unsigned char>(token[1]))) {
    token.remove_prefix(1);
  }
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return !token.empty() && ec == std::errc() && ptr == end;
}

/// The whole file as text, without a leading UTF-8 byte-order mark. A missing file, a folder or a FIFO, an unreadable file, a UTF-16
/// file and a binary file (a NUL byte) are UserErrors.
std::string read_text(const std::filesystem::path& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec && status.type() != std::filesystem::file_type::not_found) fail_file(file, "cannot open: " + ec.message());
  if (!std::filesystem::exists(status)) fail_file(file, "no such file");
  if (!std::filesystem::is_regular_file(status)) fail_file(file, "not a regular file");
  std::ifstream in(file, std::ios::binary);
  if (!in) fail_file(file, std::string("cannot open file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) fail_file(file, std::string("read error: ") + std::strerror(errno));
  std::string bytes = std::move(text).str();
  if (starts_as_utf16(bytes)) fail_file(file, "UTF-16 text; save it as ASCII or UTF-8");
  if (without_byte_order_mark(bytes).size() < bytes.size()) bytes.erase(0, kUtf8ByteOrderMark.size());
  if (const auto nul = bytes.find('\0'); nul != std::string::npos) {
    const auto line = 1 + static_cast<std::size_t>(std::count(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(nul), '\n'));
    fail_at(file, line, "a NUL byte: this is not a text file");
  }
  return bytes;
}

/// Sample intervals a ground-motion record can have: strong-motion records are sampled at
/// 0.001–0.05 s; anything outside 10 µs–1 s is a unit or header error.
constexpr double kMinDt_s = 1e-5;
constexpr double kMaxDt_s = 1.0;

/// A record needs two samples (an interval to interpolate over) and a plausible dt.
void check_sampling(const std::filesystem::path& file, std::size_t line_number, double dt_s, std::size_t samples) {
  if (const auto problem = sampling_problem(dt_s, samples); !problem.empty()) fail_at(file, line_number, problem);
}

/// value × factor in m/s², refusing a value whose conversion overflows.
double to_m_s2_checked(const std::filesystem::path& file, std::size_t line_number, double value, double factor,
                       std::string_view token) {
  const double converted = value * factor;
  if (!std::isfinite(converted)) fail_at(file, line_number, "value " + quote_token(token) + " overflows in m/s²");
  return converted;
}

/// Lines without their '\n' or "\r\n"; a last line without a line end is kept.
std::vector<std::string_view> split_lines(const std::string& text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t stop = text.find('\n', start);
    if (stop == std::string::npos) stop = text.size();
    std::string_view line(text.data() + start, stop - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = stop + 1;
  }
  return lines;
}

/// Whitespace-separated tokens of a line (AT2 data lines).
void split_whitespace(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

/// Fields of a text-record line: '#' starts a comment; fields are separated by whitespace or
/// by one comma (with optional whitespace around it). An empty field (",," or a comma at the
/// start or end) is an error rather than something to skip, so columns never shift silently.
void split_fields(const std::filesystem::path& file, std::size_t line_number,
                  std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) {
    line = line.substr(0, hash);
  }
  bool after_comma = false;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && is_space(line[i])) ++i;
    if (i == line.size()) break;
    if (line[i] == ',') {
      if (fields.empty() || after_comma) fail_at(file, line_number, "empty field (stray comma)");
      after_comma = true;
      ++i;
      continue;
    }
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i]) && line[i] != ',') ++i;
    fields.push_back(line.substr(start, i - start));
    after_comma = false;
  }
  if (after_comma) fail_at(file, line_number, "empty field (trailing comma)");
}

double parse_value(const std::filesystem::path& file, std::size_t line_number,
                   std::string_view token) {
  double value = 0.0;
  if (!parse_finite_double(token, value)) {
    fail_at(file, line_number, "non-numeric value " + quote_token(token));
  }
  return value;
}

std::string record_name(const std::filesystem::path& file) { return file.stem().string(); }

// ---- AT2 header -------------------------------------------------------------------------

constexpr std::size_t kAt2HeaderLines = 4;

struct At2Header {
  long long npts = 0;
  double dt_s = 0.0;
};

bool is_seconds_word(std::string_view w) {
  const std::string upper = to_upper(w);
  return upper == "SEC" || upper == "SECS" || upper == "S";
}

bool is_keyword(std::string_view token, std::string_view upper_keyword) {
  return to_upper(token) == upper_keyword;
}

/// True when `t[from…]` is a PEER filter description: groups `N POLE @ f [HZ]`, as in
/// `NPTS=   5590, DT=   .0100 SEC,  -5 POLE @      .10000` (a -N pole is the high-pass).
bool is_filter_description(const std::vector<std::string_view>& t, std::size_t from) {
  double number = 0.0;
  std::size_t i = from;
  while (i < t.size()) {
    if (i + 4 > t.size()) return false;
    if (!parse_finite_double(t[i], number) || !is_keyword(t[i + 1], "POLE") || t[i + 2] != "@" ||
        !parse_finite_double(t[i + 3], number))
      return false;
    i += 4;
    if (i < t.size() && is_keyword(t[i], "HZ")) ++i;
  }
  return true;
}

/// Reads NPTS and DT from the fourth header line in either PEER layout,
/// `NPTS=  7374, DT=   .0050 SEC,` or `11000  0.0050  NPTS, DT`: '=' and ',' count as blanks,
/// keywords are matched in any case, and only a time unit ("SEC") may follow, itself followed
/// at most by the filter's description (`4 POLE @ 33.0 HZ, -5 POLE @ .10000`, written by some
/// NGA-West2 downloads). Returns false when the line has neither layout; the caller reports it.
bool parse_npts_dt_line(std::string_view line, std::string& npts_text, std::string& dt_text) {
  std::string plain(line);
  std::replace(plain.begin(), plain.end(), '=', ' ');
  std::replace(plain.begin(), plain.end(), ',', ' ');
  std::vector<std::string_view> t;
  split_whitespace(plain, t);
  const bool tail_ok = t.size() == 4 || (t.size() >= 5 && is_seconds_word(t[4]) && is_filter_description(t, 5));
  if (!tail_ok) return false;
  if (is_keyword(t[0], "NPTS") && is_keyword(t[2], "DT")) {  // NGA-West2
    npts_text = t[1];
    dt_text = t[3];
    return true;
  }
  if (is_keyword(t[2], "NPTS") && is_keyword(t[3], "DT")) {  // older NGA
    npts_text = t[0];
    dt_text = t[1];
    return true;
  }
  return false;
}

At2Header parse_at2_header(const std::filesystem::path& file,
                           const std::vector<std::string_view>& lines) {
  if (lines.empty()) fail_at(file, 1, "empty file (expected 4 header lines and data)");
  if (lines.size() < kAt2HeaderLines) {
    fail_at(file, lines.size() + 1,
            "missing header line " + std::to_string(lines.size() + 1) +
                " of 4 (file ends after " + std::to_string(lines.size()) + " lines)");
  }
  // Line 3 says what the series is; refuse velocity/displacement or units other than g,
  // which would otherwise be read as accelerations in g without complaint.
  const std::string kind = to_upper(lines[2]);
  if (kind.find("VELOCITY") != std::string::npos || kind.find("DISPLACEMENT") != std::string::npos) {
    fail_at(file, 3, "not an acceleration record: " + quote_token(trim(lines[2])));
  }
  if (const std::size_t at = kind.find("UNITS OF"); at != std::string::npos) {
    std::vector<std::string_view> words;
    split_whitespace(std::string_view(kind).substr(at + 8), words);
    std::string_view unit = words.empty() ? std::string_view() : words.front();
    while (!unit.empty() && (unit.back() == '.' || unit.back() == ',')) unit.remove_suffix(1);
    if (unit != "G") fail_at(file, 3, "acceleration units " + quote_token(unit) + " are not g");
  }

  std::string npts_text;
  std::string dt_text;
  if (!parse_npts_dt_line(lines[3], npts_text, dt_text)) {
    fail_at(file, 4, "cannot read NPTS/DT header " + quote_token(trim(lines[3])));
  }
  At2Header header;
  if (!parse_integer(npts_text, header.npts)) {
    fail_at(file, 4, "NPTS " + quote_token(npts_text) + " is not an integer");
  }
  if (header.npts <= 0) fail_at(file, 4, "NPTS must be positive, got " + npts_text);
  if (!parse_finite_double(dt_text, header.dt_s)) {
    fail_at(file, 4, "DT " + quote_token(dt_text) + " is not a number");
  }
  if (!(header.dt_s > 0.0)) fail_at(file, 4, "DT must be positive, got " + dt_text);
  return header;
}

// ---- two-column bookkeeping -----------------------------------------------------------------

/// Checks, row by row, that the time column advances by one uniform step.
class TimeStepCheck {
 public:
  explicit TimeStepCheck(const std::filesystem::path& file) : file_(file) {}

  void add(double t_s, std::size_t line_number) {
    if (rows_ == 0) {
      first_t_s_ = t_s;
    } else {
      const double step_s = t_s - last_t_s_;
      if (!(step_s > 0.0)) {
        fail_at(file_, line_number, "time " + format(t_s) + " does not increase (previous " +
                                        format(last_t_s_) + ")");
      }
      if (rows_ == 1) {
        first_step_s_ = step_s;
      } else if (std::abs(step_s - first_step_s_) > kRelativeSpread * first_step_s_) {
        fail_at(file_, line_number,
                "non-uniform time step: " + format(step_s) + " s here, " + format(first_step_s_) +
                    " s between the first two rows");
      }
    }
    last_t_s_ = t_s;
    ++rows_;
  }

  /// Mean step over the whole record: less rounding than any single difference.
  double dt_s() const { return (last_t_s_ - first_t_s_) / static_cast<double>(rows_ - 1); }
  std::size_t rows() const { return rows_; }

 private:
  static constexpr double kRelativeSpread = 1e-6;
  static std::string format(double v) {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
  }
  const std::filesystem::path& file_;
  std::size_t rows_ = 0;
  double first_t_s_ = 0.0;
  double last_t_s_ = 0.0;
  double first_step_s_ = 0.0;
};

/// Checks that `skip_rows` leaves something of a file of `lines` lines.
void check_skip(const std::filesystem::path& file, std::size_t skip_rows, std::size_t lines) {
  if (skip_rows >= lines && lines > 0)
    fail_file(file, "skip_rows = " + std::to_string(skip_rows) + " skips every line of the file (" +
                        std::to_string(lines) + " lines)");
}

/// "RSN174" from "RSN174_IMPVALL.H_H-E11230": the NGA record sequence number, or "".
std::string rsn_of(const std::filesystem::path& file) {
  const std::string stem = file.stem().string();
  if (to_upper(stem.substr(0, 3)) != "RSN") return "";
  std::size_t end = 3;
  while (end < stem.size() && std::isdigit(static_cast<unsigned char>(stem[end]))) ++end;
  return end > 3 ? stem.substr(3, end - 3) : "";
}

}  // namespace

// ---- units and formats ------------------------------------------------------------------------

AccelUnit parse_accel_unit(const std::string& text) {
  const std::string key = to_lower(trim(text));
  if (key == "g") return AccelUnit::kG;
  if (key == "m/s2" || key == "m/s^2" || key == "mps2") return AccelUnit::kMeterPerSecond2;
  if (key == "cm/s2" || key == "cm/s^2" || key == "gal") return AccelUnit::kCentimeterPerSecond2;
  throw UserError("unknown acceleration unit " + quote_token(text) +
                              " (expected g, m/s2, m/s^2, mps2, cm/s2, cm/s^2 or gal)");
}

std::string to_string(AccelUnit unit) {
  switch (unit) {
    case AccelUnit::kG: return "g";
    case AccelUnit::kMeterPerSecond2: return "m/s2";
    case AccelUnit::kCentimeterPerSecond2: return "cm/s2";
  }
  return "unknown";
}

double to_m_s2(AccelUnit unit) {
  switch (unit) {
    case AccelUnit::kG: return kGravity_m_s2;
    case AccelUnit::kMeterPerSecond2: return 1.0;
    case AccelUnit::kCentimeterPerSecond2: return 0.01;
  }
  throw UserError("invalid AccelUnit value");
}

namespace {
constexpr std::array<EnumName<RecordFormat>, 3> kFormatNames{
    {{RecordFormat::kAt2, "at2"}, {RecordFormat::kTwoColumn, "two-column"}, {RecordFormat::kOneColumn, "one-column"}}};
}  // namespace

RecordFormat parse_record_format(const std::string& text) {
  return parse_name(kFormatNames, to_lower(std::string(trim(text))), "record format");
}

RecordFormat guess_record_format(const std::filesystem::path& file) {
  return to_lower(file.extension().string()) == ".at2" ? RecordFormat::kAt2
                                                        : RecordFormat::kTwoColumn;
}

// ---- readers ------------------------------------------------------------------------------------

namespace {

/// An AT2 record from its file's text (read_at2, read_record_file).
GroundMotion at2_from_text(const std::filesystem::path& file, const std::string& text) {
  const std::vector<std::string_view> lines = split_lines(text);
  const At2Header header = parse_at2_header(file, lines);
  const auto npts = static_cast<std::size_t>(header.npts);

  std::vector<double> accel_m_s2;
  accel_m_s2.reserve(std::min(npts, text.size() / 2 + 1));  // a bogus NPTS must not allocate
  std::vector<std::string_view> tokens;
  std::size_t extra_line = 0;  // line of the first value beyond NPTS, 0 if none
  std::size_t found = 0;
  for (std::size_t i = kAt2HeaderLines; i < lines.size(); ++i) {
    const std::size_t line_number = i + 1;
    split_whitespace(lines[i], tokens);
    for (std::string_view token : tokens) {
      const double value_g = parse_value(file, line_number, token);
      if (found < npts) accel_m_s2.push_back(to_m_s2_checked(file, line_number, value_g, kGravity_m_s2, token));
      else if (extra_line == 0) extra_line = line_number;
      ++found;
    }
  }
  if (extra_line != 0) {
    fail_at(file, extra_line, "more values than NPTS: found " + std::to_string(found) +
                                  ", NPTS = " + std::to_string(npts) +
                                  " (first extra value on this line)");
  }
  if (found < npts) {
    fail_at(file, lines.size(), "fewer values than NPTS: found " + std::to_string(found) +
                                    ", expected NPTS = " + std::to_string(npts));
  }
  check_sampling(file, 4, header.dt_s, accel_m_s2.size());
  return GroundMotion(record_name(file), header.dt_s, std::move(accel_m_s2));
}

/// What a file says about itself, from its text (AT2) or its name.
RecordMetadata metadata_from_text(const RecordFileSpec& spec, const std::string& text) {
  RecordMetadata meta;
  meta.rsn = rsn_of(spec.path);
  if (spec.format != RecordFormat::kAt2) return meta;
  const auto lines = split_lines(text);
  if (lines.size() < 2) return meta;
  meta.title = printable(trim(lines[1]));
  // "Event, date, station, component" (NGA-West2) or "Event, year, station, component (note)".
  std::vector<std::string> parts;
  std::string_view rest = lines[1];
  for (int k = 0; k < 3; ++k) {
    const auto comma = rest.find(',');
    if (comma == std::string_view::npos) break;
    parts.emplace_back(trim(rest.substr(0, comma)));
    rest = rest.substr(comma + 1);
  }
  parts.emplace_back(trim(rest));
  if (parts.size() >= 3) {
    meta.event = printable(parts.front());
    meta.station = printable(parts[parts.size() - 2]);
    std::vector<std::string_view> words;
    split_whitespace(parts.back(), words);  // the component is the last field's first word
    if (!words.empty()) meta.component = printable(words.front());
  }
  return meta;
}

}  // namespace

std::string sampling_problem(double dt_s, std::size_t samples) {
  if (!(dt_s >= kMinDt_s && dt_s <= kMaxDt_s)) {
    std::ostringstream text;
    text << "sample interval " << number_text(dt_s) << " s is outside the range of ground-motion records (" << kMinDt_s
         << " to " << kMaxDt_s << " s)";
    return text.str();
  }
  if (samples < 2) return "a record needs at least 2 samples, found " + std::to_string(samples);
  return {};
}

GroundMotion read_at2(const std::filesystem::path& file) { return at2_from_text(file, read_text(file)); }

GroundMotion read_two_column(const std::filesystem::path& file, AccelUnit unit, std::size_t skip_rows) {
  const std::string text = read_text(file);
  const std::vector<std::string_view> lines = split_lines(text);
  const double factor = to_m_s2(unit);

  std::vector<double> accel_m_s2;
  std::vector<std::string_view> fields;
  TimeStepCheck steps(file);
  check_skip(file, skip_rows, lines.size());
  for (std::size_t i = skip_rows; i < lines.size(); ++i) {
    const std::size_t line_number = i + 1;
    split_fields(file, line_number, lines[i], fields);
    if (fields.empty()) continue;  // blank or comment line
    if (fields.size() != 2) {
      fail_at(file, line_number, "expected 2 columns (time, acceleration), found " +
                                     std::to_string(fields.size()));
    }
    steps.add(parse_value(file, line_number, fields[0]), line_number);
    accel_m_s2.push_back(to_m_s2_checked(file, line_number, parse_value(file, line_number, fields[1]), factor, fields[1]));
  }
  if (steps.rows() < 2) {
    fail_at(file, std::max<std::size_t>(lines.size(), 1),
            "need at least 2 data rows to find the time step, found " +
                std::to_string(steps.rows()));
  }
  check_sampling(file, lines.size(), steps.dt_s(), accel_m_s2.size());
  return GroundMotion(record_name(file), steps.dt_s(), std::move(accel_m_s2));
}

GroundMotion read_one_column(const std::filesystem::path& file, double dt_s, AccelUnit unit, std::size_t skip_rows,
                             std::size_t column) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    fail_file(file, "one-column record needs dt_s > 0, got " + number_text(dt_s));
  }
  const std::string text = read_text(file);
  const std::vector<std::string_view> lines = split_lines(text);
  const double factor = to_m_s2(unit);

  std::vector<double> accel_m_s2;
  std::vector<std::string_view> fields;
  check_skip(file, skip_rows, lines.size());
  for (std::size_t i = skip_rows; i < lines.size(); ++i) {
    split_fields(file, i + 1, lines[i], fields);
    if (column > 0 && !fields.empty()) {
      if (fields.size() < column)
        fail_at(file, i + 1, "column " + std::to_string(column) + " asked for, but the row has " +
                                 std::to_string(fields.size()) + " field" + (fields.size() == 1 ? "" : "s"));
      fields = {fields[column - 1]};
    }
    for (std::string_view field : fields) {
      accel_m_s2.push_back(to_m_s2_checked(file, i + 1, parse_value(file, i + 1, field), factor, field));
    }
  }
  if (accel_m_s2.empty()) {
    fail_at(file, std::max<std::size_t>(lines.size(), 1), "no values in file");
  }
  check_sampling(file, lines.size(), dt_s, accel_m_s2.size());
  return GroundMotion(record_name(RecordFileSpec{file, RecordFormat::kOneColumn, unit, dt_s, skip_rows, column}), dt_s,
                      std::move(accel_m_s2));
}

GroundMotion read_record(const RecordFileSpec& spec) {
  switch (spec.format) {
    case RecordFormat::kAt2:
      if (spec.skip_rows > 0) fail_file(spec.path, "skip_rows applies to text records only (.AT2 has its header)");
      if (spec.column > 0) fail_file(spec.path, "column applies to one-column records only");
      return read_at2(spec.path);
    case RecordFormat::kTwoColumn:
      if (spec.column > 0) fail_file(spec.path, "column applies to one-column records only");
      return read_two_column(spec.path, spec.unit, spec.skip_rows);
    case RecordFormat::kOneColumn:
      return read_one_column(spec.path, spec.dt_s, spec.unit, spec.skip_rows, spec.column);
  }
  fail_file(spec.path, "invalid RecordFormat value");
}

std::string record_name(const RecordFileSpec& spec) {
  const std::string stem = record_name(spec.path);
  return spec.column > 0 ? stem + "_col" + std::to_string(spec.column) : stem;
}

RecordMetadata read_metadata(const RecordFileSpec& spec) {
  if (spec.format != RecordFormat::kAt2) return metadata_from_text(spec, {});
  return metadata_from_text(spec, read_text(spec.path));
}

namespace {

/// `text` in upper case with its runs of spaces as one, for comparing header fields.
std::string header_key(const std::string& text) {
  std::string key;
  for (const char c : text) {
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!key.empty() && key.back() != ' ') key += ' ';
    } else {
      key += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
  }
  if (!key.empty() && key.back() == ' ') key.pop_back();
  return key;
}

}  // namespace

std::string different_station(const ComponentHeader& a, const ComponentHeader& b) {
  const RecordMetadata &x = a.metadata, &y = b.metadata;
  if (x.event.empty() || y.event.empty() || x.station.empty() || y.station.empty()) return {};
  const bool same_event = header_key(x.event) == header_key(y.event);
  const bool same_station = header_key(x.station) == header_key(y.station);
  if (same_event && same_station) return {};
  const char* what = !same_event && !same_station ? "events and stations" : same_event ? "stations" : "events";
  return a.label + " (" + x.event + ", " + x.station + ") and " + b.label + " (" + y.event + ", " + y.station +
         ") name different " + what + ": the components of one station were expected; check the file names";
}

RecordFile read_record_file(const RecordFileSpec& spec) {
  if (spec.format != RecordFormat::kAt2) return {read_record(spec), metadata_from_text(spec, {})};
  if (spec.skip_rows > 0) fail_file(spec.path, "skip_rows applies to text records only (.AT2 has its header)");
  const std::string text = read_text(spec.path);  // once, for both
  return {at2_from_text(spec.path, text), metadata_from_text(spec, text)};
}

}  // namespace pcrf
