/// \file chunk_tiling.hpp
/// \brief What every chunk grid must be, checked by the chunk grid's tests and the cube file's.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_layout.hpp"

namespace pcrf::cube {

using Shape = std::vector<std::size_t>;

/// The chunks tile [0, cases) in order, each a hyperslab of its range, and chunk_of agrees.
inline void expect_tiles(const ChunkGrid& grid, const Shape& shape) {
  std::int64_t next = 0;
  for (std::size_t c = 0; c < grid.chunk_count(); ++c) {
    const auto r = grid.range(c);
    ASSERT_EQ(r.first, next) << "chunk " << c;
    std::int64_t volume = 1;
    for (std::size_t d = 0; d < shape.size(); ++d) {
      volume *= static_cast<std::int64_t>(r.extent[d]);
      EXPECT_LE(r.extent[d], grid.chunk_shape()[d]);
    }
    EXPECT_EQ(volume, r.count);
    EXPECT_EQ(unravel(r.first, shape), r.start);
    for (std::int64_t i = r.first; i < r.first + r.count; ++i) ASSERT_EQ(grid.chunk_of(i), c) << "case " << i;
    next += r.count;
  }
  std::int64_t total = 1;
  for (auto n : shape) total *= static_cast<std::int64_t>(n);
  EXPECT_EQ(next, total);
}

}  // namespace pcrf::cube
