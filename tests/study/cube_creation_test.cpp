// A new cube made by every rank together (issue 38; run/cube_creation.hpp): the workers seal
// the coordinates rank 0 writes. The cube is the one a single rank makes, coordinate for
// coordinate; a creation that fails (a full disk) ends every rank in order with exit code 2,
// and leaves no cube, or the old one with --overwrite.
#include <gtest/gtest.h>
#include <sys/mount.h>

#include <fstream>
#include <iterator>

#include "pcrf/cube/cube_reader.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

namespace fs = std::filesystem;

/// A Latin hypercube of `samples` frames that never lift (a weak, short record): every
/// coordinate along `case` is computed, and past 65 536 cases they come in several pieces.
std::string lhs_study(long samples) {
  return "[study]\nname = \"pieces\"\n[plan]\nkind = \"lhs\"\nsamples = " + std::to_string(samples) +
         "\nseed = 7\n[axes]\nscale = 0.05\nkappa = {from = 1.26, to = 2.34}\nlambda = {from = 1.4, to = 2.6}\n"
         "tan_alpha = {from = 0.14, to = 0.26}\n[[records]]\n"
         "synthetic = \"stochastic:seed=1,pga_g=0.026,duration_s=1,dt_s=0.01\"\n";
}

test::CommandResult study_in(const fs::path& dir, const std::string& file, const std::string& arguments,
                             const std::string& launcher = "") {
  return test::run_command("cd " + quoted(dir) + " && " + launcher + pcrf() + " study " + file + " " + arguments +
                           " --progress-interval 0");
}

TEST(CubeCreation, ThreeRanksMakeTheCoordinatesOfOneRank) {
  PCRF_REQUIRE_MPIRUN();
  const auto dir = test::scratch_dir("cube_creation_ranks");
  test::write_file(dir, "l.toml", lhs_study(140000));  // pieces of 65 536, 65 536 and 8 928 values
  const auto one = study_in(dir, "l.toml", "-o one.h5");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto three = study_in(dir, "l.toml", "-o three.h5", mpirun(3));
  ASSERT_EQ(three.exit_code, 0) << three.err;
  cube::CubeReader a(dir / "one.h5"), b(dir / "three.h5");
  ASSERT_EQ(a.layout().coordinates.size(), b.layout().coordinates.size());
  std::size_t long_ones = 0;
  for (const auto& c : a.layout().coordinates) {
    const cube::Coordinate* d = b.layout().find_coordinate(c.name);
    ASSERT_NE(d, nullptr) << c.name;
    EXPECT_EQ(c.numbers, d->numbers) << c.name;  // bit for bit: no value is NaN
    EXPECT_EQ(c.strings, d->strings) << c.name;
    EXPECT_EQ(c.is_index, d->is_index) << c.name;
    long_ones += c.size() == 140000 ? 1 : 0;
  }
  EXPECT_GE(long_ones, 4u) << "case, kappa, lambda, tan_alpha";
  expect_same_cube(dir / "one.h5", dir / "three.h5");
}

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(CubeCreation, AFullDiskDuringTheCreationEndsEveryRankAndLeavesNoCube) {
  PCRF_REQUIRE_MPIRUN();
  const auto dir = test::scratch_dir("cube_creation_full_disk");
  const auto small = dir / "small";
  fs::create_directories(small);
  ::umount(small.c_str());
  // Room for a small cube, not for 140 000 cases' coordinates (about 2.5 MB).
  if (::mount("tmpfs", small.c_str(), "tmpfs", 0, "size=1m") != 0) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  struct Unmount {  // also when an assertion ends the test early
    fs::path at;
    ~Unmount() { ::umount(at.c_str()); }
  } unmount{small};
  test::write_file(dir, "l.toml", lhs_study(140000));
  const auto full = study_in(dir, "l.toml", "-o small/l.h5", mpirun(3));
  EXPECT_EQ(full.exit_code, 2) << full.err;
  EXPECT_NE(full.err.find("pcrf: error: small/l.h5: "), std::string::npos) << full.err;
  EXPECT_NE(full.err.find("No space left on device"), std::string::npos) << full.err;
  EXPECT_TRUE(fs::is_empty(small)) << "no cube, no temporary, no lock";

  // --overwrite: the old cube stays as it was.
  test::write_file(dir, "s.toml", lhs_study(2000));
  const auto made = study_in(dir, "s.toml", "-o small/l.h5", mpirun(3));
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string before = bytes_of(small / "l.h5");
  const auto again = study_in(dir, "l.toml", "-o small/l.h5 --overwrite", mpirun(3));
  EXPECT_EQ(again.exit_code, 2) << again.err;
  EXPECT_NE(again.err.find("No space left on device"), std::string::npos) << again.err;
  EXPECT_EQ(bytes_of(small / "l.h5"), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(small), fs::directory_iterator()), 1) << "the old cube alone";
}

}  // namespace
}  // namespace pcrf::study_test
