/// \file worker_chunks.hpp
/// \brief What a worker computes for the part and streaming tests, over case_axis_layout's
/// two metrics: case i's row and status, and a chunk of them sealed as a worker seals it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/sealed_chunk.hpp"

namespace pcrf::cube {

/// Case i's two metrics: theta_max_rad [rad] and impacts [1].
inline std::vector<double> row_of(std::int64_t i) { return {1e-5 * static_cast<double>(i), static_cast<double>(i % 7)}; }
/// Case i's status: overturned (3) every eleventh case, else at rest (0).
inline std::int8_t status_of(std::int64_t i) { return i % 11 == 0 ? 3 : 0; }

/// Chunk `chunk` computed whole and sealed, as a worker does it (`code`: every status, when set);
/// every 997th case carries a note.
inline SealedChunk sealed_of(const ChunkGrid& grid, std::size_t chunk, int code = -1) {
  const auto r = grid.range(chunk);
  const auto count = static_cast<std::size_t>(r.count);
  std::vector<std::int8_t> status(count);
  std::vector<double> values(2 * count);
  std::vector<std::pair<std::int64_t, std::string>> notes;
  for (std::size_t k = 0; k < count; ++k) {
    const std::int64_t i = r.first + static_cast<std::int64_t>(k);
    status[k] = code >= 0 ? static_cast<std::int8_t>(code) : status_of(i);
    for (std::size_t m = 0; m < 2; ++m) values[m * count + k] = row_of(i)[m];
    if (i % 997 == 0) notes.emplace_back(i, "note of case " + std::to_string(i));
  }
  return seal_chunk(grid, chunk, 2, status, values, std::move(notes));
}

}  // namespace pcrf::cube
