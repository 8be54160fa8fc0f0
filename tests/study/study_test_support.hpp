// Helpers of the study tests: running `pcrf study` (with or without mpirun), writing small
// study files with short synthetic records, and comparing two cubes value by value.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <spawn.h>

#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/record/synthetic.hpp"
#include "support/test_support.hpp"
#include "pcrf/user_error.hpp"

extern char** environ;

namespace pcrf::study_test {

/// Starts `/bin/sh -c command` in the background (for tests that signal or kill a run);
/// its pid, or 0 when it could not be started. Its standard output and error go to
/// /dev/null unless the command redirects them itself: a killed run can leave an Open MPI
/// helper (a singleton's orted) behind, and one holding the test's own output pipe kept
/// ctest waiting for a quarter of an hour.
inline pid_t spawn_shell(const std::string& command) {
  pid_t pid = 0;
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&files, 2, "/dev/null", O_WRONLY, 0);
  const char* argv[] = {"/bin/sh", "-c", command.c_str(), nullptr};
  const int failed = posix_spawn(&pid, "/bin/sh", &files, nullptr, const_cast<char**>(argv), environ);
  posix_spawn_file_actions_destroy(&files);
  return failed == 0 ? pid : 0;
}

/// Done/total of the last progress line in a stderr file.
inline std::pair<long, long> last_progress(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::pair<long, long> last{0, 0};
  static const std::regex progress(R"(pcrf study: (\d+)/(\d+) cases)");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, progress)) last = {std::stol(m[1]), std::stol(m[2])};
  }
  return last;
}

/// Waits (12 s at most) until the progress lines in `err` report a tenth of the cases done.
inline void wait_for_a_tenth(const std::filesystem::path& err) {
  std::pair<long, long> progress{0, 0};
  for (int i = 0; i < 600 && !(progress.second > 0 && progress.first >= progress.second / 10); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    progress = last_progress(err);
  }
}

/// Sends SIGTERM to `pid` once `err`'s progress lines report a tenth of the cases done, and
/// waits for it: its exit code, or -1 when it did not exit (a crash).
inline int stop_after_a_tenth(pid_t pid, const std::filesystem::path& err) {
  wait_for_a_tenth(err);
  if (::kill(pid, SIGTERM) != 0) return -1;
  int wstatus = 0;
  ::waitpid(pid, &wstatus, 0);
  return WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1;
}

inline std::string pcrf() { return "'" + test::pcrf_executable().string() + "'"; }

inline std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

/// Open MPI refuses root without these; CI runs as root.
inline std::string mpirun(int ranks) {
  return "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
         "mpirun --oversubscribe -n " + std::to_string(ranks) + " ";
}

/// A TMPDIR of its own for an mpirun that a test kills, removed with this object. A launcher
/// killed by SIGKILL leaves its session folder behind (Open MPI 5: prterun.<host>.<pid>.<uid>),
/// and a later launcher given the same PID then refuses to start (PMIX_ERR_EXISTS, PRRTE's
/// session_dir.c): in the shared TMPDIR, any later test could be that one. Short, because
/// PMIx puts its Unix sockets there (108 bytes at most a path).
class LauncherTmp {
 public:
  LauncherTmp() {
    const char* base = std::getenv("TMPDIR");
    std::string folder = std::string(base != nullptr && *base != '\0' ? base : "/tmp") + "/pcrf-mpi-XXXXXX";
    if (::mkdtemp(folder.data()) != nullptr) path_ = folder;
  }
  LauncherTmp(const LauncherTmp&) = delete;
  LauncherTmp& operator=(const LauncherTmp&) = delete;
  ~LauncherTmp() {
    std::error_code ignored;
    if (!path_.empty()) std::filesystem::remove_all(path_, ignored);
  }
  /// The prefix that gives a command this TMPDIR (none when it could not be made).
  std::string env() const { return path_.empty() ? std::string() : "env TMPDIR=" + quoted(path_) + " "; }

 private:
  std::filesystem::path path_;
};

inline bool have_mpirun() { return test::run_command("command -v mpirun").exit_code == 0; }

#define PCRF_REQUIRE_MPIRUN() \
  if (!::pcrf::study_test::have_mpirun()) GTEST_SKIP() << "mpirun not found"

/// Records short enough for tests (a few ms per case).
inline const char* kPulse = "sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=3";
inline const char* kPulse2 = "sine:amplitude_g=1.3,period_s=0.7,cycles=2,duration_s=3";
inline const char* kNoise = "stochastic:seed=4,pga_g=1.4,duration_s=6";

/// A small grid: 3 records × 2 scales × 2 κ × 2 tan α = 24 cases.
inline std::string small_grid_study(const std::string& extra = "") {
  return std::string("[study]\nname = \"small\"\n\n") +
         "[[records]]\nsynthetic = [\"" + kPulse + "\", \"" + kPulse2 + "\", \"" + kNoise + "\"]\n\n" +
         "[axes]\nscale = [0.9, 1.2]\nkappa = [1.2, 2.4]\ntan_alpha = [0.18, 0.22]\n\n" + extra;
}

/// Two horizontal components of a station, h1.txt and h2.txt in `dir` (stochastic, 6 s, PGA
/// 1 g and 0.9 g; two columns, time and m/s², 17 digits), and a [[records]] table naming them
/// as a pair at azimuths 0 and 90 (`name`: the record's name).
inline std::string station_pair(const std::filesystem::path& dir, const std::string& name = "pair") {
  for (const auto& [file, seed, pga_g] : {std::tuple{"h1.txt", 3, 1.0}, std::tuple{"h2.txt", 4, 0.9}}) {
    StochasticSpec spec;
    spec.seed = static_cast<std::uint64_t>(seed);
    spec.pga_g = pga_g;
    spec.duration_s = 6.0;
    const GroundMotion motion = make_stochastic(spec);
    std::ofstream out(dir / file);
    char line[80];
    for (std::size_t i = 0; i < motion.size(); ++i) {
      std::snprintf(line, sizeof line, "%.17g %.17g\n", static_cast<double>(i) * motion.dt_s(), motion.samples_m_s2()[i]);
      out << line;
    }
  }
  return "[[records]]\nh1 = \"h1.txt\"\nh2 = \"h2.txt\"\nunits = \"m/s2\"\naz1_deg = 0\naz2_deg = 90\nname = \"" + name +
         "\"\n";
}

/// Every value of every variable of `a` equals `b` (NaN equals NaN), except `ignored`.
inline void expect_same_cube(const std::filesystem::path& a_file, const std::filesystem::path& b_file,
                             const std::vector<std::string>& ignored = {"cpu_time_s"}) {
  cube::CubeReader a(a_file), b(b_file);
  ASSERT_EQ(a.layout().shape(), b.layout().shape());
  ASSERT_EQ(a.layout().metrics.size(), b.layout().metrics.size());
  EXPECT_EQ(a.read_status(), b.read_status());
  for (const auto& m : a.layout().metrics) {
    if (std::find(ignored.begin(), ignored.end(), m.name) != ignored.end()) continue;
    const auto x = a.read_metric(m.name);
    const auto y = b.read_metric(m.name);
    std::size_t differences = 0;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (!(x[i] == y[i] || (std::isnan(x[i]) && std::isnan(y[i])))) ++differences;
    EXPECT_EQ(differences, 0u) << m.name;
  }
  EXPECT_EQ(a.read_notes().size(), b.read_notes().size());
}

/// The message of the UserError that `parse(text)` raises ("" if none).
template <class Parse>
std::string error_of(Parse parse, const std::string& text) {
  try {
    parse(text);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

}  // namespace pcrf::study_test
