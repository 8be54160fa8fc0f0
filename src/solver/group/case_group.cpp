// Solving a group of cases (pcrf/solver/case_group.hpp): one case at a time, and the CPU
// lanes (lanes/).
#include "pcrf/solver/case_group.hpp"

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <string>

#include "../lanes/lanes.hpp"
#include "group_answers.hpp"

namespace pcrf {

GroupCase detail::refused_case(std::string why) {
  GroupCase c;
  c.outcome = GroupOutcome::kRefused;
  c.result.status = CaseStatus::kSolverFailure;
  c.result.message = std::move(why);
  return c;
}

void detail::check_group_history(std::size_t cases, const HistorySink& history) {
  if (history && cases != 1)
    throw std::invalid_argument("a group's history: one case only, got " + std::to_string(cases));
}

namespace {

using detail::check_group_history;
using detail::refused_case;

std::string what_of(const std::exception_ptr& e) {
  try {
    std::rethrow_exception(e);
  } catch (const std::exception& x) {
    return x.what();
  } catch (...) {
    return "unknown exception";
  }
}

class OneAtATime final : public CaseGroupSolver {
 public:
  std::string_view name() const override { return "one-at-a-time"; }
  std::vector<GroupCase> solve(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                               const SolverSettings& solver, const OutputRequest& request,
                               const HistorySink& history) const override {
    check_group_history(frames.size(), history);
    std::vector<GroupCase> cases(frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
      try {
        cases[i].result = solve_case(*frames[i], excitation, solver, request, history);
      } catch (const std::exception& e) {  // solve_case throws only for a case it refuses
        cases[i] = refused_case(e.what());
      }
    }
    return cases;
  }
};

class CpuLanes final : public CaseGroupSolver {
 public:
  explicit CpuLanes(const BatchOptions& options) : options_(options) {}
  std::string_view name() const override { return "cpu-lanes"; }
  std::vector<GroupCase> solve(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                               const SolverSettings& solver, const OutputRequest& request,
                               const HistorySink& history) const override {
    BatchOptions options = options_;  // no wider than the group: no lane left idle throughout
    options.lanes = std::min(options.lanes, static_cast<int>(frames.size()));
    if (options.lanes <= 1 || history || !lanes_take(solver))
      return OneAtATime().solve(frames, excitation, solver, request, history);
    std::vector<std::exception_ptr> why;
    std::vector<CaseResult> results = detail::solve_in_lanes(frames, excitation, solver, request, options, why);
    std::vector<GroupCase> cases(frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
      if (why[i]) {
        cases[i] = refused_case(what_of(why[i]));
      } else {
        cases[i].result = std::move(results[i]);
      }
    }
    return cases;
  }

 private:
  BatchOptions options_;
};

}  // namespace

std::unique_ptr<CaseGroupSolver> one_at_a_time_group() { return std::make_unique<OneAtATime>(); }

std::unique_ptr<CaseGroupSolver> cpu_lanes_group(const BatchOptions& options) {
  if (options.lanes < 1) throw std::invalid_argument("batch lanes: must be at least 1, got " + std::to_string(options.lanes));
  return std::make_unique<CpuLanes>(options);
}

bool lanes_take(const SolverSettings& solver) { return batch_integrates(solver); }

std::unique_ptr<CaseGroupSolver> make_group_solver(const SolverSettings& solver, int lanes) {
  if (lanes <= 1 || !lanes_take(solver)) return one_at_a_time_group();
  BatchOptions options;
  options.lanes = lanes;
  return cpu_lanes_group(options);
}

}  // namespace pcrf
