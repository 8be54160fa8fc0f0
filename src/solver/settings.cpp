// Text forms of the physics and solver options (command line, study files, results).
#include "pcrf/solver/settings.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "pcrf/number_text.hpp"

namespace pcrf {

namespace {

constexpr std::array<EnumName<UpliftCriterion>, 3> kUpliftNames{{{UpliftCriterion::kPhysical, "physical"},
                                                                 {UpliftCriterion::kPaper, "paper"},
                                                                 {UpliftCriterion::kPaperProcedure, "paper-procedure"}}};

constexpr std::array<EnumName<Integrator>, 7> kIntegratorNames{{{Integrator::kDormandPrince5, "dopri5"},
                                                                {Integrator::kTaylor, "taylor"},
                                                                {Integrator::kArkodeErk5, "arkode-erk5"},
                                                                {Integrator::kArkodeErk8, "arkode-erk8"},
                                                                {Integrator::kCvodeAdams, "cvode-adams"},
                                                                {Integrator::kCvodeBdf, "cvode-bdf"},
                                                                {Integrator::kFixedRk4SignChange, "fixed-rk4"}}};

}  // namespace

UpliftCriterion parse_uplift_criterion(const std::string& text) {
  return parse_name(kUpliftNames, text, "uplift criterion");
}

std::string to_string(UpliftCriterion c) { return name_of(kUpliftNames, c); }

Integrator parse_integrator(const std::string& text) { return parse_name(kIntegratorNames, text, "integrator"); }

std::string to_string(Integrator i) { return name_of(kIntegratorNames, i); }

const SettingTable<PhysicsOptions>& physics_settings() {
  using P = PhysicsOptions;
  static const SettingTable<PhysicsOptions> table = [] {
    SettingTable<PhysicsOptions> t{"physics", PhysicsOptions{}, {}};
    auto& s = t.settings;
    s.push_back(choice_setting("uplift", &P::uplift, values_of(kUpliftNames),
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
    s.push_back(number_setting("theta0_rad", &P::theta0_rad, "rad", Bound::kAny,
                               "initial rotation θ₁ (0: the frame starts at rest); within the closing limit"));
    s.push_back(number_setting("omega0_rad_s", &P::omega0_rad_s, "rad/s", Bound::kAny,
                               "initial angular velocity θ̇₁ (0: the frame starts at rest)"));
    return t;
  }();
  return table;
}

const SettingTable<SolverSettings>& solver_settings() {
  using S = SolverSettings;
  static const SettingTable<SolverSettings> table = [] {
    SettingTable<SolverSettings> t{"solver", preset_settings("balanced"), {}};
    auto& s = t.settings;
    Setting<SolverSettings> preset;
    preset.key = "preset";
    preset.type = SettingType::kChoice;
    preset.choices = preset_names();
    preset.doc = "accuracy preset; sets every value below, which single keys then override";
    // Its whole effect is in the values it sets, and those are fingerprinted.
    preset.in_fingerprint = false;
    preset.get = [](const S& v) { return SettingValue(v.preset); };
    preset.set = [](S& v, const SettingValue& value) { v = preset_settings(std::get<std::string>(value)); };
    s.push_back(std::move(preset));
    s.push_back(choice_setting("integrator", &S::integrator, values_of(kIntegratorNames), &to_string, &parse_integrator,
                               "time integrator (taylor: Taylor series steps where the scene has its series, the block and the rocking frame; dopri5 elsewhere)"));
    s.push_back(number_setting("rtol", &S::rtol, "1", Bound::kPositive, "relative tolerance"));
    s.push_back(number_setting("atol_theta_rad", &S::atol_theta_rad, "rad", Bound::kPositive,
                               "absolute tolerance on θ₁"));
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
                               "a case that takes longer ends as time_limit; 0: no limit"));
    s.back().aliases = {"--time-limit"};
    s.push_back(flag_setting("verdict_check", &S::verdict_check,
                             "run each case near collapse again with its record scaled by 1 ± 1e-9, 1e-7, 1e-6: "
                             "status_stable, theta_max_spread, collapse_fraction"));
    return t;
  }();
  return table;
}

std::string tail_advice(double tail_s) {
  if (std::isnan(tail_s)) return "a longer physics.tail_s (fixed tail) or physics.max_tail_s (until-rest tail) resolves them";
  if (tail_s == kTailUntilRest) return "a longer physics.max_tail_s resolves them (the until-rest tail stops there)";
  return "a longer physics.tail_s resolves them (the tail is fixed at " + number_text(tail_s) +
         " s; physics.max_tail_s caps only an until-rest tail)";
}

}  // namespace pcrf
