// `pcrf study FILE`: runs a parametric study, on one rank or under mpirun.
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "cli/setting_flags.hpp"
#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/printable.hpp"
#include "pcrf/study/study_parser.hpp"
#include "pcrf/study/study_run.hpp"

namespace pcrf::cli {
namespace {

/// Command-line values; the [run] flags override the study file's table.
struct StudyArguments {
  study::StudyRunOptions run;
  std::unique_ptr<SettingFlags<study::RunOptions>> run_flags;
};

void run_study_command(StudyArguments& args) {
  args.run.run_overrides = args.run_flags->given();
  args.run.progress = &std::cerr;

  parallel::MpiSession mpi;
  std::optional<study::StudySummary> summary;
  try {
    summary = study::run_study(args.run, mpi);
  } catch (const study::StudyError& e) {
    // Nothing has started. Report here, before MPI_Finalize, and not through UsageError in
    // main(): once another rank has exited with code 2, mpirun may end this one at any time.
    std::cerr << "pcrf: error: " << printable(e.what()) << std::endl;
    mpi.quiet_barrier();  // the other ranks wait for this line before they leave
    exit_code() = 2;
    return;
  } catch (const std::exception& e) {
    if (mpi.size() > 1) {  // other ranks are waiting for work that will never come
      std::cerr << "pcrf: error: " << printable(e.what()) << std::endl;
      mpi.abort(1);
    }
    throw;
  }
  if (!summary) exit_code() = 2;  // rank ≠ 0 of a study that cannot run: rank 0 reported it
  if (summary && args.run.check_only && mpi.is_master()) {
    std::cout << args.run.study_file.string() << ": ok, " << summary->total << " cases, fingerprint "
              << summary->fingerprint << std::endl;
    if (summary->invalid_frames > 0)
      std::cout << args.run.study_file.string() << ": " << summary->invalid_cases << " cases ("
                << summary->invalid_frames << " frames) lie outside the model's domain and will end as invalid_frame, "
                << "e.g. " << summary->first_invalid << std::endl;
  }
}

}  // namespace

void add_study_command(CLI::App& app) {
  auto args = std::make_shared<StudyArguments>();
  auto* cmd = app.add_subcommand("study", "Run a parametric study (several ranks: mpirun -n N pcrf study FILE)");
  cmd->add_option("FILE", args->run.study_file, "study file (TOML), see studies/README.md")->required();
  cmd->add_option("-o,--output", args->run.output, "result cube (default: <study stem>.h5 in the working directory)");
  auto* resume = cmd->add_flag("--resume", args->run.resume, "continue an existing cube of the same study");
  auto* overwrite = cmd->add_flag("--overwrite", args->run.overwrite, "replace an existing cube");
  resume->excludes(overwrite);
  cmd->add_flag("--check", args->run.check_only, "check the study (records, geometry) and print its size; compute nothing");
  args->run_flags = std::make_unique<SettingFlags<study::RunOptions>>(cmd, study::run_settings());
  cmd->callback([args] { run_study_command(*args); });
}

}  // namespace pcrf::cli
