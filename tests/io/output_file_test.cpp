// The one output rule (io::OutputFile): never an input (same path, symbolic or hard link),
// an existing file replaced only when asked, complete or not at all, the user's umask, and
// every write checked (a full file system is an OutputError naming the file).
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <string>

#include "pcrf/io/output_file.hpp"
#include "support/test_support.hpp"

namespace pcrf::io {
namespace {

namespace fs = std::filesystem;

using test::read_file;

/// Files in `dir` whose name starts with '.' (a temporary left behind).
int hidden_files(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().front() == '.';
  return n;
}

std::string refusal(const fs::path& output, const std::vector<fs::path>& inputs, bool overwrite) {
  try {
    OutputFile out(output, inputs, overwrite);
  } catch (const OutputError& e) {
    return e.what();
  }
  return "";
}

TEST(OutputFile, RefusesEveryNameOfAnInputEvenWithOverwrite) {
  const auto dir = test::scratch_dir("output_inputs");
  const auto input = test::write_file(dir, "cube.h5", "the input");
  fs::create_symlink("cube.h5", dir / "link.h5");
  fs::create_hard_link(input, dir / "hard.h5");
  fs::create_directories(dir / "sub");
  for (const fs::path& name : {dir / "cube.h5", dir / "link.h5", dir / "hard.h5", dir / "sub" / ".." / "cube.h5"})
    for (bool overwrite : {false, true}) {
      const std::string why = refusal(name, {dir / "other.toml", input}, overwrite);
      EXPECT_NE(why.find("the input"), std::string::npos) << name << ": " << why;
      EXPECT_NE(why.find("--overwrite does not apply to inputs"), std::string::npos) << why;
    }
  // An input named by a relative path, the output by an absolute one.
  const fs::path here = fs::current_path();
  fs::current_path(dir);
  EXPECT_NE(refusal(dir / "cube.h5", {"cube.h5"}, true).find("the input"), std::string::npos);
  fs::current_path(here);
  EXPECT_EQ(read_file(input), "the input");
  EXPECT_EQ(hidden_files(dir), 0);
}

TEST(OutputFile, ReplacesAnExistingFileOnlyWithOverwrite) {
  const auto dir = test::scratch_dir("output_existing");
  const auto old = test::write_file(dir, "table.csv", "old");
  EXPECT_EQ(refusal(old, {}, false), old.string() + ": already exists; use --overwrite to replace it");
  EXPECT_EQ(refusal(dir, {}, true), dir.string() + ": is a folder; name a file");
  OutputFile out(old, {}, true);
  out.stream() << "new";
  EXPECT_EQ(read_file(old), "old");  // not before commit()
  out.commit();
  EXPECT_EQ(read_file(old), "new");
  EXPECT_EQ(hidden_files(dir), 0);
}

TEST(OutputFile, AnUncommittedOrFailedWriteLeavesTheOldFileAndNoTemporary) {
  const auto dir = test::scratch_dir("output_abandoned");
  const auto old = test::write_file(dir, "table.csv", "old");
  {
    OutputFile out(old, {}, true);
    out.stream() << std::string(200000, 'x');  // beyond the buffer: written to the temporary
    EXPECT_EQ(hidden_files(dir), 1);
  }  // an exception on the way: no commit()
  EXPECT_EQ(read_file(old), "old");
  EXPECT_EQ(hidden_files(dir), 0);
}

TEST(OutputFile, AFileThatAppearsMeanwhileIsNotReplacedWithoutOverwrite) {
  const auto dir = test::scratch_dir("output_race");
  OutputFile out(dir / "t.csv", {}, false);
  out.stream() << "mine";
  test::write_file(dir, "t.csv", "theirs");
  EXPECT_THROW(out.commit(), OutputError);
  EXPECT_EQ(read_file(dir / "t.csv"), "theirs");
}

TEST(OutputFile, FilesGetTheUsersUmask) {
  const auto dir = test::scratch_dir("output_umask");
  for (const mode_t mask : {mode_t{022}, mode_t{027}, mode_t{002}}) {
    const mode_t old = ::umask(mask);
    const fs::path file = dir / ("f" + std::to_string(mask) + ".csv");
    OutputFile out(file, {}, false);
    out.stream() << "x";
    out.commit();
    ::umask(old);
    struct stat st {};
    ASSERT_EQ(::stat(file.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0666 & ~mask) << file;
  }
}

TEST(OutputFile, ADeviceIsWrittenInPlace) {
  OutputFile out("/dev/null", {}, false);  // exists, but is no file to replace
  out.stream() << "discarded";
  out.commit();
  EXPECT_TRUE(fs::exists("/dev/null"));
  OutputFile full("/dev/full", {}, false);
  full.stream() << "x";
  try {
    full.commit();
    FAIL() << "a write to /dev/full succeeded";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), "/dev/full: cannot write: No space left on device");
    EXPECT_EQ(e.os_error(), ENOSPC);
  }
}

TEST(OutputFile, AFullFileSystemIsAnErrorNamingTheFileAndKeepsTheOldOne) {
  const auto dir = test::scratch_dir("output_full_disk");
  const auto small = dir / "small";
  fs::create_directories(small);
  ::umount(small.c_str());
  if (::mount("tmpfs", small.c_str(), "tmpfs", 0, "size=64k") != 0) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  struct Unmount {
    fs::path at;
    ~Unmount() { ::umount(at.c_str()); }
  } unmount{small};
  test::write_file(small, "t.csv", "old");
  try {
    OutputFile out(small / "t.csv", {}, true);
    for (int i = 0; i < 64; ++i) out.stream() << std::string(4096, 'x');
    out.commit();
    FAIL() << "256 kB fitted in a 64 kB file system";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), (small / "t.csv").string() + ": cannot write: No space left on device");
  }
  EXPECT_EQ(read_file(small / "t.csv"), "old");
  EXPECT_EQ(hidden_files(small), 0);
}

}  // namespace
}  // namespace pcrf::io
