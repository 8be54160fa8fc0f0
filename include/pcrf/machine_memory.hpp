/// \file machine_memory.hpp
/// \brief This machine's physical memory, the bound of what a study may plan and of what a
/// file may make the engine allocate.
#pragma once

#include <unistd.h>

namespace pcrf {

/// Physical memory [bytes], as a double: what it is compared with can exceed any integer.
inline double machine_memory_bytes() {
  return static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
}

/// The share of machine_memory_bytes() one process may plan to fill [-].
inline constexpr double kUsableMemoryShare = 0.8;

}  // namespace pcrf
