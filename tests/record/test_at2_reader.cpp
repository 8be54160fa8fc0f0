/// \file test_at2_reader.cpp
/// \brief read_at2 on small files written into the scratch area: both NPTS/DT header forms,
/// CRLF and LF, partial last lines, Fortran number formats, and a corpus of malformed files
/// whose errors must name the file and the line.

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "pcrf/record/record_readers.hpp"
#include "support/test_support.hpp"

namespace {

using pcrf::test::write_file;

using pcrf::kGravity_m_s2;
using pcrf::UserError;

std::string with_crlf(const std::string& lf_text) {
  std::string out;
  for (char c : lf_text) {
    if (c == '\n') out += '\r';
    out += c;
  }
  return out;
}

const std::string kTitle =
    "PEER NGA STRONG MOTION DATABASE RECORD\n"
    "Test event, 1/1/2000, Test station, 090\n"
    "ACCELERATION TIME SERIES IN UNITS OF G\n";

/// Values of kBody below, in g, in file order.
const std::vector<double> kBodyValues_g = {-.4722856E-02, 7.6753400E-05, .1717907E-01,
                                           -1.2980500E-03, 0.0,          .2113082E-02,
                                           -.6229361E-03};
const std::string kBody =
    "  -.4722856E-02   7.6753400E-05   .1717907E-01  -1.2980500E-03   0.0000000E+00\n"
    "   .2113082E-02  -.6229361E-03\n";

void expect_values_g(const pcrf::GroundMotion& g, const std::vector<double>& values_g) {
  ASSERT_EQ(g.size(), values_g.size());
  for (std::size_t i = 0; i < values_g.size(); ++i) {
    EXPECT_DOUBLE_EQ(g.samples_m_s2()[i], values_g[i] * kGravity_m_s2) << "sample " << i;
  }
}

TEST(ReadAt2, NgaWest2HeaderLf) {
  const auto dir = pcrf::test::scratch_dir("at2_west2_lf");
  const auto file = write_file(dir, "west2.AT2", kTitle + "NPTS=      7, DT=   .0050 SEC\n" + kBody);
  const auto g = pcrf::read_at2(file);
  EXPECT_EQ(g.name(), "west2");
  EXPECT_EQ(g.dt_s(), 0.005);
  expect_values_g(g, kBodyValues_g);
}

TEST(ReadAt2, NgaWest2HeaderCrlfWithTrailingCommaAndBlanks) {
  // The layout of the real NGA-West2 downloads: CRLF, a comma and blanks after SEC, the
  // short last line padded with blanks.
  const auto dir = pcrf::test::scratch_dir("at2_west2_crlf");
  const std::string body =
      "  -.4722856E-02   7.6753400E-05   .1717907E-01  -1.2980500E-03   0.0000000E+00\n"
      "   .2113082E-02  -.6229361E-03                                 \n";
  const auto file = write_file(
      dir, "west2_crlf.AT2",
      with_crlf(kTitle + "NPTS=      7, DT=   .0050 SEC,                         \n" + body));
  const auto g = pcrf::read_at2(file);
  EXPECT_EQ(g.dt_s(), 0.005);
  expect_values_g(g, kBodyValues_g);
}

TEST(ReadAt2, NgaWest2HeaderWithFilterDescription) {
  // Some NGA-West2 downloads (Bolu, Rinaldi) describe the filter after DT: "-5 POLE" is the
  // high-pass. It is read past; anything else after SEC stays an error (malformed corpus).
  const auto dir = pcrf::test::scratch_dir("at2_west2_filter");
  for (const std::string line : {"NPTS=      7, DT=   .0050 SEC,  -5 POLE @      .10000",
                                 "NPTS=      7, DT=   .0050 SEC,   4 POLE @    33.00000 HZ,  -5 POLE @      .10000",
                                 "NPTS=      7, DT=   .0050 SEC,   0 POLE @      .00000 HZ,   0 POLE @      .00000"}) {
    SCOPED_TRACE(line);
    const auto g = pcrf::read_at2(write_file(dir, "filtered.AT2", with_crlf(kTitle + line + "\n" + kBody)));
    EXPECT_EQ(g.dt_s(), 0.005);
    expect_values_g(g, kBodyValues_g);
  }
}

TEST(ReadAt2, OlderNumbersFirstHeader) {
  const auto dir = pcrf::test::scratch_dir("at2_old");
  const auto file = write_file(dir, "old.at2",
                               "PEER NGA STRONG MOTION DATABASE RECORD\n"
                               "IMPERIAL VALLEY 10/15/79 2316, EL CENTRO ARRAY #6, 230\n"
                               "ACCELERATION TIME HISTORY IN UNITS OF G\n"
                               "    7    0.0200    NPTS, DT\n" +
                                   kBody);
  const auto g = pcrf::read_at2(file);
  EXPECT_EQ(g.dt_s(), 0.02);
  expect_values_g(g, kBodyValues_g);
}

TEST(ReadAt2, OlderHeaderCrlf) {
  const auto dir = pcrf::test::scratch_dir("at2_old_crlf");
  const auto file =
      write_file(dir, "old_crlf.AT2", with_crlf(kTitle + "  7  0.0050  NPTS, DT\n" + kBody));
  const auto g = pcrf::read_at2(file);
  EXPECT_EQ(g.dt_s(), 0.005);
  expect_values_g(g, kBodyValues_g);
}

TEST(ReadAt2, PartialLastLineWithoutLineEnd) {
  const auto dir = pcrf::test::scratch_dir("at2_no_final_eol");
  std::string body = kBody;
  body.pop_back();  // file ends right after the last value
  for (const bool crlf : {false, true}) {
    const std::string text = kTitle + "NPTS=      7, DT=   .0100 SEC\n" + body;
    const auto file = write_file(dir, crlf ? "crlf.AT2" : "lf.AT2", crlf ? with_crlf(text) : text);
    const auto g = pcrf::read_at2(file);
    EXPECT_EQ(g.dt_s(), 0.01);
    expect_values_g(g, kBodyValues_g);
  }
}

TEST(ReadAt2, AnyNumberOfValuesPerLineAndTrailingBlankLines) {
  const auto dir = pcrf::test::scratch_dir("at2_layout");
  const auto file = write_file(dir, "layout.AT2",
                               kTitle + "NPTS=  7, DT= 0.01 SEC\n"
                                        "-.4722856E-02\n"
                                        "\t7.6753400E-05 .1717907E-01 -1.2980500E-03 0.0 "
                                        ".2113082E-02\n"
                                        "\n"
                                        "  -.6229361E-03\n"
                                        "\n\n");
  expect_values_g(pcrf::read_at2(file), kBodyValues_g);
}

TEST(ReadAt2, FortranNumberForms) {
  const auto dir = pcrf::test::scratch_dir("at2_fortran");
  const auto file = write_file(dir, "fortran.AT2",
                               kTitle + "NPTS= 6, DT= .005 SEC\n"
                                        "+.5E-01 1.0D-03 -2.5d+00 .0 -0. 3\n");
  expect_values_g(pcrf::read_at2(file), {0.05, 1.0e-3, -2.5, 0.0, 0.0, 3.0});
}

TEST(ReadAt2, ReadRecordAndFormatGuess) {
  const auto dir = pcrf::test::scratch_dir("at2_read_record");
  const auto file = write_file(dir, "via_spec.AT2", kTitle + "NPTS= 7, DT= .005 SEC\n" + kBody);
  pcrf::RecordFileSpec spec;
  spec.path = file;
  spec.format = pcrf::guess_record_format(file);
  EXPECT_EQ(spec.format, pcrf::RecordFormat::kAt2);
  spec.unit = pcrf::AccelUnit::kCentimeterPerSecond2;  // ignored for .AT2: always g
  const auto g = pcrf::read_record(spec);
  EXPECT_EQ(g.name(), "via_spec");
  expect_values_g(g, kBodyValues_g);

  EXPECT_EQ(pcrf::guess_record_format("a/b/c.at2"), pcrf::RecordFormat::kAt2);
  EXPECT_EQ(pcrf::guess_record_format("c.At2"), pcrf::RecordFormat::kAt2);
  EXPECT_EQ(pcrf::guess_record_format("c.txt"), pcrf::RecordFormat::kTwoColumn);
  EXPECT_EQ(pcrf::guess_record_format("c.AT2.txt"), pcrf::RecordFormat::kTwoColumn);
  EXPECT_EQ(pcrf::guess_record_format("noext"), pcrf::RecordFormat::kTwoColumn);
}

// ---- malformed corpus ---------------------------------------------------------------------

struct Malformed {
  const char* name;          ///< file name (also the test's label)
  std::string text;          ///< LF text; also tried with CRLF
  int line;                  ///< line the message must name
  const char* must_mention;  ///< a phrase or token the message must contain
};

std::string header(const std::string& npts_dt_line) { return kTitle + npts_dt_line + "\n"; }

std::vector<Malformed> malformed_corpus() {
  const std::string ok = "NPTS=  5, DT= .0100 SEC";
  return {
      {"empty.AT2", "", 1, "empty"},
      {"blank_lines_only.AT2", "\n\n", 3, "missing header line 3"},
      {"one_line.AT2", "PEER NGA STRONG MOTION DATABASE RECORD\n", 2, "missing header line 2"},
      {"three_lines.AT2", kTitle, 4, "missing header line 4"},
      {"no_npts_dt.AT2", header("1.0 2.0 3.0 4.0 5.0") + "1 2 3 4 5\n", 4, "NPTS/DT"},
      {"garbled_header.AT2", header("NPTS 5 DT") + "1 2 3 4 5\n", 4, "NPTS/DT"},
      {"header_junk_after.AT2", header("NPTS= 5, DT= .01 SEC, FILTERED") + "1 2 3 4 5\n", 4,
       "NPTS/DT"},
      {"header_half_filter.AT2", header("NPTS= 5, DT= .01 SEC, 4 POLE @") + "1 2 3 4 5\n", 4, "NPTS/DT"},
      {"header_filter_no_sec.AT2", header("NPTS= 5, DT= .01, 4 POLE @ 33.0 HZ") + "1 2 3 4 5\n", 4, "NPTS/DT"},
      {"npts_zero.AT2", header("NPTS=  0, DT= .0100 SEC"), 4, "NPTS must be positive"},
      {"npts_negative.AT2", header("NPTS= -5, DT= .0100 SEC") + "1 2 3 4 5\n", 4,
       "NPTS must be positive"},
      {"npts_not_integer.AT2", header("NPTS= 5.5, DT= .0100 SEC") + "1 2 3 4 5\n", 4, "'5.5'"},
      {"npts_text.AT2", header("NPTS= five, DT= .0100 SEC") + "1 2 3 4 5\n", 4, "'five'"},
      {"dt_zero.AT2", header("NPTS=  5, DT= .0000 SEC") + "1 2 3 4 5\n", 4, "DT must be positive"},
      {"dt_negative.AT2", header("NPTS=  5, DT= -.0100 SEC") + "1 2 3 4 5\n", 4,
       "DT must be positive"},
      {"dt_text.AT2", header("NPTS=  5, DT= abc SEC") + "1 2 3 4 5\n", 4, "'abc'"},
      {"old_dt_zero.AT2", header("5 0.0 NPTS, DT") + "1 2 3 4 5\n", 4, "DT must be positive"},
      {"too_few.AT2", header(ok) + "1 2 3\n4\n", 6, "found 4, expected NPTS = 5"},
      {"too_few_trailing_blank.AT2", header(ok) + "1 2 3\n4\n\n", 7, "found 4, expected NPTS = 5"},
      {"no_data.AT2", header(ok), 4, "found 0, expected NPTS = 5"},
      {"too_many.AT2", header(ok) + "1 2 3\n4 5\n6 7\n", 7, "found 7, NPTS = 5"},
      {"too_many_same_line.AT2", header(ok) + "1 2 3 4 5 6\n", 5, "found 6, NPTS = 5"},
      {"non_numeric.AT2", header(ok) + "1 2 3\n4 abc\n", 6, "'abc'"},
      {"non_numeric_first.AT2", header(ok) + "x1 2 3 4 5\n", 5, "'x1'"},
      {"comma_joined.AT2", header(ok) + "1 2 3\n4.0,5.0\n", 6, "'4.0,5.0'"},
      {"truncated_exponent.AT2", header(ok) + "1 2 3 4\n5.0E\n", 6, "'5.0E'"},
      {"nan_value.AT2", header(ok) + "1 2 nan 4 5\n", 5, "'nan'"},
      {"inf_value.AT2", header(ok) + "1 2 3 4\ninf\n", 6, "'inf'"},
      {"overflow_value.AT2", header(ok) + "1 2 3 4 1.0E+999\n", 5, "'1.0E+999'"},
      {"velocity.AT2",
       "PEER NGA STRONG MOTION DATABASE RECORD\nx\nVELOCITY TIME SERIES IN UNITS OF CM/S\n" + ok +
           "\n1 2 3 4 5\n",
       3, "not an acceleration record"},
      {"cm_units.AT2",
       "PEER NGA STRONG MOTION DATABASE RECORD\nx\nACCELERATION TIME SERIES IN UNITS OF CM/S/S\n" +
           ok + "\n1 2 3 4 5\n",
       3, "'CM/S/S'"},
  };
}

/// Runs read_at2 and returns the UserError message ("" and a failure if none was thrown).
std::string at2_error(const std::filesystem::path& file) {
  try {
    (void)pcrf::read_at2(file);
  } catch (const UserError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no UserError for " << file;
  return "";
}

TEST(ReadAt2, MalformedFilesNameFileAndLine) {
  const auto dir = pcrf::test::scratch_dir("at2_malformed");
  for (const Malformed& m : malformed_corpus()) {
    for (const bool crlf : {false, true}) {
      const std::string name = std::string(crlf ? "crlf_" : "lf_") + m.name;
      const auto file = write_file(dir, name, crlf ? with_crlf(m.text) : m.text);
      const std::string message = at2_error(file);
      SCOPED_TRACE(name + ": " + message);
      const std::string where = file.string() + ":" + std::to_string(m.line) + ": ";
      EXPECT_EQ(message.rfind(where, 0), 0u) << "expected prefix " << where;
      EXPECT_NE(message.find(m.must_mention), std::string::npos) << "expected " << m.must_mention;
    }
  }
}

TEST(ReadAt2, MissingFileIsUserError) {
  const auto dir = pcrf::test::scratch_dir("at2_missing");
  const auto file = dir / "does_not_exist.AT2";
  const std::string message = at2_error(file);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  // A directory is not a record either.
  EXPECT_NE(at2_error(dir).find(dir.string()), std::string::npos);
}

}  // namespace
