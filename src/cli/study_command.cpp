// `pcrf study FILE`: runs a parametric study, on one rank or under mpirun.
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/study/study_parser.hpp"
#include "pcrf/study/study_run.hpp"

namespace pcrf::cli {
namespace {

/// Command-line values; negative numbers mean "not given" (the study file decides).
struct StudyArguments {
  study::StudyRunOptions run;
  double flush_interval_s = -1.0;
  double progress_interval_s = -1.0;
  int batch_size = -1;
};

void run_study_command(StudyArguments args) {
  if (args.flush_interval_s >= 0.0) {
    if (args.flush_interval_s == 0.0) throw UsageError("--flush-interval must be positive");
    args.run.flush_interval_s = args.flush_interval_s;
  }
  if (args.progress_interval_s >= 0.0) args.run.progress_interval_s = args.progress_interval_s;
  if (args.batch_size >= 0) args.run.batch_size = static_cast<std::size_t>(args.batch_size);

  parallel::MpiSession mpi;
  std::optional<study::StudySummary> summary;
  try {
    summary = study::run_study(args.run, mpi);
  } catch (const study::StudyError& e) {
    // Nothing has started. Report here, before MPI_Finalize, and not through UsageError in
    // main(): once another rank has exited with code 2, mpirun may end this one at any time.
    std::cerr << "pcrf: error: " << e.what() << std::endl;
    mpi.quiet_barrier();  // the other ranks wait for this line before they leave
    exit_code() = 2;
    return;
  } catch (const std::exception& e) {
    if (mpi.size() > 1) {  // other ranks are waiting for work that will never come
      std::cerr << "pcrf: error: " << e.what() << std::endl;
      mpi.abort(1);
    }
    throw;
  }
  if (!summary) exit_code() = 2;  // rank ≠ 0 of a study that cannot run: rank 0 reported it
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
  cmd->add_option("--flush-interval", args->flush_interval_s, "seconds between cube flushes (default: [run] flush_interval_s, 30)");
  cmd->add_option("--progress-interval", args->progress_interval_s, "seconds between progress lines, 0: none (default 5)");
  cmd->add_option("--batch-size", args->batch_size, "cases per hand-out, 0: guided (default)");
  cmd->callback([args] { run_study_command(*args); });
}

}  // namespace pcrf::cli
