// An IDA whose curves are searched whole in chunks of the cube (issue 38: IDA curves stay whole
// within one chunk): a worker handed a chunk runs the hunt-and-fill search of each of its curves
// itself and seals the chunk, its points past a curve's last run left not run. The cube, every
// run's status and metrics and every curve's summary, equals the run-by-run search that rank 0
// drives (--batch-size turns the chunks off), at one rank and at three; a run stopped by
// SIGTERM, and one killed while a worker rank keeps chunks in its part, resume to it.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <thread>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

/// 24 576 curves of 5 runs (122 880 cases): eight chunks of the cube (3 276 whole curves each,
/// the last shorter), enough for whole chunks at one rank and at three (at least two a worker
/// and a tail chunk). LHS frames from stocky to slender under a short weak record, searched from
/// 0.5 g to 2.5 g: most never lift (cheap) and are right-censored at the cap, some rock and
/// fracture their tendons (collapses, bisected), the deepest beams are outside the model
/// (no verdict: unresolved curves); most curves end before their fifth run.
std::string units_ida() {
  return "[study]\nname = \"ida_units\"\n[plan]\nkind = \"lhs\"\nsamples = 24576\nseed = 4\n"
         "[[records]]\nsynthetic = \"stochastic:seed=1,pga_g=0.1,duration_s=2,dt_s=0.01\"\n"
         "[axes]\nkappa = {from = 1.26, to = 2.34}\ntan_alpha = {from = 0.15, to = 1.5}\n"
         "lambda_h = {from = 0.14, to = 0.26}\n[intensity]\nmeasure = \"pga_g\"\n"
         "[ida]\nstart = 0.5\nmax_intensity = 2.5\nresolution = 0.2\nmax_runs = 5\n"
         "[outputs]\nmetrics = [\"theta_max_rad\", \"impacts\"]\n";
}

const std::vector<std::string> kTimes{"wall_time_s", "cpu_time_s"};
const std::vector<std::string> kSummaries{"collapse_intensity", "last_safe_intensity", "ida_runs", "curve_state",
                                          "unresolved_runs"};

test::CommandResult study_in(const std::filesystem::path& dir, const std::string& args, const std::string& launcher = "") {
  return test::run_command("cd " + quoted(dir) + " && " + launcher + pcrf() + " study u.toml --progress-interval 0 " + args);
}

/// The cubes' runs and every curve's summaries are the same, NaN for NaN.
void expect_same_ida(const std::filesystem::path& a, const std::filesystem::path& b) {
  expect_same_cube(a, b, kTimes);
  const cube::CubeReader x(a), y(b);
  for (const auto& name : kSummaries) {
    const auto u = x.read_side(name), v = y.read_side(name);
    ASSERT_EQ(u.size(), v.size()) << name;
    std::size_t differences = 0;
    for (std::size_t i = 0; i < u.size(); ++i)
      if (!(u[i] == v[i] || (std::isnan(u[i]) && std::isnan(v[i])))) ++differences;
    EXPECT_EQ(differences, 0u) << name << " of " << b.filename();
  }
}

std::string text_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The runs a study says it computed ("N cases computed"); -1 when it does not say.
long computed(const std::string& err) {
  static const std::regex said(R"((\d+) cases computed)");
  std::smatch m;
  return std::regex_search(err, m, said) ? std::stol(m[1].str()) : -1;
}

/// Each test in its own folder (ctest runs them apart, in parallel), with the run-by-run search
/// (rank 0 hands out every run: --batch-size) as its reference.
class IdaUnits : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_dir(std::string("ida_units_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    test::write_file(dir_, "u.toml", units_ida());
    const auto runs = study_in(dir_, "--batch-size 1 -o runs.h5");
    ASSERT_EQ(runs.exit_code, 0) << runs.err;
    computed_ = computed(runs.err);
  }
  std::filesystem::path dir_;
  long computed_ = -1;
};

/// What the comparisons stand on: the study exercises every branch of the search, and its
/// cube's chunks hold whole curves, more than the units of three ranks need.
void expect_every_kind_of_curve(const std::filesystem::path& file) {
  const cube::CubeReader cube(file);
  const auto status = cube.read_status();
  const auto theta = cube.read_metric("theta_max_rad");
  const auto state = cube.read_side("curve_state");
  std::size_t not_run = 0, not_run_with_values = 0;
  for (std::size_t i = 0; i < status.size(); ++i)
    if (status[i] == cube::kStatusNotRun) {
      ++not_run;
      not_run_with_values += std::isnan(theta[i]) ? 0 : 1;
    }
  EXPECT_GT(not_run, status.size() / 10) << "curves that end early leave points not run";
  EXPECT_EQ(not_run_with_values, 0u) << "a point not run holds the cube's fill, NaN";
  std::map<int, std::size_t> states;
  for (const double s : state) ++states[std::isnan(s) ? -1 : static_cast<int>(s)];
  EXPECT_EQ(states.count(-1), 0u) << "every curve finished";
  EXPECT_GT(states[0] + states[2], 0u) << "curves that collapse (bracketed or not)";
  EXPECT_GT(states[1], 0u) << "curves right-censored at the cap";
  EXPECT_GT(states[3], 0u) << "unresolved curves";
  const cube::ChunkGrid grid(cube.layout().shape());
  EXPECT_GE(grid.chunk_count(), 7u);
  EXPECT_EQ(grid.range(0).count % 5, 0);
}

TEST_F(IdaUnits, CurvesSearchedInWholeChunksGiveTheRunByRunCubeAtOneAndThreeRanks) {
  expect_every_kind_of_curve(dir_ / "runs.h5");
  const auto one = study_in(dir_, "-o one.h5");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  expect_same_ida(dir_ / "runs.h5", dir_ / "one.h5");
  // The same runs were made and counted (a point never run is no case computed).
  EXPECT_EQ(computed(one.err), computed_) << one.err;
  EXPECT_GT(computed_, 0);
  PCRF_REQUIRE_MPIRUN();
  const auto three = study_in(dir_, "-o three.h5", mpirun(3));
  ASSERT_EQ(three.exit_code, 0) << three.err;
  EXPECT_EQ(three.err.find("instead of its part"), std::string::npos) << three.err;
  expect_same_ida(dir_ / "runs.h5", dir_ / "three.h5");
  for (const char* part : {"three.h5.part-1", "three.h5.part-2"})
    EXPECT_FALSE(std::filesystem::exists(dir_ / part)) << part << " is removed by the run's last fold";
}

// A shard's whole chunks are those whose curves are all the shard's (12 288 curves a shard:
// three whole chunks, two of them units at one rank); the merged shards are the whole cube.
TEST_F(IdaUnits, ShardsSearchTheirOwnWholeChunksAndMergeToTheSameCube) {
  for (const char* k : {"1", "2"}) {
    const auto shard = study_in(dir_, std::string("--shard ") + k + "/2 -o part" + k + ".h5");
    ASSERT_EQ(shard.exit_code, 0) << shard.err;
  }
  const auto merged = test::run_command("cd " + quoted(dir_) + " && " + pcrf() + " cube merge part1.h5 part2.h5 -o all.h5");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  expect_same_ida(dir_ / "runs.h5", dir_ / "all.h5");
}

TEST_F(IdaUnits, ARunStoppedBySigtermInsideAChunkResumesToTheSameCube) {
  const auto err = dir_ / "sig.err";
  const pid_t pid = spawn_shell("cd " + quoted(dir_) + " && exec " + pcrf() +
                                " study u.toml -o sig.h5 --flush-interval-s 1000 --progress-interval-s 0.02 2>" + quoted(err));
  ASSERT_GT(pid, 0);
  ASSERT_EQ(stop_after_a_tenth(pid, err), 128 + SIGTERM) << "the study finished before the signal: make it longer\n"
                                                         << text_of(err);
  {
    const auto status = cube::CubeReader(dir_ / "sig.h5").read_status();
    const auto reference = cube::CubeReader(dir_ / "runs.h5").read_status();
    std::size_t saved = 0, wrong = 0;
    for (std::size_t i = 0; i < status.size(); ++i) {
      if (status[i] == cube::kStatusNotRun) continue;
      ++saved;
      wrong += status[i] != reference[i] ? 1 : 0;  // every run saved is one the search makes
    }
    EXPECT_GT(saved, 0u);
    EXPECT_EQ(wrong, 0u);
  }
  const auto resumed = study_in(dir_, "-o sig.h5 --resume");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_ida(dir_ / "runs.h5", dir_ / "sig.h5");
}

TEST_F(IdaUnits, AWorkerKeepsWholeCurvesInItsPartAndAKillThereResumesToTheSameCube) {
  PCRF_REQUIRE_MPIRUN();
  const auto err = dir_ / "killed.err";
  const LauncherTmp launcher_tmp;  // the killed launcher's session folder goes with it
  const pid_t pid = spawn_shell("cd " + quoted(dir_) + " && exec setsid " + launcher_tmp.env() + mpirun(3) + pcrf() +
                                " study u.toml -o killed.h5 --flush-interval-s 0.05 --progress-interval 0 2>" + quoted(err));
  ASSERT_GT(pid, 0);
  // A worker rank makes its part when it keeps its first chunk: kill every rank then.
  bool part_seen = false;
  int ended = -1;  // the run's wait status, when it ended before a part was seen
  for (int i = 0; i < 6000 && !part_seen; ++i) {
    part_seen = std::filesystem::exists(dir_ / "killed.h5.part-1") || std::filesystem::exists(dir_ / "killed.h5.part-2");
    if (!part_seen) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) {  // the run ended
      ended = status;
      break;
    }
  }
  if (ended < 0) {
    ::kill(-pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the ranks die with their group
  EXPECT_TRUE(part_seen) << "no worker rank kept an IDA chunk in its part"
                         << (ended >= 0 ? "; the run ended first, wait status " + std::to_string(ended) : std::string())
                         << "; its stderr:\n" << text_of(err);
  const auto resumed = study_in(dir_, "-o killed.h5 --resume", mpirun(3));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_ida(dir_ / "runs.h5", dir_ / "killed.h5");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "killed.h5.part-1"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "killed.h5.part-2"));
}

}  // namespace
}  // namespace pcrf::study_test
