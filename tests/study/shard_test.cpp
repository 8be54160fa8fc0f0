// Sharded runs: K/N shards of a study, merged, equal the unsharded cube; overlapping or
// missing parts are reported, not merged; an IDA shards by curves.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "pcrf/cube/cube_reader.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

test::CommandResult study_in(const std::filesystem::path& dir, const std::string& args) {
  return test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study s.toml --progress-interval 0 " + args);
}

test::CommandResult merge_in(const std::filesystem::path& dir, const std::string& args) {
  return test::run_command("cd " + quoted(dir) + " && " + pcrf() + " cube merge " + args);
}

TEST(Shards, MergedShardsEqualTheUnshardedCube) {
  const auto dir = test::scratch_dir("shards_grid");
  test::write_file(dir, "s.toml", small_grid_study());
  ASSERT_EQ(study_in(dir, "-o whole.h5").exit_code, 0);
  for (int k = 1; k <= 3; ++k) ASSERT_EQ(study_in(dir, "--shard " + std::to_string(k) + "/3 -o part" + std::to_string(k) + ".h5").exit_code, 0);
  {
    cube::CubeReader part(dir / "part2.h5");
    EXPECT_EQ(part.layout().text_attribute("shard"), "2/3");
    const auto status = part.read_status();
    const auto done = std::count_if(status.begin(), status.end(), [](std::int8_t s) { return s != cube::kStatusNotRun; });
    EXPECT_NEAR(static_cast<double>(done), static_cast<double>(status.size()) / 3.0, 1.0);
  }
  const auto missing = merge_in(dir, "part1.h5 part3.h5 -o all.h5");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("cases are in no part"), std::string::npos) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "all.h5"));
  const auto overlap = merge_in(dir, "part1.h5 part2.h5 part2.h5 -o all.h5");
  EXPECT_EQ(overlap.exit_code, 2);
  EXPECT_NE(overlap.err.find("the parts overlap"), std::string::npos) << overlap.err;
  const auto merged = merge_in(dir, "part1.h5 part2.h5 part3.h5 -o all.h5");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  expect_same_cube(dir / "whole.h5", dir / "all.h5");
  EXPECT_EQ(cube::CubeReader(dir / "all.h5").layout().text_attribute("shard"), "");
  // A shard resumes only as the same shard.
  const auto wrong = study_in(dir, "--shard 1/3 -o part2.h5 --resume");
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_NE(wrong.err.find("is shard \"2/3\""), std::string::npos) << wrong.err;
  EXPECT_EQ(study_in(dir, "--shard 4/3 -o x.h5").exit_code, 2);
}

TEST(Shards, AnIdaShardsByCurves) {
  const auto dir = test::scratch_dir("shards_ida");
  std::string text = "[[records]]\nsynthetic = [";
  for (int seed = 1; seed <= 4; ++seed)
    text += std::string(seed > 1 ? ", " : "") + "\"stochastic:seed=" + std::to_string(seed) + ",pga_g=1,duration_s=6\"";
  text += "]\n[intensity]\nmeasure = \"pga_g\"\n[ida]\nstart = 0.5\nmax_intensity = 6\nmax_runs = 10\n";
  test::write_file(dir, "s.toml", text);
  ASSERT_EQ(study_in(dir, "-o whole.h5").exit_code, 0);
  ASSERT_EQ(study_in(dir, "--shard 1/2 -o a.h5").exit_code, 0);
  ASSERT_EQ(study_in(dir, "--shard 2/2 -o b.h5").exit_code, 0);
  // The points after a curve's end are in no part and not missing; a curve in no part is.
  const auto half = merge_in(dir, "a.h5 -o half.h5");
  EXPECT_EQ(half.exit_code, 2);
  EXPECT_NE(half.err.find("cases are in no part"), std::string::npos) << half.err;
  EXPECT_NE(half.err.find("--allow-missing"), std::string::npos) << half.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "half.h5"));
  // Merged anyway: the cube says it is partial, and its fragility neither fits nor fails
  // the curves no part ran.
  const auto allowed = merge_in(dir, "a.h5 -o half.h5 --allow-missing");
  ASSERT_EQ(allowed.exit_code, 0) << allowed.err;
  EXPECT_NE(allowed.err.find("cases are in no part: the merged cube is partial"), std::string::npos) << allowed.err;
  const auto attributes = cube::CubeReader(dir / "half.h5").layout().attributes;
  const auto missing = std::find_if(attributes.begin(), attributes.end(),
                                    [](const cube::Attribute& a) { return a.name == "merge_missing_cases"; });
  ASSERT_NE(missing, attributes.end());
  EXPECT_GT(std::get<std::int64_t>(missing->value), 0);
  const auto fragility = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " cube fragility half.h5 --csv half.csv");
  ASSERT_EQ(fragility.exit_code, 0) << fragility.err;
  EXPECT_NE(fragility.err.find("half.h5: 2 of 4 curves not run (a partial cube)"), std::string::npos) << fragility.err;
  std::ifstream csv(dir / "half.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header.rfind("frame,records,cases,collapses,failed,", 0), 0u) << header;
  EXPECT_EQ(row.rfind("all,4,2,", 0), 0u) << row;           // the two curves run
  const auto columns = [](const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    return cells;
  };
  EXPECT_EQ(columns(row).at(4), "0") << row;  // none failed: the two not run are not failures
  ASSERT_EQ(merge_in(dir, "a.h5 b.h5 -o all.h5").exit_code, 0);
  expect_same_cube(dir / "whole.h5", dir / "all.h5");
  cube::CubeReader whole(dir / "whole.h5"), all(dir / "all.h5");
  EXPECT_EQ(whole.read_side("collapse_intensity"), all.read_side("collapse_intensity"));
  EXPECT_EQ(whole.read_side("ida_runs"), all.read_side("ida_runs"));
}

TEST(Shards, OnlyKOverNWithinBoundsIsAShard) {
  const auto dir = test::scratch_dir("shards_strings");
  test::write_file(dir, "s.toml", small_grid_study());
  for (const std::string bad : {"", "1/-2", "18446744073709551615/18446744073709551615", " 1/2", "1/2x", "+1/2", "1/",
                                "/2", "0/3", "4/3", "1/1000001", "1//2", "1/2/3"}) {
    for (const std::string check : {"", " --check"}) {
      const auto r = study_in(dir, "--shard '" + bad + "' -o x.h5" + check);
      EXPECT_EQ(r.exit_code, 2) << "'" << bad << "'" << check << "\n" << r.err;
      EXPECT_EQ(r.err, "pcrf: error: --shard: expected K/N with 1 ≤ K ≤ N ≤ 1000000, e.g. 3/8, got '" + bad + "'\n");
    }
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "x.h5"));
  EXPECT_EQ(study_in(dir, "--shard 1000000/1000000 --check").exit_code, 0);
}

TEST(Shards, EachShardStoresItsHistoriesAndTheMergeJoinsThem) {
  const auto dir = test::scratch_dir("shards_histories");
  // Two histories: the first case (shard 1 of 2) and the last (shard 2 of 2).
  test::write_file(dir, "s.toml", small_grid_study(
      "[[outputs.histories]]\nlabel = \"first\"\nrecord = \"" + std::string(kPulse) +
      "\"\nscale = 0.9\nkappa = 1.2\ntan_alpha = 0.18\n"
      "[[outputs.histories]]\nlabel = \"last\"\nrecord = \"" + std::string(kNoise) +
      "\"\nscale = 1.2\nkappa = 2.4\ntan_alpha = 0.22\n"));
  EXPECT_EQ(study_in(dir, "--shard 1/2 --check").exit_code, 0);  // --check and the run agree
  ASSERT_EQ(study_in(dir, "-o whole.h5").exit_code, 0);
  ASSERT_EQ(study_in(dir, "--shard 1/2 -o a.h5").exit_code, 0);
  ASSERT_EQ(study_in(dir, "--shard 2/2 -o b.h5").exit_code, 0);
  EXPECT_EQ(cube::CubeReader(dir / "a.h5").history_names(), std::vector<std::string>{"first"});
  EXPECT_EQ(cube::CubeReader(dir / "b.h5").history_names(), std::vector<std::string>{"last"});
  ASSERT_EQ(merge_in(dir, "a.h5 b.h5 -o all.h5").exit_code, 0);
  expect_same_cube(dir / "whole.h5", dir / "all.h5");
  const cube::CubeReader whole(dir / "whole.h5"), all(dir / "all.h5");
  ASSERT_EQ(all.history_names(), whole.history_names());
  for (const auto& name : whole.history_names()) {
    const auto w = whole.read_history(name), m = all.read_history(name);
    EXPECT_EQ(w.values, m.values) << name;
    ASSERT_EQ(w.columns.size(), m.columns.size());
  }
  // A history in two parts is an overlap.
  std::filesystem::copy_file(dir / "a.h5", dir / "a2.h5");
  const auto twice = merge_in(dir, "a.h5 a2.h5 b.h5 -o x.h5");
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.h5"));
}

TEST(Shards, PartialResultsAreNamed) {
  const auto dir = test::scratch_dir("shards_partial");
  test::write_file(dir, "s.toml", small_grid_study());  // 24 cases
  ASSERT_EQ(study_in(dir, "--shard 1/2 -o part.h5").exit_code, 0);
  for (const std::string command : {"stats part.h5 --by kappa -m theta_max_rad", "info part.h5", "info --json part.h5"}) {
    const auto r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " cube " + command);
    EXPECT_EQ(r.exit_code, 0) << command << "\n" << r.err;
    EXPECT_NE(r.err.find("part.h5: 12 of 24 cases not run (a partial cube)"), std::string::npos) << command << "\n" << r.err;
  }
  const auto merged = merge_in(dir, "part.h5 -o m.h5 --allow-missing");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(merged.err.find("m.h5: 12 of 24 cases are in no part"), std::string::npos) << merged.err;
  const auto whole = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study s.toml -o w.h5 --progress-interval 0 && " +
                                       pcrf() + " cube stats w.h5 --by kappa -m theta_max_rad");
  EXPECT_EQ(whole.err.find("not run"), std::string::npos) << whole.err;  // a complete cube says nothing
}

}  // namespace
}  // namespace pcrf::study_test
