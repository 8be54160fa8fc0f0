/// \file registry.hpp
/// \brief The choice of a case's integrator, from the registry (pcrf/solver/integrator_registry.hpp).
/// Private to the solver.
#pragma once

#include <memory>

#include "integrator.hpp"
#include "pcrf/solver/integrator_registry.hpp"

namespace pcrf::detail {

/// The integrator `settings` name, for `problem` (one with no Taylor series gets the entry's
/// `without_series`). `samples`: the record's sample grid, for an integrator that steps
/// between samples itself (SUNDIALS' are stopped at each by their caller). `lockstep`: the
/// step attempts are made by the caller (the lanes); only an entry that can.
/// \throws IntegratorError for a method with no stepper (the fixed-step contender solves
/// whole cases) or one that cannot run in lockstep.
std::unique_ptr<OdeIntegrator> make_integrator(const SolverSettings& settings, OdeProblem& problem,
                                               SampleGrid samples = {}, bool lockstep = false);

}  // namespace pcrf::detail
