/// \file cube_writer.hpp
/// \brief Writes a result cube: a netCDF-4 compatible HDF5 file that xarray, netCDF4 and
/// h5py open with no custom code.
///
/// File layout (see studies/README.md, "The result cube"):
///   /<dimension>       coordinate variables, HDF5 dimension scales (netCDF-4 dimensions)
///   /<auxiliary>       1-D coordinates over one dimension (CF `coordinates` attribute)
///   /<metric>          float64 over every dimension, _FillValue NaN, `units`
///   /status            int8 over every dimension, _FillValue -1 (not run), CF flags
///   /messages/         case index and text of every case that reported a message
///   /histories/<name>/ time histories of selected cases (each its own time dimension)
/// Variables are chunked (each chunk one contiguous range of cases) and deflated.
///
/// Memory: the statuses (status_book.hpp: a code a chunk whose cases are alike, 1 byte a case
/// of a chunk of mixed codes, with how many cases have each code and how many of each chunk
/// are done) and the values stored since the last flush, chunk by chunk; nothing else of the
/// cube.
///
/// Checkpoints (docs/checkpoint.md): flush() appends what was stored since the last one to
/// the cube's journal, `<file>.journal` (cube_journal.hpp), and syncs it: its cost follows
/// what changed. The HDF5 file is never written in place: a fold replaces it by the one
/// atomic-file rule (io::AtomicFile, as every output) — the last fold copied to
/// <file>.partial, the journal and what was stored since laid over it, synced, renamed over
/// the file — and then removes the journal. flush() folds once the journal holds more
/// results than kFoldJournalShare of the cube's; close() always does. A process killed at
/// any moment leaves the last folded cube whole, and a journal whose complete records
/// --resume replays (CheckpointStep lists the kill points). Readers of the file see its
/// last fold.
///
/// The ranks' parts (cube_part.hpp) go in by the streaming fold (stream_kept): the next fold's
/// <file>.partial, made at the first chunk a worker reports kept and open for the run, receives
/// each such chunk raw as it is reported; the end's fold (close) writes only what it lacks into
/// it. While it is open a checkpoint only appends; any streaming failure drops it, and the
/// end's fold assembles the parts as before.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "pcrf/cube/status_book.hpp"

namespace pcrf::cube {

enum class OpenMode {
  kCreate,     ///< the file must not exist
  kOverwrite,  ///< replace any existing file
  kResume,     ///< continue an existing cube of the same study (create it if absent)
};

/// A fold is due when the journal holds more than this many results per result of the
/// folded cube [results in the journal / results in the cube]. Counted in results, not bytes:
/// the journal stores a result uncompressed (8 bytes a metric), the cube deflated, so a
/// ratio of bytes would fold several times as often for a cube that compresses well. With
/// a quarter, the folds of a whole run copy the cube about 1 + 1/0.25 = 5 times its final size.
inline constexpr double kFoldJournalShare = 0.25;

/// The points of a checkpoint between which a kill leaves a distinct state on disk (each is
/// described where it is reached, in cube_writer.cpp, and in docs/checkpoint.md).
enum class CheckpointStep {
  kJournalWritten,  ///< an append's records are written to the journal, not yet synced
  kJournalSynced,   ///< … and synced: the checkpoint is durable
  kFoldCopied,      ///< a fold's <file>.partial holds a copy of the cube
  kFoldWritten,     ///< … with every change written into it, synced; the cube is still the old one
  kFoldRenamed,     ///< the new cube is in place; the old journal not yet removed (stale)
  kJournalRemoved,  ///< the fold is complete (but for the parts it took)
  kPartsRemoved,    ///< … and the ranks' parts it took are removed (cube_part.hpp)
  /// A streaming fold's <file>.partial is made (CubeWriter::stream_kept): a copy of the cube,
  /// open for the run; the cube, its journal and the parts are as they were
  kStreamOpened,
  /// … and a chunk a worker kept in its part is written into it (not synced); as above
  kChunkStreamed,
};
/// Called at each CheckpointStep of every writer of the process (null: nothing). For crash
/// tests, which stop the process there.
using CheckpointObserver = void (*)(CheckpointStep);
void observe_checkpoints(CheckpointObserver observer);

/// True for a name a history group or column may have: letters, digits, '_', '-' and '.',
/// at most 255 characters, not "." or ".." (the one rule: study labels, journals).
bool valid_group_name(std::string_view name);

/// A time history to store in its own group, /histories/<name>.
struct HistoryTable {
  std::string name;                     ///< group name (valid_group_name)
  std::vector<Attribute> attributes;    ///< e.g. the case's coordinates
  std::vector<MetricVariable> columns;  ///< the first one is the time axis
  std::vector<std::vector<double>> values;  ///< one vector per column, equal lengths
};

/// Where a new cube's coordinate pieces come from, already sealed (seal_coordinate_piece):
/// from other ranks, which compute and compress them while the creating rank writes them
/// (run/cube_creation.hpp). Without one the writer seals them itself.
class CoordinateSource {
 public:
  virtual ~CoordinateSource() = default;
  /// The sealed bytes of `piece` of `layout` (the writer's layout), valid until the next
  /// call (a source keeps one buffer: no piece is copied or cleared on its way into the file).
  /// Asked only while a new cube is created, in coordinate_pieces(layout)'s order, each once.
  virtual std::span<const char> sealed(const CubeLayout& layout, const CoordinatePiece& piece) = 0;
};

class CubeWriter {
 public:
  /// \throws CubeError naming the file: exists (kCreate), belongs to another study or has
  /// another layout (kResume), or cannot be written.
  /// `coordinates` (optional, used only within the constructor): where a new cube's sealed
  /// coordinate pieces come from; null: sealed here.
  CubeWriter(std::filesystem::path file, CubeLayout layout, OpenMode mode, CoordinateSource* coordinates = nullptr);
  /// Unless closed: append() (errors ignored), keeping what was stored.
  ~CubeWriter();
  CubeWriter(const CubeWriter&) = delete;
  CubeWriter& operator=(const CubeWriter&) = delete;

  /// True when an existing cube was opened for --resume.
  bool resumed() const { return resumed_; }
  /// What opening for --resume did to the cube's journal that the user should hear, one line
  /// each: records dropped (a torn or damaged tail) and how many, or a journal that cannot be
  /// replayed set aside, and that their cases are computed again. Empty otherwise.
  const std::vector<std::string>& resume_notes() const;
  /// What ties a rank's part to this cube (cube_part.hpp); id 0 for a cube of an earlier
  /// version, which has no parts (its workers send their chunks).
  PartHeader part_header() const;
  /// Status of every case (kStatusNotRun where not computed yet), case by case or a chunk at
  /// a time (StatusBook: a code a chunk where its cases are alike). A chunk a rank kept in its
  /// part (cube_part.hpp) is not run here until close() (or a --resume) takes it in.
  const StatusBook& statuses() const { return statuses_; }
  /// Every case's status, a byte a case (made on demand: one pass).
  std::vector<std::int8_t> status() const { return statuses_.codes(); }
  /// How many cases have each status code (those of status()), without a pass over them.
  const StatusCounts& status_counts() const { return statuses_.counts(); }
  /// Cases done (status() not kStatusNotRun), without a pass over them.
  std::int64_t done_count() const { return statuses_.done(); }
  /// Cases of chunk `chunk` (grid()) done.
  std::int64_t chunk_done(std::size_t chunk) const { return statuses_.chunk_done(chunk); }
  /// A metric of every case (NaN where not computed): the last checkpoint's values with
  /// those stored since, and the chunks of the parts taken (take_parts, --resume), laid over them. Reads the whole variable: meant for small cubes
  /// (a large one is read a block of chunks at a time, below). \throws CubeError for an unknown metric.
  std::vector<double> read_values(const std::string& metric) const;
  /// The same values for the cases of chunks [first_chunk, end_chunk) of grid() only, in linear
  /// case order from grid().range(first_chunk).first (chunk_span): a slice of read_values()
  /// that holds only those chunks' values (one hyperslab read of the file per chunk), for a
  /// reader that goes through a large cube a block of chunks at a time.
  /// \throws CubeError for an unknown metric or chunks outside the cube.
  std::vector<double> read_values(const std::string& metric, std::size_t first_chunk, std::size_t end_chunk) const;
  /// Memory held by the values stored since the last checkpoint [bytes].
  std::size_t pending_bytes() const;

  /// Stores one case in memory. `values` holds one value per metric, in layout order.
  void store(std::int64_t index, std::int8_t status, const std::vector<double>& values);
  /// Stores a chunk whose every case a worker computed and sealed (sealed_chunk.hpp): its
  /// statuses join the cube's, its filtered bytes are journaled and folded as they are.
  /// \throws CubeError when the chunk is outside the cube or not whole.
  void store_sealed(SealedChunk sealed);
  /// The coordinates written live whose chunks a unit's worker seals with the unit (its piece:
  /// unit_piece) and that go in raw wherever the unit does (stream_kept, the parts, the journal);
  /// a chunk no unit brought is sealed here at a fold (the cases of units it holds) or at close
  /// (every one). Empty for a cube of an earlier version, whose coordinates are written whole.
  const std::vector<UnitCoordinate>& unit_coordinates() const;
  /// How the cube is cut into chunks (what a worker seals), and its shape.
  const ChunkGrid& grid() const;
  std::vector<std::size_t> shape() const;
  /// Stores a message for a case (written under /messages).
  void store_note(std::int64_t index, std::string note);
  /// Queues a history group (written at the next flush).
  void store_history(HistoryTable table);
  /// Replaces the values of a side variable of the layout (written at the next flush).
  /// \throws CubeError for an unknown name or a wrong number of values.
  void store_side(const std::string& name, std::vector<double> values);

  /// A checkpoint: appends what changed since the last one to the journal, synced (or folds
  /// when the journal has grown past kFoldJournalShare of the cube).
  void flush();
  /// A checkpoint that only appends, even when a fold is due (a new cube, or one of an
  /// earlier version, is still folded): for a run stopping, which a kill may end within a second.
  void append();
  /// A checkpoint that folds the journal and what changed into the cube, and removes the journal.
  void fold();
  /// Takes the ranks' parts beside the cube (this run's workers') now, as close() does: their
  /// chunks' statuses join status() at once (each case's, read from the part; close() alone
  /// counts them chunk by chunk as it writes them), read_values() reads their values, and the
  /// next fold puts them in. For a producer whose side variables are derived from every result (an IDA's
  /// summaries of the curves its workers searched), before close().
  void take_parts();
  /// A chunk that the worker of rank `rank` appended to its part and synced, and reported kept
  /// (cube_part.hpp), goes into the cube's streaming fold now, so that the end of the run has
  /// only what is left to write (issue 38: the assembly during the run, not after it). The
  /// streaming fold is the next fold's <file>.partial, made at the first such chunk as a fold
  /// makes it (io::AtomicFile, exclusively, never followed: a copy of the cube) and kept open;
  /// each chunk is read from the part (the records it committed since, checked as the end's
  /// assembly checks them) and written raw, one chunk in memory at a time. Nothing else changes
  /// until the fold: status() and read_values() see the chunk when close() (or take_parts())
  /// takes the parts, as before; while the streaming fold is open a checkpoint only appends
  /// (the journal extends the cube on disk, which is unchanged), and a fold that must come
  /// (fold(), parts taken) completes it. Never throws: a failure (a full disk, an HDF5 error, a
  /// part that cannot be read) drops the .partial, stops the streaming and says why once
  /// (take_stream_note); the end's fold then assembles as it did before. A chunk not found in
  /// the part is left to the end's fold.
  void stream_kept(std::size_t chunk, int rank);
  /// Why the streaming fold stopped, once (empty: it did not, or was said already).
  std::string take_stream_note();
  /// fold() and close: the ranks' parts beside the cube (this run's workers') go in with the
  /// fold, read from their files chunk by chunk (a part that does not fit the cube is set
  /// aside, noted in resume_notes()), and are removed after it; their statuses join status()
  /// chunk by chunk (a whole chunk of one code by one comparison and one memset:
  /// JournalReader::with_sealed). Further calls are invalid.
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  StatusBook statuses_;
  bool resumed_ = false;
};

}  // namespace pcrf::cube
