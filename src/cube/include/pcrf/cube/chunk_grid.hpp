/// \file chunk_grid.hpp
/// \brief How a cube is cut into HDF5 chunks so that each chunk is one contiguous range of
/// linear case indices: whole trailing dimensions, then part of one dimension (the cut), then 1.
///
/// That makes a chunk one contiguous run of results: the writer collects a chunk's results
/// as they come back and writes each chunk that changed as one hyperslab.
///
/// Values that belong together along a dimension (a Saltelli base sample's d + 2 frames along
/// `case`) stay in one chunk: where the cut falls on such a dimension, the chunk's extent
/// along it is a whole number of groups (`multiples`).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcrf::cube {

struct CubeLayout;
struct Coordinate;

/// About how many cases a chunk holds (ChunkGrid's rule): 16 384, 128 KiB of a metric.
inline constexpr std::size_t kChunkCases = 16384;

class ChunkGrid {
 public:
  /// \param shape cube shape (every size ≥ 1)
  /// \param target_cases about how many cases a chunk should hold
  /// \param multiples per dimension (empty: 1 each; every value ≥ 1): where the cut falls on
  ///        dimension d, the chunk's extent along it is a multiple of multiples[d] (the last
  ///        piece along it excepted, when the size is not one), above the target if need be
  explicit ChunkGrid(std::vector<std::size_t> shape, std::size_t target_cases = kChunkCases,
                     std::vector<std::size_t> multiples = {});
  /// The grid whose chunks have the extents `chunk` (a cube's, as its file stores them).
  /// \throws std::invalid_argument unless valid_chunk_shape(shape, chunk)
  static ChunkGrid of_chunk_shape(std::vector<std::size_t> shape, const std::vector<std::size_t>& chunk);
  /// True when `chunk` cuts `shape` as a grid does: 1 along the leading dimensions, then from 1
  /// to the whole of one dimension, then the whole of every later one.
  static bool valid_chunk_shape(const std::vector<std::size_t>& shape, const std::vector<std::size_t>& chunk);

  /// Chunk extent per dimension (for H5Pset_chunk).
  const std::vector<std::size_t>& chunk_shape() const { return chunk_; }
  const std::vector<std::size_t>& shape() const { return shape_; }
  std::size_t chunk_count() const;
  /// The chunk that holds a linear index.
  std::size_t chunk_of(std::int64_t index) const;

  /// A chunk as a linear range and as a hyperslab.
  struct Range {
    std::int64_t first = 0;
    std::int64_t count = 0;
    std::vector<std::size_t> start;   ///< hyperslab start
    std::vector<std::size_t> extent;  ///< hyperslab count
  };
  Range range(std::size_t chunk) const;

  /// Two grids cut a cube alike.
  bool operator==(const ChunkGrid& other) const { return shape_ == other.shape_ && chunk_ == other.chunk_; }

 private:
  ChunkGrid() = default;
  void derive();  ///< inner_ and pieces_ from shape_, chunk_ and split_

  std::vector<std::size_t> shape_;
  std::vector<std::size_t> chunk_;
  std::size_t split_ = 0;        ///< the dimension that is cut
  std::size_t inner_ = 1;        ///< cases per step of the cut dimension
  std::size_t pieces_ = 1;       ///< chunks along the cut dimension
};

/// The linear case range of chunks [first_chunk, end_chunk) of a grid (cases [first, first +
/// count)): consecutive chunks are consecutive ranges, as a chunk is whole trailing dimensions
/// along its cut one; checked chunk by chunk, not assumed.
struct ChunkSpan {
  std::int64_t first = 0;
  std::int64_t count = 0;
};
/// \throws std::out_of_range unless first_chunk ≤ end_chunk ≤ grid.chunk_count();
/// std::logic_error if two consecutive chunks are not consecutive ranges.
ChunkSpan chunk_span(const ChunkGrid& grid, std::size_t first_chunk, std::size_t end_chunk);

/// The grid of a cube's layout: its `chunk_shape` (a new cube's, as its maker chose it, or an
/// existing one's, as its file stores it), or when that is empty the rule's with no multiples
/// (every cube before chunks held whole groups).
ChunkGrid layout_grid(const CubeLayout& layout);

/// Fewest values a chunk of a coordinate holds (coordinate_chunk_values): a coordinate over a
/// dimension the grid takes a few steps at a time would otherwise be cut into chunks whose
/// index outweighs them.
inline constexpr std::size_t kCoordinateChunkMin = kChunkCases / 16;

/// Values per HDF5 chunk of a chunked coordinate written live (Coordinate::written_live) over
/// dimension `dimension` of the grid's cube: the grid's chunk extent along it, so that a unit's
/// range of that dimension is one chunk of the coordinate (a sampled plan's parameter along
/// `case` is cut as the metrics are: 16 384 values, one chunk per unit); at least
/// kCoordinateChunkMin, at most the dimension's size.
std::size_t coordinate_chunk_values(const ChunkGrid& grid, std::size_t dimension);

/// Most values a chunk of a coordinate written at the cube's creation holds (chunked, not
/// written live: the case number, a sample number, a long dimension's own coordinate). Rank 0
/// writes these chunks alone before the first hand-out (issue 38), a raw chunk write each, about
/// 8 000 instructions whatever the chunk's size: in chunks of 16 384 values (the grid's extent,
/// before) that was 0.48 instructions a case of the study (rank_costs.py, 4 ranks), 64 times
/// fewer in chunks of 2^20. Bounded: a piece is 4 MiB as int32, 8 MiB as float64, on the rank
/// that seals it, and its filtered bound on rank 0; xarray reads such a coordinate (an index)
/// whole anyway, and so does CubeReader. Cubes written before keep their chunks (HDF5 says
/// them to every reader).
inline constexpr std::size_t kCreationCoordinateChunk = std::size_t{1} << 20;

/// Values per HDF5 chunk of a chunked coordinate (Coordinate::chunked) `c` of a new cube over
/// dimension `dimension` of the grid's: coordinate_chunk_values where it is written live, else
/// (written at the creation) the dimension cut evenly into the fewest chunks of at most
/// kCreationCoordinateChunk values (the last one short by less than one value a chunk, so that
/// sealing its padding costs nothing: 2^20 + 1 cases are two chunks of 524 289, not one of
/// 2^20 and one of 2^20 values holding one).
std::size_t coordinate_chunk_values(const ChunkGrid& grid, std::size_t dimension, const Coordinate& c);
/// The same for a coordinate of a layout (its grid: layout_grid).
/// \throws std::invalid_argument for a coordinate over no dimension of the layout.
std::size_t coordinate_chunk_values(const CubeLayout& layout, const Coordinate& c);

}  // namespace pcrf::cube
