// `pcrf settings`: every setting of a study's [physics], [solver] and [run] tables, with its
// type, unit, default and meaning, as the Markdown tables of studies/README.md.
#include <CLI/CLI.hpp>

#include <iostream>

#include "cli/commands.hpp"
#include "pcrf/study/settings_doc.hpp"

namespace pcrf::cli {

void add_settings_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "settings", "List every [physics], [solver] and [run] setting (type, unit, default, meaning) as Markdown; "
                  "each key is also a flag: tail_s -> --tail-s");
  cmd->callback([] { std::cout << study::all_settings_markdown(); });
}

}  // namespace pcrf::cli
