// The chunk grid's groups (issue 38: Saltelli base samples stay whole within one chunk): where
// the cut falls on a dimension whose values come in groups, every chunk holds whole groups;
// the chunks still tile the cube as contiguous ranges and each case's chunk is the one whose
// range holds it; a grid is rebuilt exactly from its chunk shape (as a cube's file stores it),
// and a chunk shape that is not one of a grid is refused.
#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_layout.hpp"
#include "chunk_tiling.hpp"

namespace pcrf::cube {
namespace {

TEST(ChunkGridGroups, EveryChunkHoldsWholeGroupsWhereTheCutFallsOnTheirDimension) {
  // shape, target, the grouped dimension, its group
  for (const auto& [shape, target, dim, group] : std::vector<std::tuple<Shape, std::size_t, std::size_t, std::size_t>>{
           {{2, 1, 16384 * 5 * 2}, 16384, 2, 5},  // a Saltelli cube of d = 3, two records
           {{3, 2, 1000}, 64, 2, 7},              // 1000 frames are not whole groups of 7: the last piece is short
           {{4, 35}, 10, 1, 5},                   // 10 cases: 2 groups a chunk
           {{4, 35}, 3, 1, 5},                    // fewer than a group fit: one group, above the target
           {{5, 6, 12}, 20, 2, 12},               // the group is the whole dimension
           {{13, 9, 11}, 40, 2, 4}}) {
    Shape multiples(shape.size(), 1);
    multiples[dim] = group;
    const ChunkGrid grid(shape, target, multiples);
    SCOPED_TRACE(::testing::Message() << "shape " << shape[0] << "… target " << target << " group " << group);
    expect_tiles(grid, shape);
    for (std::size_t c = 0; c < grid.chunk_count(); ++c) {
      const auto r = grid.range(c);
      // Along the grouped dimension a chunk starts at a group's first value and ends at a
      // group's end (or the dimension's): no group has values in two chunks.
      EXPECT_EQ(r.start[dim] % group, 0u) << "chunk " << c;
      const std::size_t end = r.start[dim] + r.extent[dim];
      EXPECT_TRUE(end % group == 0 || end == shape[dim]) << "chunk " << c << " ends at " << end;
    }
  }
}

TEST(ChunkGridGroups, ASaltelliCubeOfThreeParametersIsCutIntoWholeBaseSamples) {
  const Shape shape{2, 1, 163840};  // 32 768 base samples of 5 frames, two records
  const ChunkGrid grid(shape, kChunkCases, {1, 1, 5});
  EXPECT_EQ(grid.chunk_shape(), (Shape{1, 1, 16380}));  // 3 276 base samples, not 16 384 frames
  EXPECT_EQ(grid.chunk_count(), 2u * 11u);
  EXPECT_EQ(grid.range(10).count, 163840 - 10 * 16380);  // the edge piece: 8 base samples
  EXPECT_EQ(grid.chunk_of(16380), 1u);
  EXPECT_EQ(grid.chunk_of(163840 + 16379), 11u);  // record 1's first piece
  // Without the group the cut splits base sample 3 276 (frames 16 380 … 16 384).
  EXPECT_EQ(ChunkGrid(shape).chunk_shape(), (Shape{1, 1, 16384}));
}

TEST(ChunkGridGroups, NothingChangesWhereTheGroupedDimensionIsWholeOrTheGroupIsOne) {
  for (const auto& [shape, target] : std::vector<std::pair<Shape, std::size_t>>{
           {{3, 4, 5}, 7}, {{13, 1, 9, 1, 1, 1, 1, 1, 1, 11}, 40}, {{2, 3}, 1000}, {{5}, 2}, {{1, 1, 100}, 30},
           {{300, 1, 5000}, 16384}}) {
    Shape ones(shape.size(), 1);
    EXPECT_EQ(ChunkGrid(shape, target, ones), ChunkGrid(shape, target));
    // A group on the last dimension changes nothing when a chunk holds that dimension whole.
    if (shape.back() <= target) {
      Shape grouped = ones;
      grouped.back() = shape.back();
      EXPECT_EQ(ChunkGrid(shape, target, grouped), ChunkGrid(shape, target));
    }
  }
}

TEST(ChunkGridGroups, AGridIsRebuiltFromItsChunkShapeAndOtherShapesAreRefused) {
  for (const auto& [shape, target, multiples] : std::vector<std::tuple<Shape, std::size_t, Shape>>{
           {{2, 1, 163840}, 16384, {1, 1, 5}}, {{3, 4, 5}, 7, {}}, {{2, 3}, 1000, {}}, {{5, 3}, 2, {1, 3}},
           {{1, 1, 100}, 30, {}}, {{13, 9, 11}, 40, {1, 1, 4}}}) {
    const ChunkGrid grid(shape, target, multiples);
    EXPECT_TRUE(ChunkGrid::valid_chunk_shape(shape, grid.chunk_shape()));
    const ChunkGrid rebuilt = ChunkGrid::of_chunk_shape(shape, grid.chunk_shape());
    EXPECT_EQ(rebuilt, grid);
    ASSERT_EQ(rebuilt.chunk_count(), grid.chunk_count());
    for (std::size_t c = 0; c < grid.chunk_count(); ++c) {
      EXPECT_EQ(rebuilt.range(c).first, grid.range(c).first);
      EXPECT_EQ(rebuilt.range(c).count, grid.range(c).count);
    }
    expect_tiles(rebuilt, shape);
  }
  EXPECT_FALSE(ChunkGrid::valid_chunk_shape({4, 5, 6}, {2, 1, 6}));  // two records, one value of the next: not contiguous
  EXPECT_FALSE(ChunkGrid::valid_chunk_shape({4, 5, 6}, {1, 5, 3}));  // part of the last, all of the one before
  EXPECT_FALSE(ChunkGrid::valid_chunk_shape({4, 5, 6}, {1, 1, 7}));  // beyond the dimension
  EXPECT_FALSE(ChunkGrid::valid_chunk_shape({4, 5, 6}, {1, 0, 6}));
  EXPECT_FALSE(ChunkGrid::valid_chunk_shape({4, 5, 6}, {1, 6}));
  EXPECT_TRUE(ChunkGrid::valid_chunk_shape({4, 5, 6}, {4, 5, 6}));  // one chunk
  EXPECT_THROW(ChunkGrid::of_chunk_shape({4, 5, 6}, {2, 1, 6}), std::invalid_argument);
  EXPECT_THROW(ChunkGrid({4, 5}, 10, {1}), std::invalid_argument);
  EXPECT_THROW(ChunkGrid({4, 5}, 10, {1, 0}), std::invalid_argument);
}

TEST(ChunkGridGroups, ALayoutsGridIsItsChunkShapeOrTheRuleWithoutGroups) {
  CubeLayout layout;
  layout.dimensions = {{"record", 2}, {"scale", 1}, {"case", 163840}};
  EXPECT_EQ(layout_grid(layout), ChunkGrid(layout.shape()));  // a cube of an earlier version
  layout.chunk_shape = {1, 1, 16380};
  EXPECT_EQ(layout_grid(layout).chunk_shape(), layout.chunk_shape);
  layout.chunk_shape = {2, 1, 16380};
  EXPECT_THROW((void)layout_grid(layout), std::invalid_argument);
}

}  // namespace
}  // namespace pcrf::cube
