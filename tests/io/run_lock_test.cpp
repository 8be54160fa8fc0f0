// One writer per file (io::RunLock): a second lock is refused at once naming the holder; a
// holder that dies (SIGKILL, no clean-up) never blocks the next one; the lock file goes with
// its holder.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

#include "pcrf/io/checked_stream.hpp"
#include "pcrf/io/run_lock.hpp"
#include "support/test_support.hpp"

namespace pcrf::io {
namespace {

TEST(RunLock, ASecondLockIsRefusedNamingTheHolder) {
  const auto dir = test::scratch_dir("run_lock_second");
  const auto cube = dir / "c.h5";
  {
    RunLock first(cube);
    EXPECT_TRUE(std::filesystem::exists(RunLock::lock_path(cube)));
    const std::string who = RunLock::holder(cube);
    EXPECT_NE(who.find("pid " + std::to_string(::getpid()) + " on host "), std::string::npos) << who;
    EXPECT_NE(who.find(", started 20"), std::string::npos) << who;
    try {
      RunLock second(cube);
      FAIL() << "two locks on one cube";
    } catch (const OutputError& e) {
      EXPECT_EQ(std::string(e.what()), cube.string() + ": in use by another run (" + who + "); wait for it to end, or give another -o");
    }
    EXPECT_EQ(RunLock::holder(cube), who);  // looking does not take it
  }
  EXPECT_FALSE(std::filesystem::exists(RunLock::lock_path(cube)));
  EXPECT_EQ(RunLock::holder(cube), "");
  RunLock again(cube);  // released
}

TEST(RunLock, AKilledHoldersLockIsStaleAndDoesNotBlock) {
  const auto dir = test::scratch_dir("run_lock_stale");
  const auto cube = dir / "c.h5";
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    RunLock held(cube);
    (void)!::write(ready[1], "x", 1);
    ::pause();  // until killed: no destructor, the lock file stays
    ::_exit(0);
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  EXPECT_THROW(RunLock refused(cube), OutputError);
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
  EXPECT_TRUE(std::filesystem::exists(RunLock::lock_path(cube)));  // left behind, but stale
  EXPECT_EQ(RunLock::holder(cube), "");
  RunLock resumed(cube);
  EXPECT_NE(RunLock::holder(cube).find("pid " + std::to_string(::getpid())), std::string::npos);
  ::close(ready[0]);
  ::close(ready[1]);
}

}  // namespace
}  // namespace pcrf::io
