/// \file status_book.hpp
/// \brief The statuses of a cube's cases as its writer keeps them (issue 38: rank 0 works per
/// chunk, not per case): every case's code, how many cases have each code, and how many cases
/// of each chunk are done. A chunk whose cases all ended alike is recorded with one memset, and
/// the done count and the counts a run's verdict notes need are read without a pass over the
/// cases.
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
  /// `cases` cases cut into chunks as `grid` (which must cover them), none run (one memset).
  StatusBook(ChunkGrid grid, std::size_t cases);

  /// Every case's code (kStatusNotRun where not done).
  const std::vector<std::int8_t>& codes() const { return codes_; }
  /// How many cases have each code (kStatusNotRun included).
  const StatusCounts& counts() const { return counts_; }
  /// Cases done (of any code but kStatusNotRun).
  std::int64_t done() const;
  /// Cases of chunk `chunk` done.
  std::int64_t chunk_done(std::size_t chunk) const { return chunk_done_[chunk]; }

  /// Case `index` (of chunk `chunk`, as the grid says) ends with `code`.
  void set(std::size_t chunk, std::int64_t index, std::int8_t code);
  /// Every case of `chunk` ends as `codes` say, in order (as many as the chunk has). One
  /// memset and constant work when they are all alike (or the chunk had none done), a pass
  /// over the chunk otherwise. \throws std::invalid_argument for another number of codes.
  void set_chunk(std::size_t chunk, std::span<const std::int8_t> codes);
  /// Every case of `chunk` ends with `code`: one memset.
  void set_chunk_to(std::size_t chunk, std::int8_t code);
  /// Every case's code at once (a cube read back): one pass.
  void assign(std::vector<std::int8_t> codes);

 private:
  void forget_chunk(std::size_t chunk, std::int64_t first, std::int64_t count);

  ChunkGrid grid_;
  std::vector<std::int8_t> codes_;
  StatusCounts counts_{};
  std::vector<std::int64_t> chunk_done_;  ///< [chunk]: its cases done
};

}  // namespace pcrf::cube
