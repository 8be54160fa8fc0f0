// A worker's sealed bytes (issue 38 item 5: its own side): sealed_bytes makes exactly the bytes
// that to_bytes makes of seal_chunk's chunk and seal_coordinate_values' pieces, every stream
// written straight into them; sealed_view_of_bytes reads them where they lie, as
// sealed_from_bytes reads them; a part written from the view holds the same bytes as one
// written from the chunk.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

/// A chunk's arguments as a worker gathers them: `metrics` values a case (noise, a ramp, one
/// repeated value, NaN where frames never lift), statuses (`code` for all when >= 0, else
/// mixed), a note every 97th case, and `pieces` coordinate pieces (noise; the last one short:
/// an edge piece).
struct Gathered {
  std::vector<std::int8_t> status;
  std::vector<double> values;
  std::vector<std::pair<std::int64_t, std::string>> notes;
  std::vector<std::vector<double>> piece_values;
  std::vector<PieceValues> pieces;
};

Gathered gathered(const ChunkGrid& grid, std::size_t chunk, std::size_t metrics, int code, std::size_t pieces,
                  std::size_t chunk_values) {
  const auto r = grid.range(chunk);
  const auto count = static_cast<std::size_t>(r.count);
  std::mt19937_64 draw(chunk * 7919 + metrics);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Gathered g;
  g.status.resize(count);
  g.values.resize(metrics * count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::int64_t i = r.first + static_cast<std::int64_t>(k);
    g.status[k] = code >= 0 ? static_cast<std::int8_t>(code) : static_cast<std::int8_t>(i % 13 == 0 ? 3 : 0);
    for (std::size_t m = 0; m < metrics; ++m)
      g.values[m * count + k] = m % 4 == 0 ? u(draw) : m % 4 == 1 ? 1e-3 * static_cast<double>(i) : m % 4 == 2 ? 0.25 : std::nan("");
    if (i % 97 == 0) g.notes.emplace_back(i, "note of case " + std::to_string(i));
  }
  for (std::size_t p = 0; p < pieces; ++p) {
    std::vector<double> v(p + 1 == pieces ? chunk_values / 3 + 1 : chunk_values);
    for (double& x : v) x = 10.0 * u(draw);
    g.piece_values.push_back(std::move(v));
  }
  for (std::size_t p = 0; p < pieces; ++p) g.pieces.push_back({p + 1, p, g.piece_values[p], chunk_values});
  return g;
}

/// The bytes as seal_chunk, seal_coordinate_values and to_bytes make them.
std::vector<char> bytes_by_chunk(const ChunkGrid& grid, std::size_t chunk, std::size_t metrics, const Gathered& g) {
  SealedChunk sealed = seal_chunk(grid, chunk, metrics, g.status, g.values, g.notes);
  for (const PieceValues& p : g.pieces)
    sealed.coordinates.push_back({p.coordinate, p.piece, seal_coordinate_values(p.values, p.chunk_values)});
  return to_bytes(sealed);
}

TEST(SealedBytes, AreTheBytesOfTheChunkSealedThenJoined) {
  const std::vector<ChunkGrid> grids{ChunkGrid({40000}),  // chunks of 16 384, and an edge chunk of 7 232
                                     ChunkGrid::of_chunk_shape({300, 70}, {128, 70})};  // 2-D, an edge along the first
  for (const ChunkGrid& grid : grids)
    for (std::size_t chunk = 0; chunk < grid.chunk_count(); ++chunk)
      for (const int code : {-1, 0})
        for (const std::size_t metrics : {std::size_t{1}, std::size_t{17}})
          for (const std::size_t pieces : {std::size_t{0}, std::size_t{3}}) {
            const Gathered g = gathered(grid, chunk, metrics, code, pieces, 2048);
            const std::vector<char> direct = sealed_bytes(grid, chunk, metrics, g.status, g.values, g.notes, g.pieces);
            const std::vector<char> expected = bytes_by_chunk(grid, chunk, metrics, g);
            ASSERT_EQ(direct, expected) << "chunk " << chunk << " of " << grid.chunk_count() << ", code " << code << ", "
                                        << metrics << " metrics, " << pieces << " pieces";
            // The pieces' values in buffers of a whole chunk each, with stale values after
            // them, padded and sealed in place: the same bytes.
            std::vector<std::vector<double>> rooms;
            std::vector<PieceValues> in_place = g.pieces;
            for (PieceValues& p : in_place) {
              rooms.emplace_back(p.chunk_values, 7.5);
              std::copy(p.values.begin(), p.values.end(), rooms.back().begin());
              p.room = rooms.back();
              p.values = p.room.first(p.values.size());
            }
            ASSERT_EQ(sealed_bytes(grid, chunk, metrics, g.status, g.values, g.notes, in_place), expected);
          }
  const ChunkGrid grid({40000});
  const Gathered g = gathered(grid, 1, 2, -1, 1, 2048);
  EXPECT_THROW(sealed_bytes(grid, 3, 2, g.status, g.values, g.notes, g.pieces), std::invalid_argument);
  EXPECT_THROW(sealed_bytes(grid, 2, 2, g.status, g.values, g.notes, g.pieces), std::invalid_argument);  // 7 232 cases
  std::vector<PieceValues> too_long{{1, 0, g.values, 16}};
  EXPECT_THROW(sealed_bytes(grid, 1, 2, g.status, g.values, g.notes, too_long), std::invalid_argument);
}

TEST(SealedBytes, AViewReadsWhatSealedFromBytesReadsWhereTheBytesLie) {
  const ChunkGrid grid({40000});
  const Gathered g = gathered(grid, 2, 3, -1, 2, 4096);
  const std::vector<char> bytes = sealed_bytes(grid, 2, 3, g.status, g.values, g.notes, g.pieces);
  const SealedChunkView view = sealed_view_of_bytes(bytes, grid, 3, "test");
  const SealedChunk copy = sealed_from_bytes(bytes, grid, 3, "test");
  const auto within = [&bytes](const void* p) {
    return static_cast<const char*>(p) >= bytes.data() && static_cast<const char*>(p) < bytes.data() + bytes.size();
  };
  EXPECT_EQ(view.chunk, copy.chunk);
  EXPECT_TRUE(within(view.status.data()));
  EXPECT_EQ(std::vector<std::int8_t>(view.status.begin(), view.status.end()), copy.status);
  ASSERT_EQ(view.filtered.size(), copy.filtered.size());
  for (std::size_t v = 0; v < view.filtered.size(); ++v) {
    EXPECT_TRUE(within(view.filtered[v].data()));
    EXPECT_EQ(std::vector<char>(view.filtered[v].begin(), view.filtered[v].end()), copy.filtered[v]);
  }
  ASSERT_EQ(view.notes.size(), copy.notes.size());
  ASSERT_FALSE(view.notes.empty());
  for (std::size_t n = 0; n < view.notes.size(); ++n) {
    EXPECT_EQ(view.notes[n].first, copy.notes[n].first);
    EXPECT_EQ(view.notes[n].second, copy.notes[n].second);
  }
  ASSERT_EQ(view.coordinates.size(), 2u);
  for (std::size_t p = 0; p < 2; ++p) {
    EXPECT_EQ(view.coordinates[p].coordinate, copy.coordinates[p].coordinate);
    EXPECT_EQ(view.coordinates[p].piece, copy.coordinates[p].piece);
    EXPECT_EQ(std::vector<char>(view.coordinates[p].filtered.begin(), view.coordinates[p].filtered.end()),
              copy.coordinates[p].filtered);
  }
  // Refused as sealed_from_bytes refuses them.
  EXPECT_THROW(sealed_view_of_bytes(bytes, grid, 4, "test"), CubeError);
  EXPECT_THROW(sealed_view_of_bytes(bytes, ChunkGrid({10}), 3, "test"), CubeError);
  for (const std::size_t cut : {std::size_t{1}, std::size_t{3}, bytes.size() / 2}) {
    const std::vector<char> shorter(bytes.begin(), bytes.end() - static_cast<std::ptrdiff_t>(cut));
    EXPECT_THROW(sealed_view_of_bytes(shorter, grid, 3, "test"), CubeError) << cut;
  }
  std::vector<char> longer = bytes;
  longer.push_back(0);
  EXPECT_THROW(sealed_view_of_bytes(longer, grid, 3, "test"), CubeError);
}

TEST(SealedBytes, APartWrittenFromTheViewHoldsTheBytesWrittenFromTheChunk) {
  const auto dir = test::scratch_dir("sealed_bytes_part");
  const ChunkGrid grid({40000});
  const PartHeader header{42, 40000, 3, "sealed-bytes-test"};
  {
    PartWriter by_chunk(dir / "c.h5.part-1", header), by_view(dir / "c.h5.part-2", header);
    for (const std::size_t chunk : {std::size_t{2}, std::size_t{0}, std::size_t{1}}) {
      const Gathered g = gathered(grid, chunk, 3, chunk == 0 ? 0 : -1, chunk, 4096);
      const std::vector<char> bytes = sealed_bytes(grid, chunk, 3, g.status, g.values, g.notes, g.pieces);
      by_chunk.add(sealed_from_bytes(bytes, grid, 3, "test"));
      by_view.add(sealed_view_of_bytes(bytes, grid, 3, "test"));
    }
  }
  const std::string one = test::read_file(dir / "c.h5.part-1"), two = test::read_file(dir / "c.h5.part-2");
  EXPECT_GT(one.size(), 3 * 1000u);
  EXPECT_EQ(one, two);
}

}  // namespace
}  // namespace pcrf::cube
