// pcrf: command-line entry point. Thin layer: every sub-command lives in its own file.
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

#include "cli/commands.hpp"
#include "pcrf/io/checked_stream.hpp"
#include "pcrf/printable.hpp"
#include "pcrf/version.hpp"

namespace pcrf::cli {
int& exit_code() {
  static int code = 0;
  return code;
}
}  // namespace pcrf::cli

namespace {

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
    return fail("pcrf: error: " + pcrf::printable(e.what()) + " (see pcrf --help)", 2);
  } catch (const pcrf::cli::UsageError& e) {
    return fail("pcrf: error: " + pcrf::printable(e.what()), 2);
  } catch (const pcrf::io::OutputError& e) {
    return fail("pcrf: error: " + pcrf::printable(e.what()), 2);
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
  try {
    return run(app, argc, argv, out);
  } catch (const pcrf::io::OutputError& e) {  // help or version could not be written
    std::cerr << "pcrf: error: " << pcrf::printable(e.what()) << "\n";
    return 2;
  }
}
