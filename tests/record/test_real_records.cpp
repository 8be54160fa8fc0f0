/// \file test_real_records.cpp
/// \brief The readers on the real PEER records in ../shared/records (never copied into the
/// repository): every .AT2 file against its own header and against MANIFEST.csv /
/// paper/INDEX.csv, and the two-column FEMA P695 and NGA-West2 sets against MANIFEST.csv.
/// Skips cleanly when the folder is absent.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "pcrf/record/record_readers.hpp"
#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using pcrf::GroundMotion;
using pcrf::kGravity_m_s2;

// ---- reading the index files ------------------------------------------------------------

using CsvRow = std::map<std::string, std::string>;

/// Minimal RFC-4180 reader: quoted fields may hold commas and doubled quotes.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1);
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') field += text[++i];
      else if (c == '"') quoted = false;
      else field += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      rows.back().push_back(std::move(field));
      field.clear();
    } else if (c == '\n') {
      rows.back().push_back(std::move(field));
      field.clear();
      rows.emplace_back();
    } else if (c != '\r') {
      field += c;
    }
  }
  if (!field.empty() || !rows.back().empty()) rows.back().push_back(std::move(field));
  if (rows.back().empty()) rows.pop_back();
  return rows;
}

std::vector<CsvRow> read_csv(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  const auto rows = parse_csv(text.str());
  std::vector<CsvRow> out;
  if (rows.empty()) return out;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    EXPECT_EQ(rows[r].size(), rows[0].size()) << file << " row " << r;
    CsvRow row;
    for (std::size_t c = 0; c < rows[0].size() && c < rows[r].size(); ++c) row[rows[0][c]] = rows[r][c];
    out.push_back(std::move(row));
  }
  return out;
}

/// What an index file says about one record file.
struct Expected {
  std::size_t npts = 0;
  double dt_s = 0.0;
  double pga_g = 0.0;
  double time_of_pga_s = 0.0;
  std::string listed_in;
};

Expected expected_from(const CsvRow& row, const std::string& listed_in) {
  Expected e;
  e.npts = std::stoul(row.at("npts"));
  e.dt_s = std::stod(row.at("dt_s"));
  e.pga_g = std::stod(row.at("pga_g"));
  e.time_of_pga_s = std::stod(row.at("time_of_pga_s"));
  e.listed_in = listed_in;
  return e;
}

/// Expected values keyed by path relative to the records folder ("paper/ER1_MUL279.AT2").
/// MANIFEST.csv lists the fema/ngawest2/peer files; paper/INDEX.csv lists the paper/ files
/// (its ER12/ER20 rows point at peer files and leave the numbers empty: MANIFEST has them).
std::map<std::string, Expected> expected_by_file(const fs::path& records) {
  std::map<std::string, Expected> out;
  for (const CsvRow& row : read_csv(records / "MANIFEST.csv")) {
    out[row.at("file")] = expected_from(row, "MANIFEST.csv");
  }
  for (const CsvRow& row : read_csv(records / "paper" / "INDEX.csv")) {
    if (row.at("npts").empty()) continue;
    const std::string& file = row.at("file");
    EXPECT_EQ(out.count(file), 0u) << file << " listed twice";
    out[file] = expected_from(row, "paper/INDEX.csv");
  }
  return out;
}

std::vector<fs::path> files_in(const fs::path& dir, const std::string& lower_extension) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && ext == lower_extension) out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string relative_key(const fs::path& file, const fs::path& records) {
  return file.lexically_relative(records).generic_string();
}

// ---- independent look at an .AT2 file ------------------------------------------------------

/// NPTS, DT, the data tokens and line 2 of an .AT2 file, read without the library.
struct At2Text {
  std::size_t npts = 0;
  double dt_s = 0.0;
  std::vector<std::string> values;
  std::string title;  // line 2
};

At2Text read_at2_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  At2Text t;
  for (int i = 1; i <= 4 && std::getline(in, line); ++i) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (i == 2) t.title = line;
    if (i != 4) continue;
    std::smatch m;
    static const std::regex west2(R"(NPTS\s*=\s*(\d+)\s*,\s*DT\s*=\s*([0-9.Ee+-]+))");
    static const std::regex older(R"(^\s*(\d+)\s+([0-9.Ee+-]+)\s+NPTS)");
    if (std::regex_search(line, m, west2) || std::regex_search(line, m, older)) {
      t.npts = std::stoul(m[1].str());
      t.dt_s = std::stod(m[2].str());
    }
  }
  std::string token;
  while (in >> token) t.values.push_back(token);
  return t;
}

// ---- checks ---------------------------------------------------------------------------------

/// PGA to the 4 decimals the index gives, time of PGA to the sample. `leading_samples` is the
/// number of samples the file has before the index's sample 0 (the FEMA converter's extra 0.0).
void expect_pga(const GroundMotion& g, const Expected& e, std::size_t leading_samples) {
  const auto& a = g.samples_m_s2();
  const auto peak = std::max_element(a.begin(), a.end(),
                                     [](double x, double y) { return std::abs(x) < std::abs(y); });
  const auto index = static_cast<std::size_t>(peak - a.begin());
  EXPECT_EQ(g.pga_m_s2(), std::abs(*peak));
  EXPECT_NEAR(g.pga_m_s2() / kGravity_m_s2, e.pga_g, 0.5e-4 + 1e-9) << "PGA vs " << e.listed_in;
  ASSERT_GE(index, leading_samples);
  const double time_of_pga_s = static_cast<double>(index - leading_samples) * g.dt_s();
  EXPECT_NEAR(time_of_pga_s, e.time_of_pga_s, 0.5 * g.dt_s()) << "time of PGA vs " << e.listed_in;
  // The engine's own clock agrees: a(t_pga) is the peak sample itself.
  EXPECT_EQ(g.accel_m_s2(static_cast<double>(index) * g.dt_s()), *peak);
}

/// The folders an index file names, each with the number of its files the index lists.
std::map<std::string, std::size_t> listed_per_folder(const std::map<std::string, Expected>& expected,
                                                     const std::string& lower_extension) {
  std::map<std::string, std::size_t> out;
  for (const auto& [key, e] : expected) {
    const fs::path file(key);
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext == lower_extension) ++out[file.parent_path().generic_string()];
  }
  return out;
}

TEST(RealRecords, EveryAt2FileMatchesItsHeaderAndTheIndex) {
  PCRF_REQUIRE_RECORDS(records);
  const auto expected = expected_by_file(records);
  const auto listed = listed_per_folder(expected, ".at2");
  ASSERT_FALSE(listed.empty()) << "the index lists no .AT2 file";
  std::size_t checked = 0;
  for (const auto& [folder, count] : listed) {
    const auto files = files_in(records / folder, ".at2");
    // Every .AT2 file of a folder the index names is listed in it, and the other way round.
    EXPECT_EQ(files.size(), count) << folder;
    for (const fs::path& file : files) {
      const std::string key = relative_key(file, records);
      SCOPED_TRACE(key);
      const GroundMotion g = pcrf::read_at2(file);
      const At2Text text = read_at2_text(file);
      ASSERT_GT(text.npts, 0u) << "test could not read the header itself";
      EXPECT_EQ(g.name(), file.stem().string());
      EXPECT_EQ(g.size(), text.npts);
      EXPECT_EQ(g.dt_s(), text.dt_s);
      EXPECT_EQ(text.values.size(), text.npts) << "file's own value count";
      EXPECT_EQ(g.samples_m_s2().front(), std::strtod(text.values.front().c_str(), nullptr) * kGravity_m_s2);
      EXPECT_EQ(g.samples_m_s2().back(), std::strtod(text.values.back().c_str(), nullptr) * kGravity_m_s2);

      const auto it = expected.find(key);
      ASSERT_NE(it, expected.end()) << "not listed in MANIFEST.csv or paper/INDEX.csv";
      EXPECT_EQ(g.size(), it->second.npts);
      EXPECT_NEAR(g.dt_s(), it->second.dt_s, 1e-12);
      expect_pga(g, it->second, 0);
      ++checked;
    }
  }
  std::size_t listed_total = 0;
  for (const auto& [folder, count] : listed) listed_total += count;
  EXPECT_EQ(checked, listed_total) << "every .AT2 file the index lists was found and checked";
}

TEST(RealRecords, FemaP695TwoColumnFiles) {
  PCRF_REQUIRE_RECORDS(records);
  const auto expected = expected_by_file(records);
  const auto files = files_in(records / "fema_p695_ff_sorted_hadi", ".txt");
  EXPECT_EQ(files.size(), listed_per_folder(expected, ".txt")["fema_p695_ff_sorted_hadi"]);
  for (const fs::path& file : files) {
    const std::string key = relative_key(file, records);
    SCOPED_TRACE(key);
    const GroundMotion g = pcrf::read_two_column(file, pcrf::AccelUnit::kG);
    const auto it = expected.find(key);
    ASSERT_NE(it, expected.end()) << "not in MANIFEST.csv";
    EXPECT_NEAR(g.dt_s(), it->second.dt_s, 1e-9 * it->second.dt_s);
    // The converter that wrote these files put an extra 0.0 row at t = 0 in front of the
    // series (README.md): the file has NPTS + 1 rows and original sample k is row k + 1.
    EXPECT_EQ(g.size(), it->second.npts + 1);
    EXPECT_EQ(g.samples_m_s2().front(), 0.0);
    expect_pga(g, it->second, 1);
  }
}

TEST(RealRecords, PaperAt2FilesAreTheFemaSeriesWithoutTheLeadingZero) {
  PCRF_REQUIRE_RECORDS(records);
  const auto files = files_in(records / "paper", ".at2");
  ASSERT_FALSE(files.empty());
  static const std::regex source(R"(SortedEQFile_\(\d+\)\.txt)");
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    std::smatch m;
    const std::string title = read_at2_text(file).title;
    ASSERT_TRUE(std::regex_search(title, m, source)) << "line 2 names no source file: " << title;
    const GroundMotion at2 = pcrf::read_at2(file);
    const GroundMotion two = pcrf::read_two_column(
        records / "fema_p695_ff_sorted_hadi" / m.str(), pcrf::AccelUnit::kG);
    ASSERT_EQ(two.size(), at2.size() + 1);
    EXPECT_NEAR(two.dt_s(), at2.dt_s(), 1e-9 * at2.dt_s());
    // Same decimal values written two ways ("0.767534E-04" / "7.6753400E-05"): same doubles.
    EXPECT_TRUE(std::equal(at2.samples_m_s2().begin(), at2.samples_m_s2().end(),
                           two.samples_m_s2().begin() + 1));
  }
}

TEST(RealRecords, NgaWest2TwoColumnFiles) {
  PCRF_REQUIRE_RECORDS(records);
  const auto expected = expected_by_file(records);
  std::size_t checked = 0;
  for (const fs::path& file : files_in(records / "ngawest2_ff_youtian95", ".txt")) {
    if (file.filename() == "MetaData.txt") continue;  // a table about the records, not a record
    const std::string key = relative_key(file, records);
    SCOPED_TRACE(key);
    const GroundMotion g = pcrf::read_two_column(file, pcrf::AccelUnit::kG);
    const auto it = expected.find(key);
    ASSERT_NE(it, expected.end()) << "not in MANIFEST.csv";
    EXPECT_EQ(g.size(), it->second.npts);
    EXPECT_NEAR(g.dt_s(), it->second.dt_s, 1e-9 * it->second.dt_s);
    expect_pga(g, it->second, 0);
    ++checked;
  }
  EXPECT_EQ(checked, listed_per_folder(expected, ".txt")["ngawest2_ff_youtian95"]);
  EXPECT_GT(checked, 0u);
}

/// Erzincan 1992 (nearfault_lihongweiseu/erzikan.txt, README of the records): N-S and E-W side
/// by side in cm/s², no time column, two '%' header lines; MANIFEST.csv lists it once per
/// column ("ERZ-NS (col 1)"), with npts the rows that hold that component's data (column 2
/// repeats column 1 after row 4155, a defect of the file).
TEST(RealRecords, SideBySideColumnsReadOneComponentEach) {
  PCRF_REQUIRE_RECORDS(records);
  std::size_t checked = 0;
  for (const CsvRow& row : read_csv(records / "MANIFEST.csv")) {
    std::smatch m;
    static const std::regex column_of(R"(\(col (\d+)\))");
    if (!std::regex_search(row.at("component"), m, column_of)) continue;
    SCOPED_TRACE(row.at("file") + " " + row.at("component"));
    pcrf::RecordFileSpec spec;
    spec.path = records / row.at("file");
    spec.format = pcrf::RecordFormat::kOneColumn;
    spec.unit = pcrf::parse_accel_unit(row.at("units"));
    spec.dt_s = std::stod(row.at("dt_s"));
    spec.skip_rows = 2;
    spec.column = std::stoul(m[1].str());
    const GroundMotion g = pcrf::read_record(spec);
    EXPECT_EQ(g.name(), spec.path.stem().string() + "_col" + m[1].str());
    const Expected e = expected_from(row, "MANIFEST.csv");
    ASSERT_GE(g.size(), e.npts);
    const auto first = g.samples_m_s2().begin();
    const auto peak = std::max_element(first, first + static_cast<std::ptrdiff_t>(e.npts),
                                       [](double x, double y) { return std::abs(x) < std::abs(y); });
    EXPECT_NEAR(static_cast<double>(peak - first) * g.dt_s(), e.time_of_pga_s, 0.5 * g.dt_s());
    // The index converted cm/s² to g with a g it does not state, and rounded to 4 decimals:
    // the gravities that map our PGA in cm/s² onto its PGA in g must include a standard one
    // (9.78–9.83 m/s² spans every convention in use).
    const double pga_cm_s2 = std::abs(*peak) * 100.0;
    const double g_low_cm_s2 = pga_cm_s2 / (e.pga_g + 0.5e-4);
    const double g_high_cm_s2 = pga_cm_s2 / (e.pga_g - 0.5e-4);
    EXPECT_GT(g_high_cm_s2, 978.0);
    EXPECT_LT(g_low_cm_s2, 983.0);
    ++checked;
  }
  EXPECT_GT(checked, 0u) << "MANIFEST.csv lists no side-by-side file";
}

}  // namespace
