// `pcrf settings`: every setting of a study's [physics], [solver] and [run] tables, with its
// type, unit, default and meaning, as the Markdown tables of studies/README.md; with --json,
// the engine's vocabulary for scripts and the figure package (statuses, history event flags,
// frame parameters).
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/json.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/ida/ida_search.hpp"
#include "pcrf/solver/history.hpp"
#include "pcrf/study/settings_doc.hpp"

namespace pcrf::cli {
namespace {

JsonObject status_json(std::string_view name, std::int8_t value, bool collapse, bool verdict) {
  JsonObject o;
  o.text("name", name).integer("value", value).text("kind", collapse ? "collapse" : verdict ? "survived" : "no_verdict");
  return o;
}

/// The names every script needs besides a cube's own: statuses (with what they say about
/// the frame), history event flags, the frame parameters in axis order.
void print_vocabulary_json(std::ostream& out) {
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
  out << root.str() << '\n';
}

}  // namespace

void add_settings_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand(
      "settings", "List every [physics], [solver] and [run] setting (type, unit, default, meaning) as Markdown; "
                  "each key is also a flag: tail_s -> --tail-s");
  cmd->add_flag("--json", *json,
                "instead: the engine's vocabulary as one JSON object: statuses [{name, value, kind: survived | collapse | "
                "no_verdict}], history_events [{name, flag, meaning}], parameters [{name, long_name, units}], curve_states [{name, value}] (an IDA cube's curve_state codes)");
  cmd->callback([json] {
    if (*json) print_vocabulary_json(std::cout);
    else std::cout << study::all_settings_markdown();
  });
}

}  // namespace pcrf::cli
