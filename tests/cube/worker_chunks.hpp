/// \file worker_chunks.hpp
/// \brief What a worker computes for the part and streaming tests, over case_axis_layout's
/// two metrics: case i's row and status, and a chunk of them sealed as a worker seals it.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/sealed_chunk.hpp"

namespace pcrf::cube {

/// Case i's two metrics: theta_max_rad [rad] and impacts [1].
inline std::vector<double> row_of(std::int64_t i) { return {1e-5 * static_cast<double>(i), static_cast<double>(i % 7)}; }
/// Case i's status: overturned (3) every eleventh case, else at rest (0).
inline std::int8_t status_of(std::int64_t i) { return i % 11 == 0 ? 3 : 0; }

/// Chunk `chunk` computed whole and sealed, as a worker does it: case i's `metrics` values are
/// row(i), its status status(i); every 997th case carries a note.
template <class Row, class Status>
SealedChunk sealed_from(const ChunkGrid& grid, std::size_t chunk, std::size_t metrics, Row row, Status status_at) {
  const auto r = grid.range(chunk);
  const auto count = static_cast<std::size_t>(r.count);
  std::vector<std::int8_t> status(count);
  std::vector<double> values(metrics * count);
  std::vector<std::pair<std::int64_t, std::string>> notes;
  for (std::size_t k = 0; k < count; ++k) {
    const std::int64_t i = r.first + static_cast<std::int64_t>(k);
    status[k] = status_at(i);
    const std::vector<double> case_row = row(i);
    for (std::size_t m = 0; m < metrics; ++m) values[m * count + k] = case_row[m];
    if (i % 997 == 0) notes.emplace_back(i, "note of case " + std::to_string(i));
  }
  return seal_chunk(grid, chunk, metrics, status, values, std::move(notes));
}

/// Chunk `chunk` of row_of's two metrics and status_of's statuses (`code`: every status, when
/// set), sealed as a worker does it.
inline SealedChunk sealed_of(const ChunkGrid& grid, std::size_t chunk, int code = -1) {
  return sealed_from(grid, chunk, 2, row_of, [code](std::int64_t i) {
    return code >= 0 ? static_cast<std::int8_t>(code) : status_of(i);
  });
}

/// The cube at `file` reads without damage; the cases of `chunks` hold what row_of says, with
/// status_of's statuses but in `overturned` (a chunk sealed with every status 3); the others
/// are not run; every note of a case stored is there once.
inline void expect_chunks(const std::filesystem::path& file, const std::vector<std::size_t>& chunks,
                          std::size_t overturned = std::numeric_limits<std::size_t>::max()) {
  const CubeReader reader(file);
  EXPECT_TRUE(reader.damage().empty()) << file;
  const ChunkGrid grid(reader.layout().shape());
  const auto status = reader.read_status();
  const auto theta = reader.read_metric("theta_max_rad");
  const auto impacts = reader.read_metric("impacts");
  std::size_t wrong = 0, notes_expected = 0;
  for (std::size_t c = 0; c < grid.chunk_count(); ++c) {
    const bool stored = std::find(chunks.begin(), chunks.end(), c) != chunks.end();
    const auto r = grid.range(c);
    for (std::int64_t i = r.first; i < r.first + r.count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (stored) {
        wrong += status[k] != (c == overturned ? 3 : status_of(i)) || theta[k] != row_of(i)[0] || impacts[k] != row_of(i)[1];
        notes_expected += i % 997 == 0;
      } else {
        wrong += status[k] != kStatusNotRun || !std::isnan(theta[k]);
      }
    }
  }
  EXPECT_EQ(wrong, 0u) << file;
  EXPECT_EQ(reader.read_notes().size(), notes_expected) << file;
}

}  // namespace pcrf::cube
