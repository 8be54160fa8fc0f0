/// \file kill_points.hpp
/// \brief A writer's run killed (SIGKILL) at a chosen checkpoint step, in a forked child, for
/// the crash tests of the journal and of the streaming fold.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>

#include "pcrf/cube/cube_writer.hpp"

namespace pcrf::cube {

/// The `occurrence`-th time a writer reaches `step`; `name` tells the test's cases apart.
struct KillPoint {
  CheckpointStep step;
  int occurrence;
  const char* name;
};

namespace kill_detail {
inline KillPoint armed{};
inline int left = 0;
inline void kill_here(CheckpointStep step) {
  if (step == armed.step && --left == 0) ::raise(SIGKILL);
}
}  // namespace kill_detail

/// Runs `run` in a forked child whose writer is killed at `k`; the child's wait status (a run
/// that ends or throws first exits 0 or 1). -1 when the child could not be made.
inline int run_killed_at(const KillPoint& k, const std::function<void()>& run) {
  kill_detail::armed = k;
  kill_detail::left = k.occurrence;
  const pid_t child = ::fork();
  if (child < 0) return -1;
  if (child == 0) {
    observe_checkpoints(kill_detail::kill_here);
    try {
      run();
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(0);
  }
  int wstatus = 0;
  return ::waitpid(child, &wstatus, 0) == child ? wstatus : -1;
}

/// True when a wait status says SIGKILL ended the child.
inline bool killed(int wstatus) { return wstatus >= 0 && WIFSIGNALED(wstatus) && WTERMSIG(wstatus) == SIGKILL; }

}  // namespace pcrf::cube
