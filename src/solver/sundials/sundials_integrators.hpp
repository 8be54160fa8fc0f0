/// \file sundials_integrators.hpp
/// \brief The SUNDIALS family: CVODE (Adams, BDF) and ARKODE ERKStep behind the solver's
/// integrator interface. Private to the solver; registry.cpp lists them.
#pragma once

#include <memory>

#include "../integrator/integrator.hpp"

namespace pcrf::detail {

/// CVODE: BDF (orders 1–5, dense Newton, the problem's Jacobian) or Adams–Moulton (orders
/// 1–12, fixed point). \throws IntegratorError naming the SUNDIALS call that failed.
std::unique_ptr<OdeIntegrator> make_cvode(const SolverSettings& settings, OdeProblem& problem, bool bdf);
/// ARKODE ERKStep with Dormand–Prince 5(4) (`order` 5) or Fehlberg 8(7) (`order` 8).
/// \throws IntegratorError as make_cvode, and for another order.
std::unique_ptr<OdeIntegrator> make_arkode_erk(const SolverSettings& settings, OdeProblem& problem, int order);

}  // namespace pcrf::detail
