// Whole chunks handed out as units (issue 38): a study large enough that workers compute and
// seal whole chunks of the cube gives the cube of the case-by-case hand-out (--batch-size
// turns units off), at one rank and at two, and in shards that merge.
#include <gtest/gtest.h>

#include "pcrf/cube/cube_reader.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

/// 70 000 frames that never lift (a weak record): five chunks of the cube (four of 16 384 and
/// an edge one), enough for units at one and two ranks (at least 2 a worker and a tail chunk).
std::string units_study() {
  return "[study]\nname = \"units\"\n[plan]\nkind = \"lhs\"\nsamples = 70000\nseed = 4\n"
         "[[records]]\nsynthetic = \"stochastic:seed=1,pga_g=0.026,duration_s=4,dt_s=0.01\"\n"
         "[axes]\nkappa = {from = 1.26, to = 2.34}\ntan_alpha = {from = 0.14, to = 0.26}\n"
         "lambda_h = {from = 0.14, to = 0.26}\n";
}

test::CommandResult study_in(const std::filesystem::path& dir, const std::string& args, const std::string& launcher = "") {
  return test::run_command("cd " + quoted(dir) + " && " + launcher + pcrf() + " study u.toml --progress-interval 0 " + args);
}

TEST(UnitsStudy, SealedChunksGiveTheCubeOfTheCaseByCaseHandOut) {
  const auto dir = test::scratch_dir("units_study");
  test::write_file(dir, "u.toml", units_study());
  const auto one_by_one = study_in(dir, "--batch-size 64 -o cases.h5");
  ASSERT_EQ(one_by_one.exit_code, 0) << one_by_one.err;
  const auto units = study_in(dir, "-o units.h5");
  ASSERT_EQ(units.exit_code, 0) << units.err;
  EXPECT_NE(units.err.find("70000 cases computed, 0 failed"), std::string::npos) << units.err;
  expect_same_cube(dir / "cases.h5", dir / "units.h5", {"wall_time_s", "cpu_time_s"});
  const auto status = cube::CubeReader(dir / "units.h5").read_status();
  EXPECT_EQ(std::count(status.begin(), status.end(), cube::kStatusNotRun), 0);
  if (have_mpirun()) {
    const auto two = study_in(dir, "-o two.h5", mpirun(2));
    ASSERT_EQ(two.exit_code, 0) << two.err;
    expect_same_cube(dir / "cases.h5", dir / "two.h5", {"wall_time_s", "cpu_time_s"});
  }
  // Shards: only the chunks whole inside a shard are units; the merge is the whole cube.
  for (const char* k : {"1", "2"})
    ASSERT_EQ(study_in(dir, std::string("--shard ") + k + "/2 -o part" + k + ".h5").exit_code, 0);
  const auto merged = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " cube merge part1.h5 part2.h5 -o all.h5");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  expect_same_cube(dir / "cases.h5", dir / "all.h5", {"wall_time_s", "cpu_time_s"});
}

}  // namespace
}  // namespace pcrf::study_test
