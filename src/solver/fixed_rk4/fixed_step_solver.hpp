/// \file fixed_step_solver.hpp
/// \brief The hand-written contender: classical RK4 at a fixed step, impacts found only as
/// sign changes of θ₁ between steps, no return-to-rest rule. Private to the solver.
///
/// What it does, step by step (this is the point of it, not an accident):
///   - rest until the net force opens the joints (the same exact rule as the main solver,
///     so both start rocking at the same instant);
///   - then RK4 steps of size h on the branch of the sign of θ₁ at the step start;
///   - when θ₁ changes sign over a step, the velocity at the step end is multiplied by r
///     and the branch flips; the crossing is not located and the state is not moved back;
///   - the frame is never put back at rest: flights shorter than h become a chatter at the
///     step scale.
/// Peaks are the largest values at step ends.
#pragma once

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/model/scene.hpp"
#include "pcrf/excitation/excitation.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace pcrf::detail {

CaseResult solve_case_fixed_step(const Scene& scene, const Excitation& excitation,
                                 const PhysicsOptions& physics, const SolverSettings& solver,
                                 const HistorySink& history);

}  // namespace pcrf::detail
