// The one atomic-file rule (io::AtomicFile) as the cube checkpoint uses it: a "NAME.partial"
// temporary that reuses a stray one, content copied from the old file, the target untouched
// until commit(), and the temporary gone after a failure.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "pcrf/io/atomic_file.hpp"
#include "pcrf/io/checked_stream.hpp"
#include "support/test_support.hpp"

namespace pcrf::io {
namespace {

namespace fs = std::filesystem;

using test::read_file;

TEST(AtomicFile, APartialTemporaryReusesAStrayOneAndReplacesTheTargetAtCommit) {
  const auto dir = test::scratch_dir("atomic_partial");
  const auto cube = test::write_file(dir, "c.h5", std::string(300000, 'a'));
  test::write_file(dir, "c.h5.partial", "left by a killed run, longer than what follows");
  AtomicFile next(cube, true, AtomicFile::Temporary::kPartial);
  EXPECT_EQ(next.temporary(), fs::path(cube.string() + ".partial"));
  next.copy_from(cube);
  next.write("b", 1);
  next.close();
  EXPECT_EQ(read_file(cube), std::string(300000, 'a'));  // not before commit()
  next.commit();
  EXPECT_EQ(read_file(cube), std::string(300000, 'a') + "b");
  EXPECT_FALSE(fs::exists(dir / "c.h5.partial"));
}

TEST(AtomicFile, AnUncommittedPartialGoesAndItsErrorsNameIt) {
  const auto dir = test::scratch_dir("atomic_abandoned");
  const auto cube = test::write_file(dir, "c.h5", "old");
  {
    AtomicFile next(cube, true, AtomicFile::Temporary::kPartial);
    next.write("new", 3);
    EXPECT_TRUE(fs::exists(dir / "c.h5.partial"));
  }
  EXPECT_EQ(read_file(cube), "old");
  EXPECT_FALSE(fs::exists(dir / "c.h5.partial"));
  try {
    AtomicFile next(dir / "no" / "c.h5", true, AtomicFile::Temporary::kPartial);
    FAIL() << "a temporary in a missing folder";
  } catch (const OutputError& e) {
    const std::string target = (dir / "no" / "c.h5").string();
    EXPECT_EQ(std::string(e.what()), target + ": cannot write " + target + ".partial: No such file or directory");
    EXPECT_EQ(e.os_error(), ENOENT);
  }
  AtomicFile next(cube, true, AtomicFile::Temporary::kPartial);
  EXPECT_THROW(next.copy_from(dir / "gone.h5"), OutputError);
}

TEST(AtomicFile, AUniqueTemporaryIsHiddenBesideTheTarget) {
  const auto dir = test::scratch_dir("atomic_unique");
  AtomicFile out(dir / "t.csv", false);
  EXPECT_EQ(out.temporary().parent_path(), dir);
  EXPECT_EQ(out.temporary().filename().string().rfind(".t.csv.", 0), 0u) << out.temporary();
  out.write("x", 1);
  out.commit();
  EXPECT_EQ(read_file(dir / "t.csv"), "x");
}

}  // namespace
}  // namespace pcrf::io
