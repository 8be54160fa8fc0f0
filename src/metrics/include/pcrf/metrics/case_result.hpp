/// \file case_result.hpp
/// \brief The per-case result record: peaks, times, counts and the final status.
///
/// Every quantity carries its unit in its name. A metric that does not exist for a case
/// (no uplift, solver failure) is NaN; the JSON form writes it as null.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/json.hpp"

namespace pcrf {

/// How a case ended. The integer values are stored in result cubes (CF flag_values):
/// never renumber them.
enum class CaseStatus : std::int8_t {
  kAtRest = 0,          ///< record (and tail) over, frame at rest
  kRockingAtEnd = 1,    ///< record (and tail) over, frame still rocking
  kTendonFracture = 2,  ///< a tendon reached the fracture strain
  kOverturned = 3,      ///< the mechanism reached its limit angle and cannot close
  kSolverFailure = 4,   ///< the integrator failed or produced a non-finite state
  kTimeLimit = 5,       ///< the case hit its wall-time limit
  /// The frame cannot be built, or lies outside the domain where the rigid-body rocking
  /// model holds (studies/README.md, "Valid frames"); it is not simulated.
  kInvalidFrame = 6,
  /// The ground fell faster than gravity (g + ü_v ≤ 0): the frame leaves its supports, which
  /// the model does not describe (docs/vertical_excitation.md). The case ends there.
  kGroundFreeFall = 7,
  kNotRun = -1,         ///< placeholder in a cube for a case not computed yet
};

/// Stable text name of a status ("at_rest", "rocking_at_end", ...).
std::string_view status_name(CaseStatus status);
/// The status a name spells. \throws std::invalid_argument "unknown status 'x' (expected …)".
CaseStatus parse_status(const std::string& text);
/// All statuses that a case can end with, in flag order (kNotRun excluded).
const std::vector<CaseStatus>& all_final_statuses();
/// A collapse: a tendon fractured or the frame overturned.
bool is_collapse(CaseStatus status);
/// The case says something about the frame: it came to rest or collapsed. A frame still
/// rocking when its tail ended (unresolved), a solver failure, a time limit, an invalid frame
/// or a ground in free fall does not.
bool has_verdict(CaseStatus status);
/// The frame was still rocking when the case ended (the record plus its tail): neither safe
/// nor collapsed. Counted apart by every summary, never as safe.
bool is_unresolved(CaseStatus status);
/// The model no longer applies (an invalid frame, a ground in free fall): the case says
/// nothing about the frame, whatever the intensity.
bool is_outside_model(CaseStatus status);
/// Neither safe nor collapsed, and no failure of the computation: unresolved or outside the
/// model. An IDA's search stops at such a run without calling it a collapse; a curve whose
/// lowest stopping run is one is unresolved (ida::CurveState::kUnresolved), never safe.
bool gives_no_verdict(CaseStatus status);
/// What a case says about the frame, as verdict checks and benchmarks compare cases.
enum class Verdict { kSurvived, kTendonFracture, kOverturned, kNone };
Verdict verdict_of(CaseStatus status);

/// Solver work counters, summed over every re-initialization of the integrator.
struct SolverCounts {
  long steps = 0;
  long rhs_evals = 0;
  long root_evals = 0;
  long reinits = 0;
};

/// The result record of one case (one frame, one ground motion).
struct CaseResult {
  // Properties of the frame (independent of the record).
  // Every quantity starts as NaN, "does not exist": a solver path sets each one it computes
  // (tests/solver/result_contract_test.cpp checks that every path sets every metric it claims).
  double lambda_g = kNone;            ///< paper's uplift coefficient G(0)/S(0) [-] (×g)
  double uplift_threshold_g = kNone;  ///< physical uplift acceleration incl. prestress [g]
  double restitution = kNone;         ///< coefficient of restitution r [-]
  // Response.
  double t_trigger_paper_s = kNone;   ///< first sample with |ü_g| ≥ λ_g·g (paper's t_RI) [s]; NaN if none
  double t_uplift_s = kNone;          ///< first lift-off [s]; NaN if none
  double theta_max_rad = kNone;       ///< max |θ₁| [rad] (0 for a frame that never lifts)
  double t_theta_max_s = kNone;       ///< time of theta_max_rad [s]; NaN if no uplift
  double omega_max_rad_s = kNone;     ///< max |θ̇₁| [rad/s]; NaN when not requested
  double t_omega_max_s = kNone;       ///< time of omega_max_rad_s [s]; NaN if no uplift or not requested
  double strain_column_max = kNone;   ///< max column tendon strain, initial strain included [-]; NaN without tendons
  double strain_beam_max = kNone;     ///< max beam tendon strain, initial strain included [-]; NaN without tendons
  long impacts = 0;                 ///< number of impacts (θ₁ crossing zero)
  CaseStatus status = CaseStatus::kNotRun;
  double t_end_s = kNone;           ///< time at which the case ended [s]
  SolverCounts counts;
  /// CPU time of the thread that solved the case [s]; in a lane batch, its share of the
  /// batch's (metric::cpu_time()'s doc says exactly what it counts).
  double cpu_time_s = kNone;
  // Verdict check (SolverSettings::verdict_check); NaN when not checked.
  double status_stable = kNotChecked;     ///< 1: every perturbed twin reached the same verdict; 0: not
  double theta_max_spread = kNotChecked;  ///< (max − min)/θ_max over the case and its twins [-]
  double collapse_fraction = kNotChecked; ///< share of the case and its twins that collapsed [-]
  static constexpr double kNotChecked = std::numeric_limits<double>::quiet_NaN();
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  std::string message;              ///< failure detail; empty when none
};

/// One metric of CaseResult, as studies and cubes name it.
struct MetricInfo {
  std::string_view name;   ///< e.g. "theta_max_rad"
  std::string_view units;  ///< UDUNITS text, e.g. "rad", "s", "1"
  std::string_view description;
  double (*get)(const CaseResult&);
  bool is_count = false;  ///< an integer count (impacts, steps, ...)
  bool needs_verdict_check = false;  ///< only computed with [solver] verdict_check = true
  /// The name older versions wrote (cubes keep it; a study file naming it is told the new one).
  std::string_view former_name = {};
  /// The time of an event: the metric whose positive value says the event happened (this one
  /// is NaN exactly when that one is not positive). The result contract reads it
  /// (tests/solver/result_contract_test.cpp). Empty: not a time of an event.
  std::string_view exists_with = {};
};

/// Every numeric metric of CaseResult (status excluded), in a stable order. Defined below,
/// beside the members it reads: a new metric is its member and its row in this header
/// (docs/developer.md, "What a new thing costs").
inline const std::vector<MetricInfo>& all_metrics();
/// Looks a metric up by name; nullptr when unknown.
const MetricInfo* find_metric(std::string_view name);

/// Handles to the metrics other layers act on by meaning (the IDA's angle limit, the
/// verdict check, the optional ω peak; the figures' own labels): each is the table's own
/// entry, so its name is written once, in all_metrics().
namespace metric {
const MetricInfo& theta_max();        ///< peak |θ₁|
const MetricInfo& omega_max();        ///< peak |θ̇₁|
const MetricInfo& t_omega_max();      ///< its time
const MetricInfo& status_stable();    ///< verdict check: the verdict survives perturbation
const MetricInfo& collapse_fraction();///< verdict check: share of twins that collapse
const MetricInfo& t_theta_max();      ///< time of peak |θ₁|
const MetricInfo& strain_column_max();///< peak column tendon strain
const MetricInfo& strain_beam_max();  ///< peak beam tendon strain
const MetricInfo& impacts();          ///< number of impacts
const MetricInfo& cpu_time();         ///< CPU time of a case
}  // namespace metric

/// The record's keys (the metrics' names, status, reinits, message; NaN as null), added to
/// an object the caller is building (e.g. with the scale factor).
void add_to_json(JsonObject& json, const CaseResult& result);

/// The names other layers act on by meaning (metric:: handles); every other name is written
/// only in the table below.
namespace metric_names {
inline constexpr std::string_view kThetaMax = "theta_max_rad";
inline constexpr std::string_view kOmegaMax = "omega_max_rad_s";
inline constexpr std::string_view kTOmegaMax = "t_omega_max_s";
inline constexpr std::string_view kStatusStable = "status_stable";
inline constexpr std::string_view kCollapseFraction = "collapse_fraction";
inline constexpr std::string_view kTThetaMax = "t_theta_max_s";
inline constexpr std::string_view kStrainColumnMax = "strain_column_max";
inline constexpr std::string_view kStrainBeamMax = "strain_beam_max";
inline constexpr std::string_view kImpacts = "impacts";
inline constexpr std::string_view kCpuTime = "cpu_time_s";
}  // namespace metric_names

/// The table (declared above): one row per member of CaseResult that is a metric.
inline const std::vector<MetricInfo>& all_metrics() {
  using namespace metric_names;
  static const std::vector<MetricInfo> metrics = {
      {"lambda_g", "1", "paper's uplift coefficient G(0)/S(0), in units of g",
       [](const CaseResult& r) { return r.lambda_g; }},
      {"uplift_threshold_g", "1", "ground acceleration that opens the frame, prestress included, in units of g",
       [](const CaseResult& r) { return r.uplift_threshold_g; }},
      {"restitution", "1", "coefficient of restitution r",
       [](const CaseResult& r) { return r.restitution; }},
      {"t_trigger_paper_s", "s", "first sample with |ug''| >= lambda_g g (paper's t_RI)",
       [](const CaseResult& r) { return r.t_trigger_paper_s; }},
      {"t_uplift_s", "s", "first lift-off", [](const CaseResult& r) { return r.t_uplift_s; }},
      {kThetaMax, "rad", "peak |theta1|", [](const CaseResult& r) { return r.theta_max_rad; }},
      {.name = kTThetaMax, .units = "s", .description = "time of peak |theta1|",
       .get = [](const CaseResult& r) { return r.t_theta_max_s; }, .exists_with = kThetaMax},
      {kOmegaMax, "rad s-1", "peak |dtheta1/dt|", [](const CaseResult& r) { return r.omega_max_rad_s; }},
      {.name = kTOmegaMax, .units = "s", .description = "time of peak |dtheta1/dt|",
       .get = [](const CaseResult& r) { return r.t_omega_max_s; }, .exists_with = kOmegaMax},
      {kStrainColumnMax, "1", "peak column tendon strain, initial strain included",
       [](const CaseResult& r) { return r.strain_column_max; }},
      {kStrainBeamMax, "1", "peak beam tendon strain, initial strain included",
       [](const CaseResult& r) { return r.strain_beam_max; }},
      {kImpacts, "1",
       "number of impacts (theta1 crossing zero), counted until a flight would rise less than the return-to-rest "
       "cut-off that defines them: [physics] rest_rise_rad (cube attribute physics_rest_rise_rad, pcrf run's rest_rise_rad)",
       [](const CaseResult& r) { return static_cast<double>(r.impacts); }, true},
      {"t_end_s", "s", "time at which the case ended", [](const CaseResult& r) { return r.t_end_s; }},
      {"steps", "1", "integrator steps", [](const CaseResult& r) { return static_cast<double>(r.counts.steps); }, true},
      {"rhs_evals", "1", "right-hand-side evaluations",
       [](const CaseResult& r) { return static_cast<double>(r.counts.rhs_evals); }, true},
      {"root_evals", "1", "root-function evaluations",
       [](const CaseResult& r) { return static_cast<double>(r.counts.root_evals); }, true},
      {kCpuTime, "s",
       "CPU time of the thread that solved the case (set-up, integration, verdict-check twins; "
       "CLOCK_THREAD_CPUTIME_ID); in a lane batch its share of the batch thread's CPU time, each "
       "interval split equally among the cases then in lanes; never time descheduled or another case's",
       [](const CaseResult& r) { return r.cpu_time_s; }, false, false, "wall_time_s"},
      {kStatusStable, "1", "1 when the verdict survives the perturbation test (record x (1 +- 1e-9, 1e-7, 1e-6)), else 0",
       [](const CaseResult& r) { return r.status_stable; }, false, true},
      {"theta_max_spread", "1", "relative spread (max - min)/theta_max of peak |theta1| across the perturbation test",
       [](const CaseResult& r) { return r.theta_max_spread; }, false, true},
      {kCollapseFraction, "1", "share of the perturbation test's runs (the case and its six twins) that collapse",
       [](const CaseResult& r) { return r.collapse_fraction; }, false, true},
  };
  return metrics;
}

}  // namespace pcrf
