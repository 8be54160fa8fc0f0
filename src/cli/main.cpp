// pcrf: command-line entry point. Thin layer: every sub-command lives in its own file.
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

#include "cli/commands.hpp"
#include "pcrf/printable.hpp"
#include "pcrf/version.hpp"

namespace pcrf::cli {
int& exit_code() {
  static int code = 0;
  return code;
}
}  // namespace pcrf::cli

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
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "pcrf: error: " << pcrf::printable(e.what()) << " (see pcrf --help)\n";
    return 2;
  } catch (const pcrf::cli::UsageError& e) {
    std::cerr << "pcrf: error: " << pcrf::printable(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "pcrf: internal error: " << pcrf::printable(e.what()) << "\n";
    return 1;
  }
  return pcrf::cli::exit_code();
}
