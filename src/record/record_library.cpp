// Response spectra of a record library, and their table (see record_library.hpp).
#include "pcrf/record/record_library.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "pcrf/number_text.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/rotd.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kFixedColumns{"name", "kind", "file", "file_h2", "dt_s", "samples", "damping", "pga_g"};
const std::string kSaPrefix = "sa_g_";

bool is_at2(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".at2";
}

/// "RSN1063_NORTHR_RRS228" → station "RSN1063_NORTHR", component "RRS228".
std::pair<std::string, std::string> station_and_component(const fs::path& file) {
  const std::string stem = file.stem().string();
  const auto cut = stem.rfind('_');
  if (cut == std::string::npos) return {stem, stem};
  return {stem.substr(0, cut), stem.substr(cut + 1)};
}

/// x to 4 significant digits, as the nearest double to its 4-digit decimal text.
double round_to_4_digits(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", x);
  return std::strtod(text, nullptr);
}

LibraryEntry component_entry(const GroundMotion& m, const fs::path& file, const std::vector<double>& periods_s,
                             double damping) {
  LibraryEntry e{m.name(), "component", file.string(), "", m.dt_s(), m.size(), damping, peak_acceleration(m).pga_g, {}};
  for (double t : periods_s) e.sa_g.push_back(spectral_acceleration_g(m, t, damping));
  return e;
}

LibraryEntry pair_entry(const std::string& station, const HorizontalPair& pair, const fs::path& f1,
                        const fs::path& f2, const std::vector<double>& periods_s, double damping) {
  LibraryEntry e{station, "rotd50", f1.string(), f2.string(), pair.h1.dt_s(), std::max(pair.h1.size(), pair.h2.size()),
                 damping, 0.0, {}};
  e.pga_g = rotd(pair, IntensitySpec{IntensityMeasure::kPgaRotD50, 0.0, damping, SetNormalisation::kNone}).rotd50;
  for (double t : periods_s)
    e.sa_g.push_back(rotd(pair, IntensitySpec{IntensityMeasure::kSaRotD50, t, damping, SetNormalisation::kNone}).rotd50);
  return e;
}

// ---- CSV ----------------------------------------------------------------------------------

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') field += line[++i];
      else if (c == '"') quoted = false;
      else field += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.push_back(std::move(field));
      field.clear();
    } else if (c != '\r') {
      field += c;
    }
  }
  fields.push_back(std::move(field));
  return fields;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::optional<double> parse_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value)) return std::nullopt;
  return value;
}

[[noreturn]] void fail(const std::string& file, int line, const std::string& key, const std::string& problem) {
  throw UserError(Where{{key}, file, line}, problem);
}

std::vector<double> header_periods(const std::vector<std::string>& header, const std::string& file, int line) {
  for (std::size_t c = 0; c < kFixedColumns.size(); ++c)
    if (c >= header.size() || header[c] != kFixedColumns[c])
      fail(file, line, c < header.size() ? header[c] : "header",
           "column " + std::to_string(c + 1) + " must be '" + kFixedColumns[c] + "' (a table of pcrf record spectra)");
  std::vector<double> periods;
  for (std::size_t c = kFixedColumns.size(); c < header.size(); ++c) {
    const std::string& name = header[c];
    const bool named = name.size() > kSaPrefix.size() + 1 && name.rfind(kSaPrefix, 0) == 0 && name.back() == 's';
    const auto t = named ? parse_number(name.substr(kSaPrefix.size(), name.size() - kSaPrefix.size() - 1)) : std::nullopt;
    if (!t || *t <= 0.0) fail(file, line, name, "is not a spectral column 'sa_g_<period>s' with a positive period");
    if (!periods.empty() && *t <= periods.back())
      fail(file, line, name, "periods must increase (" + number_text(*t) + " s after " + number_text(periods.back()) + " s)");
    periods.push_back(*t);
  }
  if (periods.empty()) fail(file, line, "header", "the table has no Sa columns");
  return periods;
}

double positive_field(const std::vector<std::string>& row, std::size_t c, const std::vector<std::string>& header,
                      const std::string& file, int line, bool allow_zero) {
  const auto v = parse_number(row[c]);
  if (!v || *v < 0.0 || (!allow_zero && *v == 0.0))
    fail(file, line, header[c], "'" + row[c] + "' is not a " + (allow_zero ? "non-negative" : "positive") + " finite number");
  return *v;
}

}  // namespace

std::vector<double> default_spectra_periods_s() {
  std::vector<double> periods;
  constexpr int kCount = 30;
  for (int i = 0; i < kCount; ++i)
    periods.push_back(round_to_4_digits(0.05 * std::pow(10.0 / 0.05, static_cast<double>(i) / (kCount - 1))));
  return periods;
}

std::string periods_problem(const std::vector<double>& periods_s) {
  if (periods_s.empty()) return "no periods given";
  for (std::size_t i = 0; i < periods_s.size(); ++i) {
    if (const std::string p = sa_period_problem(periods_s[i], 0.0); !p.empty()) return p;
    if (i > 0 && periods_s[i] <= periods_s[i - 1])
      return "periods must increase (" + number_text(periods_s[i]) + " s after " + number_text(periods_s[i - 1]) + " s)";
  }
  return "";
}

std::vector<fs::path> library_files(const std::vector<fs::path>& paths, std::vector<std::string>& skipped) {
  std::vector<fs::path> found;
  for (const auto& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      for (fs::recursive_directory_iterator it(p, fs::directory_options::skip_permission_denied, ec), end; it != end;
           it.increment(ec)) {
        if (ec) break;
        if (it->is_regular_file(ec) && is_at2(it->path())) found.push_back(it->path());
      }
    } else if (fs::is_regular_file(p, ec)) {
      found.push_back(p);
    } else {
      throw UserError(p.string() + ": no such file or folder");
    }
  }
  std::sort(found.begin(), found.end());
  std::set<std::string> names;
  std::vector<fs::path> unique;
  for (const auto& f : found) {
    if (names.insert(f.filename().string()).second) unique.push_back(f);
    else skipped.push_back(f.string() + ": left out, a file of the same name is already in the library");
  }
  return unique;
}

SpectraTable compute_spectra(const std::vector<fs::path>& files, const std::vector<double>& periods_s, double damping,
                             std::vector<std::string>& skipped,
                             const std::function<void(std::size_t, std::size_t, const std::string&)>& progress) {
  if (const std::string p = periods_problem(periods_s); !p.empty()) throw UserError("periods_s", p, {"periods_s"});
  if (!(damping >= 0.0 && damping < 1.0)) throw UserError("damping", "must be in [0, 1)", {"damping"});
  SpectraTable table{periods_s, {}};
  // Stations: files of one folder whose names differ only in the component.
  struct Component {
    fs::path file;
    GroundMotion motion;
    double az_deg;
  };
  std::map<std::string, std::vector<Component>> stations;
  std::vector<std::string> order;
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (progress) progress(i, files.size(), files[i].string());
    const auto [station, component] = station_and_component(files[i]);
    if (is_vertical_component(component)) continue;
    try {
      GroundMotion m = read_at2(files[i]);
      if (const std::string p = sa_period_problem(periods_s.front(), m.dt_s()); !p.empty()) {
        skipped.push_back(files[i].string() + ": left out: " + p);
        continue;
      }
      table.entries.push_back(component_entry(m, files[i], periods_s, damping));
      const auto az = azimuth_of_component(component);
      const std::string key = (files[i].parent_path() / station).string();
      if (!stations.count(key)) order.push_back(key);
      stations[key].push_back(Component{files[i], std::move(m), az ? *az : std::nan("")});
    } catch (const UserError& e) {
      skipped.push_back(files[i].string() + ": left out: " + e.what());
    }
  }
  if (progress) progress(files.size(), files.size(), "");
  for (const auto& key : order) {
    const auto& c = stations[key];
    if (c.size() != 2 || std::isnan(c[0].az_deg) || std::isnan(c[1].az_deg)) continue;
    try {
      const HorizontalPair pair{c[0].motion, c[0].az_deg, c[1].motion, c[1].az_deg};
      table.entries.push_back(pair_entry(fs::path(key).filename().string(), pair, c[0].file, c[1].file, periods_s, damping));
    } catch (const UserError& e) {
      skipped.push_back(c[0].file.string() + " and " + c[1].file.filename().string() + ": no RotD50: " + e.what());
    }
  }
  return table;
}

void write_spectra_csv(std::ostream& out, const SpectraTable& table) {
  out << "# pcrf record spectra: pseudo-spectral acceleration Sa [g] of each record (kind component) and the\n"
         "# RotD50 of each horizontal pair (kind rotd50, Boore 2010), exact for the piecewise-linear record.\n";
  for (std::size_t c = 0; c < kFixedColumns.size(); ++c) out << (c ? "," : "") << kFixedColumns[c];
  for (double t : table.periods_s) out << ',' << kSaPrefix << number_text(t) << 's';
  out << '\n';
  for (const auto& e : table.entries) {
    out << csv_field(e.name) << ',' << e.kind << ',' << csv_field(e.file) << ',' << csv_field(e.file_h2) << ','
        << number_text(e.dt_s) << ',' << e.samples << ',' << number_text(e.damping) << ',' << number_text(e.pga_g);
    for (double sa : e.sa_g) out << ',' << number_text(sa);
    out << '\n';
  }
}

SpectraTable read_spectra_csv(std::istream& in, const std::string& file) {
  SpectraTable table;
  std::vector<std::string> header;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#' || line == "\r") continue;
    std::vector<std::string> row = split_csv_line(line);
    if (header.empty()) {
      header = std::move(row);
      table.periods_s = header_periods(header, file, number);
      continue;
    }
    if (row.size() != header.size())
      fail(file, number, "row", "has " + std::to_string(row.size()) + " fields, the header " + std::to_string(header.size()));
    LibraryEntry e;
    e.name = row[0];
    e.kind = row[1];
    if (e.kind != "component" && e.kind != "rotd50") fail(file, number, "kind", "'" + e.kind + "' is not component or rotd50");
    e.file = row[2];
    e.file_h2 = row[3];
    if (e.file.empty()) fail(file, number, "file", "is empty");
    e.dt_s = positive_field(row, 4, header, file, number, false);
    const double samples = positive_field(row, 5, header, file, number, false);
    if (samples != std::floor(samples) || samples > 1e12) fail(file, number, "samples", "'" + row[5] + "' is not a whole number of samples");
    e.samples = static_cast<std::size_t>(samples);
    e.damping = positive_field(row, 6, header, file, number, true);
    e.pga_g = positive_field(row, 7, header, file, number, true);
    for (std::size_t c = kFixedColumns.size(); c < row.size(); ++c)
      e.sa_g.push_back(positive_field(row, c, header, file, number, false));
    table.entries.push_back(std::move(e));
  }
  if (header.empty()) fail(file, number, "header", "the file has no header row (is it a table of pcrf record spectra?)");
  return table;
}

}  // namespace pcrf
