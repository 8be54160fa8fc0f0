// A metric read for a range of chunks (CubeWriter::read_values(metric, first_chunk, end_chunk),
// what rank 0 reads an IDA's values by, a block of chunks at a time) is the slice of the whole
// read_values(metric) over those chunks, whatever its values come from: the file (a fold), the
// journal (records of cases and a sealed chunk), a rank's part taken, and pending cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "case_axis_layout.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

constexpr std::int64_t kCases = 70000;  // chunks of 16 384 (four) and an edge chunk of 4 464

CubeLayout ranged_layout() { return case_axis_layout(kCases, "ranged-values-test"); }

/// The value of case i stored by source `source` (1: file, 2: journal, 3: sealed, 4: part,
/// 5: pending): each source's values differ, so that a wrong overlay shows.
double theta_rad(std::int64_t i, int source) { return 1e-6 * static_cast<double>(i) + static_cast<double>(source); }
std::vector<double> row(std::int64_t i, int source) { return {theta_rad(i, source), static_cast<double>(source)}; }

/// Chunk `chunk` sealed whole with the values of `source`.
SealedChunk sealed_chunk_of(const ChunkGrid& grid, std::size_t chunk, int source) {
  const auto r = grid.range(chunk);
  const auto count = static_cast<std::size_t>(r.count);
  std::vector<std::int8_t> status(count, 0);
  std::vector<double> values(2 * count);
  for (std::size_t k = 0; k < count; ++k) {
    values[k] = theta_rad(r.first + static_cast<std::int64_t>(k), source);
    values[count + k] = static_cast<double>(source);
  }
  return seal_chunk(grid, chunk, 2, status, values, {});
}

/// Bit for bit (NaN equal to NaN): how many values differ.
std::size_t differing(const std::vector<double>& a, const double* b) {
  std::size_t wrong = 0;
  for (std::size_t k = 0; k < a.size(); ++k) wrong += std::memcmp(&a[k], b + k, sizeof(double)) != 0;
  return wrong;
}

TEST(RangedValues, ARangeOfChunksIsTheSliceOfTheWholeReadWhateverItsSource) {
  const auto dir = test::scratch_dir("ranged_values");
  const auto file = dir / "c.h5";
  const ChunkGrid grid(ranged_layout().shape());
  ASSERT_EQ(grid.chunk_count(), 5u);
  CubeWriter writer(file, ranged_layout(), OpenMode::kCreate);
  for (std::int64_t i = 0; i < 20000; i += 3) writer.store(i, 0, row(i, 1));  // chunks 0 and 1
  writer.flush();  // the new cube's first fold: in the file
  for (std::int64_t i = 16384; i < 30000; i += 5) writer.store(i, 0, row(i, 2));  // over the file's in chunk 1
  writer.store_sealed(sealed_chunk_of(grid, 2, 3));
  writer.append();  // journaled: records of cases and a sealed chunk
  {
    PartWriter part(part_path(file, 1), writer.part_header());  // a worker rank's edge chunk
    part.add(sealed_chunk_of(grid, 4, 4));
  }
  writer.take_parts();
  for (std::int64_t i = 1; i < 16384; i += 7) writer.store(i, 0, row(i, 5));      // pending over the file's
  for (std::int64_t i = 49152; i < 60000; i += 11) writer.store(i, 0, row(i, 5));  // pending in chunk 3

  const auto whole = writer.read_values("theta_max_rad");
  ASSERT_EQ(whole.size(), static_cast<std::size_t>(kCases));
  int sources_seen = 0;
  for (int source = 1; source <= 5; ++source)
    sources_seen += std::any_of(whole.begin(), whole.end(), [&](double v) { return v >= source && v < source + 1; });
  EXPECT_EQ(sources_seen, 5) << "every source's values are in the cube";
  EXPECT_TRUE(std::isnan(whole[60001])) << "a case never stored";
  EXPECT_EQ(whole[3], theta_rad(3, 1));            // the file's
  EXPECT_EQ(whole[15], theta_rad(15, 5));          // pending over the file's
  EXPECT_EQ(whole[16384], theta_rad(16384, 2));    // the journal's cases
  EXPECT_EQ(whole[32768], theta_rad(32768, 3));    // the journal's sealed chunk
  EXPECT_EQ(whole[49152], theta_rad(49152, 5));    // pending
  EXPECT_EQ(whole[69999], theta_rad(69999, 4));    // the part's edge chunk

  const std::vector<std::pair<std::size_t, std::size_t>> ranges{{0, 5}, {0, 1}, {1, 3}, {2, 5}, {3, 4}, {4, 5}, {2, 2}};
  for (const auto& [first, end] : ranges) {
    const auto slice = writer.read_values("theta_max_rad", first, end);
    const std::int64_t from = first < end ? grid.range(first).first : 0;
    const std::int64_t to = first < end ? grid.range(end - 1).first + grid.range(end - 1).count : 0;
    ASSERT_EQ(slice.size(), static_cast<std::size_t>(to - from)) << "chunks [" << first << ", " << end << ")";
    EXPECT_EQ(differing(slice, whole.data() + from), 0u) << "chunks [" << first << ", " << end << ")";
  }
  const auto impacts = writer.read_values("impacts", 3, 5);
  EXPECT_EQ(impacts[49152 - 49152], 5.0);
  EXPECT_EQ(impacts.back(), 4.0);
  EXPECT_THROW((void)writer.read_values("theta_max_rad", 4, 6), CubeError);
  EXPECT_THROW((void)writer.read_values("theta_max_rad", 3, 2), CubeError);
  EXPECT_THROW((void)writer.read_values("no_such_metric", 0, 1), CubeError);
  writer.close();
}

}  // namespace
}  // namespace pcrf::cube
