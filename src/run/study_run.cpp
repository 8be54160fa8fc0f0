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
#include <sstream>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "pcrf/io/output_file.hpp"
#include "pcrf/io/run_lock.hpp"
#include "pcrf/parallel/scheduler.hpp"
#include "pcrf/parallel/work_queue.hpp"
#include "pcrf/solver/case_group.hpp"
#include "pcrf/run/case_runner.hpp"
#include "pcrf/run/cost_estimate.hpp"
#include "pcrf/run/cube_creation.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/run/ida_work.hpp"
#include "pcrf/run/progress.hpp"
#include "pcrf/run/run_device.hpp"
#include "pcrf/study/study_check.hpp"
#include "pcrf/run/study_cube.hpp"
#include "pcrf/run/unit_order.hpp"
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
  /// What solves the cases of one excitation: the study's [run] device (run_device.hpp).
  std::shared_ptr<const CaseGroupSolver> group;

  explicit Prepared(Study s)
      : study(std::move(s)),
        space(sized_space(study)),
        records(std::make_unique<RecordCache>(study.records)) {}
};

/// Rank 0's part of the preparation: the checks and the lock (prepare_master), then the open
/// cube (create_cube, with every rank).
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
/// lock, journal, fold's .partial and the ranks' parts there).
void check_output_is_not_an_input(const std::filesystem::path& output, const StudyRunOptions& options, const Study& study) {
  using io::same_file;  // the one rule of every command's outputs (symbolic and hard links)
  const std::string cube = output.string();
  std::vector<std::filesystem::path> beside{output, io::RunLock::lock_path(output), cube::journal_path(output),
                                            std::filesystem::path(cube + ".partial")};
  for (auto& part : cube::part_files(output)) beside.push_back(std::move(part));  // a part not there is made exclusively
  for (const std::filesystem::path& written : beside) {
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

/// A worker rank's note (it has no StudyRunOptions::notes): a line on stderr, which pcrf.study
/// under mpirun warns as a PcrfWarning.
void say_rank_note(int rank, const std::string& note) {
  std::cerr << "pcrf study: note: rank " << rank << ": " << note << '\n';
}

/// A worker's failure before the run (its study, its share of the cube's creation): said on
/// its stderr, and every rank ends at once (exit code 2), as MPI_Abort ends them.
[[noreturn]] void end_every_rank(const parallel::MpiSession& mpi, const std::exception& e) {
  std::cerr << "pcrf: error on rank " << mpi.rank() << ": " << e.what() << std::endl;
  mpi.abort(2);
}

/// The cube's shard attribute ("2/8"); empty when unsharded.
std::string shard_text(const StudyRunOptions& options) {
  return options.shard_count > 1 ? std::to_string(options.shard_index + 1) + "/" + std::to_string(options.shard_count) : "";
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
  const std::string shard = shard_text(options);
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
  return m;
}

/// Rank 0's cube: a new one (its coordinates sealed by `coordinates`, or here when null) or
/// the one --resume continues. The lock and every check of prepare_master come first.
void open_cube(const StudyRunOptions& options, const Prepared& p, MasterSetup& m, cube::CoordinateSource* coordinates) {
  const std::string shard = shard_text(options);
  const auto mode = options.resume ? cube::OpenMode::kResume
                                   : (options.overwrite ? cube::OpenMode::kOverwrite : cube::OpenMode::kCreate);
  try {
    auto layout = make_cube_layout(p.study, *p.space, *p.records, m.checked.fingerprint);
    if (!shard.empty()) layout.attributes.push_back({cube::kShardName, shard});
    m.writer = std::make_unique<cube::CubeWriter>(m.output, std::move(layout), mode, coordinates);
  } catch (const cube::CubeError& e) {
    throw UserError(e.what());
  }
  for (const auto& note : m.writer->resume_notes()) say_note(options, note);
}

/// The cube made by every rank together (cube_creation.hpp), once every rank has the study:
/// rank 0 writes it, the workers seal its coordinates. True when it is made; false on a worker
/// when rank 0 failed, which then rethrows its error (a UserError: every rank ends in order,
/// as after a failed check). A worker that fails here ends the run, as receive_study does.
/// Never inlined: its own frame in a profile, where bench/master/rank_costs.py counts it in the set-up.
[[gnu::noinline]] bool create_cube(const StudyRunOptions& options, const Prepared& p, MasterSetup& m,
                                   const parallel::MpiSession& mpi) {
  const std::string fingerprint = mpi.broadcast(mpi.is_master() ? m.checked.fingerprint : std::string());
  if (mpi.is_master()) {
    if (mpi.size() == 1) {  // no other rank: rank 0 seals the pieces itself
      open_cube(options, p, m, nullptr);
      return true;
    }
    WorkerCoordinates workers(mpi);
    try {
      open_cube(options, p, m, &workers);
    } catch (...) {
      workers.finish(false);
      throw;
    }
    workers.finish(true);
    return true;
  }
  try {
    return seal_coordinates_for_rank0(mpi, [&] { return make_cube_layout(p.study, *p.space, *p.records, fingerprint); });
  } catch (const std::exception& e) {
    end_every_rank(mpi, e);
  }
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

/// True when the study's cases go to workers in blocks of one excitation (docs/batches.md):
/// for the CPU lanes, or for a GPU (run_device.hpp: kGpuGroupCases a block).
bool in_lanes(const Study& study) {
  return !study.ida && (on_gpu(study) || (study.run.lanes > 1 && lanes_take(study.solver)));
}

/// Frames of a tile whose cases go out an excitation at a time (CaseSpace::frame_major).
std::int64_t frames_together(const Study& study) { return on_gpu(study) ? kGpuWindowCases : kFramesTogether; }

/// Cases of a chunk whose rows metric_major copies together, when consecutive: a metric's
/// values of them are then one contiguous store (2.3 instructions a value, against 6 one case
/// at a time, callgrind).
constexpr std::size_t kRowsTogether = 8;

/// The rows of `outcomes` (cases of the chunk from case `first`, each once, rows checked) into
/// `values` at [metric * count + k], k the case's place in the chunk.
void metric_major(std::span<const parallel::CaseOutcome> outcomes, std::int64_t first, std::size_t count,
                  std::vector<double>& values) {
  const std::size_t metrics = count == 0 ? 0 : values.size() / count;
  std::size_t i = 0;
  while (i < outcomes.size()) {
    const auto at = static_cast<std::size_t>(outcomes[i].case_index - first);
    bool together = i + kRowsTogether <= outcomes.size();
    for (std::size_t j = 1; together && j < kRowsTogether; ++j)
      together = outcomes[i + j].case_index == outcomes[i].case_index + static_cast<std::int64_t>(j);
    if (!together) {
      const double* row = outcomes[i].row.data();
      for (std::size_t m = 0; m < metrics; ++m) values[m * count + at] = row[m];
      ++i;
      continue;
    }
    const double* rows[kRowsTogether];
    for (std::size_t j = 0; j < kRowsTogether; ++j) rows[j] = outcomes[i + j].row.data();
    double* to = values.data() + at;
    for (std::size_t m = 0; m < metrics; ++m, to += count)
      for (std::size_t j = 0; j < kRowsTogether; ++j) to[j] = rows[j][m];
    i += kRowsTogether;
  }
}

/// A worker's side of the cube (issue 38: no rank handles every result): a chunk handed out
/// whole comes back from the worker that computed it as the cube stores it, every variable
/// shuffled and deflated (cube::seal_chunk); the writing rank copies its bytes.
class ChunkSealer {
 public:
  /// `gaps`: a case of the chunk without an outcome is sealed not run (status not_run, every
  /// metric NaN: the cube's fill), as an IDA curve's points past its last run are.
  ChunkSealer(cube::ChunkGrid grid, std::size_t metrics, bool gaps = false)
      : grid_(std::move(grid)), metrics_(metrics), gaps_(gaps) {}

  /// The unit's chunks of the coordinates the cube's writer takes from the units
  /// (CubeWriter::unit_coordinates, rank 0's list) are sealed with it (issue 38: written during
  /// the run, not at the creation): each from this rank's plan, by its batch path
  /// (Coordinate::numbers_into, the values case_at gives), found by its name; one this rank's
  /// plan does not have is left to rank 0's writer.
  void carry(const std::vector<cube::UnitCoordinate>& carried, const CaseSpace& space) {
    auto own = space.plan().coordinates();
    for (const auto& u : carried)
      for (auto& c : own)
        if (c.name == u.name && c.written_live() && u.dimension < grid_.shape().size() &&
            c.size() == grid_.shape()[u.dimension]) {
          carried_.push_back({u, c});
          break;
        }
  }

  /// nullopt (the cases then go back one by one) unless `outcomes` are every case of the chunk
  /// once (with gaps: cases of the chunk, each at most once).
  /// Never inlined: its own frame in a profile, where bench/master/rank_costs.py counts a worker's sealing.
  [[gnu::noinline]] std::optional<std::vector<char>> operator()(std::int64_t unit,
                                                                std::span<const parallel::CaseOutcome> outcomes) const {
    if (unit < 0 || static_cast<std::size_t>(unit) >= grid_.chunk_count()) return std::nullopt;
    const auto chunk = static_cast<std::size_t>(unit);
    const auto r = grid_.range(chunk);
    const auto count = static_cast<std::size_t>(r.count);
    if (gaps_ ? outcomes.size() > count : outcomes.size() != count) return std::nullopt;
    // This thread's buffers, kept from unit to unit: without gaps every value and status is
    // written below (each case of the chunk once), so none is filled first (a fill of the
    // values was 136 instructions a non-lifting case, callgrind's count of memset's bytes).
    thread_local std::vector<std::int8_t> status;
    thread_local std::vector<char> seen;
    thread_local std::vector<double> values;
    status.resize(count);
    seen.assign(count, 0);
    values.resize(metrics_ * count);
    if (gaps_) {
      std::fill(status.begin(), status.end(), cube::kStatusNotRun);
      std::fill(values.begin(), values.end(), std::nan(""));
    }
    std::vector<std::pair<std::int64_t, std::string>> notes;
    for (const parallel::CaseOutcome& outcome : outcomes) {
      const std::int64_t k = outcome.case_index - r.first;
      if (k < 0 || k >= r.count || seen[static_cast<std::size_t>(k)] || outcome.row.size() != metrics_) return std::nullopt;
      const auto at = static_cast<std::size_t>(k);
      seen[at] = 1;
      status[at] = static_cast<std::int8_t>(outcome_status(outcome));
      if (!outcome.note.empty()) notes.emplace_back(outcome.case_index, outcome.note);
    }
    metric_major(outcomes, r.first, count, values);
    // The unit's coordinate pieces' values, each in a buffer of this thread's, kept (a piece's
    // values computed in one pass), then every stream sealed straight into the unit's bytes.
    thread_local std::vector<std::vector<double>> own;
    if (own.size() < carried_.size()) own.resize(carried_.size());
    std::vector<cube::PieceValues> pieces;
    pieces.reserve(carried_.size());
    for (std::size_t k = 0; k < carried_.size(); ++k) {
      const auto& [u, c] = carried_[k];
      const auto piece = cube::unit_piece(grid_, chunk, u);
      if (!piece) continue;
      const std::size_t first = *piece * u.chunk_values, values_in = std::min(u.chunk_values, c.size() - first);
      own[k].resize(u.chunk_values);  // the piece's values, then room to pad them in place
      const std::span<double> room(own[k]);
      c.numbers_into(first, room.first(values_in));
      pieces.push_back({u.coordinate, *piece, room.first(values_in), u.chunk_values, room});
    }
    return cube::sealed_bytes(grid_, chunk, metrics_, status, values, notes, pieces);
  }

 private:
  cube::ChunkGrid grid_;
  std::size_t metrics_;
  bool gaps_;
  struct Carried {
    cube::UnitCoordinate unit;
    cube::Coordinate values;  ///< this rank's plan's, computed from the case number
  };
  std::vector<Carried> carried_;
};

/// What rank 0 tells workers about the coordinates its cube takes from the units
/// (CubeWriter::unit_coordinates): one line each, "coordinate dimension chunk_values name".
std::string unit_coordinates_text(const cube::CubeWriter& writer) {
  std::string text;
  for (const auto& u : writer.unit_coordinates())
    text += std::to_string(u.coordinate) + " " + std::to_string(u.dimension) + " " + std::to_string(u.chunk_values) + " " +
            u.name + "\n";
  return text;
}

/// Inverse of unit_coordinates_text.
std::vector<cube::UnitCoordinate> parse_unit_coordinates(const std::string& text) {
  std::vector<cube::UnitCoordinate> carried;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream in(line);
    cube::UnitCoordinate u;
    if (in >> u.coordinate >> u.dimension >> u.chunk_values >> u.name) carried.push_back(std::move(u));
  }
  return carried;
}

/// A rank's own part of the cube (issue 38; cube_part.hpp): each unit its worker sealed (a
/// worker rank's, or rank 0's worker thread's at two ranks or more: keep_rank0_part) is
/// appended to `<cube>.part-<rank>` and synced before the unit is reported, so that rank 0
/// hears only its number and counts. The part is made at the first unit. If it cannot be (a
/// file already there, a folder this node does not see) or a write fails, the rank says so
/// once and its units travel to rank 0 as before (rank 0 journals them).
class PartKeeper {
 public:
  PartKeeper(std::filesystem::path part, cube::PartHeader header, cube::ChunkGrid grid, std::size_t metrics, int rank)
      : state_(std::make_shared<State>(State{std::move(part), std::move(header), std::move(grid), metrics, rank, {}, false})) {}

  /// The unit's failures once it is durable in the part; nullopt when it is not kept.
  std::optional<std::int64_t> operator()(std::int64_t unit, const std::vector<char>& bytes) const {
    State& s = *state_;
    if (s.broken) return std::nullopt;
    try {
      // The bytes this worker just sealed, read where they lie (checked, nothing copied).
      const cube::SealedChunkView chunk = cube::sealed_view_of_bytes(bytes, s.grid, s.metrics, "unit " + std::to_string(unit));
      if (!s.writer) s.writer = std::make_unique<cube::PartWriter>(s.part, s.header);
      s.writer->add(chunk);
      std::int64_t failed = 0;
      for (const std::int8_t code : chunk.status) failed += is_failure(static_cast<CaseStatus>(code)) ? 1 : 0;
      return failed;
    } catch (const cube::CubeError& e) {
      s.broken = true;
      say_rank_note(s.rank, std::string(e.what()) + "; this rank's chunks go to rank 0's journal instead of its part");
      return std::nullopt;
    }
  }

 private:
  struct State {
    std::filesystem::path part;
    cube::PartHeader header;
    cube::ChunkGrid grid;
    std::size_t metrics;
    int rank;
    std::unique_ptr<cube::PartWriter> writer;
    bool broken;
  };
  std::shared_ptr<State> state_;  // one part per rank: shared by the copies a std::function makes
};

/// What rank 0 tells workers about their parts: its header and the cube's path (empty: no
/// parts, a cube of an earlier version). One line each; the path last (it may hold anything).
std::string part_text(const cube::CubeWriter& writer, const std::filesystem::path& output) {
  const cube::PartHeader h = writer.part_header();
  if (h.id == 0) return {};
  return std::to_string(h.id) + " " + std::to_string(h.cases) + " " + std::to_string(h.metrics) + "\n" + h.fingerprint +
         "\n" + std::filesystem::absolute(output).string();
}

/// Inverse of part_text: the header and the path of rank `rank`'s part, if any.
std::optional<std::pair<cube::PartHeader, std::filesystem::path>> parse_part_text(const std::string& text, int rank) {
  if (text.empty()) return std::nullopt;
  std::istringstream in(text);
  cube::PartHeader h;
  std::string line, cube;
  in >> h.id >> h.cases >> h.metrics;
  std::getline(in, line);
  std::getline(in, h.fingerprint);
  std::getline(in, cube, '\0');
  return std::make_pair(h, cube::part_path(cube, rank));
}

/// Rank 0's own worker thread keeps its chunks in `<cube>.part-0` as the other ranks keep
/// theirs, when there are any (issue 38: rank 0's main thread then hears a number and counts a
/// chunk, and takes the chunk in at the end by a raw write, never through its journal). Alone,
/// it hands them over in memory to the journal, as before.
void keep_rank0_part(parallel::ScheduleOptions& schedule, const cube::CubeWriter& writer,
                     const std::filesystem::path& output, std::size_t metrics, const parallel::MpiSession& mpi) {
  if (mpi.size() < 2) return;
  if (auto part = parse_part_text(part_text(writer, output), 0))
    schedule.keep = PartKeeper(part->second, part->first, writer.grid(), metrics, 0);
}

/// `stop_signal`: a signal stops the workers between two cases, reporting the ones done.
/// `grid`: the cube's chunks, which workers seal when handed one whole.
parallel::ScheduleOptions schedule_options(const Study& study, const CaseRunner& runner, const std::atomic<int>* stop_signal,
                                           const cube::ChunkGrid& grid, const std::vector<cube::UnitCoordinate>& carried,
                                           const CaseSpace& space) {
  parallel::ScheduleOptions options;
  // An IDA's chunks handed out whole are searched curve by curve on the worker (ida_work.hpp);
  // the points a curve never runs stay not run.
  ChunkSealer sealer(grid, runner.row_width(), study.ida.has_value());
  sealer.carry(carried, space);
  options.seal = std::move(sealer);
  if (study.ida) options.evaluate_unit = ida_unit_evaluator(study);
  options.row_width = runner.row_width();
  options.fixed_batch = study.run.batch_size;
  options.interrupt = stop_signal;
  if (in_lanes(study)) options.evaluate_together = static_cast<std::size_t>(frames_together(study));
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
    after_store();
  }

  /// Chunks a worker sealed: their bytes go to the writer as they are (no result unpacked).
  void store_sealed(parallel::SealedUnits&& units) {
    for (auto& unit : units) {
      if (unit.kept) {  // durable in its worker's part: streamed into the next fold from there
        meter_.add(unit.cases, unit.failed);
        kept_.push_back(static_cast<std::size_t>(unit.unit));
        stream_kept(unit);
        continue;
      }
      cube::SealedChunk chunk = cube::sealed_from_bytes(unit.bytes, writer_.grid(), metrics_, "a worker's message");
      std::vector<char>().swap(unit.bytes);
      std::int64_t failed = 0, cases = 0;  // an IDA chunk's points never run are no cases computed
      for (const std::int8_t s : chunk.status) {
        failed += is_failure(static_cast<CaseStatus>(s)) ? 1 : 0;
        cases += s != cube::kStatusNotRun ? 1 : 0;
      }
      writer_.store_sealed(std::move(chunk));
      meter_.add(cases, failed);
    }
    after_store();
  }

  /// Values per result row (the cube's metrics).
  void row_width(std::size_t metrics) { metrics_ = metrics; }

 private:
  /// A chunk durable in its worker's part goes into the cube's streaming fold at once
  /// (CubeWriter::stream_kept), so that the end's fold writes only what is left. A streaming
  /// failure is said once; the end's fold then takes the parts as before.
  void stream_kept(const parallel::SealedUnit& unit) {
    if (!error_.empty() || unit.unit < 0) return;
    writer_.stream_kept(static_cast<std::size_t>(unit.unit), unit.worker);
    say_stream_note();
  }

  /// Why streaming stopped, when it just did (the writer keeps it until taken).
  void say_stream_note() {
    if (const std::string note = writer_.take_stream_note(); !note.empty()) say_rank_note(0, note);
  }

  void after_store() {
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

 public:
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
    say_stream_note();
    check_kept();
  }

  /// The first write error (a full disk, an I/O error), naming the file and the reason.
  const std::string& error() const { return error_; }
  cube::CubeError::Cause error_cause() const { return error_cause_; }
  /// Called once when a write fails, to stop the hand-out of work.
  void on_error(std::function<void()> stop) { stop_ = std::move(stop); }

 private:
  /// Every chunk a worker said it kept in its part is in the closed cube (cases of it done,
  /// counted per chunk; an IDA's chunk may hold runs never run): a part rank 0 could not see
  /// (a folder not shared between the nodes) is a failed write, never a success.
  void check_kept() {
    if (!error_.empty()) return;
    std::size_t missing = 0;
    for (const std::size_t chunk : kept_)
      if (chunk >= writer_.grid().chunk_count() || writer_.chunk_done(chunk) == 0) ++missing;
    if (missing == 0) return;
    error_ = cube_ + ": " + std::to_string(missing) + " of the " + std::to_string(kept_.size()) +
             " chunks that workers kept in their ranks' parts (" + cube_ + ".part-<rank>) were not found there by rank 0 "
             "(is the cube's folder one shared file system on every node?); the cube holds the rest, and --resume "
             "computes them again";
    error_cause_ = cube::CubeError::Cause::kOther;
  }

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
  std::size_t metrics_ = 0;
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
  std::vector<std::size_t> kept_;  ///< chunks workers kept in their parts (one number a chunk)
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
/// Cases in a chunk handed out whole (those of `units`) are not in the queue.
parallel::WorkQueue pending_cases(const cube::CubeWriter& writer, const std::map<std::int64_t, const HistoryRequest*>& histories,
                                  const Study& study, const CaseSpace& space, const parallel::MpiSession& mpi,
                                  const StudyRunOptions& options, std::vector<char> in_unit) {
  const auto [first, last] = shard_range(space.size(), options.shard_index, options.shard_count);
  const auto& status = writer.statuses();
  const auto& grid = writer.grid();
  auto pending = [&status](std::int64_t i) { return status[static_cast<std::size_t>(i)] == cube::kStatusNotRun; };
  // The first position from k on that is not in a chunk handed out whole: such a chunk is
  // skipped at once. In storage order a chunk is a run of positions; frame by frame, a column
  // (FrameColumns) every chunk of which is handed out whole is one, and only the columns with
  // chunks of both kinds (the tail's, a resumed run's partly done ones, one pinned by a
  // history) are looked at case by case. So the scan costs rank 0 a few instructions a chunk,
  // not a case (issue 38). `in_unit` is copied: the windows outlive the caller's.
  const bool skipping = std::find(in_unit.begin(), in_unit.end(), 1) != in_unit.end();
  const FrameColumns columns = hands_out_by_frame(space) ? frame_columns(grid, space) : FrameColumns{};
  std::vector<char> column_whole;  // [q]: every chunk of column q is handed out whole
  if (skipping && columns) {
    column_whole.assign(columns.columns, 1);
    for (std::size_t c = 0; c < in_unit.size(); ++c)
      if (!in_unit[c]) column_whole[columns.column_of(c)] = 0;
  }
  auto from = [&grid, &space, skipping, columns, column_whole = std::move(column_whole), in_unit = std::move(in_unit),
               total = space.size()](std::int64_t k) {
    while (skipping && k < total) {
      const std::size_t c = grid.chunk_of(columns ? space.handout_index(k) : k);
      if (!in_unit[c]) break;
      if (!columns) {
        const auto r = grid.range(c);
        k = r.first + r.count;
      } else if (const std::size_t q = columns.column_of(c); column_whole[q]) {
        k = columns.positions(grid, q).second;
      } else {
        ++k;
      }
    }
    return k;
  };
  std::vector<std::int64_t> pinned;
  std::int64_t shared_total = 0;
  for (std::int64_t k = from(first); k < last; k = from(k + 1)) {
    const std::int64_t i = space.handout_index(k);
    if (!pending(i)) continue;
    if (histories.count(i)) pinned.push_back(i);
    else ++shared_total;
  }
  // Positions in the hand-out order (storage order, or a Saltelli design's frame by frame).
  const bool lanes = in_lanes(study);
  const std::int64_t tile = lanes ? frames_together(study) : 1;
  const std::int64_t window_cases = on_gpu(study) ? kGpuWindowCases : kWindowCases;
  auto next_window = [pending, from, &histories, &space, tile, window_cases, cursor = first, last = last]() mutable {
    std::vector<std::int64_t> window;
    while (window.empty() && cursor < last) {
      const std::int64_t end = std::min(last, cursor + window_cases);
      std::int64_t k = from(cursor);
      for (; k < end; k = from(k + 1))
        if (const std::int64_t i = space.handout_index(k); pending(i) && !histories.count(i)) window.push_back(i);
      cursor = std::min(last, std::max(end, k));
    }
    return space.frame_major(std::move(window), tile);
  };
  // A GPU rank is handed a group of one excitation at a time (unless batch_size says otherwise).
  const std::size_t batch = study.run.batch_size == 0 && on_gpu(study) ? static_cast<std::size_t>(kGpuGroupCases)
                                                                      : study.run.batch_size;
  parallel::WorkQueue queue(std::move(next_window), shared_total, std::move(pinned), parallel::worker_count(mpi.comm()),
                            batch);
  if (lanes) queue.group_by([&space](std::int64_t i) { return space.excitation_of(i); });
  return queue;
}

/// Chunks of the cube a worker computes whole and seals (issue 38; docs/checkpoint.md): every
/// case of the chunk in this shard and not done, none with a history, with guided sizes; in
/// storage order, or for a plan handed out frame by frame column by column (FrameColumns; none
/// where its chunks allow no columns: its cases go case by case, frame by frame). The last
/// kTailChunks of them, and all when there are fewer than kUnitsPerWorker per worker, go case
/// by case instead, so that the run still ends balanced.
constexpr std::size_t kUnitsPerWorker = 2;
constexpr std::size_t kTailChunks = 1;

std::vector<std::size_t> whole_chunks(const cube::CubeWriter& writer, const std::map<std::int64_t, const HistoryRequest*>& histories,
                                      const Study& study, const CaseSpace& space, int workers, const StudyRunOptions& options) {
  std::vector<std::size_t> units;
  if (study.run.batch_size > 0) return units;  // the user fixed what a hand-out is
  const auto& grid = writer.grid();
  const auto [first, last] = shard_range(space.size(), options.shard_index, options.shard_count);
  for (const std::size_t c : unit_order(grid, space)) {
    const auto r = grid.range(c);
    // The shard owns hand-out positions; a chunk's first and last cases are its least and greatest.
    if (space.handout_position(r.first) < first || space.handout_position(r.first + r.count - 1) >= last) continue;
    bool whole = writer.chunk_done(c) == 0;  // counted per chunk by the writer: no case looked at
    if (whole && histories.lower_bound(r.first) != histories.lower_bound(r.first + r.count)) whole = false;
    if (whole) units.push_back(c);
  }
  if (units.size() < kUnitsPerWorker * static_cast<std::size_t>(std::max(workers, 1)) + kTailChunks) return {};
  units.resize(units.size() - kTailChunks);
  return units;
}

/// Whole chunks first (each one batch, its cases a frame at a time), then the other cases
/// from the queue.
class UnitsThenCases final : public parallel::WorkSource {
 public:
  UnitsThenCases(std::vector<std::size_t> units, const cube::ChunkGrid& grid, const CaseSpace& space, bool lanes,
                 parallel::WorkQueue rest)
      : units_(std::move(units)), grid_(grid), space_(space), lanes_(lanes), rest_(std::move(rest)) {
    // A chunk within one excitation (1 along every axis before the frame axes, no IDA runs
    // after them) holds a frame of its own in every case, in storage order.
    const auto& chunk = grid_.chunk_shape();
    own_frames_ = space_.distinct_frames() == space_.size() ||
                  (space_.ida_runs() == 0 &&
                   std::all_of(chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(space_.frame_dimension()),
                               [](std::size_t n) { return n == 1; }));
  }
  parallel::WorkBatch take(bool in_process) override {
    if (next_ == units_.size()) return rest_.take(in_process);
    const std::size_t chunk = units_[next_++];
    const auto r = grid_.range(chunk);
    // Storage order has the frame axes fastest: in lanes, a call's cases already share their
    // excitation, and where every case is a frame of its own (every chunk lies within one
    // excitation: a Saltelli design's columns) there is nothing to reorder, so the unit goes
    // out as its range (three items; the worker lists its cases). Otherwise a frame's cases
    // come together (prepared once): on the master, a sort of the chunk (about 300
    // instructions a case).
    if (lanes_ || own_frames_)
      return parallel::unit_range_batch(static_cast<std::int64_t>(chunk), r.first, r.count);
    std::vector<std::int64_t> cases(static_cast<std::size_t>(r.count));
    for (std::size_t k = 0; k < cases.size(); ++k) cases[k] = r.first + static_cast<std::int64_t>(k);
    return parallel::unit_batch(static_cast<std::int64_t>(chunk), space_.frame_major(std::move(cases), 1));
  }
  void completed(const parallel::CaseOutcome& o) override { rest_.completed(o); }
  bool exhausted() const override { return next_ == units_.size() && rest_.exhausted(); }

 private:
  std::vector<std::size_t> units_;
  std::size_t next_ = 0;
  const cube::ChunkGrid& grid_;
  const CaseSpace& space_;
  bool lanes_;
  bool own_frames_ = false;  ///< every case of a chunk is a frame of its own
  parallel::WorkQueue rest_;
};

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
  CaseRunner runner(p.study, *p.space, *p.records, p.group);
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
  bool finishing = false;  // every result is back: the IDA's summaries of its whole chunks are due
  if (p.study.ida) {
    const int workers = parallel::worker_count(mpi.comm());
    auto ida = make_ida_curves(p.study, *p.space, *m.writer, workers);
    const auto [first, last] = shard_range(p.space->curves(), options.shard_index, options.shard_count);
    for (std::int64_t c = 0; c < p.space->curves(); ++c)
      if (c < first || c >= last) ida->skip(static_cast<std::size_t>(c));
    // Whole chunks by the rule of every plan's (whole_chunks); --batch-size keeps every run apart.
    auto units = p.study.run.batch_size > 0
                     ? std::vector<std::size_t>{}
                     : ida_unit_chunks(*m.writer, m.checked.history_cases, *p.space, first, last,
                                       kUnitsPerWorker * static_cast<std::size_t>(std::max(workers, 1)) + kTailChunks,
                                       kTailChunks);
    auto ida_work = std::make_unique<IdaWork>(std::move(ida), std::move(units), m.writer->grid());
    before_flush = [&study = p.study, work = ida_work.get(), writer = m.writer.get(), &finishing] {
      store_ida_summaries(study, *work, *writer, finishing);
    };
    work = std::move(ida_work);
  } else {
    const int workers = parallel::worker_count(mpi.comm());
    auto units = whole_chunks(*m.writer, history_requests, p.study, *p.space, workers, options);
    std::vector<char> in_unit(m.writer->grid().chunk_count(), 0);
    for (const std::size_t c : units) in_unit[c] = 1;
    work = std::make_unique<UnitsThenCases>(std::move(units), m.writer->grid(), *p.space, in_lanes(p.study),
                                            pending_cases(*m.writer, history_requests, p.study, *p.space, mpi, options,
                                                          std::move(in_unit)));
  }
  ResultSink sink(*m.writer, meter, inbox, p.study.run.flush_interval_s, before_flush);
  sink.row_width(runner.row_width());
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
  auto schedule = schedule_options(p.study, runner, stop_signal, m.writer->grid(), m.writer->unit_coordinates(), *p.space);
  schedule.on_sealed = [&sink](parallel::SealedUnits&& units) { sink.store_sealed(std::move(units)); };
  keep_rank0_part(schedule, *m.writer, m.output, runner.row_width(), mpi);
  parallel::run_master(mpi.comm(), stoppable, schedule,
                       evaluate, [&sink](parallel::ResultBatch&& batch) { sink.store(std::move(batch)); },
                       [&sink, &options] {
                         if (options.poll) options.poll();
                         sink.idle();
                       });
  const std::size_t notes_said = m.writer->resume_notes().size();  // prepare_master said these
  schedule.keep = nullptr;  // rank 0's part closed: the last fold takes it in
  finishing = true;
  sink.close();
  for (std::size_t n = notes_said; n < m.writer->resume_notes().size(); ++n) say_note(options, m.writer->resume_notes()[n]);
  meter.finish(m.output.string());
  if (const std::string note = gpu_refusal_note(*p.group); !note.empty()) say_note(options, "rank 0: " + note);
  summary.computed = meter.computed();
  summary.failed = meter.failed();
  if (stoppable.stopped()) summary.stopped_by = stop_signal->load();
  summary.error = sink.error();
  summary.error_cause = sink.error_cause();
  summary.verdict_notes = schema::verdict_notes(
      m.writer->status_counts(), p.study.ida ? std::optional<std::string>(p.study.ida->collapse) : std::nullopt,
      "neither safe nor collapsed", p.study.physics.tail_s);
  return summary;
}

void run_worker_rank(const Prepared& p, const parallel::MpiSession& mpi, const std::atomic<int>* stop_signal,
                     const cube::ChunkGrid& grid, const std::string& parts, const std::string& carried) {
  CaseRunner runner(p.study, *p.space, *p.records, p.group);
  auto schedule = schedule_options(p.study, runner, stop_signal, grid, parse_unit_coordinates(carried), *p.space);
  if (auto part = parse_part_text(parts, mpi.rank()))
    schedule.keep = PartKeeper(part->second, part->first, grid, runner.row_width(), mpi.rank());
  parallel::run_worker(mpi.comm(), schedule,
                       [&runner](std::span<const parallel::WorkItem> items) { return runner.run(items); });
  if (const std::string note = gpu_refusal_note(*p.group); !note.empty())
    say_rank_note(mpi.rank(), note);
}

/// Rank 0's [run] values, the front end's overrides applied, one "key=value" a line.
std::string run_settings_text(const RunOptions& run) {
  std::string text;
  for (const auto& s : run_settings().settings) text += std::string(s.key) + "=" + setting_text(s.get(run)) + "\n";
  return text;
}

/// Sets `run` from run_settings_text (rank 0's values, already checked there).
void apply_run_settings_text(const std::string& text, RunOptions& run) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const auto equals = line.find('=');
    const auto* setting = run_settings().find(line.substr(0, equals));
    if (setting == nullptr) continue;
    SettingValue value = parse_setting_text(*setting, line.substr(equals + 1));
    if (check_setting(*setting, value).empty()) setting->set(run, value);
  }
}

/// Workers parse the study text rank 0 checked (same base folder for relative records), and
/// take rank 0's [run] values (its flags and keywords included: --device, --lanes).
std::unique_ptr<Prepared> receive_study(const parallel::MpiSession& mpi, const Prepared* master,
                                        const GpuBackend& gpu) {
  const std::string text = mpi.broadcast(master ? master->study.text : std::string());
  const std::string file = mpi.broadcast(master ? master->study.file : std::string());
  const std::string base = mpi.broadcast(master ? master->study.base_dir.string() : std::string());
  const std::string run = mpi.broadcast(master ? run_settings_text(master->study.run) : std::string());
  if (master != nullptr) return nullptr;
  try {
    auto prepared = std::make_unique<Prepared>(parse_study(text, file, base));
    apply_run_settings_text(run, prepared->study.run);
    prepared->group = device_group_solver(prepared->study, prepared->study.where("run.device"), gpu);  // this rank's device
    return prepared;
  } catch (const std::exception& e) {  // e.g. records not visible from this node
    end_every_rank(mpi, e);
  }
}

/// The cube's shape and its chunks' (as its file has them), for the workers: the numbers of
/// each separated by spaces, the two lists by '/'.
std::string grid_text(const cube::ChunkGrid& grid) {
  std::string text;
  for (const std::size_t n : grid.shape()) text += std::to_string(n) + " ";
  text += "/";
  for (const std::size_t n : grid.chunk_shape()) text += " " + std::to_string(n);
  return text;
}

/// The grid rank 0 sent (grid_text).
cube::ChunkGrid parse_grid(const std::string& text) {
  auto numbers = [](const std::string& part) {
    std::istringstream in(part);
    std::vector<std::size_t> values;
    for (std::size_t n = 0; in >> n;) values.push_back(n);
    return values;
  };
  const auto slash = text.find('/');
  return cube::ChunkGrid::of_chunk_shape(numbers(text.substr(0, slash)), numbers(text.substr(slash + 1)));
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
      // Before anything is written: a GPU asked for and not usable is the user's to fix.
      prepared->group = device_group_solver(prepared->study, device_where(options, prepared->study), options.gpu_backend);
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
  if (auto received = receive_study(mpi, prepared.get(), options.gpu_backend)) prepared = std::move(received);
  if (!create_cube(options, *prepared, setup, mpi)) {  // rank 0 failed: it threw, and reports it
    mpi.quiet_barrier();
    return std::nullopt;
  }
  // The cube's shape and chunks, so that workers seal the chunks rank 0's writer stores.
  const std::string shape_text = mpi.broadcast(mpi.is_master() ? grid_text(setup.writer->grid()) : std::string());
  // Where each worker keeps the chunks it seals (its part), and what ties it to the cube.
  const std::string parts = mpi.broadcast(mpi.is_master() ? part_text(*setup.writer, setup.output) : std::string());
  // The coordinates whose chunks the workers seal with their units (issue 38).
  const std::string carried = mpi.broadcast(mpi.is_master() ? unit_coordinates_text(*setup.writer) : std::string());

  std::optional<StudySummary> summary;
  static std::ostream nowhere(nullptr);  // a stream without a buffer discards what it is given
  if (mpi.is_master())
    summary = run_master_rank(*prepared, setup, mpi, options.progress ? *options.progress : nowhere, options);
  else
    run_worker_rank(*prepared, mpi, options.stop_signal, parse_grid(shape_text), parts, carried);
  mpi.quiet_barrier();
  return summary ? summary : StudySummary{};
}

}  // namespace pcrf::run
