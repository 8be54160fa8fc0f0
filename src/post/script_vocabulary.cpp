// The engine's names for scripts and figures (see script_vocabulary.hpp).
#include "pcrf/post/script_vocabulary.hpp"

#include <cstdint>
#include <string_view>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/json.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/metrics/curve_state.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/solver/history.hpp"

namespace pcrf::post {
namespace {

JsonObject status_json(std::string_view name, std::int8_t value, bool collapse, bool verdict) {
  JsonObject o;
  o.text("name", name).integer("value", value).text("kind", collapse ? "collapse" : verdict ? "survived" : "no_verdict");
  return o;
}

}  // namespace

std::string script_vocabulary_json() {
  std::vector<JsonObject> statuses, events, parameters, curve_states;
  for (CaseStatus s : all_final_statuses())
    statuses.push_back(status_json(status_name(s), static_cast<std::int8_t>(s), is_collapse(s), has_verdict(s)));
  statuses.push_back(status_json(cube::kStatusNotRunName, cube::kStatusNotRun, false, false));
  for (const auto& e : history_events()) {
    events.emplace_back();
    events.back().text("name", e.name).integer("flag", e.flag).text("meaning", e.meaning);
  }
  for (const auto& p : all_parameters()) {
    parameters.emplace_back();
    parameters.back().text("name", p.name).text("long_name", p.long_name).text("units", p.units);
  }
  for (const auto& c : kCurveStateNames) {
    curve_states.emplace_back();
    curve_states.back().text("name", c.name).integer("value", static_cast<int>(c.value));
  }
  JsonObject cube_names, metric_roles;
  for (const auto& n : schema::cube_names()) cube_names.text(n.role, n.name);
  std::vector<JsonObject> metrics;
  for (const auto& m : all_metrics()) {
    metrics.emplace_back();
    metrics.back().text("name", m.name).text("units", m.units);
  }
  // The metrics other layers act on by meaning (case_result.hpp, namespace metric).
  for (const auto& [role, m] : {std::pair{"THETA_MAX", &metric::theta_max()}, std::pair{"OMEGA_MAX", &metric::omega_max()},
                                std::pair{"T_OMEGA_MAX", &metric::t_omega_max()}, std::pair{"STATUS_STABLE", &metric::status_stable()},
                                std::pair{"COLLAPSE_FRACTION", &metric::collapse_fraction()},
                                std::pair{"T_THETA_MAX", &metric::t_theta_max()},
                                std::pair{"STRAIN_COLUMN_MAX", &metric::strain_column_max()},
                                std::pair{"STRAIN_BEAM_MAX", &metric::strain_beam_max()}, std::pair{"IMPACTS", &metric::impacts()},
                                std::pair{"CPU_TIME", &metric::cpu_time()}})
    metric_roles.text(role, m->name);
  JsonObject root;
  root.objects("curve_states", curve_states).objects("statuses", statuses).objects("history_events", events).objects("parameters", parameters);
  root.object("cube_names", cube_names).objects("metrics", metrics).object("metric_roles", metric_roles);
  return root.str();
}

}  // namespace pcrf::post
