// A hazard curve from CSV (see hazard_file.hpp).
#include "pcrf/hazard/hazard_file.hpp"

#include "pcrf/user_error.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <system_error>
#include <vector>

#include "pcrf/byte_order_mark.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/printable.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/units.hpp"

namespace pcrf::hazard {
namespace {

constexpr const char* kRateColumn = "annual_rate_per_yr";

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

/// A whole field as a finite number, or nullopt.
std::optional<double> number(const std::string& text) {
  const std::string t = trim(text);
  if (t.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// A unit a curve's intensities may have been written in, and the factor to the measure's.
struct ReadingAs {
  const char* unit;
  double to_measure;  ///< value in `unit` × this = value in the measure's units (g or m/s)
};

/// What a value read under an acceleration header (in g) may have been written in, and
/// the same for a velocity header (in m/s).
constexpr ReadingAs kAccelerationUnits[] = {{"cm/s2", 1.0 / (100.0 * kGravity_m_s2)},
                                            {"m/s2", 1.0 / kGravity_m_s2},
                                            {"% g", 0.01}};
constexpr ReadingAs kVelocityUnits[] = {{"cm/s", 0.01}, {"mm/s", 0.001}};

std::string four_digits(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

/// "is it in cm/s2 (3 g) or % g (29.4 g)?": each unit under which the largest intensity
/// would be one a hazard curve can end at, or what else to check.
std::string likely_units(double largest, bool velocity) {
  const double most = velocity ? kMaxHazardVelocity_m_s : kMaxHazardAcceleration_g;
  const double least = velocity ? kLeastHazardEnd_m_s : kLeastHazardEnd_g;
  const char* units = velocity ? "m/s" : "g";
  std::string guesses;
  auto consider = [&](const ReadingAs& r) {
    const double as = largest * r.to_measure;
    if (as > most || as < least) return;
    guesses += std::string(guesses.empty() ? "" : " or ") + r.unit + " (" + four_digits(as) + " " + units + ")";
  };
  if (velocity)
    for (const auto& r : kVelocityUnits) consider(r);
  else
    for (const auto& r : kAccelerationUnits) consider(r);
  return guesses.empty() ? "check its units" : "is it in " + guesses + "? convert it to " + units;
}

}  // namespace

std::vector<UserError> hazard_warnings(const HazardFile& hazard, std::size_t first_row, std::size_t last_row) {
  std::vector<UserError> warnings;
  const auto& x = hazard.curve.intensities();
  const auto& rates = hazard.curve.rates_per_yr();
  const std::string file = hazard.file.string();
  bool velocity = false;
  try {
    velocity = intensity_units(parse_intensity_measure(hazard.measure)) == "m/s";
  } catch (const std::invalid_argument&) {
    return warnings;  // the header's measure is checked where it is read
  }
  const double most = velocity ? kMaxHazardVelocity_m_s : kMaxHazardAcceleration_g;
  if (x.back() > most)
    warnings.emplace_back(Where{{}, file, static_cast<int>(last_row)},
                          "the largest intensity, " + four_digits(x.back()) + " " + (velocity ? "m/s" : "g") +
                              ", is beyond any " + hazard.measure + " (at most " + four_digits(most) + " " +
                              (velocity ? "m/s" : "g") + " on a hazard curve): " + likely_units(x.back(), velocity));
  // Every rate at most 1, the first close to it: the saturation of a probability of
  // exceedance in a period (OpenQuake's poe over its investigation_time), not an annual rate.
  if (rates.front() >= kProbabilityLikeRate_per_yr && rates.front() <= 1.0)
    warnings.emplace_back(Where{{}, file, static_cast<int>(first_row)},
                          "the rates start at " + four_digits(rates.front()) + " /yr and never exceed 1: if the column "
                          "holds probabilities of exceedance over a period of T years (e.g. 50), give annual rates, "
                          "-ln(1 - p)/T, under " + std::string(kRateColumn));
  return warnings;
}

namespace {

class Reader {
 public:
  explicit Reader(std::filesystem::path file) : file_(std::move(file)) {}

  [[noreturn]] void fail(std::size_t line, const std::string& problem) const {
    throw UserError(Where{{}, file_.string(), static_cast<int>(line)}, problem);
  }

  /// `# period_s = 1.0`: the period of an sa measure.
  void comment(const std::string& text, std::size_t line) {
    std::string body = trim(text.substr(1));
    const auto eq = body.find('=');
    if (eq == std::string::npos || trim(body.substr(0, eq)) != "period_s") return;
    if (header_) fail(line, "# period_s must come before the header line");
    const auto v = number(body.substr(eq + 1));
    if (!v || !(*v > 0.0)) fail(line, "period_s must be a positive number of seconds, not '" + printable(trim(body.substr(eq + 1))) + "'");
    period_ = *v;
  }

  void header(const std::string& text, std::size_t line) {
    const auto comma = text.find(',');
    const std::string first = trim(text.substr(0, comma));
    const std::string second = comma == std::string::npos ? "" : trim(text.substr(comma + 1));
    try {
      (void)parse_intensity_measure(first);
    } catch (const std::invalid_argument&) {
      fail(line, "the header's first column must name the intensity measure as a study spells it (pga_g, pgv_m_s, "
                 "sa_g, …), not '" + printable(first) + "'");
    }
    if (second != kRateColumn)
      fail(line, "the header's second column must be " + std::string(kRateColumn) + ", not '" + printable(second) + "'");
    if (first.rfind("sa_", 0) == 0 && !period_) fail(line, "an sa measure needs a '# period_s = …' line before the header");
    measure_ = first;
    header_ = line;
  }

  void row(const std::string& text, std::size_t line) {
    const auto comma = text.find(',');
    if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos)
      fail(line, "expected two fields, intensity,annual_rate_per_yr");
    const auto x = number(text.substr(0, comma)), rate = number(text.substr(comma + 1));
    if (!x) fail(line, "the intensity is not a number: '" + printable(trim(text.substr(0, comma))) + "'");
    if (!rate) fail(line, "the rate is not a number: '" + printable(trim(text.substr(comma + 1))) + "'");
    if (!(*x > 0.0)) fail(line, "the intensity must be positive");
    if (!(*rate > 0.0)) fail(line, "the annual rate must be positive (a rate of 0 has no logarithm: end the curve before it)");
    if (!x_.empty() && !(*x > x_.back())) fail(line, "intensities must increase (the line before has " + number_text(x_.back()) + ")");
    if (!rate_.empty() && !(*rate < rate_.back()))
      fail(line, "the curve is not decreasing: the rate must fall as the intensity grows (the line before has " +
                     number_text(rate_.back()) + " /yr)");
    if (x_.size() >= kMaxHazardPoints)
      fail(line, "more than " + std::to_string(kMaxHazardPoints) + " points: a hazard curve has tens (thin it out)");
    x_.push_back(*x);
    rate_.push_back(*rate);
    if (!first_row_) first_row_ = line;
    last_row_ = line;
  }

  HazardFile finish(risk::Tail tail) const {
    if (!header_) fail(0, "no header line (e.g. pga_g,annual_rate_per_yr)");
    if (x_.size() < 2) fail(0, "a hazard curve needs at least two points");
    HazardFile read{file_, measure_, period_, *header_, risk::HazardCurve(x_, rate_, tail), {}};
    read.warnings = hazard_warnings(read, first_row_.value_or(0), last_row_.value_or(0));
    return read;
  }

  bool has_header() const { return header_.has_value(); }

 private:
  std::filesystem::path file_;
  std::optional<std::size_t> header_;
  std::optional<double> period_;
  std::string measure_;
  std::vector<double> x_, rate_;
  std::optional<std::size_t> first_row_, last_row_;
};

}  // namespace

HazardFile read_hazard_file(const std::filesystem::path& file, risk::Tail tail) {
  Reader reader(file);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) reader.fail(0, "no such file");
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) reader.fail(0, "cannot read its size: " + ec.message());
  if (size > kMaxHazardFileBytes) reader.fail(0, "larger than " + std::to_string(kMaxHazardFileBytes >> 20) + " MiB: not a hazard curve");
  std::ifstream in(file);
  if (!in) reader.fail(0, "cannot open it");
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (number == 1) {
      if (starts_as_utf16(line)) reader.fail(1, "UTF-16 text; save it as ASCII or UTF-8");
      line = std::string(without_byte_order_mark(line));  // a spreadsheet's "CSV UTF-8"
    }
    const std::string text = trim(line);
    if (text.empty()) continue;
    if (text[0] == '#') reader.comment(text, number);
    else if (!reader.has_header()) reader.header(text, number);
    else reader.row(text, number);
  }
  if (in.bad()) reader.fail(0, "read error");
  return reader.finish(tail);
}

}  // namespace pcrf::hazard
