// `pcrf study FILE`: runs a parametric study, on one rank or under mpirun.
#include <CLI/CLI.hpp>

#include <charconv>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <atomic>
#include <memory>
#include <string_view>
#include <utility>

#include "cli/commands.hpp"
#include "cli/setting_flags.hpp"
#include "pcrf/io/file_kind.hpp"
#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/printable.hpp"
#include "pcrf/study/study_parser.hpp"
#include "pcrf/run/study_run.hpp"

namespace pcrf::cli {
namespace {

/// Command-line values; the [run] flags override the study file's table.
struct StudyArguments {
  run::StudyRunOptions run;
  std::string shard;  ///< "K/N"
  CLI::Option* shard_flag = nullptr;
  std::unique_ptr<SettingFlags<study::RunOptions>> run_flags;
};

/// The signal that asked the run to stop (SIGTERM from a scheduler, SIGINT from Ctrl-C or
/// forwarded by mpirun); 0 while none has.
std::atomic<int> stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

/// The first signal asks the run to stop in order; a second ends the process at once, by
/// the signal's default action, once the temporaries beside the cube are removed.
extern "C" void on_stop_signal(int number) {
  if (stop_signal.load() == 0) {
    stop_signal.store(number);
    return;
  }
  io::remove_temporaries();
  ::signal(number, SIG_DFL);
  ::raise(number);
}

/// Shards a study may be split into, at most: more than any job array needs, few enough
/// that a typo (a pasted size, a negative number read as a huge one) is caught.
constexpr std::size_t kMaxShards = 1000000;

/// "K/N" with digits only and 1 ≤ K ≤ N ≤ kMaxShards. \throws UserError otherwise.
std::pair<std::size_t, std::size_t> parse_shard(const std::string& text) {
  auto fail = [&text]() -> UserError {
    return UserError("shard", "expected K/N with 1 ≤ K ≤ N ≤ " + std::to_string(kMaxShards) + ", e.g. 3/8, got '" + text + "'");
  };
  const auto slash = text.find('/');
  if (slash == std::string::npos) throw fail();
  auto number = [&](std::string_view digits) {
    std::size_t value = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size()) throw fail();
    return value;
  };
  const std::string_view all(text);
  const std::size_t k = number(all.substr(0, slash)), n = number(all.substr(slash + 1));
  if (k < 1 || k > n || n > kMaxShards) throw fail();
  return {k, n};
}

/// Every rank catches SIGTERM and SIGINT: rank 0 stops handing out work and flushes, the
/// others finish the batch they hold and are then told to stop. A second signal ends the
/// process (its default action), leaving no temporary.
void catch_stop_signals() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  action.sa_flags = 0;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGTERM, &action, nullptr);
  ::sigaction(SIGINT, &action, nullptr);
}

/// What to do after a write error, by its cause: only a full disk is cured by space.
std::string advice(cube::CubeError::Cause cause) {
  using Cause = cube::CubeError::Cause;
  switch (cause) {
    case Cause::kNoSpace: return "the cube keeps its last complete checkpoint: free space, then --resume";
    case Cause::kGone: return "the results computed are lost with it: run the study again";
    case Cause::kReplaced: return "this run's results since its last checkpoint are lost: run it again into another -o";
    case Cause::kLostLock:
      return "the cube keeps its last complete checkpoint; make sure no other run writes it, then --resume";
    case Cause::kOther: break;
  }
  return "the cube keeps its last complete checkpoint: once the cause above is fixed, --resume continues it";
}

/// `word` as a POSIX shell reads it back: as it is when it holds only safe characters, else
/// in single quotes.
std::string shell_word(const std::string& word) {
  const bool safe = !word.empty() && word.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                                           "0123456789_-./:=+,@%") == std::string::npos;
  if (safe) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// The whole command that continues a stopped run: under mpirun with as many ranks, the same
/// study, cube, shard and [run] flags, and --resume.
std::string resume_command(const StudyArguments& args, const run::StudySummary& summary, int ranks) {
  std::string command = ranks > 1 ? "mpirun -n " + std::to_string(ranks) + " " : "";
  command += "pcrf study " + shell_word(args.run.study_file.string()) + " -o " + shell_word(summary.output.string()) + " --resume";
  if (args.shard_flag->count() > 0) command += " --shard " + shell_word(args.shard);
  for (const auto& word : args.run_flags->given_words()) command += " " + shell_word(word);
  return command;
}

void run_study_command(StudyArguments& args) {
  args.run.run_overrides = args.run_flags->given();
  if (args.shard_flag->count() > 0) {
    const auto [k, n] = parse_shard(args.shard);
    args.run.shard_index = k - 1;
    args.run.shard_count = n;
  }
  args.run.progress = &std::cerr;
  args.run.stop_signal = &stop_signal;

  if (const auto problem = parallel::MpiSession::startup_problem(); !problem.empty()) throw UserError(problem);
  parallel::MpiSession mpi;
  catch_stop_signals();
  std::optional<run::StudySummary> summary;
  try {
    summary = run::run_study(args.run, mpi);
  } catch (const UserError& e) {
    // Nothing has started. Report here, before MPI_Finalize, and not through UserError in
    // main(): once another rank has exited with code 2, mpirun may end this one at any time.
    std::cerr << error_line(e) << std::endl;
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
  if (summary && mpi.is_master() && summary->stopped_by != 0) {
    std::cerr << "pcrf study: " << run::stop_report(*summary) << "; continue with: "
              << resume_command(args, *summary, mpi.size()) << std::endl;
  }
  if (summary && mpi.is_master())
    for (const auto& note : summary->verdict_notes) std::cerr << "pcrf study: note: " << printable(note) << std::endl;
  if (summary && summary->stopped_by != 0) exit_code() = 128 + summary->stopped_by;
  if (summary && !summary->error.empty()) {
    std::cerr << error_line("write", summary->error + "; " + advice(summary->error_cause)) << std::endl;
    exit_code() = 2;
  }
  if (!mpi.is_master() && stop_signal.load() != 0) exit_code() = 128 + stop_signal.load();
  if (summary && args.run.check_only && mpi.is_master()) {
    std::cout << args.run.study_file.string() << ": ok, " << summary->total << " cases, fingerprint "
              << summary->fingerprint << std::endl;
    if (summary->invalid_frames > 0)
      std::cout << args.run.study_file.string() << ": " << summary->invalid_cases << " cases ("
                << summary->invalid_frames << " frames) lie outside the model's domain and will end as invalid_frame, "
                << "e.g. " << summary->first_invalid << std::endl;
    std::cout << args.run.study_file.string() << ": " << summary->cost_estimate << std::endl;
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
  cmd->add_flag("--check", args->run.check_only,
                "check the study (records, geometry), print its size and its cost estimated from a timed sample "
                "of its cases; write nothing");
  args->run_flags = std::make_unique<SettingFlags<study::RunOptions>>(cmd, study::run_settings());
  args->shard_flag = cmd->add_option("--shard", args->shard,
                  "compute shard K of N (K/N): a deterministic 1/N of the cases; join the parts with pcrf cube merge");
  cmd->callback([args] { run_study_command(*args); });
}

}  // namespace pcrf::cli
