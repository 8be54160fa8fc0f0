/// \file chunk_grid.hpp
/// \brief How a cube is cut into HDF5 chunks so that each chunk is one contiguous range of
/// linear case indices: whole trailing dimensions, then part of one dimension, then 1.
///
/// That makes a chunk one contiguous run of results: the writer collects a chunk's results
/// as they come back and writes each chunk that changed as one hyperslab.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcrf::cube {

class ChunkGrid {
 public:
  /// \param shape cube shape (every size ≥ 1)
  /// \param target_cases about how many cases a chunk should hold
  explicit ChunkGrid(std::vector<std::size_t> shape, std::size_t target_cases = 16384);

  /// Chunk extent per dimension (for H5Pset_chunk).
  const std::vector<std::size_t>& chunk_shape() const { return chunk_; }
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

 private:
  std::vector<std::size_t> shape_;
  std::vector<std::size_t> chunk_;
  std::size_t split_ = 0;        ///< the dimension that is cut
  std::size_t inner_ = 1;        ///< cases per step of the cut dimension
  std::size_t pieces_ = 1;       ///< chunks along the cut dimension
};

}  // namespace pcrf::cube
