// `pcrf plot KIND INPUT …`: hands the arguments to the bundled figure package (src/plot,
// Python + matplotlib), which draws with numbers it asks this same executable for.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "pcrf/io/output_file.hpp"

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

struct OutputArguments {
  std::string file;
  std::vector<std::string> inputs;
  bool overwrite = false;
};

/// `pcrf output check|write FILE --input INPUT… [--overwrite]`, hidden: how the figure
/// package writes its figure by the one output rule (io::OutputFile) instead of its own:
/// `check` before drawing, `write` with the figure's bytes on stdin.
void add_output_command(CLI::App& app) {
  auto args = std::make_shared<OutputArguments>();
  auto* cmd = app.add_subcommand("output", "Write stdin to FILE by the rule of every output (for pcrf plot)");
  cmd->group("");  // not listed: an interface between pcrf and its figure package
  cmd->require_subcommand(1);
  for (const bool write : {false, true}) {
    auto* sub = cmd->add_subcommand(write ? "write" : "check", write ? "write stdin to FILE" : "refuse FILE now, if at all");
    sub->add_option("FILE", args->file, "the output")->required();
    sub->add_option("--input", args->inputs, "an input the output must not be (repeatable)");
    sub->add_flag("--overwrite", args->overwrite, "replace an existing FILE");
    sub->callback([args, write] {
      const std::vector<std::filesystem::path> inputs(args->inputs.begin(), args->inputs.end());
      if (!write) return io::check_output(args->file, inputs, args->overwrite);
      io::OutputFile out(args->file, inputs, args->overwrite);
      std::vector<char> block(1 << 16);
      while (std::cin.read(block.data(), static_cast<std::streamsize>(block.size())) || std::cin.gcount() > 0)
        out.stream().write(block.data(), std::cin.gcount());
      out.commit();
    });
  }
}

}  // namespace

void add_plot_command(CLI::App& app) {
  add_output_command(app);
  auto* cmd = app.add_subcommand("plot",
                                 "Draw a figure: pcrf plot KIND INPUT [-w NAME=VALUE]... [-m METRIC] -o FILE.png|.pdf|.svg "
                                 "(kinds: history, sweep, ida, spectrum, fragility, sensitivity, status, table3; pcrf plot --help)");
  // Every argument, --help included, belongs to the figure package: it owns the kinds.
  cmd->prefix_command();
  cmd->set_help_flag();
  cmd->callback([cmd] { run_figure_package(cmd->remaining()); });
}

}  // namespace pcrf::cli
