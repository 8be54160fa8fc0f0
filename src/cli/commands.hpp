/// \file commands.hpp
/// \brief Sub-commands of the `pcrf` executable. Each adds itself to the CLI11 app and
/// runs from its callback; a command reports bad input by throwing UserError, which
/// main() turns into a one-line message (keys as flags) and exit code 2.
#pragma once

#include "pcrf/user_error.hpp"

namespace CLI {
class App;
}

namespace pcrf::cli {

/// Bad arguments or bad input files: one line on stderr, exit code 2. The error every layer
/// throws for bad input (pcrf/user_error.hpp); its keys are printed as flags.
using UsageError = UserError;

/// Exit code a sub-command asks main() to return (set by its callback; default 0).
int& exit_code();

void add_run_command(CLI::App& app);    ///< `pcrf run`: one case, JSON on stdout
void add_frame_command(CLI::App& app);  ///< `pcrf frame`: a frame's properties and pushover curve
void add_record_command(CLI::App& app); ///< `pcrf record FILE`: intensity measures, JSON on stdout
void add_record_library_commands(CLI::App* record);  ///< `pcrf record spectra|select`
void add_study_command(CLI::App& app);  ///< `pcrf study FILE`: a parametric study (MPI)
void add_cube_command(CLI::App& app);   ///< `pcrf cube info|export|stats|fragility|sensitivity|merge`
void add_plot_command(CLI::App& app);   ///< `pcrf plot KIND INPUT -o FILE`: figures (pcrf.plot of the Python module, matplotlib)
void add_settings_command(CLI::App& app);  ///< `pcrf settings`: every setting, as Markdown

}  // namespace pcrf::cli
