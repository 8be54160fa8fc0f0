// pcrf: command-line entry point. Thin layer: every sub-command lives in its own file.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <exception>
#include <iostream>
#include <string_view>
#include <vector>

#include "cli/commands.hpp"
#include "pcrf/closest_word.hpp"
#include "pcrf/io/checked_stream.hpp"
#include "pcrf/json.hpp"
#include "pcrf/io/file_kind.hpp"
#include "pcrf/printable.hpp"
#include "pcrf/version.hpp"

namespace pcrf::cli {
int& exit_code() {
  static int code = 0;
  return code;
}

namespace {

/// Whether the environment asks for errors as JSON (PCRF_ERROR_FORMAT=json).
bool json_errors() {
  const char* format = std::getenv("PCRF_ERROR_FORMAT");
  return format != nullptr && std::string_view(format) == "json";
}

}  // namespace

std::string error_line(const UserError& e) {
  if (!json_errors()) return "pcrf: error: " + printable(e.message(Dialect::kFlag));
  const Where& where = e.where();
  return "pcrf: error: " + JsonObject()
                               .text("kind", "input")
                               .text("message", e.message(Dialect::kKeyword))
                               .text("key", last_key_name(where.keys))
                               .text("file", where.file)
                               .integer("line", where.line)
                               .str();
}

std::string error_line(const std::string& kind, const std::string& message) {
  if (!json_errors()) return "pcrf: error: " + printable(message);
  return "pcrf: error: " + JsonObject().text("kind", kind).text("message", message).str();
}

}  // namespace pcrf::cli

namespace {

/// The deepest subcommand the command line reached: where an unknown flag was given.
const CLI::App* reached(const CLI::App& app) {
  const CLI::App* at = &app;
  while (!at->get_subcommands().empty()) at = at->get_subcommands().front();
  return at;
}

/// "cube stats": the subcommands' names down to `at`.
std::string command_path(const CLI::App* at) {
  std::string path;
  for (; at != nullptr && at->get_parent() != nullptr; at = at->get_parent())
    path = at->get_name() + (path.empty() ? "" : " " + path);
  return path;
}

/// The flag `at` knows that `flag` most likely means: its own spelling with dashes for
/// underscores (--tan_alpha, a study key, is --tan-alpha), else the closest flag.
std::string meant_flag(const std::string& flag, const CLI::App& at) {
  std::vector<std::string> names;
  for (const CLI::Option* o : at.get_options()) {
    for (const auto& l : o->get_lnames()) names.push_back("--" + l);
    for (const auto& s : o->get_snames()) names.push_back("-" + s);
  }
  std::string word = flag.substr(0, flag.find('='));
  std::string dashed = word;
  std::replace(dashed.begin(), dashed.end(), '_', '-');
  if (std::find(names.begin(), names.end(), dashed) != names.end()) return dashed;
  return pcrf::closest_word(word, std::vector<std::string_view>(names.begin(), names.end()));
}

/// The first flag the command line did not know, as one line with the flag meant; empty
/// when every argument left over is a value. A misspelt required flag is reported so, not
/// as the required flag missing.
std::string unknown_flag_message(const CLI::App& app) {
  const CLI::App* at = reached(app);
  for (const auto& arg : app.remaining(true)) {
    if (arg.size() < 2 || arg[0] != '-' || (arg[1] >= '0' && arg[1] <= '9') || arg[1] == '.') continue;
    const std::string path = command_path(at), hint = meant_flag(arg, *at);
    return "pcrf: error: " + (path.empty() ? "" : path + ": ") + "unknown flag " + pcrf::printable(arg) +
           (hint.empty() ? " (see pcrf " + (path.empty() ? "" : path + " ") + "--help)" : " (did you mean " + hint + "?)");
  }
  return {};
}

/// Runs the command line; every write to stdout is checked (OutputError), and what is
/// buffered is written before an error line so that the two keep their order.
int run(CLI::App& app, int argc, char** argv, pcrf::io::CheckedStdout& out) {
  auto fail = [&out](const std::string& line, int code) {
    try {
      out.finish();
    } catch (const pcrf::io::OutputError&) {  // the error line says what went wrong first
    }
    std::cerr << line << "\n";
    return code;
  };
  auto shown = [&out](int code) {  // help or version: an OutputError goes to main()
    out.finish();
    return code;
  };
  try {
    app.parse(argc, argv);
    out.finish();
  } catch (const CLI::CallForHelp& e) {
    return shown(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return shown(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return shown(app.exit(e));
  } catch (const CLI::ParseError& e) {
    if (const auto unknown = unknown_flag_message(app); !unknown.empty()) return fail(unknown, 2);
    return fail("pcrf: error: " + pcrf::printable(e.what()) + " (see pcrf --help)", 2);
  } catch (const pcrf::UserError& e) {
    return fail(pcrf::cli::error_line(e), 2);
  } catch (const pcrf::io::OutputError& e) {
    return fail(pcrf::cli::error_line("output", e.what()), 2);
  } catch (const std::exception& e) {
    return fail("pcrf: internal error: " + pcrf::printable(e.what()), 1);
  }
  return pcrf::cli::exit_code();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pcrf: seismic response of prestressed concrete rocking frames"};
  app.set_version_flag("--version", pcrf::kVersion);
  app.require_subcommand(1);
  pcrf::cli::add_run_command(app);
  pcrf::cli::add_frame_command(app);
  pcrf::cli::add_record_command(app);
  pcrf::cli::add_study_command(app);
  pcrf::cli::add_cube_command(app);
  pcrf::cli::add_plot_command(app);
  pcrf::cli::add_settings_command(app);
  pcrf::io::CheckedStdout out;
  // A command stopped by SIGTERM, SIGINT or SIGHUP leaves no temporary beside its outputs
  // (`pcrf study` replaces these handlers with its own, which stop it in order).
  pcrf::io::remove_temporaries_on_signals();
  try {
    return run(app, argc, argv, out);
  } catch (const pcrf::io::OutputError& e) {  // help or version could not be written
    std::cerr << "pcrf: error: " << pcrf::printable(e.what()) << "\n";
    return 2;
  }
}
