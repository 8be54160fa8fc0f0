/// \file study_run.hpp
/// \brief Runs a study on every MPI rank: checks it, opens the cube (rank 0), schedules the
/// cases, stores results as they come back and flushes periodically.
#pragma once

#include <cstddef>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/solver/case_group.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;

struct StudyRunOptions {
  std::filesystem::path study_file;
  /// The study itself when it comes from no file (a Python dict, parsed by parse_study_table
  /// with record paths relative to the working directory); `study_file` then only names it.
  /// None: read `study_file`.
  std::optional<Study> study;
  std::filesystem::path output;   ///< empty: "<study file stem>.h5" in the working directory
  bool resume = false;            ///< continue an existing cube of the same study
  bool overwrite = false;         ///< replace an existing cube
  bool check_only = false;        ///< validate, print the case count, write nothing
  /// Where rank 0 writes progress lines and the closing line (the CLI: stderr); null: nowhere.
  std::ostream* progress = nullptr;
  /// Where rank 0 puts the study's notes (a record's components padded, …) for a front end
  /// that says them its own way (Python warns them); null: stderr, as "pcrf study: note: …".
  std::vector<std::string>* notes = nullptr;
  /// Compute only shard `shard_index` (0-based) of `shard_count`: a contiguous 1/N of the
  /// cases in the order they are handed out (frames together), or of the IDA's curves.
  std::size_t shard_index = 0;
  std::size_t shard_count = 1;
  /// Set (to the signal's number) when the run should stop: rank 0 hands out no more work,
  /// collects what is in flight, flushes and returns. Null: never.
  const std::atomic<int>* stop_signal = nullptr;
  /// Called on rank 0's calling thread between the scheduler's messages (at least every
  /// ScheduleOptions::poll_interval_s) while the cases run: a front end whose signals arrive
  /// elsewhere than in a handler of its own (the Python module: the interpreter's SIGINT)
  /// looks there and sets `stop_signal`. Empty: nothing to look at.
  std::function<void()> poll;
  /// [run] values that override the study file's (already checked against run_settings()).
  std::vector<std::pair<const Setting<RunOptions>*, SettingValue>> run_overrides;
  /// The GPU backend of a run with [run] device = "gpu" (nullptr and why where there is
  /// none); empty: gpu_group. A test gives the host build of the case kernel, to run the
  /// GPU's path (its hand-out, its groups, its cube) where no device is.
  std::function<std::unique_ptr<CaseGroupSolver>(std::string& why_not)> gpu_backend;
};

/// What rank 0 reports when the study is done.
struct StudySummary {
  std::int64_t total = 0;
  std::int64_t already_done = 0;
  std::int64_t computed = 0;
  std::int64_t failed = 0;
  std::filesystem::path output;
  std::string fingerprint;  ///< the study's fingerprint (also what --check reports)
  /// Cases whose frame the model cannot represent, their frames, one of them and why: counted
  /// where every frame was built up front (--check, a displaced start; study_check.hpp,
  /// FrameCheck), else 0 (a run's cube gives each such case the status invalid_frame).
  std::int64_t invalid_cases = 0;
  std::int64_t invalid_frames = 0;
  std::string first_invalid;
  int stopped_by = 0;              ///< the signal that stopped the run early; 0: it ran to the end
  /// A write error that ended the run early (the cube keeps its last complete checkpoint).
  std::string error;
  /// What a user can do about `error` (free space, or the cube was removed or replaced).
  cube::CubeError::Cause error_cause = cube::CubeError::Cause::kOther;
  /// Lines for the end of the run about the cube's verdicts: cases unresolved (the frame
  /// still rocking when its tail ended), and collapse statuses that occurred although the
  /// study's [ida] collapse leaves them out.
  std::vector<std::string> verdict_notes;
  /// --check: what the run will cost, measured on a sample of its cases (CostEstimate::text).
  std::string cost_estimate;
  /// The study's warnings (CheckedStudy::warnings), for a front end that did not print them.
  std::vector<std::string> warnings;
};

/// "stopped by SIGINT: 120 of 324 cases saved in demo.h5": what a run stopped by a signal
/// (summary.stopped_by) leaves, for the front end to add how it resumes.
std::string stop_report(const StudySummary& summary);

/// Default output of a study file.
std::filesystem::path default_output(const std::filesystem::path& study_file);

/// Runs on every rank. A study that cannot run (bad file, unreadable record, output exists,
/// other study's cube) throws UserError on rank 0 before any work and before the output is
/// created; the other ranks then wait in MpiSession::quiet_barrier() and return std::nullopt
/// (the caller exits with code 2). Rank 0's caller reports the error, then joins the barrier.
/// Errors after work has started propagate on rank 0 (the caller must abort MPI).
std::optional<StudySummary> run_study(const StudyRunOptions& options, const parallel::MpiSession& mpi);

}  // namespace pcrf::run
