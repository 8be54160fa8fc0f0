/// \file settings.hpp
/// \brief Physics options and integrator settings of one case.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/metrics/unresolved.hpp"
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
  /// Dormand–Prince 5(4), purpose-built for the rocking scenes (src/solver/dopri5/dormand_prince.hpp):
  /// steps between record samples on its own, events located on its dense output.
  kDormandPrince5,
  /// Taylor series steps where the scene has its series (Housner's block, the rocking frame:
  /// RigidRocker::taylor_series; src/solver/taylor/taylor_integrator.hpp), between record samples,
  /// events located on the series; dopri5 otherwise.
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
/// The integrators' text forms and choices: the registry's (integrator_registry.hpp).
Integrator parse_integrator(const std::string& text);  ///< "dopri5", "taylor", "cvode-bdf", "cvode-adams", "arkode-erk5", "arkode-erk8", "fixed-rk4"
std::string to_string(Integrator i);
std::vector<Integrator> integrator_choices();  ///< every registered integrator, in its order

// kTailUntilRest and tail_advice: pcrf/metrics/unresolved.hpp (below the solver: the schema's
// verdict notes use them too).

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
  /// Return to rest when the next flight would rise less than this [rad] (docs/physics.md,
  /// "Return to rest"): physics, one value for every preset, never a solver tolerance.
  double rest_rise_rad = 1e-10;
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
  /// 0: no limit; else status kTimeLimit when the case's wall-clock time (steady clock from its
  /// start: time descheduled and, in a lane batch, its lane-mates' time included) exceeds it.
  double wall_time_limit_s = 0.0;
  bool verdict_check = false;      ///< perturbed twin runs: status_stable, theta_max_spread, collapse_fraction

  bool operator==(const SolverSettings&) const = default;
};


/// Named accuracy presets: "fast", "balanced" (the default) and "reference". Each is a
/// complete SolverSettings, numerics only (the physics, the rest cut-off included, is
/// PhysicsOptions'); docs/results.md lists the error and cost measured for each.
/// \throws std::invalid_argument naming the unknown preset.
SolverSettings preset_settings(const std::string& name);
/// Names of all presets, in order of increasing accuracy.
const std::vector<std::string>& preset_names();

namespace detail {

/// The enumerations' text forms (to_string, parse_*, the tables' choices).
inline constexpr std::array<EnumName<UpliftCriterion>, 3> kUpliftNames{{{UpliftCriterion::kPhysical, "physical"},
                                                                 {UpliftCriterion::kPaper, "paper"},
                                                                 {UpliftCriterion::kPaperProcedure, "paper-procedure"}}};

}  // namespace detail

// The tables, here beside the members they describe: a new setting is its member and its row
// in this one header, and its use (docs/developer.md, "What a new thing costs").

/// The [physics] table: every PhysicsOptions member, in the order study files document them.
inline const SettingTable<PhysicsOptions>& physics_settings() {
  using P = PhysicsOptions;
  static const SettingTable<PhysicsOptions> table = [] {
    SettingTable<PhysicsOptions> t{"physics", PhysicsOptions{}, {}};
    auto& s = t.settings;
    s.push_back(choice_setting("uplift", &P::uplift, values_of(detail::kUpliftNames),
                               &to_string, &parse_uplift_criterion,
                               "uplift criterion (docs/physics.md, \"Uplift criteria\"); paper-procedure is NON-PHYSICAL "
                               "(motion from the paper's t_RI, no contact condition; with integrator fixed-rk4)"));
    s.back().aliases = {"--criterion"};
    s.push_back(number_setting("fracture_strain", &P::fracture_strain, "1", Bound::kPositive,
                               "total tendon strain at fracture"));
    s.push_back(number_or_word_setting("tail_s", &P::tail_s, "s", Bound::kNonNegative, {{"until-rest", kTailUntilRest}},
                                       "free vibration computed after the record ends: a time, or until the frame "
                                       "rests or collapses (at most max_tail_s; still rocking then: unresolved)"));
    s.back().aliases = {"--tail"};
    s.push_back(number_setting("max_tail_s", &P::max_tail_s, "s", Bound::kPositive,
                               "longest until-rest tail; a frame still rocking then is rocking_at_end, unresolved"));
    s.push_back(number_setting("zeno_time_s", &P::zeno_time_s, "s", Bound::kPositive,
                               "return-to-rest time scale (docs/physics.md, \"Return to rest\")"));
    s.back().aliases = {"--zeno-time"};
    s.push_back(number_setting("rest_rise_rad", &P::rest_rise_rad, "rad", Bound::kNonNegative,
                               "return-to-rest rise: after an impact, a flight that would rise less than this is not flown and the "
                               "frame is at rest (so it bounds the impacts counted); physics, the same for every preset "
                               "(docs/physics.md, \"Return to rest\")"));
    s.push_back(number_setting("theta0_rad", &P::theta0_rad, "rad", Bound::kAny,
                               "initial rotation θ₁ (0: the frame starts at rest); within the closing limit"));
    s.push_back(number_setting("omega0_rad_s", &P::omega0_rad_s, "rad/s", Bound::kAny,
                               "initial angular velocity θ̇₁ (0: the frame starts at rest)"));
    return t;
  }();
  return table;
}

/// The [solver] table: `preset` first (it sets every other value), then the members of
/// SolverSettings. Defaults: the "balanced" preset.
inline const SettingTable<SolverSettings>& solver_settings() {
  using S = SolverSettings;
  static const SettingTable<SolverSettings> table = [] {
    SettingTable<SolverSettings> t{"solver", preset_settings("balanced"), {}};
    auto& s = t.settings;
    Setting<SolverSettings> preset;
    preset.key = "preset";
    preset.type = SettingType::kChoice;
    preset.choices = preset_names();
    preset.doc = "accuracy preset: numerics only, the physics (the return-to-rest cut-off included) is [physics]'s, "
                 "the same for every preset; sets every value below, which single keys then override (measured "
                 "errors: docs/results.md)";
    // Its whole effect is in the values it sets, and those are fingerprinted.
    preset.in_fingerprint = false;
    preset.get = [](const S& v) { return SettingValue(v.preset); };
    preset.set = [](S& v, const SettingValue& value) { v = preset_settings(std::get<std::string>(value)); };
    s.push_back(std::move(preset));
    s.push_back(choice_setting("integrator", &S::integrator, integrator_choices(), &to_string, &parse_integrator,
                               "time integrator (taylor: Taylor series steps where the scene has its series, the block and the rocking frame; dopri5 elsewhere)"));
    s.push_back(number_setting("rtol", &S::rtol, "1", Bound::kPositive, "relative tolerance"));
    s.push_back(number_setting("atol_theta_rad", &S::atol_theta_rad, "rad", Bound::kPositive,
                               "absolute tolerance on θ₁ (numerics only; when a frame rests is [physics] rest_rise_rad)"));
    s.back().aliases = {"--atol-theta"};
    s.push_back(number_setting("atol_omega_rad_s", &S::atol_omega_rad_s, "rad/s", Bound::kPositive,
                               "absolute tolerance on θ̇₁"));
    s.back().aliases = {"--atol-omega"};
    s.push_back(number_setting("max_step_s", &S::max_step_s, "s", Bound::kNonNegative, "largest step; 0: no limit"));
    s.back().aliases = {"--max-step"};
    s.push_back(number_setting("fixed_step_s", &S::fixed_step_s, "s", Bound::kNonNegative,
                               "step of fixed-rk4; 0: the record's dt"));
    s.back().aliases = {"--fixed-step"};
    s.push_back(flag_setting("stop_at_samples", &S::stop_at_samples,
                             "stop the integrator at every record sample (kinks of the interpolated record)"));
    s.push_back(integer_setting("max_steps", &S::max_steps, Bound::kAtLeastOne,
                                "steps per case, all segments together"));
    s.push_back(number_setting("wall_time_limit_s", &S::wall_time_limit_s, "s", Bound::kNonNegative,
                               "a case whose wall-clock time (steady clock from its start, time descheduled and lane-mates' "
                               "time included; not its cpu_time_s) exceeds this ends as time_limit; 0: no limit"));
    s.back().aliases = {"--time-limit"};
    s.push_back(flag_setting("verdict_check", &S::verdict_check,
                             "run each case near collapse again with its record scaled by 1 ± 1e-9, 1e-7, 1e-6: "
                             "status_stable, theta_max_spread, collapse_fraction"));
    return t;
  }();
  return table;
}

/// The work budgets of one case, beside the rows that set them: the message of the first one
/// `counts` (the integrator's, all segments together) exceeds, or null. The case machine
/// checks them after every advance, for every stepper and in the CPU lanes (the fixed-step
/// contender has no budget); such a case ends as solver_failure. A new cap is its member,
/// its row and its line here (docs/developer.md, "What a new thing costs").
inline const char* exceeded_budget(const SolverSettings& s, const SolverCounts& counts) {
  if (counts.steps > s.max_steps) return "more than max_steps steps";
  return nullptr;
}

}  // namespace pcrf
