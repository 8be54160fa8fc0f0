// Study files built to break the parser (issue 29, "Fuzzing"): each is refused with one
// line naming the file and the line, never a crash or an uncaught exception.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "pcrf/study/study_parser.hpp"
#include "support/test_support.hpp"

namespace pcrf::study {
namespace {

const std::string kRecords = "[[records]]\nsynthetic = \"sine:amplitude_g=1.5\"\n";

std::string dotted(std::size_t parts) {
  std::string name = "a";
  for (std::size_t i = 1; i < parts; ++i) name += ".a";
  return name;
}

std::string error_of(const std::string& text) {
  try {
    parse_study(text, "deep.toml", test::source_dir());
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

// Finding 2: toml++ 3.3 recursed once per part of a dotted key or table header: one key of
// 50 000 parts (100 kB) overflowed the stack of `study --check`.
TEST(HostileStudy, OverDeepKeysAndHeadersAreRefusedBeforeParsing) {
  for (const std::string& deep : {dotted(50000) + " = 1\n", "[" + dotted(50000) + "]\n", "[[" + dotted(50000) + "]]\n",
                                   "x = { " + dotted(50000) + " = 1 }\n", "\"q\" . " + dotted(65) + " = 1\n"}) {
    const std::string message = error_of(kRecords + deep);
    EXPECT_EQ(message.rfind("deep.toml:", 0), 0u) << message;
    EXPECT_NE(message.find("64"), std::string::npos) << message;
    EXPECT_NE(message.find(":3:"), std::string::npos) << message;  // the line of the key
  }
}

TEST(HostileStudy, DotsInStringsCommentsAndValuesAreNotKeyParts) {
  const std::string many_dots(500, '.');
  const std::string text = kRecords + "# " + many_dots + "\n[study]\nname = \"" + many_dots + "\"\ndescription = '''\n" +
                           many_dots + "\n'''\n[axes]\nkappa = [1.5, 2.5]\n";
  EXPECT_EQ(error_of(text), "");
  // A key of exactly the most parts allowed reaches the study's own checks (an unknown key).
  const std::string message = error_of(kRecords + "[axes]\n" + dotted(64) + " = 1\n");
  EXPECT_NE(message.find("unknown key"), std::string::npos) << message;
}

// toml++'s own limit holds for arrays and inline tables: a clear line, not a crash.
TEST(HostileStudy, OverDeepArraysAreRefusedByTheParser) {
  const std::string message = error_of(kRecords + "x = " + std::string(100000, '[') + std::string(100000, ']') + "\n");
  EXPECT_NE(message.find("deep.toml:3"), std::string::npos) << message;
}

TEST(HostileStudy, TheCommandRefusesAnOverDeepKeyInOneLine) {
  const auto dir = test::scratch_dir("hostile_deep");
  test::write_file(dir, "deep.toml", kRecords + dotted(50000) + " = 1\n");
  const auto r = test::run_command("cd " + dir.string() + " && " + test::pcrf_executable().string() +
                                   " study deep.toml --check");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("deep.toml:3"), std::string::npos) << r.err;
}

// Finding 5: a `files` glob over a folder holding a symbolic-link loop ended in an uncaught
// filesystem_error (exit 1). The loop is no regular file: the glob takes the records only.
TEST(HostileStudy, AGlobOverALinkLoopTakesTheRegularFilesOnly) {
  const auto dir = test::scratch_dir("hostile_glob_loop");
  std::filesystem::create_directories(dir / "rec");
  test::write_file(dir / "rec", "a.txt", "0 0\n0.01 0.1\n");
  std::filesystem::create_symlink(dir / "rec" / "loop.txt", dir / "rec" / "loop.txt");
  const Study s = parse_study("[[records]]\nfiles = [\"rec/*.txt\"]\nunits = \"g\"\n", "t.toml", dir);
  ASSERT_EQ(s.records.size(), 1u);
  EXPECT_EQ(s.records[0].name, "a");
  // Only the loop matches: no file, said in one line.
  test::write_file(dir, "loop.toml", "[[records]]\nfiles = [\"rec/loop*\"]\nunits = \"g\"\n");
  const auto r = test::run_command("cd " + dir.string() + " && " + test::pcrf_executable().string() +
                                   " study loop.toml --check");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("loop.toml:2"), std::string::npos) << r.err;
}

// A link loop named as the study, as a record of a study, or as a record of `pcrf record`:
// one line saying so, exit 2.
TEST(HostileStudy, LinkLoopsAsStudyOrRecordFilesAreRefusedInOneLine) {
  const auto dir = test::scratch_dir("hostile_loops");
  for (const char* name : {"loop.toml", "loop.AT2"}) std::filesystem::create_symlink(dir / name, dir / name);
  test::write_file(dir, "record_loop.toml", "[[records]]\nfile = \"loop.AT2\"\n");
  const std::string pcrf = test::pcrf_executable().string();
  for (const std::string& command : {pcrf + " study loop.toml --check", pcrf + " study record_loop.toml --check",
                                     pcrf + " record loop.AT2"}) {
    const auto r = test::run_command("cd " + dir.string() + " && timeout 60 " + command);
    EXPECT_EQ(r.exit_code, 2) << command << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << command << ": " << r.err;
    EXPECT_NE(r.err.find("loop."), std::string::npos) << command << ": " << r.err;
  }
}

}  // namespace
}  // namespace pcrf::study
