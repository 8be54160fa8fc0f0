/// \file case_group.hpp
/// \brief Solving a group of cases: N prepared frames of one study under one excitation and
/// one set of solver settings, one answer each. The run layer (src/run) solves through this
/// interface only.
///
/// A backend owns its loop over the cases, events included: one case at a time (solve_case),
/// the CPU lanes (batch_solver.hpp: W cases per vector instruction), and a device kernel
/// beside them (issue 40) are each one implementation. The answers are solve_case's, bit for
/// bit, whichever backend gives them. A case a backend refuses (settings or an initial state
/// no case can have, a frame its set-up rejects) is that case's answer, GroupOutcome::kRefused
/// with the reason: the group's other cases are solved, and nothing is run again.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/excitation/excitation.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/solver/batch_solver.hpp"
#include "pcrf/solver/history.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf {

/// How a group handled one of its cases.
enum class GroupOutcome : std::int8_t {
  kSolved = 0,   ///< `result` is the case's (its own status says how the case ended)
  kRefused = 1,  ///< not solved: `result.message` says why; no metric of `result` is set
};

/// One case's answer from a group.
struct GroupCase {
  GroupOutcome outcome = GroupOutcome::kSolved;
  CaseResult result;
};

/// A way to solve a group of cases.
class CaseGroupSolver {
 public:
  virtual ~CaseGroupSolver() = default;
  /// The backend's name ("one-at-a-time", "cpu-lanes").
  virtual std::string_view name() const = 0;
  /// Solves frames[i] under `excitation` into answer i. `history`: the rows of a group of
  /// one case (a group of more takes none). \throws std::invalid_argument for a history with
  /// more than one case; never for one case's settings, state or failure (its answer says).
  virtual std::vector<GroupCase> solve(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                                       const SolverSettings& solver, const OutputRequest& request,
                                       const HistorySink& history = {}) const = 0;
};

/// One case at a time, each by solve_case.
std::unique_ptr<CaseGroupSolver> one_at_a_time_group();
/// The CPU lanes (solve_batch), `options.lanes` wide at most and never wider than the group;
/// a group they do not take (lanes_take, a group of one, a history) one case at a time.
std::unique_ptr<CaseGroupSolver> cpu_lanes_group(const BatchOptions& options);
/// True when the CPU lanes solve groups under these settings (the registry's in_lanes, no
/// verdict check).
bool lanes_take(const SolverSettings& solver);
/// The group solver for `lanes` lanes: the CPU lanes where more than one and lanes_take,
/// else one at a time.
std::unique_ptr<CaseGroupSolver> make_group_solver(const SolverSettings& solver, int lanes);

/// The case kernel (src/solver/device/) compiled for the host: the device's code path, case by case.
/// A case the kernel does not cover (scene, integrator, output) is GroupOutcome::kRefused, with why.
std::unique_ptr<CaseGroupSolver> kernel_host_group();
/// The GPU backend; nullptr where this build has no CUDA or the machine no usable device, `why_not` saying which.
std::unique_ptr<CaseGroupSolver> gpu_group(std::string& why_not);

}  // namespace pcrf
