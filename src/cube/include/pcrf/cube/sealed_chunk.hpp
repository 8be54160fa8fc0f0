/// \file sealed_chunk.hpp
/// \brief One chunk of a result cube, every variable of it already filtered (shuffled and
/// deflated) exactly as the cube's HDF5 filter pipeline stores it, so that the rank that
/// writes the cube copies its bytes into the file (H5Dwrite_chunk) and never touches its
/// results one by one (issue 38: no rank handles every result; docs/checkpoint.md).
///
/// A worker that computed every case of a chunk seals it (seal_chunk); the bytes travel
/// (to_bytes/from_bytes), are journaled as they are (JournalWriter::add_sealed) and folded
/// into the cube by a raw chunk write.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_layout.hpp"

namespace pcrf::cube {

/// zlib level of every chunked variable of a cube (metrics, status, long coordinates).
/// Level 1 (zlib's fast path): against level 4, 11 % fewer instructions per non-lifting case
/// (31.2 k -> 27.8 k) for a cube 0.5 % larger (docs/throughput.md).
inline constexpr unsigned kDeflateLevel = 1;

/// A chunk of a coordinate written live (Coordinate::written_live) that a unit's worker sealed
/// with the unit (seal_coordinate_values): the unit's range of that coordinate's dimension, for
/// the first unit along the others (unit_coordinate_pieces).
struct SealedPiece {
  std::size_t coordinate = 0;   ///< its position in the cube's CubeLayout::coordinates
  std::size_t piece = 0;        ///< its chunk
  std::vector<char> filtered;   ///< as its variable stores it (shuffled, deflated)
  bool operator==(const SealedPiece&) const = default;
};

struct SealedChunk {
  std::size_t chunk = 0;
  std::vector<std::int8_t> status;  ///< the chunk's cases in order (ChunkGrid::range(chunk).count)
  /// Per metric (layout order), then the status: the variable's whole chunk (padded to the
  /// chunk's full shape at the cube's edge) shuffled and deflated.
  std::vector<std::vector<char>> filtered;
  std::vector<std::pair<std::int64_t, std::string>> notes;  ///< case index, message
  /// The chunks of the live coordinates its cases carry (none: the writer seals them at a fold).
  std::vector<SealedPiece> coordinates;
};

/// A sealed chunk's parts where they lie (a SealedChunk's, or its bytes': sealed_view_of_bytes),
/// valid while they are: what a rank that sealed a chunk writes to its part without copying
/// its streams again (PartWriter::add, JournalWriter::add_sealed).
struct SealedChunkView {
  struct Piece {
    std::size_t coordinate = 0;        ///< as SealedPiece
    std::size_t piece = 0;
    std::span<const char> filtered;
  };
  std::size_t chunk = 0;
  std::span<const std::int8_t> status;
  std::vector<std::span<const char>> filtered;
  std::vector<std::pair<std::int64_t, std::string_view>> notes;
  std::vector<Piece> coordinates;
};
/// The view of `sealed` (valid while it is unchanged).
SealedChunkView view_of(const SealedChunk& sealed);

/// A coordinate whose chunks go in with the units (issue 38): the cube stores it in chunks of
/// the grid's extent along its dimension, so that one unit's range of it is one chunk.
struct UnitCoordinate {
  std::size_t coordinate = 0;    ///< its position in the cube's CubeLayout::coordinates
  std::string name;              ///< its name (a worker finds its values by it)
  std::size_t dimension = 0;     ///< the dimension it is over
  std::size_t chunk_values = 0;  ///< values per chunk (= the grid's chunk extent along it)
};

/// The piece of `c` that unit `unit` of `grid` carries: its range of the coordinate's
/// dimension when the unit is the first along every other dimension and that range is one
/// whole chunk of it (or the edge one); nullopt otherwise.
std::optional<std::size_t> unit_piece(const ChunkGrid& grid, std::size_t unit, const UnitCoordinate& c);

/// Seals a chunk all of whose cases were computed: `values` holds [metric * count + k],
/// `status` one code per case. \throws std::invalid_argument for sizes that do not match.
SealedChunk seal_chunk(const ChunkGrid& grid, std::size_t chunk, std::size_t metrics,
                       std::span<const std::int8_t> status, std::span<const double> values,
                       std::vector<std::pair<std::int64_t, std::string>> notes);

/// The status variable of a sealed chunk of `padded` values (padded_elements) that all have
/// `code`, as seal_chunk makes it: the same bytes, so that a reader knows such a chunk (every
/// case of a whole chunk ended alike: at rest, where frames never lift) from one comparison,
/// not from a look at each case. Made once per thread, size and code.
const std::vector<char>& uniform_status_stream(std::size_t padded, std::int8_t code);

/// The bytes of a sealed chunk (one process's, to another running the same binary).
std::vector<char> to_bytes(const SealedChunk& sealed);
/// The values of a coordinate's piece a unit carries (SealedChunk::coordinates), not yet sealed:
/// `values` are the piece's (not padded), of a chunk of `chunk_values` (seal_coordinate_values).
struct PieceValues {
  std::size_t coordinate = 0;
  std::size_t piece = 0;
  std::span<const double> values;
  std::size_t chunk_values = 0;
  /// Optional: a buffer of `chunk_values` values whose first are `values` (the same memory),
  /// which sealed_bytes pads and seals in place, without copying them (its values after the
  /// piece's are overwritten).
  std::span<double> room = {};
};
/// to_bytes of the chunk seal_chunk makes of these arguments, with `pieces` sealed by
/// seal_coordinate_values as its coordinates, the same bytes, each stream written once, straight
/// into them (a worker's sealing: no SealedChunk of streams in between, no second copy).
/// \throws std::invalid_argument as seal_chunk and seal_coordinate_values do.
std::vector<char> sealed_bytes(const ChunkGrid& grid, std::size_t chunk, std::size_t metrics,
                               std::span<const std::int8_t> status, std::span<const double> values,
                               std::span<const std::pair<std::int64_t, std::string>> notes,
                               std::span<const PieceValues> pieces);
/// Inverse of to_bytes, checked as sealed_from_bytes checks it, its parts where they lie in
/// `bytes` (nothing copied). \throws CubeError naming `what` when they do not fit.
SealedChunkView sealed_view_of_bytes(std::span<const char> bytes, const ChunkGrid& grid, std::size_t metrics,
                                     const std::string& what);
/// Inverse of to_bytes, checked against the cube's grid and metrics (counts, sizes, the
/// chunk's number, note case indices, coordinate pieces' sizes: sealed_piece_size_bound).
/// \throws CubeError naming `what` when they do not fit.
SealedChunk sealed_from_bytes(const std::vector<char>& bytes, const ChunkGrid& grid, std::size_t metrics,
                              const std::string& what);

/// Most bytes a filtered variable of a chunk of `elements` values of `element_bytes` may take
/// (zlib's compressBound: a deflate stream of stored blocks and its header and checksum).
std::size_t filtered_bound(std::size_t elements, std::size_t element_bytes);

/// Undoes the filters of one variable: its chunk's `elements` values of `element_bytes`
/// each. \throws CubeError naming `what` when the bytes are not such a chunk.
std::vector<char> unfilter(const std::vector<char>& filtered, std::size_t elements, std::size_t element_bytes,
                           const std::string& what);

/// Values of the chunk's padded shape (ChunkGrid::chunk_shape's product).
std::size_t padded_elements(const ChunkGrid& grid);
/// Most bytes a coordinate piece a unit carries may take: float64 values of one unit's range
/// along a dimension, at most a chunk's padded values.
std::size_t sealed_piece_size_bound(const ChunkGrid& grid);

/// One chunk of a chunked coordinate (Coordinate::chunked) of a cube, sealed as its variable
/// stores it, so that the rank writing the cube copies its bytes raw and other ranks can
/// compute and compress it (issue 38: the cube's creation off rank 0's serial path; a
/// coordinate written during the run, Coordinate::written_live, with its unit).
struct CoordinatePiece {
  std::size_t coordinate = 0;    ///< its position in CubeLayout::coordinates
  std::size_t piece = 0;         ///< its chunk: values [piece * chunk_values, ...)
  std::size_t chunk_values = 0;  ///< values per chunk of its variable (coordinate_chunk_values)
  bool operator==(const CoordinatePiece&) const = default;
};

/// The pieces a new cube's creation seals, in the order it writes them: every chunk of each
/// coordinate that is chunked and written_later but not written_live (the case number),
/// coordinates in layout order, chunks in order.
std::vector<CoordinatePiece> coordinate_pieces(const CubeLayout& layout);

/// A piece of coordinate `c` as its chunk of `chunk_values` values is stored: its values
/// (Coordinate::numbers_into), int32 for an index coordinate, float64 otherwise (little-endian,
/// the file's types), the edge chunk padded with zeros (never read), shuffled, then deflated
/// at kDeflateLevel. Float64 values as a metric's chunk: each byte plane by zlib's run-length
/// strategy or by Huffman codes alone, a noise plane stored (a random LHS parameter: 6.63 B a
/// value in 32 ns coded by runs, against 6.70 B in 102 ns with the default strategy, zlib via
/// Python on this machine). An index (0, 1, 2, ...) by the default strategy: its low plane
/// repeats at distance 256, which runs cannot see and which looks like noise (0.03 B a value,
/// against 1.01 B by runs).
/// \throws std::invalid_argument unless `c` is chunked and has that piece.
std::vector<char> seal_coordinate_piece(const Coordinate& c, std::size_t chunk_values, std::size_t piece);
/// The same from the piece's values already computed (`values`: the piece's, not padded), as
/// a worker has them from its cases: the same bytes as seal_coordinate_piece.
std::vector<char> seal_coordinate_values(std::span<const double> values, std::size_t chunk_values);

/// Pieces of a chunked coordinate of `size` values in chunks of `chunk_values`.
inline std::size_t piece_count(std::size_t size, std::size_t chunk_values) {
  return (size + chunk_values - 1) / chunk_values;
}

/// Most bytes a sealed piece of `c` may take (filtered_bound of its chunk of `chunk_values`).
std::size_t sealed_piece_bound(const Coordinate& c, std::size_t chunk_values);

}  // namespace pcrf::cube
