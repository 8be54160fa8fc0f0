// `pcrf settings`: every setting of a study's [physics], [solver] and [run] tables, with its
// type, unit, default and meaning, as the Markdown tables of studies/README.md; with --json,
// the engine's vocabulary for scripts and the figure package (statuses, history event flags,
// frame parameters).
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "pcrf/post/script_vocabulary.hpp"
#include "pcrf/study/settings_doc.hpp"

namespace pcrf::cli {

void add_settings_command(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto* cmd = app.add_subcommand(
      "settings", "List every [physics], [solver] and [run] setting (type, unit, default, meaning) as Markdown; "
                  "each key is also a flag: tail_s -> --tail-s");
  cmd->add_flag("--json", *json,
                "instead: the engine's vocabulary as one JSON object: statuses [{name, value, kind: survived | collapse | "
                "no_verdict}], history_events [{name, flag, meaning}], parameters [{name, long_name, units}], curve_states [{name, value}] (an IDA cube's curve_state codes)");
  cmd->callback([json] {
    if (*json) std::cout << post::script_vocabulary_json() << '\n';
    else std::cout << study::all_settings_markdown();
  });
}

}  // namespace pcrf::cli
