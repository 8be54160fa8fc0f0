/// \file cube_journal.hpp
/// \brief The journal of a result cube, `<cube>.journal`: what a run stored since the cube
/// was last folded (docs/checkpoint.md). A checkpoint appends it (io::LogWriter: a size and
/// a CRC-32 per record, then fdatasync), so that its cost follows what changed; the HDF5 cube
/// is never written in place, only replaced whole by a fold (CubeWriter), after which the
/// journal is removed.
///
/// A journal extends one folded state of its cube: its first record carries the cube's
/// `journal_id` attribute, which each fold draws anew. A journal whose id is not its cube's
/// (a fold renamed into place, then a kill before the journal was removed; a cube replaced
/// by --overwrite) is stale: its results are in the cube already, or belong to another, and
/// it is ignored and replaced.
///
/// Records (their kinds JournalRecord; payloads little-endian):
///   header   id i64, cases i64, metrics u32
///   cases    chunk u64, n u32, n offsets in the chunk u32 (ascending), n statuses i8, then
///            per metric: u8 0 and n f64, or u8 1 and one f64 that every case has (a metric
///            that is 0 or NaN wherever frames never lift costs 9 bytes, not 8 n)
///   notes    n u32, then n × (case i64, length u32, text)
///   history  a HistoryTable: name, attributes, columns and their values
///   sealed   chunk u64, n u32 (the chunk's cases), n statuses i8, variables u32 (metrics,
///            then status), per variable: size u64 and the chunk's bytes as the cube's
///            filters store them (sealed_chunk.hpp; folded by a raw chunk write)
///   commit   nothing: the records since the last commit are one checkpoint
/// A checkpoint's records count only once its commit record is complete: a tail torn
/// anywhere drops the whole checkpoint (never a case's values without its note).
/// Side variables are not journaled: their producer stores them anew on --resume, and a
/// fold writes the writer's own.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/cube/cube_writer.hpp"

namespace pcrf::io {
class LogReader;
class LogWriter;
struct LogRecord;
}  // namespace pcrf::io

namespace pcrf::cube {

/// Global attribute of a cube: the id its journal must carry to extend it (int64, drawn at
/// each fold). A cube without it (an earlier version's) has no journal.
inline constexpr const char* kJournalIdName = "journal_id";

/// The kinds of a journal's records (io::LogRecord::kind).
enum JournalRecord : std::uint32_t {
  kJournalHeader = 1,
  kJournalCases = 2,
  kJournalNotes = 3,
  kJournalHistory = 4,
  kJournalCommit = 5,
  kJournalSealed = 6,
  /// The first record of a rank's part (cube_part.hpp), instead of kJournalHeader.
  kPartHeader = 7,
};

/// `<cube>.journal`.
std::filesystem::path journal_path(const std::filesystem::path& cube);

/// The cube's journal id (its kJournalIdName attribute); 0 when it has none.
std::int64_t journal_id_of(const CubeLayout& layout);

/// A journal whose checksums hold but whose content does not fit its cube (a forged or
/// foreign journal): what() names the journal, the record, its offset and the problem.
/// `--resume` sets such a journal aside (CubeWriter) and computes its cases again.
class JournalDamage : public CubeError {
 public:
  explicit JournalDamage(const std::string& what) : CubeError(what) {}
};

/// Cases of one chunk, as a checkpoint stored them.
struct JournalCases {
  std::size_t chunk = 0;
  std::vector<std::uint32_t> offsets;  ///< in the chunk, ascending
  std::vector<std::int8_t> status;     ///< one per offset
  std::vector<double> values;          ///< [metric * offsets.size() + j]
};

/// The statuses of a sealed record as a raw write of it takes them (JournalReader::with_sealed).
struct SealedStatuses {
  /// True when the record's status variable is the stream of a whole chunk of one code
  /// (uniform_status_stream of `code`): known from one comparison of its bytes, the record's
  /// statuses not looked at one by one.
  bool alike = false;
  std::int8_t code = kStatusNotRun;   ///< when alike: every case's
  std::span<const std::int8_t> each;  ///< otherwise: each case's, in order, checked
};

/// The journal beside a cube, as a reader or a resuming writer finds it.
class JournalReader {
 public:
  /// Reads `journal_path(cube)` for the cube of `layout`, whose journal id is `id` (0: none).
  /// A missing, stale or unreadable-header journal reads as current() false. The complete,
  /// checksum-valid records are kept up to the first that is not, and of those up to the last
  /// commit (a torn tail is dropped: the checkpoint it held is computed again).
  /// Every value of a record is checked against the layout before it is handed out: chunks,
  /// counts, sizes, case offsets, status codes (those of the layout's flags only), note case
  /// indices, history names, columns and lengths.
  /// \throws CubeError naming the journal when it cannot be read (a symbolic link or a FIFO
  /// there included); JournalDamage when a record whose CRC holds does not fit the cube.
  JournalReader(const std::filesystem::path& cube, const CubeLayout& layout, std::int64_t id);
  /// Reads a rank's part of the cube (cube_part.hpp) at `part`: the same records, sealed
  /// chunks each with its notes and a commit, after a kPartHeader record whose payload must be
  /// `part_header` (part_header_payload). A part headed otherwise, or that is no log at all, is
  /// foreign(); one without a complete header (a kill as it was made) is neither current nor
  /// foreign: it holds nothing. Records of other kinds make it a JournalDamage.
  /// `verify_checksums` false: the frames' CRCs are not computed (a part this run's workers
  /// synced, read at its end: io::LogReader::Checksums::kFramesOnly); every other check holds.
  JournalReader(const std::filesystem::path& part, const CubeLayout& layout, const std::string& part_header,
                bool verify_checksums = true);
  ~JournalReader();
  JournalReader(const JournalReader&) = delete;
  JournalReader& operator=(const JournalReader&) = delete;

  /// True when the journal extends this cube (its header carries the cube's id).
  bool current() const { return current_; }
  /// A part (the part constructor) of another cube or another study, or no part at all.
  bool foreign() const { return foreign_; }
  /// The file read.
  const std::filesystem::path& file() const { return file_; }
  /// Closes the file, keeping what was read of it (a fold that takes many parts holds one
  /// open at a time); reopen_file() before reading a record again. \throws CubeError when the
  /// file is no longer the one read.
  void release_file();
  void reopen_file();
  /// A part its worker is still appending to (current, open: reopen_file()): indexes the
  /// records it committed since, checked as the constructor checks them (sealed_chunks() then
  /// lists their chunks too). Records past the last commit stay unread until a later call.
  /// \throws CubeError naming the part when it was replaced or cut; JournalDamage as the constructor.
  void extend();
  /// Case results in its records (a case stored twice counts twice).
  std::int64_t results() const { return results_; }
  /// Where a writer continues it [bytes] (the end of its last commit); 0 when not current.
  std::uint64_t valid_bytes() const { return valid_bytes_; }
  /// Bytes past the last commit (a torn tail), dropped.
  std::uint64_t dropped_bytes() const { return dropped_bytes_; }
  /// Complete, checksum-valid records past the last commit (a checkpoint not closed), dropped.
  std::size_t dropped_records() const { return dropped_records_; }
  /// Case results in the dropped records of cases (those of a damaged tail cannot be counted).
  std::int64_t dropped_results() const { return dropped_results_; }
  /// True when a record that does not match its CRC or does not fit the file ended what was
  /// read (damage, or a tail torn in the middle of a record).
  bool damaged() const { return damaged_; }
  /// Reads and checks every record (cases, notes, histories) once. \throws JournalDamage.
  void check_all() const;

  /// Chunks with journaled cases, each with its records in journal order (for cases()).
  const std::map<std::size_t, std::vector<std::size_t>>& chunks() const { return chunks_; }
  /// One record of cases, decoded and checked against the layout.
  JournalCases cases(std::size_t record) const;
  /// Chunks with sealed records, each with its records in journal order (for sealed()).
  const std::map<std::size_t, std::vector<std::size_t>>& sealed_chunks() const { return sealed_; }
  /// One sealed record, its sizes and statuses checked (check_all() also inflates it).
  SealedChunk sealed(std::size_t record) const;
  /// One sealed record's statuses, then its variables (metrics, then the status) as the file
  /// holds them, from one read of the record and without a copy (a raw chunk write). Every
  /// size is checked as sealed() checks it before anything is handed out. The statuses go to
  /// `statuses` first: per chunk when the status variable is a whole chunk of one code the
  /// cube's flags name (SealedStatuses::alike: one comparison with uniform_status_stream, so
  /// that what the cube receives is what was checked), else case by case (each code one the
  /// flags name); then `variable(index, bytes, size)` receives each variable.
  /// Then `piece(coordinate, piece, bytes, size)` receives each coordinate piece the record
  /// carries (SealedChunk::coordinates; a record without them, an earlier version's, has none).
  void with_sealed(std::size_t record, const std::function<void(const SealedStatuses&)>& statuses,
                   const std::function<void(std::size_t, const char*, std::size_t)>& variable,
                   const std::function<void(std::size_t, std::size_t, const char*, std::size_t)>& piece = {}) const;
  /// The statuses of one sealed record only (its head, checked as sealed() checks them).
  std::vector<std::int8_t> sealed_status(std::size_t record) const;
  /// The notes of a part's sealed record: those of the notes record right after it (before
  /// its commit), each of a case of its chunk (none for a journal's, whose notes are notes()).
  /// \throws JournalDamage for a note outside it.
  std::vector<std::pair<std::int64_t, std::string>> notes_after(std::size_t sealed_record) const;
  /// Every record of cases, in journal order.
  void for_each_cases(const std::function<void(const JournalCases&)>& visit) const;
  /// The notes, in journal order.
  std::vector<std::pair<std::int64_t, std::string>> notes() const;
  /// The history tables, in journal order (a later one of a name replaces an earlier).
  void for_each_history(const std::function<void(HistoryTable&&)>& visit) const;

 private:
  JournalReader(std::filesystem::path file, const CubeLayout& layout, bool verify_checksums = true);
  void index(bool part);
  void index_from(std::size_t first);
  void check_statuses(std::size_t record, const std::int8_t* status, std::size_t n, bool sealed = false) const;
  bool names(std::int8_t code) const;
  std::size_t sealed_chunk_of(std::size_t record) const;
  std::vector<std::pair<std::int64_t, std::string>> notes_of(std::size_t record) const;
  std::string payload(std::size_t record) const;
  std::string payload_head(const io::LogRecord& record) const;
  [[noreturn]] void fail(std::size_t record, const std::string& problem) const;

  std::filesystem::path file_;
  std::size_t metrics_;
  std::size_t coordinates_;  ///< the cube's coordinates: most pieces a sealed record may carry
  std::vector<std::size_t> piece_values_;  ///< per coordinate: values of its chunk (coordinate_chunk_values)
  std::int64_t cases_;
  ChunkGrid grid_;
  std::unique_ptr<io::LogReader> log_;
  bool current_ = false;
  bool foreign_ = false;
  bool part_ = false;  ///< a part: its notes follow their chunk's sealed record
  std::size_t kept_ = 0;  ///< records kept: those up to the last commit
  std::uint64_t valid_bytes_ = 0;
  std::uint64_t dropped_bytes_ = 0;
  std::size_t dropped_records_ = 0;
  std::int64_t dropped_results_ = 0;
  bool damaged_ = false;
  std::vector<std::int8_t> statuses_;  ///< the codes a case may have: the layout's flags but not_run
  std::int64_t results_ = 0;
  std::map<std::size_t, std::vector<std::size_t>> chunks_;
  std::map<std::size_t, std::vector<std::size_t>> sealed_;
  static constexpr std::size_t kNoChunk = static_cast<std::size_t>(-1);
  std::vector<std::size_t> sealed_record_chunk_;  ///< [record]: its chunk when sealed, else kNoChunk
};

/// Appends to the journal of a cube. \throws CubeError naming the journal on every failure.
class JournalWriter {
 public:
  /// Starts the journal of the cube folded with `id` anew (replacing any file there), or,
  /// with `keep_bytes` > 0 (a current JournalReader's valid_bytes()), continues it there.
  JournalWriter(const std::filesystem::path& cube, const CubeLayout& layout, std::int64_t id,
                std::uint64_t keep_bytes);
  /// Starts a rank's part (cube_part.hpp) at `part`, of a cube of `metrics` metrics, headed by
  /// `part_header` (part_header_payload) and synced. The caller makes sure nothing is there.
  JournalWriter(const std::filesystem::path& part, std::size_t metrics, const std::string& part_header);
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;

  /// Writes the stored cases of one chunk (not synced): `stored[k]` marks case k of the
  /// chunk, `values` holds [metric * count + k], `status` the chunk's statuses.
  void add_cases(std::size_t chunk, const std::vector<char>& stored, const std::vector<double>& values,
                 const std::int8_t* status);
  /// Writes a sealed chunk's statuses and filtered bytes (not synced; its notes go by add_notes).
  void add_sealed(const SealedChunk& sealed);
  /// The same from where its parts lie: the same record, its streams written as they are
  /// (LogWriter::add_pieces), never copied into a payload.
  void add_sealed(const SealedChunkView& sealed);
  void add_notes(const std::vector<std::pair<std::int64_t, std::string>>& notes);
  void add_notes(std::span<const std::pair<std::int64_t, std::string_view>> notes);
  void add_history(const HistoryTable& table);
  /// Writes the commit record that makes the records added since the last one a checkpoint.
  void commit();
  /// Syncs what was written to disk: the checkpoint is then durable.
  void sync();
  /// Bytes of the journal (committed records).
  std::uint64_t bytes() const;
  /// True while the journal's path names the file this writer appends to.
  bool in_place() const;

 private:
  template <class Action>
  void guarded(Action action);

  std::filesystem::path file_;
  std::size_t metrics_;
  std::unique_ptr<io::LogWriter> log_;
  std::string payload_;        ///< reused: no fresh pages for every record
  std::vector<double> column_;  ///< reused
};

}  // namespace pcrf::cube
