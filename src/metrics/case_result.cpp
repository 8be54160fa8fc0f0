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

using namespace metric_names;

namespace {
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
