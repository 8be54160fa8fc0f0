/// \file thread_cpu.hpp
/// \brief CPU time of the calling thread: what a case costs (cpu_time_s) and what `study --check`
/// samples, whatever else the machine runs and however long the thread was descheduled.
#pragma once

#include <ctime>

namespace pcrf {

/// CPU time of the calling thread [s] (CLOCK_THREAD_CPUTIME_ID).
inline double thread_cpu_s() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace pcrf
