/// \file test_bad_files.cpp
/// \brief Files that are not ground-motion records: folders, FIFOs, binary and UTF-16 files,
/// absurd sample intervals, single samples, values that overflow. Each is a UserError
/// naming the file (and the line), and no message carries raw bytes to the terminal.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <string>

#include "pcrf/printable.hpp"
#include "pcrf/record/record_readers.hpp"
#include "support/test_support.hpp"

namespace pcrf {
namespace {

std::string error_of(const RecordFileSpec& spec) {
  try {
    (void)read_record(spec);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

RecordFileSpec spec_for(const std::filesystem::path& path, RecordFormat format = RecordFormat::kAt2, double dt_s = 0.0) {
  RecordFileSpec spec;
  spec.path = path;
  spec.format = format;
  spec.dt_s = dt_s;
  return spec;
}

/// No byte below 0x20 (but none is expected at all: messages are one line).
bool has_control_bytes(const std::string& text) {
  for (unsigned char c : text)
    if (c < 0x20 || c == 0x7F) return true;
  return false;
}

const std::string kHeader = "PEER NGA STRONG MOTION DATABASE RECORD\nX\nACCELERATION TIME SERIES IN UNITS OF G\n";

TEST(BadFiles, FolderAndFifoAreNotRegularFiles) {
  const auto dir = test::scratch_dir("bad_files_kinds");
  EXPECT_NE(error_of(spec_for(dir)).find(dir.string() + ": not a regular file"), std::string::npos);
  const auto fifo = dir / "pipe.AT2";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(error_of(spec_for(fifo)).find("pipe.AT2: not a regular file"), std::string::npos);
  EXPECT_NE(error_of(spec_for(dir / "missing.AT2")).find("missing.AT2: no such file"), std::string::npos);
}

TEST(BadFiles, BinaryAndUtf16FilesAreNamedWithoutRawBytes) {
  const auto dir = test::scratch_dir("bad_files_binary");
  const std::string utf16("\xFF\xFEP\0E\0E\0R\0\n\0", 12);
  const auto e16 = error_of(spec_for(test::write_file(dir, "u16.AT2", utf16)));
  EXPECT_NE(e16.find("u16.AT2: UTF-16 text"), std::string::npos) << e16;
  const std::string nul = kHeader + "NPTS=  2, DT= .01 SEC\n" + std::string("0.1\0 0.2\n", 9);
  const auto enul = error_of(spec_for(test::write_file(dir, "nul.AT2", nul)));
  EXPECT_NE(enul.find("nul.AT2:5: a NUL byte"), std::string::npos) << enul;
  // Control bytes and invalid UTF-8 in a header line are quoted escaped.
  const std::string junk = kHeader + "NPTS=\x1b[31m\xC3\x28 garbage\n";
  const auto ejunk = error_of(spec_for(test::write_file(dir, "junk.AT2", junk)));
  EXPECT_NE(ejunk.find("junk.AT2:4:"), std::string::npos) << ejunk;
  EXPECT_NE(ejunk.find("\\x1B[31m\\xC3("), std::string::npos) << ejunk;
  EXPECT_FALSE(has_control_bytes(ejunk)) << ejunk;
}

TEST(BadFiles, AbsurdSampleIntervalsAndSingleSamplesAreRejected) {
  const auto dir = test::scratch_dir("bad_files_sampling");
  for (const char* dt : {"1e300", "1e-300", "5"}) {
    const auto file = test::write_file(dir, "dt.AT2", kHeader + "NPTS=  3, DT= " + dt + " SEC\n0.1 0.2 0.1\n");
    const auto e = error_of(spec_for(file));
    EXPECT_NE(e.find("dt.AT2:4: sample interval"), std::string::npos) << dt << ": " << e;
  }
  const auto one = test::write_file(dir, "one.AT2", kHeader + "NPTS=  1, DT= .01 SEC\n0.1\n");
  EXPECT_NE(error_of(spec_for(one)).find("one.AT2:4: a record needs at least 2 samples, found 1"), std::string::npos);
  const auto single = test::write_file(dir, "single.txt", "1.5\n");
  EXPECT_NE(error_of(spec_for(single, RecordFormat::kOneColumn, 0.01)).find("at least 2 samples"), std::string::npos);
  const auto fine = test::write_file(dir, "fine.AT2", kHeader + "NPTS=  2, DT= .01 SEC\n0.1 0.2\n");
  EXPECT_EQ(error_of(spec_for(fine)), "");
}

TEST(BadFiles, AValueThatOverflowsNamesItsLine) {
  const auto dir = test::scratch_dir("bad_files_overflow");
  const auto file = test::write_file(dir, "big.txt", "0 0.1\n0.01 1e308\n0.02 0.1\n");
  const auto e = error_of(spec_for(file, RecordFormat::kTwoColumn));
  EXPECT_NE(e.find("big.txt:2: value '1e308' overflows in m/s²"), std::string::npos) << e;
}

TEST(Printable, KeepsUtf8AndEscapesTheRest) {
  EXPECT_EQ(printable("θ₁ = 0.1 rad"), "θ₁ = 0.1 rad");
  EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(printable("\xFF\xFE" "x"), "\\xFF\\xFEx");
  EXPECT_EQ(printable("tab\there\n"), "tab\\x09here\\x0A");
  EXPECT_EQ(printable("\xE2\x82"), "\\xE2\\x82");  // a cut-off sequence
}

}  // namespace
}  // namespace pcrf
