// Per-case result record: metric table, status names, JSON.
#include "pcrf/metrics/case_result.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace pcrf {

std::string_view status_name(CaseStatus status) {
  switch (status) {
    case CaseStatus::kAtRest: return "at_rest";
    case CaseStatus::kRockingAtEnd: return "rocking_at_end";
    case CaseStatus::kTendonFracture: return "tendon_fracture";
    case CaseStatus::kOverturned: return "overturned";
    case CaseStatus::kSolverFailure: return "solver_failure";
    case CaseStatus::kTimeLimit: return "time_limit";
    case CaseStatus::kNotRun: return "not_run";
  }
  return "unknown";
}

const std::vector<CaseStatus>& all_final_statuses() {
  static const std::vector<CaseStatus> all = {CaseStatus::kAtRest,         CaseStatus::kRockingAtEnd,
                                              CaseStatus::kTendonFracture, CaseStatus::kOverturned,
                                              CaseStatus::kSolverFailure,  CaseStatus::kTimeLimit};
  return all;
}

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
      {"theta_max_rad", "rad", "peak |theta1|", [](const CaseResult& r) { return r.theta_max_rad; }},
      {"t_theta_max_s", "s", "time of peak |theta1|", [](const CaseResult& r) { return r.t_theta_max_s; }},
      {"omega_max_rad_s", "rad s-1", "peak |dtheta1/dt|", [](const CaseResult& r) { return r.omega_max_rad_s; }},
      {"t_omega_max_s", "s", "time of peak |dtheta1/dt|", [](const CaseResult& r) { return r.t_omega_max_s; }},
      {"strain_column_max", "1", "peak column tendon strain, initial strain included",
       [](const CaseResult& r) { return r.strain_column_max; }},
      {"strain_beam_max", "1", "peak beam tendon strain, initial strain included",
       [](const CaseResult& r) { return r.strain_beam_max; }},
      {"impacts", "1", "number of impacts", [](const CaseResult& r) { return static_cast<double>(r.impacts); }, true},
      {"t_end_s", "s", "time at which the case ended", [](const CaseResult& r) { return r.t_end_s; }},
      {"steps", "1", "integrator steps", [](const CaseResult& r) { return static_cast<double>(r.counts.steps); }, true},
      {"rhs_evals", "1", "right-hand-side evaluations",
       [](const CaseResult& r) { return static_cast<double>(r.counts.rhs_evals); }, true},
      {"root_evals", "1", "root-function evaluations",
       [](const CaseResult& r) { return static_cast<double>(r.counts.root_evals); }, true},
      {"wall_time_s", "s", "wall-clock time of the case", [](const CaseResult& r) { return r.wall_time_s; }},
  };
  return metrics;
}

const MetricInfo* find_metric(std::string_view name) {
  for (const auto& m : all_metrics()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

namespace {

void write_number(std::ostringstream& os, double v) {
  if (!std::isfinite(v)) {
    os << "null";
    return;
  }
  // Shortest text that reads back to the same double (2.69, not 2.6899999999999999).
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
  os << std::string_view(buf, static_cast<std::size_t>(end - buf));
}

void write_string(std::ostringstream& os, std::string_view s) {
  os << '"';
  for (const char c : s) {
    switch (c) {
      case '"': os << "\\\""; break;
      case '\\': os << "\\\\"; break;
      case '\n': os << "\\n"; break;
      case '\t': os << "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          os << buf;
        } else {
          os << c;
        }
    }
  }
  os << '"';
}

}  // namespace

std::string to_json(const CaseResult& r) {
  std::ostringstream os;
  os << '{';
  bool first = true;
  for (const auto& m : all_metrics()) {
    if (!first) os << ", ";
    first = false;
    write_string(os, m.name);
    os << ": ";
    if (m.is_count) {
      os << static_cast<long>(m.get(r));
    } else {
      write_number(os, m.get(r));
    }
  }
  os << ", \"status\": ";
  write_string(os, status_name(r.status));
  os << ", \"reinits\": " << r.counts.reinits;
  os << ", \"message\": ";
  write_string(os, r.message);
  os << '}';
  return os.str();
}

}  // namespace pcrf
