// The engine's names for scripts and figures (see script_vocabulary.hpp).
#include "pcrf/post/script_vocabulary.hpp"

#include <cstdint>
#include <string_view>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/json.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/ida/ida_search.hpp"
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
  for (const auto& c : ida::kCurveStateNames) {
    curve_states.emplace_back();
    curve_states.back().text("name", c.name).integer("value", static_cast<int>(c.value));
  }
  JsonObject root;
  root.objects("curve_states", curve_states).objects("statuses", statuses).objects("history_events", events).objects("parameters", parameters);
  return root.str();
}

}  // namespace pcrf::post
