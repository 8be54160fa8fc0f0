/// \file status_book.hpp
/// \brief The statuses of a cube's cases as its writer keeps them (issue 38: rank 0 works per
/// chunk, not per case): every case's code, how many cases have each code, and how many cases
/// of each chunk are done. A chunk whose cases all have one code (none run yet, or a chunk a
/// worker computed whose cases all ended alike) is kept as that code alone; only a chunk of
/// mixed codes holds one byte a case. So rank 0 neither fills nor holds a byte a case of a
/// study handed out in whole chunks, and the done count and the counts a run's verdict notes
/// need are read without a pass over the cases.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pcrf/cube/chunk_grid.hpp"

namespace pcrf::cube {

/// Cases of each status code [cases], indexed by the code's byte (count_of).
using StatusCounts = std::array<std::int64_t, 256>;
/// The counts of `status`, one pass.
StatusCounts count_statuses(std::span<const std::int8_t> status);
/// Cases of `counts` with code `code` [cases].
inline std::int64_t count_of(const StatusCounts& counts, std::int8_t code) {
  return counts[static_cast<std::uint8_t>(code)];
}

class StatusBook {
 public:
  /// `cases` cases cut into chunks as `grid`, none run: a code a chunk, no byte a case.
  /// \throws std::invalid_argument when the grid holds another number of cases.
  StatusBook(ChunkGrid grid, std::size_t cases);

  /// Cases of the book.
  std::size_t cases() const { return static_cast<std::size_t>(first_.back()); }
  /// Case `index`'s code (kStatusNotRun where not done); index < cases().
  std::int8_t operator[](std::size_t index) const;
  /// Chunk `chunk`'s codes, in order: its own when they are mixed, else `scratch` filled with
  /// its one code (valid until the book or `scratch` changes).
  std::span<const std::int8_t> chunk_codes(std::size_t chunk, std::vector<std::int8_t>& scratch) const;
  /// Every case's code, in order (one pass: a byte a case, made on demand).
  std::vector<std::int8_t> codes() const;
  /// How many cases have each code (kStatusNotRun included).
  const StatusCounts& counts() const { return counts_; }
  /// Cases done (of any code but kStatusNotRun).
  std::int64_t done() const;
  /// Cases of chunk `chunk` done.
  std::int64_t chunk_done(std::size_t chunk) const { return chunk_done_[chunk]; }
  /// Chunks that hold a byte a case (mixed codes) now.
  std::size_t mixed_chunks() const;

  /// Case `index` (of chunk `chunk`, as the grid says) ends with `code`.
  void set(std::size_t chunk, std::int64_t index, std::int8_t code);
  /// Every case of `chunk` ends as `codes` say, in order (as many as the chunk has). Constant
  /// work when they are all alike, a pass over the chunk otherwise.
  /// \throws std::invalid_argument for another number of codes.
  void set_chunk(std::size_t chunk, std::span<const std::int8_t> codes);
  /// Every case of `chunk` ends with `code`: constant work.
  void set_chunk_to(std::size_t chunk, std::int8_t code);
  /// Every case's code at once (a cube read back): one pass.
  void assign(const std::vector<std::int8_t>& codes);

 private:
  /// Cases of chunk `chunk`.
  std::int64_t count(std::size_t chunk) const { return first_[chunk + 1] - first_[chunk]; }
  void forget_chunk(std::size_t chunk, std::int64_t cases);
  void keep_mixed(std::size_t chunk, std::span<const std::int8_t> codes);

  ChunkGrid grid_;
  std::vector<std::int64_t> first_;              ///< [chunk]: its first case; then the end of the last
  std::vector<std::int8_t> uniform_;             ///< [chunk]: its one code, where mixed_[chunk] is empty
  std::vector<std::vector<std::int8_t>> mixed_;  ///< [chunk]: its cases' codes when they differ, else empty
  StatusCounts counts_{};
  std::vector<std::int64_t> chunk_done_;  ///< [chunk]: its cases done
};

}  // namespace pcrf::cube
