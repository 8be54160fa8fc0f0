// Per-case result record: metric table, status names, JSON.
#include "pcrf/metrics/case_result.hpp"

#include <array>

#include "pcrf/setting.hpp"

#include "pcrf/json.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace pcrf {

namespace {
/// Every status's only spelling: the final ones in flag order, then the placeholder.
constexpr std::array<EnumName<CaseStatus>, 9> kStatusNames{{{CaseStatus::kAtRest, "at_rest"},
                                                           {CaseStatus::kRockingAtEnd, "rocking_at_end"},
                                                           {CaseStatus::kTendonFracture, "tendon_fracture"},
                                                           {CaseStatus::kOverturned, "overturned"},
                                                           {CaseStatus::kSolverFailure, "solver_failure"},
                                                           {CaseStatus::kTimeLimit, "time_limit"},
                                                           {CaseStatus::kInvalidFrame, "invalid_frame"},
                                                           {CaseStatus::kGroundFreeFall, "ground_free_fall"},
                                                           {CaseStatus::kNotRun, "not_run"}}};
}  // namespace

std::string_view status_name(CaseStatus status) {
  for (const auto& n : kStatusNames)
    if (n.value == status) return n.name;
  return "unknown";
}

CaseStatus parse_status(const std::string& text) { return parse_name(kStatusNames, text, "status"); }

const std::vector<CaseStatus>& all_final_statuses() {
  static const std::vector<CaseStatus> all = [] {
    std::vector<CaseStatus> statuses = values_of(kStatusNames);
    std::erase(statuses, CaseStatus::kNotRun);
    return statuses;
  }();
  return all;
}

bool is_collapse(CaseStatus status) {
  return status == CaseStatus::kTendonFracture || status == CaseStatus::kOverturned;
}

bool has_verdict(CaseStatus status) {
  return status == CaseStatus::kAtRest || is_collapse(status);
}

bool is_unresolved(CaseStatus status) { return status == CaseStatus::kRockingAtEnd; }

bool is_outside_model(CaseStatus status) {
  return status == CaseStatus::kInvalidFrame || status == CaseStatus::kGroundFreeFall;
}

bool gives_no_verdict(CaseStatus status) { return is_unresolved(status) || is_outside_model(status); }

Verdict verdict_of(CaseStatus status) {
  switch (status) {
    case CaseStatus::kAtRest:
    case CaseStatus::kRockingAtEnd: return Verdict::kSurvived;
    case CaseStatus::kTendonFracture: return Verdict::kTendonFracture;
    case CaseStatus::kOverturned: return Verdict::kOverturned;
    default: return Verdict::kNone;
  }
}

namespace {
// The names other layers act on by meaning (metric:: handles); every other name is written
// only in the table below.
constexpr std::string_view kThetaMax = "theta_max_rad";
constexpr std::string_view kOmegaMax = "omega_max_rad_s";
constexpr std::string_view kTOmegaMax = "t_omega_max_s";
constexpr std::string_view kStatusStable = "status_stable";
constexpr std::string_view kCollapseFraction = "collapse_fraction";
constexpr std::string_view kTThetaMax = "t_theta_max_s";
constexpr std::string_view kStrainColumnMax = "strain_column_max";
constexpr std::string_view kStrainBeamMax = "strain_beam_max";
constexpr std::string_view kImpacts = "impacts";
constexpr std::string_view kCpuTime = "cpu_time_s";

const MetricInfo& handle(std::string_view name) { return *find_metric(name); }
}  // namespace

namespace metric {
const MetricInfo& theta_max() { return handle(kThetaMax); }
const MetricInfo& omega_max() { return handle(kOmegaMax); }
const MetricInfo& t_omega_max() { return handle(kTOmegaMax); }
const MetricInfo& status_stable() { return handle(kStatusStable); }
const MetricInfo& collapse_fraction() { return handle(kCollapseFraction); }
const MetricInfo& t_theta_max() { return handle(kTThetaMax); }
const MetricInfo& strain_column_max() { return handle(kStrainColumnMax); }
const MetricInfo& strain_beam_max() { return handle(kStrainBeamMax); }
const MetricInfo& impacts() { return handle(kImpacts); }
const MetricInfo& cpu_time() { return handle(kCpuTime); }
}  // namespace metric

const std::vector<MetricInfo>& all_metrics() {
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
      {kTThetaMax, "s", "time of peak |theta1|", [](const CaseResult& r) { return r.t_theta_max_s; }},
      {kOmegaMax, "rad s-1", "peak |dtheta1/dt|", [](const CaseResult& r) { return r.omega_max_rad_s; }},
      {kTOmegaMax, "s", "time of peak |dtheta1/dt|", [](const CaseResult& r) { return r.t_omega_max_s; }},
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

const MetricInfo* find_metric(std::string_view name) {
  for (const auto& m : all_metrics()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

void add_to_json(JsonObject& json, const CaseResult& r) {
  for (const auto& m : all_metrics()) {
    if (m.is_count)
      json.integer(m.name, static_cast<long long>(m.get(r)));
    else
      json.number(m.name, m.get(r));
  }
  json.text("status", status_name(r.status));
  json.integer("reinits", r.counts.reinits);
  json.text("message", r.message);
}

}  // namespace pcrf
