/// \file kernel_cases.hpp
/// \brief The host's side of the case kernel (case_kernel.hpp): which groups and cases it
/// takes, their numbers set up from a prepared frame, and a kernel answer made a CaseResult
/// with the CPU path's messages. Shared by the host backend and the GPU backend
/// (kernel_group.cpp). Private to the solver.
#pragma once

#include <string>
#include <vector>

#include "case_kernel.hpp"
#include "pcrf/excitation/excitation.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/solver/history.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf::device {

/// Why the kernel takes no case of this group (empty: it takes them, case by case).
std::string kernel_refuses(const Excitation& excitation, const SolverSettings& solver, bool history);

/// The case's numbers (a prestressed frame's table appended to `tables`); the reason when the
/// kernel does not take this frame (empty: `c` set).
/// \throws what solve_case throws for a case it refuses (settings, initial state).
std::string kernel_case(PreparedFrame& frame, const Excitation& excitation, const SolverSettings& solver,
                        const OutputRequest& request, KernelCase& c, KernelTableStore& tables);

/// The horizontal record as the kernel reads it (the samples stay the record's).
KernelRecord kernel_record(const GroundMotion& record);

/// The kernel's answer as solve_case gives it (cpu_time_s not set).
CaseResult kernel_result(PreparedFrame& frame, const Excitation& excitation, const OutputRequest& request,
                         const KernelResult& k);

}  // namespace pcrf::device
