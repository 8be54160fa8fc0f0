/// \file test_text_readers.cpp
/// \brief Two-column and one-column text records, unit and format parsing, and the errors
/// for malformed text files (file and line named).

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "pcrf/record/record_readers.hpp"
#include "support/test_support.hpp"

namespace {

using pcrf::test::write_file;

using pcrf::AccelUnit;
using pcrf::kGravity_m_s2;
using pcrf::UserError;

template <typename Read>
std::string record_error(Read&& read) {
  try {
    (void)read();
  } catch (const UserError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no UserError";
  return "";
}

TEST(AccelUnit, ParsesEveryDocumentedSpelling) {
  EXPECT_EQ(pcrf::parse_accel_unit("g"), AccelUnit::kG);
  EXPECT_EQ(pcrf::parse_accel_unit("G"), AccelUnit::kG);
  for (const char* s : {"m/s2", "m/s^2", "mps2", " M/S2 "}) {
    EXPECT_EQ(pcrf::parse_accel_unit(s), AccelUnit::kMeterPerSecond2) << s;
  }
  for (const char* s : {"cm/s2", "cm/s^2", "gal", "Gal"}) {
    EXPECT_EQ(pcrf::parse_accel_unit(s), AccelUnit::kCentimeterPerSecond2) << s;
  }
  for (const char* s : {"", "gg", "m/s", "mm/s2", "cm"}) {
    EXPECT_THROW(pcrf::parse_accel_unit(s), std::invalid_argument) << s;
  }
  try {
    pcrf::parse_accel_unit("furlongs");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("furlongs"), std::string::npos);
  }
}

TEST(AccelUnit, ConversionFactors) {
  EXPECT_EQ(pcrf::to_m_s2(AccelUnit::kG), kGravity_m_s2);
  EXPECT_EQ(pcrf::to_m_s2(AccelUnit::kG), 9.81);
  EXPECT_EQ(pcrf::to_m_s2(AccelUnit::kMeterPerSecond2), 1.0);
  EXPECT_EQ(pcrf::to_m_s2(AccelUnit::kCentimeterPerSecond2), 0.01);
}

TEST(RecordFormat, ParsesNames) {
  EXPECT_EQ(pcrf::parse_record_format("at2"), pcrf::RecordFormat::kAt2);
  EXPECT_EQ(pcrf::parse_record_format("AT2"), pcrf::RecordFormat::kAt2);
  EXPECT_EQ(pcrf::parse_record_format("two-column"), pcrf::RecordFormat::kTwoColumn);
  EXPECT_EQ(pcrf::parse_record_format("one-column"), pcrf::RecordFormat::kOneColumn);
  try {
    pcrf::parse_record_format("csv");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("csv"), std::string::npos);
  }
}

TEST(ReadTwoColumn, WhitespaceCommasCommentsAndBlankLines) {
  const auto dir = pcrf::test::scratch_dir("two_col_ok");
  const auto file = write_file(dir, "mixed.txt",
                               "# time [s], acceleration [g]\n"
                               "\n"
                               "0.00 0.10\n"
                               "0.01,\t-0.20\n"
                               "   # indented comment\n"
                               "0.02 , 0.30   # trailing comment\r\n"
                               "0.03\t\t-4.0E-01\n"
                               "\n");
  const auto g = pcrf::read_two_column(file, AccelUnit::kG);
  EXPECT_EQ(g.name(), "mixed");
  EXPECT_NEAR(g.dt_s(), 0.01, 1e-15);
  const std::vector<double> expected_g = {0.10, -0.20, 0.30, -0.40};
  ASSERT_EQ(g.size(), expected_g.size());
  for (std::size_t i = 0; i < expected_g.size(); ++i) {
    EXPECT_DOUBLE_EQ(g.samples_m_s2()[i], expected_g[i] * kGravity_m_s2);
  }
}

TEST(ReadTwoColumn, UnitsAreConverted) {
  const auto dir = pcrf::test::scratch_dir("two_col_units");
  const auto file = write_file(dir, "units.csv", "0,1.5\n0.02,-3\n0.04,250\n");
  const auto in_g = pcrf::read_two_column(file, AccelUnit::kG);
  const auto in_m = pcrf::read_two_column(file, AccelUnit::kMeterPerSecond2);
  const auto in_cm = pcrf::read_two_column(file, AccelUnit::kCentimeterPerSecond2);
  const std::vector<double> raw = {1.5, -3.0, 250.0};
  for (std::size_t i = 0; i < raw.size(); ++i) {
    EXPECT_DOUBLE_EQ(in_g.samples_m_s2()[i], raw[i] * 9.81);
    EXPECT_DOUBLE_EQ(in_m.samples_m_s2()[i], raw[i]);
    EXPECT_DOUBLE_EQ(in_cm.samples_m_s2()[i], raw[i] / 100.0);
  }
  EXPECT_NEAR(in_g.dt_s(), 0.02, 1e-15);
}

TEST(ReadTwoColumn, NonZeroStartKeepsSamplesFromTimeZero) {
  // Documented shift: a record starting at t = 5 s is read as if it started at 0.
  const auto dir = pcrf::test::scratch_dir("two_col_shift");
  const auto file = write_file(dir, "late.txt", "5.0 1\n5.5 2\n6.0 3\n");
  const auto g = pcrf::read_two_column(file, AccelUnit::kMeterPerSecond2);
  EXPECT_EQ(g.dt_s(), 0.5);
  EXPECT_EQ(g.accel_m_s2(0.0), 1.0);
  EXPECT_EQ(g.accel_m_s2(1.0), 3.0);
}

TEST(ReadTwoColumn, ToleratesRoundingInTheTimeColumn) {
  // Times written with 4 decimals for dt = 1/300 s wobble by ±0.5e-4 … too much: rejected.
  // Times with 12 decimals wobble by 1e-12 relative: accepted, dt is the mean step.
  const auto dir = pcrf::test::scratch_dir("two_col_rounding");
  std::string fine;
  std::string coarse;
  char line[64];
  for (int i = 0; i < 301; ++i) {
    std::snprintf(line, sizeof line, "%.12f %d\n", i / 300.0, i % 7);
    fine += line;
    std::snprintf(line, sizeof line, "%.4f %d\n", i / 300.0, i % 7);
    coarse += line;
  }
  const auto g = pcrf::read_two_column(write_file(dir, "fine.txt", fine), AccelUnit::kG);
  EXPECT_EQ(g.size(), 301u);
  EXPECT_NEAR(g.dt_s(), 1.0 / 300.0, 1e-14);
  const std::string msg = record_error(
      [&] { return pcrf::read_two_column(write_file(dir, "coarse.txt", coarse), AccelUnit::kG); });
  EXPECT_NE(msg.find("non-uniform time step"), std::string::npos) << msg;
}

struct MalformedText {
  const char* name;
  std::string text;
  int line;
  const char* must_mention;
};

TEST(ReadTwoColumn, MalformedFilesNameFileAndLine) {
  const auto dir = pcrf::test::scratch_dir("two_col_malformed");
  const std::vector<MalformedText> corpus = {
      {"uneven.txt", "0 1\n0.01 2\n0.02 3\n0.035 4\n0.045 5\n", 4, "non-uniform time step"},
      {"uneven_after_comment.txt", "# h\n0 1\n0.01 2\n\n0.03 3\n", 5, "non-uniform time step"},
      {"repeated_time.txt", "0 1\n0.01 2\n0.01 3\n", 3, "does not increase"},
      {"decreasing_time.txt", "0.02 1\n0.01 2\n", 2, "does not increase"},
      {"three_columns.txt", "0 1\n0.01 2 7\n", 2, "found 3"},
      {"one_column.txt", "0 1\n0.01\n", 2, "found 1"},
      {"non_numeric_acc.txt", "0 1\n0.01 x2\n", 2, "'x2'"},
      {"non_numeric_time.txt", "t acc\n0 1\n", 1, "'t'"},
      {"double_comma.txt", "0,1\n0.01,,2\n", 2, "empty field"},
      {"leading_comma.txt", "0,1\n,0.01,2\n", 2, "empty field"},
      {"trailing_comma.txt", "0,1\n0.01,2,\n", 2, "empty field"},
      {"single_row.txt", "# c\n0 1\n", 2, "at least 2 data rows"},
      {"empty.txt", "", 1, "at least 2 data rows"},
      {"comments_only.txt", "# a\n# b\n\n", 3, "found 0"},
      {"nan.txt", "0 1\n0.01 nan\n", 2, "'nan'"},
  };
  for (const auto& m : corpus) {
    const auto file = write_file(dir, m.name, m.text);
    const std::string message =
        record_error([&] { return pcrf::read_two_column(file, AccelUnit::kG); });
    SCOPED_TRACE(std::string(m.name) + ": " + message);
    const std::string where = file.string() + ":" + std::to_string(m.line) + ": ";
    EXPECT_EQ(message.rfind(where, 0), 0u) << "expected prefix " << where;
    EXPECT_NE(message.find(m.must_mention), std::string::npos) << "expected " << m.must_mention;
  }
}

TEST(ReadOneColumn, ValuesOneOrManyPerLine) {
  const auto dir = pcrf::test::scratch_dir("one_col_ok");
  const auto file = write_file(dir, "vals.txt",
                               "# acceleration in cm/s2, dt = 0.01 s\n"
                               "1.5\n"
                               "-2.5, 3.0\r\n"
                               "\n"
                               "4.0E+01 -5 # five\n");
  const auto g = pcrf::read_one_column(file, 0.01, AccelUnit::kCentimeterPerSecond2);
  EXPECT_EQ(g.name(), "vals");
  EXPECT_EQ(g.dt_s(), 0.01);
  const std::vector<double> expected_cm = {1.5, -2.5, 3.0, 40.0, -5.0};
  ASSERT_EQ(g.size(), expected_cm.size());
  for (std::size_t i = 0; i < expected_cm.size(); ++i) {
    EXPECT_DOUBLE_EQ(g.samples_m_s2()[i], expected_cm[i] * 0.01);
  }
}

TEST(ReadOneColumn, OneFieldOfSeriesSideBySide) {
  // Two components side by side without a time column (the Erzincan file's layout): column K
  // reads the K-th field of every row, and the name says which.
  const auto dir = pcrf::test::scratch_dir("one_col_column");
  const auto file = write_file(dir, "pair.txt", "% N-S and E-W, cm/s2\n% dt = 0.005 s\n1 10\n2 20\n-3 -30\n");
  for (std::size_t column : {1u, 2u}) {
    const pcrf::RecordFileSpec spec{file, pcrf::RecordFormat::kOneColumn, AccelUnit::kCentimeterPerSecond2, 0.005, 2,
                                    column};
    const auto g = pcrf::read_record(spec);
    EXPECT_EQ(g.name(), "pair_col" + std::to_string(column));
    EXPECT_EQ(g.name(), pcrf::record_name(spec));
    const double scale_cm = column == 1 ? 1.0 : 10.0;
    ASSERT_EQ(g.size(), 3u);
    EXPECT_DOUBLE_EQ(g.samples_m_s2()[2], -3.0 * scale_cm * 0.01);
  }
  const std::string m = record_error(
      [&] { return pcrf::read_one_column(file, 0.005, AccelUnit::kG, 2, 3); });
  EXPECT_NE(m.find("pair.txt:3: column 3 asked for, but the row has 2 fields"), std::string::npos) << m;
  const std::string at2 = record_error([&] {
    return pcrf::read_record({file, pcrf::RecordFormat::kTwoColumn, AccelUnit::kG, 0.0, 2, 1});
  });
  EXPECT_NE(at2.find("column applies to one-column records only"), std::string::npos) << at2;
}

TEST(ReadOneColumn, Errors) {
  const auto dir = pcrf::test::scratch_dir("one_col_errors");
  const auto good = write_file(dir, "good.txt", "1\n2\n");
  for (const double bad_dt : {0.0, -0.01, std::numeric_limits<double>::quiet_NaN()}) {
    const std::string m = record_error([&] { return pcrf::read_one_column(good, bad_dt, AccelUnit::kG); });
    EXPECT_NE(m.find(good.string()), std::string::npos) << m;
    EXPECT_NE(m.find("dt_s"), std::string::npos) << m;
  }
  const auto bad = write_file(dir, "bad.txt", "1\n2\n3 three\n");
  std::string m = record_error([&] { return pcrf::read_one_column(bad, 0.01, AccelUnit::kG); });
  EXPECT_EQ(m.rfind(bad.string() + ":3: ", 0), 0u) << m;
  EXPECT_NE(m.find("'three'"), std::string::npos) << m;
  const auto none = write_file(dir, "none.txt", "# nothing\n\n");
  m = record_error([&] { return pcrf::read_one_column(none, 0.01, AccelUnit::kG); });
  EXPECT_EQ(m.rfind(none.string() + ":2: ", 0), 0u) << m;
  m = record_error([&] { return pcrf::read_one_column(dir / "missing.txt", 0.01, AccelUnit::kG); });
  EXPECT_NE(m.find("missing.txt"), std::string::npos) << m;
}

TEST(ReadRecord, DispatchesOnFormat) {
  const auto dir = pcrf::test::scratch_dir("read_record_dispatch");
  const auto two = write_file(dir, "two.txt", "0 100\n0.02 -200\n");
  const auto one = write_file(dir, "one.dat", "100\n-200\n");
  pcrf::RecordFileSpec spec;
  spec.path = two;
  spec.format = pcrf::RecordFormat::kTwoColumn;
  spec.unit = AccelUnit::kCentimeterPerSecond2;
  auto g = pcrf::read_record(spec);
  EXPECT_EQ(g.name(), "two");
  EXPECT_EQ(g.size(), 2u);
  EXPECT_DOUBLE_EQ(g.samples_m_s2()[1], -2.0);
  EXPECT_NEAR(g.dt_s(), 0.02, 1e-15);

  spec.path = one;
  spec.format = pcrf::RecordFormat::kOneColumn;
  spec.dt_s = 0.005;
  g = pcrf::read_record(spec);
  EXPECT_EQ(g.name(), "one");
  EXPECT_EQ(g.dt_s(), 0.005);
  EXPECT_DOUBLE_EQ(g.samples_m_s2()[0], 1.0);

  spec.dt_s = 0.0;  // one-column without dt
  EXPECT_THROW(pcrf::read_record(spec), UserError);
}

}  // namespace
