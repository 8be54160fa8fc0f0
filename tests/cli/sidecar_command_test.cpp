// Issue 41 on the command line: no input is ever an output (a hazard curve included); a
// symbolic link at each file beside a cube (lock, journal, .partial) and at each input is
// refused or seen through, never written through; a FIFO where a journal, a cube or an output
// is expected is refused at once; `cube info` mentions any journal beside the cube; a command
// stopped by SIGTERM leaves no temporary.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "study/study_test_support.hpp"

namespace pcrf {
namespace {

using study_test::pcrf;
using study_test::quoted;
namespace fs = std::filesystem;

int lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

/// `pcrf ARGS` in `dir`, ended after 60 s (a command that waits on a FIFO fails the test).
test::CommandResult in(const fs::path& dir, const std::string& args) {
  return test::run_command("cd " + quoted(dir) + " && timeout 60 " + pcrf() + " " + args);
}

void expect_refused(const test::CommandResult& r, const std::string& says, const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err;
  EXPECT_EQ(lines(r.err), 1) << what << "\n" << r.err;
  EXPECT_NE(r.err.find(says), std::string::npos) << what << "\n" << r.err;
}

constexpr const char* kHazard = "pga_g,annual_rate_per_yr\n0.05,0.178885\n0.1,0.0316228\n0.3,0.00202837\n1,0.0001\n3,6.415e-06\n";

TEST(Sidecars, ARiskReportIsNeverWrittenOverItsHazardCurve) {
  const auto dir = test::scratch_dir("sidecar_risk_hazard");
  test::write_file(dir, "f.toml",
                   "[[records]]\nsynthetic = [\"stochastic:seed=1,pga_g=1,duration_s=4\", \"stochastic:seed=2,pga_g=1,duration_s=4\"]\n"
                   "[intensity]\nmeasure = \"pga_g\"\n[axes]\nintensity = [1, 3]\n");
  ASSERT_EQ(in(dir, "study f.toml -o f.h5 --progress-interval 0").exit_code, 0);
  test::write_file(dir, "h.csv", kHazard);
  fs::create_symlink("h.csv", dir / "h_link.csv");
  fs::create_directories(dir / "sub");
  for (const std::string out : {"h.csv", "h_link.csv", "sub/../h.csv"})
    for (const std::string flag : {"--csv", "--json --csv"})
      for (const std::string overwrite : {"", " --overwrite"}) {
        const std::string command = "cube risk f.h5 --hazard h.csv " + flag + " " + out + overwrite;
        expect_refused(in(dir, command), "the input", command);
      }
  EXPECT_EQ(test::read_file(dir / "h.csv"), kHazard);
  // The hazard curve named through a link is still the input.
  expect_refused(in(dir, "cube risk f.h5 --hazard h_link.csv --csv h.csv --overwrite"), "the input", "via a link");
  EXPECT_EQ(test::read_file(dir / "h.csv"), kHazard);
  EXPECT_EQ(in(dir, "cube risk f.h5 --hazard h.csv --csv report.csv").exit_code, 0);
  // A figure is not drawn over the hazard curve either (a curve named like a figure).
  if (test::run_command(std::string("'") + PCRF_PYTHON + "' -c 'import matplotlib, numpy'").exit_code == 0) {
    test::write_file(dir, "h.svg", kHazard);
    expect_refused(in(dir, "plot risk f.h5 --hazard h.svg -o h.svg --overwrite"), "the input", "plot risk");
    EXPECT_EQ(test::read_file(dir / "h.svg"), kHazard);
  }
}

/// A small study in `dir` (s.toml) and its cube s.h5.
void make_study_and_cube(const fs::path& dir) {
  test::write_file(dir, "s.toml", study_test::small_grid_study());
  const auto r = in(dir, "study s.toml -o s.h5 --progress-interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

TEST(Sidecars, ALinkBesideTheCubeIsNeverWrittenThrough) {
  const auto dir = test::scratch_dir("sidecar_study_links");
  make_study_and_cube(dir);
  const std::string study = test::read_file(dir / "s.toml");
  for (const std::string sidecar : {".lock", ".journal", ".partial"})
    for (const std::string mode : {"--resume", "--overwrite", ""}) {
      const std::string out = mode.empty() ? "new.h5" : "s.h5";
      fs::create_symlink("s.toml", dir / (out + sidecar));
      const std::string command = "study s.toml -o " + out + " " + mode + " --progress-interval 0";
      // Refused as a link, or (a link to the study file) as the study file itself.
      expect_refused(in(dir, command), out + sidecar, command);
      EXPECT_EQ(test::read_file(dir / "s.toml"), study) << command;
      EXPECT_FALSE(fs::exists(dir / "new.h5")) << command;
      fs::remove(dir / (out + sidecar));
    }
  // A sidecar that is the study file itself (its name), not a link: the study is not the lock.
  fs::copy_file(dir / "s.toml", dir / "t.h5.lock");
  expect_refused(in(dir, "study t.h5.lock -o t.h5 --progress-interval 0"), "is the study file itself", "lock as study");
  EXPECT_EQ(test::read_file(dir / "t.h5.lock"), study);
}

TEST(Sidecars, AFifoIsRefusedAtOnceNeverWaitedOn) {
  const auto dir = test::scratch_dir("sidecar_fifos");
  make_study_and_cube(dir);
  ASSERT_EQ(::mkfifo((dir / "s.h5.journal").c_str(), 0600), 0);
  // cube info reads the cube and says its journal cannot be read.
  const auto info = in(dir, "cube info s.h5");
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.err.find("s.h5.journal: is a FIFO"), std::string::npos) << info.err;
  expect_refused(in(dir, "study s.toml -o s.h5 --resume --progress-interval 0"), "s.h5.journal: is a FIFO", "resume");
  expect_refused(in(dir, "study s.toml -o s.h5 --overwrite --progress-interval 0"), "s.h5.journal: is a FIFO", "overwrite");
  expect_refused(in(dir, "cube merge s.h5 -o m.h5"), "s.h5.journal: is a FIFO", "merge");
  fs::remove(dir / "s.h5.journal");
  ASSERT_EQ(::mkfifo((dir / "m.h5").c_str(), 0600), 0);
  expect_refused(in(dir, "cube merge s.h5 -o m.h5 --overwrite"), "m.h5: is a FIFO; the merged cube must be a regular file", "-o FIFO");
  ASSERT_EQ(::mkfifo((dir / "out.csv").c_str(), 0600), 0);
  expect_refused(in(dir, "cube export s.h5 -o out.csv"), "out.csv: is a FIFO that no process reads", "export to FIFO");
}

TEST(Sidecars, CubeInfoMentionsAJournalBesideTheCube) {
  const auto dir = test::scratch_dir("sidecar_info_journal");
  make_study_and_cube(dir);
  EXPECT_EQ(in(dir, "cube info s.h5").err.find("journal"), std::string::npos);
  // A journal of another fold (stale), or not a journal at all: said, not silently ignored.
  test::write_file(dir, "s.h5.journal", "pcrf-log");
  const auto stale = in(dir, "cube info s.h5");
  EXPECT_EQ(stale.exit_code, 0) << stale.err;
  EXPECT_NE(stale.err.find("s.h5: its journal s.h5.journal"), std::string::npos) << stale.err;
  EXPECT_NE(stale.err.find("is not of its last fold"), std::string::npos) << stale.err;
}

TEST(Sidecars, ARunStoppedBySigtermLeavesNoTemporary) {
  const auto dir = test::scratch_dir("sidecar_run_sigterm");
  const auto err = dir / "run.err";
  // A history of 10^6 rows: seconds of writing into the temporary.
  const pid_t pid = study_test::spawn_shell(
      "cd " + quoted(dir) + " && exec " + pcrf() + " run --synthetic 'sine:amplitude_g=0.5,period_s=0.5,cycles=40,duration_s=20' "
      "--history h.csv --history-dt-s 2e-5 2>" + quoted(err));
  ASSERT_GT(pid, 0);
  bool started = false;
  for (int i = 0; i < 3000 && !started; ++i) {
    for (const auto& e : fs::directory_iterator(dir))
      started = started || (e.path().filename().string().rfind(".h.csv.", 0) == 0 && fs::file_size(e.path()) > 0);
    if (!started) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(started) << "the history's temporary never appeared";
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int wstatus = 0;
  ::waitpid(pid, &wstatus, 0);
  EXPECT_TRUE(WIFSIGNALED(wstatus) && WTERMSIG(wstatus) == SIGTERM);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_NE(e.path().filename().string().front(), '.') << e.path() << ": a temporary left behind";
  EXPECT_FALSE(fs::exists(dir / "h.csv"));
}

/// The child of `parent` whose environment says it is MPI rank `rank` (0 when none does).
pid_t rank_of(pid_t parent, int rank) {
  const auto children = test::run_command("pgrep -P " + std::to_string(parent)).out;
  std::istringstream in(children);
  for (pid_t child = 0; in >> child;) {
    std::ifstream environ("/proc/" + std::to_string(child) + "/environ", std::ios::binary);
    std::string variables((std::istreambuf_iterator<char>(environ)), std::istreambuf_iterator<char>());
    if (variables.find(std::string("OMPI_COMM_WORLD_RANK=") + std::to_string(rank) + '\0') != std::string::npos) return child;
  }
  return 0;
}

// Issue 41 item 9: the advice after SIGTERM is the whole command, mpirun included.
TEST(Sidecars, TheSigtermAdviceUnderMpirunIsTheWholeCommand) {
  PCRF_REQUIRE_MPIRUN();
  const auto dir = test::scratch_dir("sidecar_mpirun_advice");
  const auto study = test::write_file(dir, "sig.toml",
                                      "[[records]]\nsynthetic = [\"stochastic:seed=4,pga_g=1.4,duration_s=20\"]\n"
                                      "[axes]\nkappa = {from = 1.0, to = 3.0, count = 60}\ntan_alpha = {from = 0.16, to = 0.24, count = 20}\n");
  const auto err = dir / "sig.err";
  const pid_t pid = study_test::spawn_shell("cd " + quoted(dir) + " && exec " + study_test::mpirun(2) + pcrf() +
                                            " study sig.toml -o sig.h5 --flush-interval-s 1000 --batch-size 4 "
                                            "--progress-interval-s 0.05 2>" + quoted(err));
  ASSERT_GT(pid, 0);
  study_test::wait_for_a_tenth(err);
  const pid_t rank0 = rank_of(pid, 0);
  ASSERT_GT(rank0, 0) << "rank 0 not found among mpirun's children";
  ASSERT_EQ(::kill(rank0, SIGTERM), 0);  // as a scheduler that signals the ranks themselves
  ::waitpid(pid, nullptr, 0);
  const std::string text = test::read_file(err);
  EXPECT_NE(text.find("continue with: mpirun -n 2 pcrf study sig.toml -o sig.h5 --resume --flush-interval-s=1000 "
                      "--progress-interval-s=0.05 --batch-size=4"),
            std::string::npos) << text;
}

TEST(Sidecars, RecordSelectionReadsNoFifo) {
  // `pcrf record select` reads its target and library as regular files: a FIFO there is
  // refused at once (it blocked before), naming the file; nothing is written.
  const auto dir = test::scratch_dir("sidecar_select_fifo");
  fs::remove(dir / "t.csv");
  fs::remove(dir / "lib.csv");
  ASSERT_EQ(::mkfifo((dir / "t.csv").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir / "lib.csv").c_str(), 0600), 0);
  expect_refused(in(dir, "record select --target t.csv --library lib.csv -n 2 -o sel.toml"), "t.csv: not a regular file",
                 "target FIFO");
  test::write_file(dir, "t2.csv", "period_s,mean_ln_sa,sigma_ln_sa\n0.5,-1,0.5\n1,-1.5,0.5\n");
  expect_refused(in(dir, "record select --target t2.csv --library lib.csv -n 2 -o sel.toml"), "lib.csv: not a regular file",
                 "library FIFO");
  EXPECT_FALSE(fs::exists(dir / "sel.toml"));
}

}  // namespace
}  // namespace pcrf
