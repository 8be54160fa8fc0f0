// Long runs that survive: a kill at random instants never leaves a cube that cannot be read
// or resumed, and the resumed cube equals the uninterrupted one; a full disk ends the run
// with one line and exit code 2, keeping the last complete cube for --resume.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mount.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <functional>
#include <sstream>
#include <random>
#include <thread>

#include "pcrf/cube/cube_reader.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

const std::string kStudy = std::string("[[records]]\nsynthetic = [\"") + kPulse + "\", \"" + kPulse2 + "\", \"" + kNoise +
                           "\"]\n[axes]\nscale = [0.9, 1.1, 1.3]\nkappa = {from = 1.0, to = 3.0, count = 6}\n"
                           "tan_alpha = {from = 0.16, to = 0.24, count = 6}\n";


TEST(CrashSafety, KillsAtRandomInstantsNeverCorruptTheCube) {
  const auto dir = test::scratch_dir("crash_kills");
  test::write_file(dir, "k.toml", kStudy);
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study k.toml -o whole.h5 --progress-interval 0").exit_code, 0);
  const double whole_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> instant(0.0, 1.2 * whole_s);
  const int kills = 24;
  int interrupted = 0;
  for (int k = 0; k < kills; ++k) {
    // Each run continues the last one: creation, checkpoints and the final close all get hit.
    const pid_t pid = spawn_shell("cd " + quoted(dir) + " && exec " + pcrf() +
                                  " study k.toml -o killed.h5 --resume --flush-interval-s 0.001 --progress-interval 0 2>/dev/null");
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::duration<double>(instant(random)));
    ::kill(pid, SIGKILL);
    int wstatus = 0;
    ::waitpid(pid, &wstatus, 0);
    interrupted += WIFSIGNALED(wstatus);
    if (!std::filesystem::exists(dir / "killed.h5")) continue;  // killed before the first checkpoint
    const auto info = test::run_command(pcrf() + " cube info " + quoted(dir / "killed.h5"));
    ASSERT_EQ(info.exit_code, 0) << "kill " << k << " left a cube that cannot be read:\n" << info.out << info.err;
    // A finished cube is started over, so that later kills hit creation and checkpoints
    // again rather than runs with nothing left to do.
    if (info.out.find("(100.0 %)") != std::string::npos) std::filesystem::remove(dir / "killed.h5");
  }
  EXPECT_GT(interrupted, kills / 3);
  const auto resumed = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study k.toml -o killed.h5 --resume --progress-interval 0");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_cube(dir / "whole.h5", dir / "killed.h5");
}

TEST(CrashSafety, AFullDiskEndsTheRunCleanlyAndTheCubeResumes) {
  const auto dir = test::scratch_dir("crash_full_disk");
  const auto small = dir / "small";
  std::filesystem::create_directories(small);
  ::umount(small.c_str());
  if (::mount("tmpfs", small.c_str(), "tmpfs", 0, "size=192k") != 0) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  struct Unmount {  // also when an assertion ends the test early
    std::filesystem::path at;
    ~Unmount() { ::umount(at.c_str()); }
  } unmount{small};
  test::write_file(dir, "f.toml", kStudy);
  const auto full = test::run_command("cd " + quoted(dir) + " && " + pcrf() +
                                      " study f.toml -o small/f.h5 --flush-interval-s 0.01 --progress-interval 0");
  EXPECT_EQ(full.exit_code, 2) << full.err;
  EXPECT_NE(full.err.find("No space left on device"), std::string::npos) << full.err;
  EXPECT_NE(full.err.find("free space, then --resume"), std::string::npos) << full.err;
  ASSERT_TRUE(std::filesystem::exists(small / "f.h5"));
  EXPECT_EQ(test::run_command(pcrf() + " cube info " + quoted(small / "f.h5")).exit_code, 0);
  std::filesystem::copy_file(small / "f.h5", dir / "f.h5", std::filesystem::copy_options::overwrite_existing);
  ::umount(small.c_str());
  // Space freed (here: a disk with room): --resume finishes it, equal to an uninterrupted run.
  ASSERT_EQ(test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study f.toml -o f.h5 --resume --progress-interval 0").exit_code, 0);
  ASSERT_EQ(test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study f.toml -o whole.h5 --progress-interval 0").exit_code, 0);
  expect_same_cube(dir / "whole.h5", dir / "f.h5");
}

/// 3600 cases: several seconds, long enough to act on the cube while it runs.
// Long enough (14 400 cases, about 5 s on one rank here) that a run is still going while a
// test acts on it: at 3600 cases the faster engine finished in 1.3 s, and a loaded machine
// let it end before the test's three refused runs had been made.
const std::string kLongStudy = std::string("[[records]]\nsynthetic = [\"") + kPulse + "\", \"" + kPulse2 + "\", \"" +
                               kNoise + "\"]\n[axes]\nscale = [0.9, 1.1, 1.3]\nkappa = {from = 1.0, to = 3.0, count = 40}\n"
                               "tan_alpha = {from = 0.16, to = 0.24, count = 40}\n";

/// Starts the long study into dir/out/l.h5, waits until it has run a while, does `act`, and
/// returns what the run said on stderr (its exit code is expected to be 2).
std::string interfere(const std::filesystem::path& dir, const std::function<void()>& act) {
  test::write_file(dir, "l.toml", kLongStudy);
  std::filesystem::create_directories(dir / "out");
  const pid_t pid = spawn_shell("cd " + quoted(dir) + " && exec " + pcrf() +
                                " study l.toml -o out/l.h5 --flush-interval-s 0.3 --progress-interval 0 2> err.txt");
  EXPECT_GT(pid, 0);
  // The first checkpoint exists from the start; a few later ones, then the interference.
  for (int i = 0; i < 3000 && !std::filesystem::exists(dir / "out" / "l.h5"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  act();
  int wstatus = 0;
  ::waitpid(pid, &wstatus, 0);
  EXPECT_TRUE(WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 2) << "the run ended before the interference";
  std::ifstream in(dir / "err.txt");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(CrashSafety, AdviceMatchesTheCause) {
  const auto gone_dir = test::scratch_dir("crash_folder_gone");
  // Taken away at once (a rename): remove_all would race with the run still writing into it
  // (a .partial or journal made during the walk: "Directory not empty", thrown).
  const std::string gone =
      interfere(gone_dir, [&] { std::filesystem::rename(gone_dir / "out", gone_dir / "taken_away"); });
  // Noticed before a checkpoint ("is gone") or during one (its .partial file cannot be written).
  EXPECT_NE(gone.find("pcrf: error: out/l.h5: "), std::string::npos) << gone;
  EXPECT_NE(gone.find("No such file or directory"), std::string::npos) << gone;
  EXPECT_NE(gone.find("run the study again"), std::string::npos) << gone;
  EXPECT_EQ(gone.find("free space"), std::string::npos) << gone;

  // Another file put in the cube's place is neither copied into nor overwritten.
  const auto replaced_dir = test::scratch_dir("crash_cube_replaced");
  const std::string foreign = "not this run's cube";
  const std::string replaced = interfere(replaced_dir, [&] {
    test::write_file(replaced_dir / "out", "other", foreign);
    std::filesystem::rename(replaced_dir / "out" / "other", replaced_dir / "out" / "l.h5");
  });
  EXPECT_NE(replaced.find("out/l.h5: was replaced by another file during the run"), std::string::npos) << replaced;
  EXPECT_NE(replaced.find("another -o"), std::string::npos) << replaced;
  EXPECT_EQ(replaced.find("free space"), std::string::npos) << replaced;
  // A lock file removed: the run stops before writing again, saying why.
  const auto lock_dir = test::scratch_dir("crash_lock_removed");
  const std::string unlocked = interfere(lock_dir, [&] { std::filesystem::remove(lock_dir / "out" / "l.h5.lock"); });
  EXPECT_NE(unlocked.find("out/l.h5: its lock out/l.h5.lock was removed during the run"), std::string::npos) << unlocked;
  EXPECT_NE(unlocked.find("make sure no other run writes it, then --resume"), std::string::npos) << unlocked;
  EXPECT_EQ(unlocked.find("free space"), std::string::npos) << unlocked;
  EXPECT_EQ(test::run_command(pcrf() + " cube info " + quoted(lock_dir / "out" / "l.h5")).exit_code, 0);

  std::ifstream kept(replaced_dir / "out" / "l.h5");
  std::string text;
  std::getline(kept, text);
  EXPECT_EQ(text, foreign);
}

TEST(CrashSafety, OneRunPerCube) {
  const auto dir = test::scratch_dir("crash_one_run");
  test::write_file(dir, "l.toml", kLongStudy);
  const pid_t first = spawn_shell("cd " + quoted(dir) + " && exec " + pcrf() +
                                  " study l.toml -o l.h5 --flush-interval-s 0.05 --progress-interval 0 2>/dev/null");
  ASSERT_GT(first, 0);
  for (int i = 0; i < 3000 && !std::filesystem::exists(dir / "l.h5"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  for (const std::string mode : {"", " --resume", " --overwrite"}) {
    const auto second = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study l.toml -o l.h5 --progress-interval 0" + mode);
    EXPECT_EQ(second.exit_code, 2) << mode << "\n" << second.err;
    EXPECT_NE(second.err.find("l.h5: in use by another run (pid " + std::to_string(first) + " on host "), std::string::npos)
        << mode << "\n" << second.err;
    EXPECT_EQ(std::count(second.err.begin(), second.err.end(), '\n'), 1) << second.err;
    // Refused at once, not after waiting for the lock: the first run is still going. (No wall
    // time is asserted; a loaded machine makes any bound flaky.)
    EXPECT_EQ(::waitpid(first, nullptr, WNOHANG), 0) << mode << ": the second run waited for the first to end";
  }
  const auto info = test::run_command(pcrf() + " cube info " + quoted(dir / "l.h5"));
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.err.find("a run holds it (pid " + std::to_string(first)), std::string::npos) << info.err;
  int wstatus = 0;
  ::waitpid(first, &wstatus, 0);
  ASSERT_TRUE(WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0) << "the first run was disturbed";
  EXPECT_NE(test::run_command(pcrf() + " cube info " + quoted(dir / "l.h5")).out.find("(100.0 %)"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "l.h5.lock"));

  // A run killed outright leaves its lock file; it is stale and the resume goes ahead.
  const pid_t killed = spawn_shell("cd " + quoted(dir) + " && exec " + pcrf() +
                                   " study l.toml -o k.h5 --flush-interval-s 0.05 --progress-interval 0 2>/dev/null");
  for (int i = 0; i < 3000 && !std::filesystem::exists(dir / "k.h5"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(killed, SIGKILL);
  ::waitpid(killed, nullptr, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "k.h5.lock"));
  const auto resumed = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study l.toml -o k.h5 --resume --progress-interval 0");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_cube(dir / "l.h5", dir / "k.h5");
}

}  // namespace
}  // namespace pcrf::study_test
