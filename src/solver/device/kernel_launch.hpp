/// \file kernel_launch.hpp
/// \brief The CUDA side of the case kernel (case_kernel.cu, built where PCRF_HAVE_CUDA): the
/// device query and the launch of one thread per case. Host functions; no CUDA header here,
/// so that kernel_group.cpp stays plain C++. Private to the solver.
#pragma once

#include <cstddef>
#include <string>

#include "case_kernel.hpp"

namespace pcrf::device {

/// Why this machine has no CUDA device the kernel can run on (empty: device 0 can; `name`
/// is then its name).
std::string cuda_device_problem(std::string& name);

/// Solves cases[i] under `record` (its samples and the tables in host memory) into results[i] on device 0,
/// one thread per case. False, with `error` saying which CUDA call failed, when the device
/// did not run them (no result is then set).
bool cuda_solve_cases(const KernelCase* cases, std::size_t count, const KernelRecord& record,
                      const KernelTableStore& tables, KernelResult* results, std::string& error);

}  // namespace pcrf::device
