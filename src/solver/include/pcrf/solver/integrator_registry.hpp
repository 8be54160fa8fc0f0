/// \file integrator_registry.hpp
/// \brief The one list of integrators: each one's name, what it can do, and how it is made.
///
/// Everything that asks "which integrator" reads this list: the choice of integrator for a
/// case (detail::make_integrator), the settings' names (parse_integrator, to_string, the
/// [solver] table's choices), the presets, the group of cases' test for its lanes
/// (case_group.hpp), and every test that runs "every integrator". A family added here is
/// covered by those tests without editing them (docs/developer.md, "What a new thing costs").
#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "pcrf/excitation/excitation.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/model/scene.hpp"
#include "pcrf/solver/history.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf {

namespace detail {
class OdeIntegrator;
class OdeProblem;
struct SampleGrid;
}  // namespace detail

/// What an integrator can do.
struct IntegratorCapabilities {
  /// Runs from record sample to record sample on its own (the samples are its breakpoints):
  /// the case machine need not stop it at each.
  bool steps_between_samples = false;
  /// Can hand its step attempts to its caller (lockstep): the CPU lanes' kernels make them.
  bool lockstep = false;
  /// Steps by the scene's Taylor series: a scene without one is solved by `without_series`.
  bool needs_series = false;
  /// A group of cases may solve it in the CPU lanes (itself in lockstep, or a case it would
  /// not step in lockstep one at a time beside them).
  bool in_lanes = false;
  /// Locates its events (impacts, peaks, stops) and applies the return-to-rest rule. False
  /// for the fixed-step contender, which sees impacts as sign changes at step ends: the tests
  /// of exact physics (energy, mirrored records, convergence) leave it out for that reason.
  bool locates_events = true;
};

/// One integrator.
struct IntegratorEntry {
  Integrator id;
  std::string_view name;  ///< the settings' spelling ("dopri5", …)
  IntegratorCapabilities can;
  /// Makes the stepper the case machine drives between events; `samples`: the record's
  /// sample grid; `lockstep` only where can.lockstep. Null for a method that solves whole
  /// cases itself (`solve`).
  std::unique_ptr<detail::OdeIntegrator> (*make)(const SolverSettings& settings, detail::OdeProblem& problem,
                                                 const detail::SampleGrid& samples, bool lockstep) = nullptr;
  /// A method with its own case loop (the fixed-step contender): solves one case start to
  /// end. Null for a stepper (`make`).
  CaseResult (*solve)(const Scene& scene, const Excitation& excitation, const PhysicsOptions& physics,
                      const SolverSettings& settings, const HistorySink& history) = nullptr;
  /// Where can.needs_series: the integrator of a scene without a series.
  Integrator without_series = Integrator::kDormandPrince5;
};

/// Every integrator, in the order the settings list them.
std::span<const IntegratorEntry> integrator_registry();
/// The entry of `id`. \throws std::invalid_argument for a value not in the registry.
const IntegratorEntry& registry_entry(Integrator id);
/// The entry that solves `scene`'s cases under `id`: its `without_series` where it needs a
/// series the scene does not have.
const IntegratorEntry& entry_for_scene(Integrator id, const Scene& scene);

}  // namespace pcrf
