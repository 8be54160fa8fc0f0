/// \file rocking_solver.hpp
/// \brief Solves one case: a frame under an excitation (its in-plane horizontal and vertical
/// ground acceleration; a single record converts to one), from rest, through impacts.
///
/// State y = (θ₁, θ̇₁). Between impacts the equation of motion (31) is integrated on the
/// branch of the current sway direction (θ₁ ≤ 0 or the mirrored θ₁ ≥ 0) with SUNDIALS
/// CVODE or ARKODE. Root functions:
///   g₀ = θ₁              impact (only in the closing direction),
///   g₁ = θ̇₁              extremum of θ₁ (exact θ_max and its time),
///   g₂ = θ̈₁              extremum of θ̇₁ (exact ω_max and its time; only if requested),
///   g₃ = |θ₁| − θ_stop   tendon fracture or overturning, whichever angle is smaller.
/// At an impact the velocity is multiplied by the coefficient of restitution r, the branch
/// flips and the integrator is re-initialized; the root at the new initial point is inactive
/// until θ₁ leaves zero. At rest the frame is not integrated at all: the solver scans the
/// record for the first time the net force opens the joints (exact, within the linear
/// interpolation of the record). See README "Physics" for the return-to-rest rule.
#pragma once

#include <functional>

#include <memory>
#include <stdexcept>

#include "pcrf/excitation/excitation.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/model/scene.hpp"
#include "pcrf/solver/history.hpp"
#include "pcrf/solver/settings.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {

/// What the caller wants computed; anything false is skipped (and left NaN).
struct OutputRequest {
  bool omega_peak = true;  ///< locate max |θ̇₁| exactly (adds the root g₂)
  /// Output interval of the history [s]; 0: the record's sample interval. Rows between
  /// steps come from the integrator's interpolant (the fixed-step contender has none and
  /// gives a row per step).
  double history_dt_s = 0.0;
};

/// Checks that a displaced initial state (physics.theta0_rad) is one the frame can be in:
/// |θ₀| below its overturning angle (95 % of the closing limit, where the linkage folds).
/// \throws std::invalid_argument "theta0_rad: …" naming both angles.
void check_initial_state(const Frame& frame, const PhysicsOptions& physics);
/// The same for any scene.
void check_initial_state(const Scene& scene, const PhysicsOptions& physics);

/// A frame prepared for solving under fixed physics options. Only what a case needs is
/// computed, when it first needs it, and kept for every later case of the same frame: the
/// uplift threshold and restitution at once; the closing limit, the fracture angle and the
/// tabulated coefficients of Eq. (31) only when a case lifts the frame. Not thread-safe:
/// one per thread.
class PreparedFrame;

/// \throws UserError naming the failed condition (a frame the rigid-body rocking model cannot represent).
std::shared_ptr<PreparedFrame> prepare_frame(const Frame& frame, const PhysicsOptions& physics);

/// The same for any rocking scene (scene.hpp: the rigid block, the Makris–Vassiliou frame).
/// \throws UserError naming the failed condition (a frame the rigid-body rocking model cannot represent).
std::shared_ptr<PreparedFrame> prepare_scene(std::unique_ptr<Scene> scene, const PhysicsOptions& physics);

/// The longest a case on a record of `record_s` seconds can run [s]: the record and its tail
/// (an until-rest tail: max_tail_s); the ground's free fall may end it sooner.
double longest_case_s(double record_s, const PhysicsOptions& physics);

/// Solves one case. Never throws for a physical or numerical failure: the result's
/// status says what happened (message gives detail). Throws std::invalid_argument only
/// for invalid settings (a value outside its description, an impossible initial state, a
/// history interval beyond check_history_interval's bound over longest_case_s, before any row).
CaseResult solve_case(PreparedFrame& frame, const Excitation& excitation, const SolverSettings& solver,
                      const OutputRequest& request = {}, const HistorySink& history = {});

/// The same for a frame used once. \throws UserError as prepare_frame().
CaseResult solve_case(const Frame& frame, const Excitation& excitation,
                      const PhysicsOptions& physics, const SolverSettings& solver,
                      const OutputRequest& request = {}, const HistorySink& history = {});

}  // namespace pcrf
