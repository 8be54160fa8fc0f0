// `pcrf plot KIND INPUT …`: hands the arguments to the figure package `pcrf.plot` of the
// Python module (src/python/pcrf/plot, matplotlib), which reads every number in process
// through the module and writes the figure by the rule of every output (io::OutputFile).
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/commands.hpp"

namespace pcrf::cli {
namespace {

/// An environment override, or the value CMake found at configure time.
std::string configured(const char* variable, const char* fallback) {
  const char* value = std::getenv(variable);
  return value != nullptr && *value != '\0' ? value : fallback;
}

/// The folder that holds the package `pcrf` (build/python), checked to hold its figures.
std::string module_folder() {
  const std::string folder = configured("PCRF_MODULE_DIR", PCRF_MODULE_DIR);
  if (folder.empty())
    throw UsageError("pcrf plot draws with the Python module, which this build lacks "
                     "(apt-get install python3-dev pybind11-dev, then configure and build again)");
  if (!std::filesystem::exists(std::filesystem::path(folder) / "pcrf" / "plot" / "__main__.py"))
    throw UsageError("the Python module's figures are missing: " + folder +
                     "/pcrf/plot (build the module, or set PCRF_MODULE_DIR to the folder holding pcrf)");
  return folder;
}

[[noreturn]] void run_figure_package(const std::vector<std::string>& arguments) {
  const std::string python = configured("PCRF_PYTHON", PCRF_PYTHON);
  const std::string folder = module_folder();
  const char* old_path = std::getenv("PYTHONPATH");
  const std::string path = folder + (old_path != nullptr && *old_path != '\0' ? ":" + std::string(old_path) : "");
  setenv("PYTHONPATH", path.c_str(), 1);
  // python3 -m pcrf.plot, but a module that does not import (built for another Python, or
  // not built) is one line and exit code 2, as every failure of pcrf plot.
  const std::string start =
      "import sys\n"
      "try:\n"
      "    from pcrf.plot.cli import main\n"
      "except ImportError as e:\n"
      "    print(f'pcrf plot: error: cannot import the Python module pcrf from " + folder + " with {sys.executable}: {e}',\n"
      "          file=sys.stderr)\n"
      "    sys.exit(2)\n"
      "sys.exit(main(sys.argv[1:]))\n";
  std::vector<std::string> words{python, "-c", start};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  execvp(python.c_str(), argv.data());
  throw UsageError("cannot start Python '" + python + "': " + std::strerror(errno) +
                   " (apt-get install python3 python3-matplotlib, or set PCRF_PYTHON)");
}

}  // namespace

void add_plot_command(CLI::App& app) {
  // The kinds: the figure package's one table (src/python/pcrf/plot/kinds.json, read by CMake).
  auto* cmd = app.add_subcommand("plot",
                                 "Draw a figure: pcrf plot KIND INPUT [-w NAME=VALUE]... [-m METRIC] -o FILE.png|.pdf|.svg "
                                 "(kinds: " PCRF_PLOT_KINDS "; pcrf plot --help)");
  // Every argument, --help included, belongs to the figure package: it owns the kinds.
  cmd->prefix_command();
  cmd->set_help_flag();
  cmd->callback([cmd] { run_figure_package(cmd->remaining()); });
}

}  // namespace pcrf::cli
