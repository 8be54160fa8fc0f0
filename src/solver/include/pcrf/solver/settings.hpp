/// \file settings.hpp
/// \brief Physics options and integrator settings of one case.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "pcrf/setting.hpp"

namespace pcrf {

/// When a frame at rest starts to rock.
enum class UpliftCriterion {
  /// The net generalized force at θ₁ = 0 (ground inertia, gravity, tendon prestress)
  /// opens the joints: |ü_g| > uplift_threshold_g·g. Default.
  kPhysical,
  /// The paper's Eq. (34): |ü_g| ≥ λ_g·g, prestress ignored. See README ("Uplift
  /// criteria") for what happens while the prestress still holds the frame closed.
  kPaper,
  /// NON-PHYSICAL, to reproduce the paper's numbers: the motion starts at the paper's
  /// trigger t_RI with no unilateral contact (the frame is integrated into its supports),
  /// with the fixed-step RK4 that finds impacts as sign changes at step ends. Only with
  /// integrator fixed-rk4. docs/paper_comparison.md shows how its answer depends on the step.
  kPaperProcedure,
};
UpliftCriterion parse_uplift_criterion(const std::string& text);  ///< "physical" | "paper" | "paper-procedure"
std::string to_string(UpliftCriterion c);

/// Which time integrator solves the equation of motion between impacts.
enum class Integrator {
  /// Dormand–Prince 5(4), purpose-built for the rocking scenes (src/solver/dormand_prince.hpp):
  /// steps between record samples on its own, events located on its dense output.
  kDormandPrince5,
  /// Taylor series steps where the scene has its series (Housner's block, the rocking frame:
  /// RigidRocker::taylor_series), with dopri5's breakpoints and events; dopri5 otherwise.
  kTaylor,
  kCvodeBdf,    ///< SUNDIALS CVODE, BDF (orders 1–5), dense Newton
  kCvodeAdams,  ///< SUNDIALS CVODE, Adams–Moulton (orders 1–12), fixed point
  kArkodeErk5,  ///< SUNDIALS ARKODE ERKStep, Dormand–Prince 5(4)
  kArkodeErk8,  ///< SUNDIALS ARKODE ERKStep, Fehlberg 8(7)
  /// Classical RK4 at a fixed step with impacts found only as sign changes of θ₁ between
  /// steps and no return-to-rest rule: the scheme many hand-written codes use. Kept as a
  /// contender for the work-precision study and the numerics audit, not for production.
  kFixedRk4SignChange,
};
Integrator parse_integrator(const std::string& text);  ///< "dopri5", "taylor", "cvode-bdf", "cvode-adams", "arkode-erk5", "arkode-erk8", "fixed-rk4"
std::string to_string(Integrator i);

/// tail_s = "until-rest": the free vibration after the record goes on until the frame rests.
inline constexpr double kTailUntilRest = std::numeric_limits<double>::infinity();

/// The setting that resolves a case still rocking at its end (rocking_at_end) for a tail of
/// `tail_s` [s]: "a longer physics.tail_s …" when the tail is fixed, "… physics.max_tail_s …"
/// when it runs until rest (kTailUntilRest); both when NaN (not known).
std::string tail_advice(double tail_s);

/// What the physics of a case includes. Every member is described (key, unit, default,
/// check, doc) in physics_settings(); the comments here say only what the code needs.
struct PhysicsOptions {
  UpliftCriterion uplift = UpliftCriterion::kPhysical;
  double fracture_strain = 0.01;   ///< total tendon strain at fracture [-]
  /// Free vibration after the record [s]: a fixed time, or kTailUntilRest (the default): until
  /// the frame is at rest or has collapsed, at most max_tail_s. A case still rocking when its
  /// tail ends is `rocking_at_end`, and has no verdict (is_unresolved).
  double tail_s = kTailUntilRest;
  double max_tail_s = 60.0;        ///< cap of an until-rest tail [s]
  /// Return to rest when the remaining Zeno sequence would end within this time [s]
  /// (see README, "Return to rest").
  double zeno_time_s = 1e-4;
  /// Initial state (free-rocking studies and tests). Zero: the frame starts at rest.
  /// A non-zero state starts in flight on the side of θ₁ (of −θ̇₁ when θ₁ = 0).
  double theta0_rad = 0.0;
  double omega0_rad_s = 0.0;

  bool operator==(const PhysicsOptions&) const = default;
};

/// How the equation of motion is integrated. Described in solver_settings(), whose defaults
/// are the "balanced" preset; a default-constructed SolverSettings is a tighter set used by
/// tests and benchmarks that choose every value themselves.
struct SolverSettings {
  std::string preset = "custom";   ///< the preset these values started from
  Integrator integrator = Integrator::kDormandPrince5;
  double rtol = 1e-8;
  double atol_theta_rad = 1e-11;   ///< absolute tolerance on θ₁ [rad]
  double atol_omega_rad_s = 1e-10; ///< absolute tolerance on θ̇₁ [rad/s]
  double max_step_s = 0.0;         ///< 0: no limit
  double fixed_step_s = 0.0;       ///< step of kFixedRk4SignChange [s]; 0: the record's dt
  long max_steps = 2000000;        ///< per case, all segments together
  /// Never step across a record sample: ü_g is linear between samples and has a kink at
  /// each, so the right-hand side is smooth only between them. Stopping at every sample
  /// keeps the integrators at their design order (without restarting them).
  bool stop_at_samples = true;
  double wall_time_limit_s = 0.0;  ///< 0: no limit; else status kTimeLimit
  bool verdict_check = false;      ///< perturbed twin runs: status_stable, theta_max_spread, collapse_fraction

  bool operator==(const SolverSettings&) const = default;
};

/// The [physics] table: every PhysicsOptions member, in the order study files document them.
const SettingTable<PhysicsOptions>& physics_settings();
/// The [solver] table: `preset` first (it sets every other value), then the members of
/// SolverSettings. Defaults: the "balanced" preset.
const SettingTable<SolverSettings>& solver_settings();

/// Named accuracy presets: "fast", "balanced" (the default) and "reference". Each is a
/// complete SolverSettings; the README lists the error and cost measured for each.
/// \throws std::invalid_argument naming the unknown preset.
SolverSettings preset_settings(const std::string& name);
/// Names of all presets, in order of increasing accuracy.
const std::vector<std::string>& preset_names();

}  // namespace pcrf
