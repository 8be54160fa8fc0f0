// Ranks' parts (issue 38: no rank handles every result): at several ranks each worker (rank 0's
// own worker thread included, in `<cube>.part-0`) keeps the whole chunks it seals in its own
// part beside the cube, and the run's last fold puts them in. The cube equals the one of one
// rank and of the case-by-case hand-out; a symbolic link at a part name is refused, its target
// untouched; a run killed mid-way at three ranks resumes to the uninterrupted cube, and rank 0
// never journals a whole chunk there.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

/// 120 000 frames that never lift (a weak record): eight chunks of the cube (seven of 16 384
/// and an edge one), enough for units at three ranks (at least 2 a worker and a tail chunk;
/// the 70 000 of units_study_test.cpp give units at one and two ranks only).
std::string parts_study() {
  return "[study]\nname = \"parts\"\n[plan]\nkind = \"lhs\"\nsamples = 120000\nseed = 4\n"
         "[[records]]\nsynthetic = \"stochastic:seed=1,pga_g=0.026,duration_s=4,dt_s=0.01\"\n"
         "[axes]\nkappa = {from = 1.26, to = 2.34}\ntan_alpha = {from = 0.14, to = 0.26}\n"
         "lambda_h = {from = 0.14, to = 0.26}\n";
}

test::CommandResult study_in(const std::filesystem::path& dir, const std::string& args, const std::string& launcher = "") {
  return test::run_command("cd " + quoted(dir) + " && " + launcher + pcrf() + " study p.toml --progress-interval 0 " + args);
}

const std::vector<std::string> kTimes{"wall_time_s", "cpu_time_s"};

TEST(PartsStudy, ThreeRanksKeepingPartsGiveTheCubeOfOneRankAndOfTheCaseByCaseHandOut) {
  PCRF_REQUIRE_MPIRUN();
  const auto dir = test::scratch_dir("parts_study");
  test::write_file(dir, "p.toml", parts_study());
  const auto one_by_one = study_in(dir, "--batch-size 64 -o cases.h5");
  ASSERT_EQ(one_by_one.exit_code, 0) << one_by_one.err;
  const auto one = study_in(dir, "-o one.h5");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto three = study_in(dir, "-o three.h5", mpirun(3));
  ASSERT_EQ(three.exit_code, 0) << three.err;
  EXPECT_NE(three.err.find("120000 cases computed, 0 failed"), std::string::npos) << three.err;
  EXPECT_EQ(three.err.find("instead of its part"), std::string::npos) << three.err;
  expect_same_cube(dir / "cases.h5", dir / "one.h5", kTimes);
  expect_same_cube(dir / "cases.h5", dir / "three.h5", kTimes);
  for (const char* part : {"three.h5.part-0", "three.h5.part-1", "three.h5.part-2"})
    EXPECT_FALSE(std::filesystem::exists(dir / part)) << part << " is removed by the run's last fold";
}

TEST(PartsStudy, ALinkAtAPartNameIsRefusedAndItsTargetUntouched) {
  for (const std::string part : {"c.h5.part-2", "c.h5.part-0"}) {  // a worker rank's, rank 0's own
    const auto dir = test::scratch_dir("parts_link_" + part.substr(part.size() - 1));
    test::write_file(dir, "p.toml", parts_study());
    test::write_file(dir, "mine.txt", "the user's\n");
    std::filesystem::create_symlink("mine.txt", dir / part);
    const auto run = study_in(dir, "-o c.h5", have_mpirun() ? mpirun(3) : "");
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find(part + ": is a symbolic link"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "c.h5"));
    EXPECT_TRUE(std::filesystem::is_symlink(dir / part));
    std::ifstream in(dir / "mine.txt");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "the user's\n");
  }
}

/// Whole chunks in the journal of `cube` (as a kill left it): rank 0 journals none at several
/// ranks, its own worker thread keeping them in its part (`<cube>.part-0`).
std::size_t sealed_in_journal(const std::filesystem::path& cube) {
  if (!std::filesystem::exists(cube) || !std::filesystem::exists(cube::journal_path(cube))) return 0;
  const cube::CubeReader reader(cube);
  const cube::JournalReader journal(cube, reader.layout(), cube::journal_id_of(reader.layout()));
  return journal.sealed_chunks().size();
}

TEST(PartsStudy, ARunKilledAtThreeRanksResumesToTheUninterruptedCube) {
  PCRF_REQUIRE_MPIRUN();
  const auto dir = test::scratch_dir("parts_kill");
  test::write_file(dir, "p.toml", parts_study());
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(study_in(dir, "-o whole.h5", mpirun(3)).exit_code, 0);
  const double whole_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Kills at instants spread over a run (start-up included), each a --resume of the last.
  bool parts_seen = false, rank0_part_seen = false;
  for (int k = 1; k <= 6; ++k) {
    const LauncherTmp launcher_tmp;  // the killed launcher's session folder goes with it
    const pid_t pid = spawn_shell("cd " + quoted(dir) + " && exec setsid " + launcher_tmp.env() + mpirun(3) + pcrf() +
                                  " study p.toml -o killed.h5 --resume --flush-interval-s 0.001 --progress-interval 0");
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::duration<double>(whole_s * k / 7.0));
    ::kill(-pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the ranks die with their group
    parts_seen = parts_seen || std::filesystem::exists(dir / "killed.h5.part-1") ||
                 std::filesystem::exists(dir / "killed.h5.part-2");
    rank0_part_seen = rank0_part_seen || std::filesystem::exists(dir / "killed.h5.part-0");
    EXPECT_EQ(sealed_in_journal(dir / "killed.h5"), 0u) << "kill " << k << ": rank 0 journaled whole chunks";
    if (!std::filesystem::exists(dir / "killed.h5")) continue;
    const auto info = test::run_command(pcrf() + " cube info " + quoted(dir / "killed.h5"));
    ASSERT_EQ(info.exit_code, 0) << "kill " << k << " left a cube that cannot be read:\n" << info.out << info.err;
  }
  const auto resumed = study_in(dir, "-o killed.h5 --resume", mpirun(3));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_cube(dir / "whole.h5", dir / "killed.h5", kTimes);
  EXPECT_FALSE(std::filesystem::exists(dir / "killed.h5.part-1"));
  EXPECT_FALSE(std::filesystem::exists(dir / "killed.h5.part-0"));
  if (!parts_seen) std::cerr << "note: no kill left a part (the run was too quick to catch)\n";
  if (!rank0_part_seen) std::cerr << "note: no kill left rank 0's part\n";
}

// A stopped run's parts (rank `rank`'s): cube info says what waits in them, cube merge refuses
// the cube until --resume folds them in (a chunk the cube holds already is skipped) and removes them.
void expect_readers_mention_part_and_merge_waits(int rank) {
  const std::string part = "c.h5.part-" + std::to_string(rank);
  const auto dir = test::scratch_dir("parts_readers_" + std::to_string(rank));
  test::write_file(dir, "p.toml", parts_study());
  ASSERT_EQ(study_in(dir, "-o c.h5").exit_code, 0);
  {  // chunk 2 as a worker of a stopped run kept it (the cube holds it too: a kill after the last fold's rename)
    const cube::CubeReader reader(dir / "c.h5");
    const cube::ChunkGrid grid(reader.layout().shape());
    const auto status = reader.read_status();
    const auto r = grid.range(2);
    const std::size_t metrics = reader.layout().metrics.size();
    std::vector<std::int8_t> codes(status.begin() + r.first, status.begin() + r.first + r.count);
    std::vector<double> values(metrics * codes.size(), 0.0);
    cube::PartWriter writer(dir / part, cube::part_header_of(reader.layout()));
    writer.add(cube::seal_chunk(grid, 2, metrics, codes, values, {}));
  }
  const auto info = test::run_command(pcrf() + " cube info " + quoted(dir / "c.h5"));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.err.find("16384 results wait in its ranks' parts (" + part + ")"), std::string::npos) << info.err;
  const auto merge = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " cube merge c.h5 -o m.h5");
  EXPECT_NE(merge.exit_code, 0);
  EXPECT_NE(merge.err.find("--resume its run first"), std::string::npos) << merge.err;
  ASSERT_EQ(study_in(dir, "-o c.h5 --resume").exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(dir / part));
  EXPECT_EQ(test::run_command(pcrf() + " cube info " + quoted(dir / "c.h5")).err.find("parts"), std::string::npos);
  ASSERT_EQ(study_in(dir, "--batch-size 64 -o cases.h5").exit_code, 0);
  expect_same_cube(dir / "cases.h5", dir / "c.h5", kTimes);  // the part's zeros were not laid over the cube
}

TEST(PartsStudy, ReadersMentionPartsAndMergeWaitsForTheResume) {
  expect_readers_mention_part_and_merge_waits(1);
  expect_readers_mention_part_and_merge_waits(0);  // rank 0's own worker thread's
}

}  // namespace
}  // namespace pcrf::study_test
