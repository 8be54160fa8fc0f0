/// \file cube_part.hpp
/// \brief A rank's own part of a result cube, `<cube>.part-<rank>` (issue 38: no rank handles
/// every result; docs/checkpoint.md). A worker that computed and sealed a whole chunk of the
/// cube (sealed_chunk.hpp) appends it to its rank's part and makes it durable before it reports
/// the chunk done; rank 0 hears only the chunk's number and counts. Rank 0's own worker thread
/// keeps `<cube>.part-0` when the run has other ranks (alone, it hands its chunks to rank 0's
/// journal in memory). As each chunk is reported, rank 0 reads its record from the rank's part
/// (the records committed since its last read: JournalReader::extend) and writes it raw into
/// the next fold's open <cube>.partial (CubeWriter::stream_kept); the end of the run (the
/// writer's last fold) writes the rest, or, where streaming failed, every chunk, as the first
/// fold of a `--resume` does: by raw chunk writes, each record read from its part by reference;
/// then the parts are removed.
///
/// A part is a log of the journal's own records (io::LogWriter framing, cube_journal.hpp): a
/// kPartHeader record, then per chunk a sealed record, the chunk's notes (if any) and a commit.
/// The header ties the part to its cube: the cube's `part_id` attribute (drawn when the cube
/// is made, kept by every fold, renewed by --overwrite), its case and metric counts and the
/// study's fingerprint. A part is untrusted input, read as the journal is (JournalReader).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/cube/sealed_chunk.hpp"

namespace pcrf::cube {

class JournalWriter;

/// Global attribute of a cube: the id its parts carry (int64, drawn when the cube is made). A
/// cube without it (an earlier version's) has no parts: its workers send their chunks to rank 0.
inline constexpr const char* kPartIdName = "part_id";

/// `<cube>.part-<rank>`.
std::filesystem::path part_path(const std::filesystem::path& cube, int rank);

/// Every entry of the cube's folder named as one of its parts (`<cube name>.part-<rank>`,
/// rank 0 to 999999 without leading zeros), whatever it is (a symbolic link included), in
/// rank order. Nothing when the folder cannot be read.
std::vector<std::filesystem::path> part_files(const std::filesystem::path& cube);

/// The rank whose part of `cube` the file `part` is by its name (part_files' rule: the name
/// part_path(cube, rank) has, rank 0 to 999999 without leading zeros); nothing for any other.
std::optional<int> part_rank(const std::filesystem::path& cube, const std::filesystem::path& part);
/// The cube's part id (its kPartIdName attribute); 0 when it has none.
std::int64_t part_id_of(const CubeLayout& layout);

/// What ties a part to its cube.
struct PartHeader {
  std::int64_t id = 0;        ///< the cube's part_id
  std::int64_t cases = 0;     ///< the cube's cases
  std::size_t metrics = 0;    ///< the cube's metrics
  std::string fingerprint;    ///< the study's (kFingerprintName)
};
/// The header of the parts of the cube of `layout`.
PartHeader part_header_of(const CubeLayout& layout);
/// The payload of a part's kPartHeader record: id i64, cases i64, metrics u32, fingerprint
/// (length u32, bytes).
std::string part_header_payload(const PartHeader& header);

/// Appends a worker rank's sealed chunks to its part.
class PartWriter {
 public:
  /// Creates `part` exclusively (nothing may be there: a file, a symbolic link, a FIFO or a
  /// folder is refused) with its header, synced with its folder.
  /// \throws CubeError naming the part.
  PartWriter(const std::filesystem::path& part, const PartHeader& header);
  ~PartWriter();
  PartWriter(const PartWriter&) = delete;
  PartWriter& operator=(const PartWriter&) = delete;

  /// Appends a sealed chunk, its notes and a commit, and syncs them (fdatasync): the chunk is
  /// durable when this returns. \throws CubeError naming the part (the file is then cut back
  /// to its last commit, best effort: a torn tail, which readers drop).
  void add(const SealedChunk& sealed);
  /// The same from where its parts lie (a worker's own sealed bytes: sealed_view_of_bytes).
  void add(const SealedChunkView& sealed);
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  std::unique_ptr<JournalWriter> log_;
};

}  // namespace pcrf::cube
