// Running a study across MPI ranks (see study_run.hpp). Rank 0 checks the study, opens the
// cube and schedules; every rank (rank 0 in its worker thread) computes cases.
#include "pcrf/run/study_run.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <exception>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <span>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/io/output_file.hpp"
#include "pcrf/io/run_lock.hpp"
#include "pcrf/parallel/scheduler.hpp"
#include "pcrf/parallel/work_queue.hpp"
#include "pcrf/solver/case_group.hpp"
#include "pcrf/run/case_runner.hpp"
#include "pcrf/run/cost_estimate.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/run/ida_work.hpp"
#include "pcrf/run/progress.hpp"
#include "pcrf/study/study_check.hpp"
#include "pcrf/run/study_cube.hpp"
#include "pcrf/study/study_parser.hpp"
#include "pcrf/study/study_size.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;
namespace {

/// The case space, once the study is known to fit (a plan is drawn whole when made).
std::unique_ptr<CaseSpace> sized_space(const Study& study) {
  check_study_size(study);
  return std::make_unique<CaseSpace>(study);
}

/// What every rank needs to compute cases.
struct Prepared {
  Study study;
  std::unique_ptr<CaseSpace> space;
  std::unique_ptr<RecordCache> records;

  explicit Prepared(Study s)
      : study(std::move(s)),
        space(sized_space(study)),
        records(std::make_unique<RecordCache>(study.records)) {}
};

/// Rank 0's part of the preparation: the checks and the open cube.
struct MasterSetup {
  CheckedStudy checked;
  std::filesystem::path output;
  std::unique_ptr<io::RunLock> lock;  ///< one run per cube, for the whole run (outlives the writer)
  std::unique_ptr<cube::CubeWriter> writer;
};

void apply_overrides(const StudyRunOptions& options, RunOptions& run) {
  for (const auto& [setting, value] : options.run_overrides) setting->set(run, value);
}

/// An output must never be one of the study's inputs (the study file, its records, its
/// hazard curve), whatever --overwrite says; nor may a file the run writes beside it (its
/// lock, journal and fold's .partial).
void check_output_is_not_an_input(const std::filesystem::path& output, const StudyRunOptions& options, const Study& study) {
  using io::same_file;  // the one rule of every command's outputs (symbolic and hard links)
  const std::string cube = output.string();
  for (const std::filesystem::path& written : {output, io::RunLock::lock_path(output), cube::journal_path(output),
                                              std::filesystem::path(cube + ".partial")}) {
    const std::string as = written == output ? cube + ": {} names " : cube + ": {}'s " + written.string() + " is ";
    if (same_file(written, options.study_file))
      throw UserError(Where{}, as + "the study file itself; choose another output ({} does not apply to inputs)",
                      {"output", "overwrite"});
    for (const auto& r : study.records)
      for (const RecordFileSpec* file : r.files())
        if (same_file(written, file->path))
          throw UserError(Where{}, as + "the record file of \"" + r.name +
                                       "\"; choose another output ({} does not apply to inputs)", {"output", "overwrite"});
    if (const auto& sel = study.selection) {  // its library and targets
      if (same_file(written, sel->library_file))
        throw UserError(Where{}, as + "the record library " + sel->library +
                                     " of [selection]; choose another output ({} does not apply to inputs)", {"output", "overwrite"});
      for (const auto& stripe : sel->stripes)
        if (same_file(written, study.base_dir / stripe.target))
          throw UserError(Where{}, as + "the target " + stripe.target +
                                       " of [selection]; choose another output ({} does not apply to inputs)", {"output", "overwrite"});
    }
    if (study.hazard_stripes && same_file(written, study.hazard_stripes->file))
      throw UserError(Where{}, as + "the hazard curve " + study.hazard_stripes->hazard +
                                   " of [intensity]; choose another output ({} does not apply to inputs)", {"output", "overwrite"});
  }
}

/// A note for the user: to StudyRunOptions::notes when the caller collects them (pcrf.study
/// warns them as PcrfWarning), else on stderr as the command line prints it.
void say_note(const StudyRunOptions& options, const std::string& note) {
  if (options.notes != nullptr) options.notes->push_back(note);
  else std::cerr << "pcrf study: note: " << note << '\n';
}

MasterSetup prepare_master(const StudyRunOptions& options, const Prepared& p) {
  MasterSetup m;
  m.checked = check_study(p.study, *p.space, *p.records,
                          options.check_only ? FrameCheck::kEveryFrame : FrameCheck::kWhereNeeded);
  for (const auto& note : m.checked.notes) say_note(options, note);
  if (options.progress != nullptr)
    for (const auto& warning : m.checked.warnings) *options.progress << "pcrf study: warning: " << warning << '\n';
  if (options.check_only) return m;
  m.output = options.output.empty() ? default_output(options.study_file) : options.output;
  check_output_is_not_an_input(m.output, options, p.study);
  try {  // before anything looks at the cube: a second run, even --overwrite, leaves the first alone
    m.lock = std::make_unique<io::RunLock>(m.output);
  } catch (const io::OutputError& e) {
    throw UserError(e.what());
  }
  const std::string shard = options.shard_count > 1 ? std::to_string(options.shard_index + 1) + "/" +
                                                           std::to_string(options.shard_count) : "";
  if (options.resume && std::filesystem::exists(m.output)) {
    try {
      const std::string theirs = cube::CubeReader(m.output).layout().text_attribute(cube::kShardName);
      if (theirs != shard)
        throw UserError(Where{{}, m.output.string(), 0}, "is shard \"" + (theirs.empty() ? "none" : theirs) +
                                                             "\" of the study; this run is shard \"" +
                                                             (shard.empty() ? "none" : shard) + "\"");
    } catch (const cube::CubeError&) {  // not readable: CubeWriter says why
    }
  }
  if (std::filesystem::exists(m.output) && !options.resume && !options.overwrite)
    throw UserError(Where{}, m.output.string() + ": already exists; use {} to continue it or {} to replace it",
                    {"resume", "overwrite"});
  const auto mode = options.resume ? cube::OpenMode::kResume
                                   : (options.overwrite ? cube::OpenMode::kOverwrite : cube::OpenMode::kCreate);
  try {
    auto layout = make_cube_layout(p.study, *p.space, *p.records, m.checked.fingerprint);
    if (!shard.empty()) layout.attributes.push_back({cube::kShardName, shard});
    m.writer = std::make_unique<cube::CubeWriter>(m.output, std::move(layout), mode);
  } catch (const cube::CubeError& e) {
    throw UserError(e.what());
  }
  for (const auto& note : m.writer->resume_notes()) say_note(options, note);
  return m;
}

/// Time histories made in rank 0's worker thread, waiting for the master thread to store them.
class HistoryInbox {
 public:
  void push(cube::HistoryTable table) {
    std::lock_guard lock(mutex_);
    tables_.push_back(std::move(table));
  }
  std::vector<cube::HistoryTable> take() {
    std::lock_guard lock(mutex_);
    return std::exchange(tables_, {});
  }

 private:
  std::mutex mutex_;
  std::vector<cube::HistoryTable> tables_;
};

/// Frames whose cases of one excitation a worker is handed together, to solve in lockstep
/// lanes (CaseRunner::run of many cases): the hand-out order takes tiles of this many frames,
/// every excitation of a tile in turn; the master's blocks never mix two excitations; a
/// signal stops a worker between two such blocks.
constexpr std::int64_t kFramesTogether = 64;

/// True when the study's cases go to workers in blocks of one excitation (docs/batches.md).
bool in_lanes(const Study& study) { return study.run.lanes > 1 && lanes_take(study.solver) && !study.ida; }

/// `stop_signal`: a signal stops the workers between two cases, reporting the ones done.
parallel::ScheduleOptions schedule_options(const Study& study, const CaseRunner& runner, const std::atomic<int>* stop_signal) {
  parallel::ScheduleOptions options;
  options.row_width = runner.row_width();
  options.fixed_batch = study.run.batch_size;
  options.interrupt = stop_signal;
  if (in_lanes(study)) options.evaluate_together = kFramesTogether;
  return options;
}

/// Rank 0's receiving end: stores outcomes and histories in the cube, flushes it every
/// flush interval and reports progress. Runs in the master thread only.
class ResultSink {
 public:
  /// `before_flush` (optional) updates what the cube holds besides the cases (IDA summaries).
  ResultSink(cube::CubeWriter& writer, ProgressMeter& meter, HistoryInbox& inbox, double flush_interval_s,
             std::function<void()> before_flush = {})
      : writer_(writer), meter_(meter), inbox_(inbox), flush_interval_s_(flush_interval_s),
        before_flush_(std::move(before_flush)) {}

  void store(parallel::ResultBatch&& batch) {
    std::int64_t failed = 0;
    for (auto& outcome : batch) {
      const CaseStatus status = outcome_status(outcome);
      writer_.store(outcome.case_index, static_cast<std::int8_t>(status), std::move(outcome.row));
      if (!outcome.note.empty()) writer_.store_note(outcome.case_index, std::move(outcome.note));
      failed += is_failure(status) ? 1 : 0;
    }
    meter_.add(static_cast<std::int64_t>(batch.size()), failed);
    // Stopping on a signal: each batch that comes back goes to disk at once (the launcher's
    // SIGKILL may follow within a second).
    if (error_.empty() && stop_flushed_) {
      checkpoint();
      return;
    }
    // Rank 0's memory stays bounded whatever the rate: results held since the last
    // checkpoint never exceed kPendingLimitBytes.
    if (error_.empty() && writer_.pending_bytes() > kPendingLimitBytes) checkpoint();
  }

  void idle() {
    take_histories();
    // A stop signal: checkpoint at once, before the cases in flight come back. Under mpirun
    // the signal came from Open MPI, which SIGKILLs every rank about a second later
    // (odls_base_sigkill_timeout): what is computed must be on disk by then. close() adds
    // the cases that return in the time left.
    if (stop_signal_ != nullptr && stop_signal_->load() != 0 && !stop_flushed_) {
      stop_flushed_ = true;
      if (error_.empty()) checkpoint();
    }
    // A checkpoint appends to the cube's journal, and now and then folds it into a copy of
    // the cube (docs/checkpoint.md): the next one comes a flush interval after this one
    // ends, and never sooner than 9 × its duration, so checkpoints take at most a tenth of the run.
    const double period_s = std::max(flush_interval_s_, 9.0 * last_checkpoint_s_);
    const auto since = std::chrono::steady_clock::now() - last_flush_;
    if (error_.empty() && std::chrono::duration<double>(since).count() >= period_s) checkpoint();
    meter_.tick();
  }

  /// The run's lock on the cube: each checkpoint first checks it is still held.
  void guard_with(const io::RunLock* lock, std::string cube) {
    lock_ = lock;
    cube_ = std::move(cube);
  }

  /// The signal that stops the run (null: none): its arrival is checkpointed at once.
  void flush_on(const std::atomic<int>* stop_signal) { stop_signal_ = stop_signal; }

  /// Results held in memory between checkpoints, at most [bytes].
  static constexpr std::size_t kPendingLimitBytes = kPendingResultsBytes;

  void close() {
    take_histories();
    if (!error_.empty()) return;  // the last complete checkpoint stays as it is
    guard([&] {
      check_lock();
      if (before_flush_) before_flush_();
      writer_.close();
    });
  }

  /// The first write error (a full disk, an I/O error), naming the file and the reason.
  const std::string& error() const { return error_; }
  cube::CubeError::Cause error_cause() const { return error_cause_; }
  /// Called once when a write fails, to stop the hand-out of work.
  void on_error(std::function<void()> stop) { stop_ = std::move(stop); }

 private:
  void take_histories() {
    for (auto& table : inbox_.take()) writer_.store_history(std::move(table));
  }

  /// A lock file removed during the run no longer keeps another run off the cube: stop
  /// before writing into a cube that may no longer be this run's alone.
  void check_lock() const {
    // A cube gone with its folder (and the lock with it) is the writer's to report.
    if (lock_ != nullptr && !lock_->held() && std::filesystem::exists(cube_))
      throw cube::CubeError(cube_ + ": its lock " + io::RunLock::lock_path(cube_).string() +
                                " was removed during the run, so another run may write the cube",
                            cube::CubeError::Cause::kLostLock);
  }

  void checkpoint() {
    const auto start = std::chrono::steady_clock::now();
    guard([&] {
      check_lock();
      if (before_flush_) before_flush_();
      // Stopping (a kill may follow within a second): an append, never a fold, whose time
      // follows what changed; close() folds if there is time.
      if (stop_flushed_) writer_.append();
      else writer_.flush();
    });
    last_flush_ = std::chrono::steady_clock::now();
    last_checkpoint_s_ = std::chrono::duration<double>(last_flush_ - start).count();
  }

  /// Runs a write; a CubeError ends the run in order instead of tearing it down.
  template <class Write>
  void guard(Write write) {
    try {
      write();
    } catch (const cube::CubeError& e) {
      error_ = e.what();
      error_cause_ = e.cause();
      if (stop_) stop_();
    }
  }

  cube::CubeWriter& writer_;
  ProgressMeter& meter_;
  HistoryInbox& inbox_;
  double flush_interval_s_;
  std::function<void()> before_flush_;
  std::function<void()> stop_;
  const std::atomic<int>* stop_signal_ = nullptr;
  bool stop_flushed_ = false;
  const io::RunLock* lock_ = nullptr;
  std::string cube_;
  std::string error_;
  cube::CubeError::Cause error_cause_ = cube::CubeError::Cause::kOther;
  double last_checkpoint_s_ = 0.0;
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
};

/// Cases not done yet; the cases with a history stay on rank 0 (pinned).
/// The half-open range [first, last) of `total` items that shard `index` of `count` owns.
std::pair<std::int64_t, std::int64_t> shard_range(std::int64_t total, std::size_t index, std::size_t count) {
  const auto n = static_cast<std::int64_t>(count), k = static_cast<std::int64_t>(index);
  return {total * k / n, total * (k + 1) / n};
}

/// Cases a master hands out in one window (in storage order, so about four cube chunks of
/// 16 384 cases), so that the chunks being computed are few and the writer holds only those.
constexpr std::int64_t kWindowCases = 65536;

/// The shard's cases not done yet, window by window in hand-out order (CaseSpace::handout_index:
/// storage order, or a Saltelli design's base sample by base sample; never the whole list):
/// the chunks of a window finish together and the cube writer releases them at its next
/// checkpoint. Inside a window the cases of a frame come together (CaseSpace::frame_major),
/// so a worker prepares each frame once per window; in lanes, those of a tile of frames, an
/// excitation at a time, in blocks of one excitation. Cases with a history stay on rank 0.
parallel::WorkQueue pending_cases(const cube::CubeWriter& writer, const std::map<std::int64_t, const HistoryRequest*>& histories,
                                  const Study& study, const CaseSpace& space, const parallel::MpiSession& mpi,
                                  const StudyRunOptions& options) {
  const auto [first, last] = shard_range(space.size(), options.shard_index, options.shard_count);
  const auto& status = writer.status();
  auto pending = [&status](std::int64_t i) { return status[static_cast<std::size_t>(i)] == cube::kStatusNotRun; };
  std::vector<std::int64_t> pinned;
  std::int64_t shared_total = 0;
  for (std::int64_t k = first; k < last; ++k) {
    const std::int64_t i = space.handout_index(k);
    if (!pending(i)) continue;
    if (histories.count(i)) pinned.push_back(i);
    else ++shared_total;
  }
  // Positions in the hand-out order (storage order, or a Saltelli design's frame by frame).
  const bool lanes = in_lanes(study);
  auto next_window = [pending, &histories, &space, lanes, cursor = first, last = last]() mutable {
    std::vector<std::int64_t> window;
    while (window.empty() && cursor < last) {
      const std::int64_t end = std::min(last, cursor + kWindowCases);
      for (std::int64_t k = cursor; k < end; ++k)
        if (const std::int64_t i = space.handout_index(k); pending(i) && !histories.count(i)) window.push_back(i);
      cursor = end;
    }
    return space.frame_major(std::move(window), lanes ? kFramesTogether : 1);
  };
  parallel::WorkQueue queue(std::move(next_window), shared_total, std::move(pinned), parallel::worker_count(mpi.comm()),
                            study.run.batch_size);
  if (lanes) queue.group_by([&space](std::int64_t i) { return space.excitation_of(i); });
  return queue;
}

/// A work source that runs dry when a stop signal arrives or the cube cannot be written: the
/// master then tells every worker to stop and collects the cases in flight, and the run ends
/// in order (no rank is left waiting).
class StopOnSignal final : public parallel::WorkSource {
 public:
  StopOnSignal(parallel::WorkSource& work, const std::atomic<int>* signal) : work_(work), signal_(signal) {}
  parallel::WorkBatch take(bool in_process) override { return stopping() ? parallel::WorkBatch{} : work_.take(in_process); }
  void completed(const parallel::CaseOutcome& o) override { work_.completed(o); }
  bool exhausted() const override { return stopping() || work_.exhausted(); }
  bool stopped() const { return signal_ != nullptr && signal_->load() != 0; }
  void fail() { failed_ = true; }

 private:
  bool stopping() const { return stopped() || failed_; }
  parallel::WorkSource& work_;
  const std::atomic<int>* signal_;
  bool failed_ = false;  // master thread only
};

StudySummary run_master_rank(const Prepared& p, MasterSetup& m, const parallel::MpiSession& mpi,
                             std::ostream& progress, const StudyRunOptions& options) {
  const std::atomic<int>* stop_signal = options.stop_signal;
  CaseRunner runner(p.study, *p.space, *p.records);
  std::map<std::int64_t, const HistoryRequest*> history_requests;
  for (std::size_t h = 0; h < p.study.histories.size(); ++h)
    history_requests[m.checked.history_cases[h]] = &p.study.histories[h];

  StudySummary summary{p.space->size(), m.writer->done_count(), 0, 0, m.output, m.checked.fingerprint,
                       m.checked.invalid_cases, m.checked.invalid_frames, m.checked.first_invalid, 0, {}, {}, {}, {}, m.checked.warnings};
  ProgressMeter meter(summary.total, summary.already_done, p.study.run.progress_interval_s, progress);
  HistoryInbox inbox;
  // The cases come from the IDA's search, or from the list of cases not done yet.
  std::unique_ptr<parallel::WorkSource> work;
  std::function<void()> before_flush;
  if (p.study.ida) {
    auto ida = make_ida_curves(p.study, *p.space, *m.writer, parallel::worker_count(mpi.comm()));
    const auto [first, last] = shard_range(p.space->curves(), options.shard_index, options.shard_count);
    for (std::int64_t c = 0; c < p.space->curves(); ++c)
      if (c < first || c >= last) ida->skip(static_cast<std::size_t>(c));
    before_flush = [&study = p.study, curves = ida.get(), writer = m.writer.get()] {
      store_ida_summaries(study, *curves, *writer);
    };
    work = std::move(ida);
  } else {
    work = std::make_unique<parallel::WorkQueue>(pending_cases(*m.writer, history_requests, p.study, *p.space, mpi, options));
  }
  ResultSink sink(*m.writer, meter, inbox, p.study.run.flush_interval_s, before_flush);
  sink.flush_on(stop_signal);
  sink.guard_with(m.lock.get(), m.output.string());

  // Runs in rank 0's worker thread; the only place where histories are recorded.
  auto evaluate = [&](std::span<const parallel::WorkItem> items) {
    const auto history = [&](const parallel::WorkItem& item) { return history_requests.count(item.case_index) > 0; };
    if (std::none_of(items.begin(), items.end(), history)) return runner.run(items);
    parallel::ResultBatch outcomes;
    for (const parallel::WorkItem& item : items) {
      const auto request = history_requests.find(item.case_index);
      if (request == history_requests.end()) {
        outcomes.push_back(runner.run(item));
        continue;
      }
      std::vector<HistorySample> samples;
      outcomes.push_back(
          runner.run(item, [&samples](const HistorySample& s) { samples.push_back(s); }, request->second->dt_s));
      inbox.push(make_history_table(request->second->label, item.case_index, p.study, *p.space, samples));
    }
    return outcomes;
  };
  StopOnSignal stoppable(*work, stop_signal);
  sink.on_error([&stoppable] { stoppable.fail(); });
  parallel::run_master(mpi.comm(), stoppable, schedule_options(p.study, runner, stop_signal),
                       evaluate, [&sink](parallel::ResultBatch&& batch) { sink.store(std::move(batch)); },
                       [&sink, &options] {
                         if (options.poll) options.poll();
                         sink.idle();
                       });
  sink.close();
  meter.finish(m.output.string());
  summary.computed = meter.computed();
  summary.failed = meter.failed();
  if (stoppable.stopped()) summary.stopped_by = stop_signal->load();
  summary.error = sink.error();
  summary.error_cause = sink.error_cause();
  summary.verdict_notes = schema::verdict_notes(
      m.writer->status(), p.study.ida ? std::optional<std::string>(p.study.ida->collapse) : std::nullopt,
      "neither safe nor collapsed", p.study.physics.tail_s);
  return summary;
}

void run_worker_rank(const Prepared& p, const parallel::MpiSession& mpi, const std::atomic<int>* stop_signal) {
  CaseRunner runner(p.study, *p.space, *p.records);
  parallel::run_worker(mpi.comm(), schedule_options(p.study, runner, stop_signal),
                       [&runner](std::span<const parallel::WorkItem> items) { return runner.run(items); });
}

/// Workers parse the study text rank 0 checked (same base folder for relative records).
std::unique_ptr<Prepared> receive_study(const parallel::MpiSession& mpi, const Prepared* master) {
  const std::string text = mpi.broadcast(master ? master->study.text : std::string());
  const std::string file = mpi.broadcast(master ? master->study.file : std::string());
  const std::string base = mpi.broadcast(master ? master->study.base_dir.string() : std::string());
  if (master != nullptr) return nullptr;
  try {
    return std::make_unique<Prepared>(parse_study(text, file, base));
  } catch (const std::exception& e) {  // e.g. records not visible from this node
    std::cerr << "pcrf: error on rank " << mpi.rank() << ": " << e.what() << std::endl;
    mpi.abort(2);
  }
}

}  // namespace

std::string stop_report(const StudySummary& summary) {
  const int number = summary.stopped_by;
  const std::string name = number == SIGTERM ? "SIGTERM" : number == SIGINT ? "SIGINT" : "a signal";
  return "stopped by " + name + ": " + std::to_string(summary.already_done + summary.computed) + " of " +
         std::to_string(summary.total) + " cases saved in " + summary.output.string();
}

std::filesystem::path default_output(const std::filesystem::path& study_file) {
  return std::filesystem::current_path() / (study_file.stem().string() + ".h5");
}

std::optional<StudySummary> run_study(const StudyRunOptions& options, const parallel::MpiSession& mpi) {
  std::unique_ptr<Prepared> prepared;
  MasterSetup setup;
  std::exception_ptr error;  // a UserError, as found (its Where for the front end to spell)
  if (mpi.is_master()) {
    try {
      prepared = std::make_unique<Prepared>(options.study ? *options.study : load_study(options.study_file));
      apply_overrides(options, prepared->study.run);
      setup = prepare_master(options, *prepared);
    } catch (const UserError&) {
      error = std::current_exception();
    }
  }
  if (mpi.broadcast(error ? 0 : 1) == 0) {
    if (mpi.is_master()) std::rethrow_exception(error);  // the caller reports it, then joins the barrier
    mpi.quiet_barrier();
    return std::nullopt;
  }
  if (options.check_only) {
    if (!mpi.is_master()) return StudySummary{};
    const auto& c = setup.checked;
    StudySummary summary{prepared->space->size(), 0, 0, 0, {}, c.fingerprint, c.invalid_cases, c.invalid_frames,
                         c.first_invalid, 0, {}, {}, {}, {}, c.warnings};
    summary.cost_estimate = estimate_cost(prepared->study, *prepared->space, *prepared->records, 16, 2.0).text();
    return summary;
  }
  if (auto received = receive_study(mpi, prepared.get())) prepared = std::move(received);

  std::optional<StudySummary> summary;
  static std::ostream nowhere(nullptr);  // a stream without a buffer discards what it is given
  if (mpi.is_master())
    summary = run_master_rank(*prepared, setup, mpi, options.progress ? *options.progress : nowhere, options);
  else
    run_worker_rank(*prepared, mpi, options.stop_signal);
  mpi.quiet_barrier();
  return summary ? summary : StudySummary{};
}

}  // namespace pcrf::run
