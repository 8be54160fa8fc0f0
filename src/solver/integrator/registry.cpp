// The registry of integrators (pcrf/solver/integrator_registry.hpp): one row per integrator.
// A new family is its folder beside this one and its row here.
#include "registry.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "../dopri5/dormand_prince.hpp"
#include "../fixed_rk4/fixed_step_solver.hpp"
#include "../sundials/sundials_integrators.hpp"
#include "../taylor/taylor_integrator.hpp"

namespace pcrf {
namespace {

using detail::OdeIntegrator;
using detail::OdeProblem;
using detail::SampleGrid;

std::unique_ptr<OdeIntegrator> make_dopri5(const SolverSettings& s, OdeProblem& p, const SampleGrid& samples,
                                           bool lockstep) {
  // In lockstep (the lanes) the samples are always its breakpoints: the kernels keep each
  // lane within one record interval.
  auto integrator =
      std::make_unique<detail::DormandPrinceIntegrator>(s, p, lockstep || s.stop_at_samples ? samples : SampleGrid{});
  if (lockstep) integrator->set_lockstep(true);
  return integrator;
}
std::unique_ptr<OdeIntegrator> make_taylor(const SolverSettings& s, OdeProblem& p, const SampleGrid& samples, bool) {
  return std::make_unique<detail::TaylorIntegrator>(s, p, samples);  // always between samples
}
std::unique_ptr<OdeIntegrator> make_cvode_bdf(const SolverSettings& s, OdeProblem& p, const SampleGrid&, bool) {
  return detail::make_cvode(s, p, true);
}
std::unique_ptr<OdeIntegrator> make_cvode_adams(const SolverSettings& s, OdeProblem& p, const SampleGrid&, bool) {
  return detail::make_cvode(s, p, false);
}
std::unique_ptr<OdeIntegrator> make_erk5(const SolverSettings& s, OdeProblem& p, const SampleGrid&, bool) {
  return detail::make_arkode_erk(s, p, 5);
}
std::unique_ptr<OdeIntegrator> make_erk8(const SolverSettings& s, OdeProblem& p, const SampleGrid&, bool) {
  return detail::make_arkode_erk(s, p, 8);
}

// Capabilities: steps between samples, lockstep, needs a series, in lanes, locates events.
constexpr IntegratorCapabilities kDopri5{true, true, false, true, true};
constexpr IntegratorCapabilities kTaylorSteps{true, false, true, true, true};
constexpr IntegratorCapabilities kSundials{false, false, false, false, true};
constexpr IntegratorCapabilities kContender{false, false, false, false, false};

// In the order of the settings' documentation (the first is a SolverSettings' default).
const IntegratorEntry kRegistry[] = {
    {Integrator::kDormandPrince5, "dopri5", kDopri5, make_dopri5, nullptr},
    {Integrator::kTaylor, "taylor", kTaylorSteps, make_taylor, nullptr, Integrator::kDormandPrince5},
    {Integrator::kArkodeErk5, "arkode-erk5", kSundials, make_erk5, nullptr},
    {Integrator::kArkodeErk8, "arkode-erk8", kSundials, make_erk8, nullptr},
    {Integrator::kCvodeAdams, "cvode-adams", kSundials, make_cvode_adams, nullptr},
    {Integrator::kCvodeBdf, "cvode-bdf", kSundials, make_cvode_bdf, nullptr},
    {Integrator::kFixedRk4SignChange, "fixed-rk4", kContender, nullptr, detail::solve_case_fixed_step},
};

const IntegratorEntry* find_entry(Integrator id) {
  for (const IntegratorEntry& e : kRegistry)
    if (e.id == id) return &e;
  return nullptr;
}

}  // namespace

std::span<const IntegratorEntry> integrator_registry() { return kRegistry; }

const IntegratorEntry& registry_entry(Integrator id) {
  if (const IntegratorEntry* e = find_entry(id)) return *e;
  throw std::invalid_argument("integrator " + std::to_string(static_cast<int>(id)) + " is not in the registry");
}

const IntegratorEntry& entry_for_scene(Integrator id, const Scene& scene) {
  const IntegratorEntry& e = registry_entry(id);
  return e.can.needs_series && scene.taylor_order_max() <= 0 ? registry_entry(e.without_series) : e;
}

// The settings' text forms (settings.hpp), from the registry.

std::vector<Integrator> integrator_choices() {
  std::vector<Integrator> ids;
  for (const IntegratorEntry& e : kRegistry) ids.push_back(e.id);
  return ids;
}

/// \throws std::invalid_argument "unknown integrator 'x' (expected a, b or c)".
Integrator parse_integrator(const std::string& text) {
  std::string expected;
  const std::size_t n = std::size(kRegistry);
  for (std::size_t i = 0; i < n; ++i) {
    if (text == kRegistry[i].name) return kRegistry[i].id;
    expected += (i == 0 ? "" : i + 1 == n ? " or " : ", ") + std::string(kRegistry[i].name);
  }
  throw std::invalid_argument("unknown integrator '" + text + "' (expected " + expected + ")");
}

std::string to_string(Integrator i) {
  const IntegratorEntry* e = find_entry(i);
  return e != nullptr ? std::string(e->name) : "unknown";
}

namespace detail {

std::unique_ptr<OdeIntegrator> make_integrator(const SolverSettings& settings, OdeProblem& problem, SampleGrid samples,
                                               bool lockstep) {
  const IntegratorEntry* e = find_entry(settings.integrator);
  if (e != nullptr && e->can.needs_series && problem.taylor_order_max() <= 0) e = find_entry(e->without_series);
  if (e == nullptr || e->make == nullptr) throw IntegratorError("integrator " + to_string(settings.integrator) + " has no stepper");
  if (lockstep && !e->can.lockstep) throw IntegratorError("integrator " + std::string(e->name) + " cannot run in lockstep");
  return e->make(settings, problem, samples, lockstep);
}

}  // namespace detail
}  // namespace pcrf
