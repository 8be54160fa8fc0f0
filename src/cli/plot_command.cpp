// `pcrf plot KIND INPUT …`: hands the arguments to the bundled figure package (src/plot,
// Python + matplotlib), which draws with numbers it asks this same executable for.
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

[[noreturn]] void run_figure_package(const std::vector<std::string>& arguments) {
  const std::string python = configured("PCRF_PYTHON", PCRF_PYTHON);
  const std::string package = configured("PCRF_PLOT_DIR", PCRF_PLOT_DIR);
  if (!std::filesystem::exists(std::filesystem::path(package) / "pcrf_plot" / "__main__.py"))
    throw UsageError("the figure package is missing: " + package + "/pcrf_plot (set PCRF_PLOT_DIR to the checkout's src/plot)");
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) setenv("PCRF_EXECUTABLE", self.c_str(), 1);
  const char* old_path = std::getenv("PYTHONPATH");
  const std::string path = package + (old_path != nullptr && *old_path != '\0' ? ":" + std::string(old_path) : "");
  setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> words{python, "-m", "pcrf_plot"};
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
  auto* cmd = app.add_subcommand("plot",
                                 "Draw a figure: pcrf plot KIND INPUT [-w NAME=VALUE]... [-m METRIC] -o FILE.png|.pdf|.svg "
                                 "(kinds: history, sweep, ida, fragility, sensitivity, status, table3; pcrf plot --help)");
  // Every argument, --help included, belongs to the figure package: it owns the kinds.
  cmd->prefix_command();
  cmd->set_help_flag();
  cmd->callback([cmd] { run_figure_package(cmd->remaining()); });
}

}  // namespace pcrf::cli
