/// \file lanes.hpp
/// \brief The CPU lanes as a backend of a group of cases (group/case_group.cpp). Private to
/// the solver.
#pragma once

#include <exception>
#include <span>
#include <vector>

#include "pcrf/solver/batch_solver.hpp"

namespace pcrf::detail {

/// solve_batch, with a case it refuses (its settings or initial state, a frame its set-up
/// rejects) as refused[i] (why) instead of an exception: the other cases are solved.
std::vector<CaseResult> solve_in_lanes(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                                       const SolverSettings& solver, const OutputRequest& request,
                                       const BatchOptions& options, std::vector<std::exception_ptr>& refused,
                                       BatchStats* stats = nullptr);

}  // namespace pcrf::detail
