// The writer's statuses (issue 38: rank 0 per chunk, not per case): whatever is set, case by
// case, chunk by chunk (alike or mixed) or all at once, the counts per code, the done count and
// each chunk's done count are those of a recount of every case's code.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/cube/status_book.hpp"

namespace pcrf::cube {
namespace {

/// What a StatusBook must say of its codes, counted case by case.
void expect_recounted(const StatusBook& book, const ChunkGrid& grid) {
  const auto& codes = book.codes();
  EXPECT_EQ(book.counts(), count_statuses(codes));
  std::int64_t done = 0;
  for (std::size_t c = 0; c < grid.chunk_count(); ++c) {
    const auto r = grid.range(c);
    std::int64_t in_chunk = 0;
    for (std::int64_t k = r.first; k < r.first + r.count; ++k) in_chunk += codes[static_cast<std::size_t>(k)] != kStatusNotRun;
    EXPECT_EQ(book.chunk_done(c), in_chunk) << "chunk " << c;
    done += in_chunk;
  }
  EXPECT_EQ(book.done(), done);
}

TEST(StatusBook, EveryWayOfSettingKeepsTheCountsOfARecount) {
  const ChunkGrid grid({5, 9000});  // five chunks of one row (9000 cases) each
  const std::size_t cases = 5 * 9000;
  StatusBook book(grid, cases);
  EXPECT_EQ(book.done(), 0);
  EXPECT_EQ(count_of(book.counts(), kStatusNotRun), static_cast<std::int64_t>(cases));
  expect_recounted(book, grid);
  std::mt19937 draw(5);
  std::uniform_int_distribution<int> code(-1, 7), pick(0, 3);
  for (int step = 0; step < 400; ++step) {
    const std::size_t chunk = static_cast<std::size_t>(draw() % grid.chunk_count());
    const auto r = grid.range(chunk);
    switch (pick(draw)) {
      case 0: {  // a case (not run again included)
        const std::int64_t index = r.first + static_cast<std::int64_t>(draw() % static_cast<unsigned>(r.count));
        book.set(chunk, index, static_cast<std::int8_t>(code(draw)));
        break;
      }
      case 1: {  // a chunk of mixed codes
        std::vector<std::int8_t> codes(static_cast<std::size_t>(r.count));
        for (auto& c : codes) c = static_cast<std::int8_t>(code(draw));
        book.set_chunk(chunk, codes);
        break;
      }
      case 2:  // a chunk of one code, given case by case
        book.set_chunk(chunk, std::vector<std::int8_t>(static_cast<std::size_t>(r.count), static_cast<std::int8_t>(code(draw))));
        break;
      default:
        book.set_chunk_to(chunk, static_cast<std::int8_t>(code(draw)));
    }
    expect_recounted(book, grid);
    if (::testing::Test::HasFailure()) return;
  }
  std::vector<std::int8_t> all(cases, 3);
  all[17] = kStatusNotRun;
  book.assign(all);
  EXPECT_EQ(book.codes(), all);
  EXPECT_EQ(book.done(), static_cast<std::int64_t>(cases) - 1);
  expect_recounted(book, grid);
  EXPECT_THROW(book.set_chunk(0, std::vector<std::int8_t>(3, 0)), std::invalid_argument);
  EXPECT_THROW(book.assign(std::vector<std::int8_t>(3, 0)), std::invalid_argument);
}

TEST(StatusBook, OnlyAChunkOfMixedCodesHoldsAByteACase) {
  const ChunkGrid grid = ChunkGrid::of_chunk_shape({4, 1000}, {1, 1000});  // four chunks of a row each
  StatusBook book(grid, 4000);
  EXPECT_EQ(book.mixed_chunks(), 0u);  // a new study: a code a chunk
  // Chunk 0 done case by case, all alike: mixed while it fills, one code once it is done.
  for (std::int64_t k = 0; k < 1000; ++k) {
    book.set(0, k, 2);
    if (k == 0 || k == 998) {
      EXPECT_EQ(book.mixed_chunks(), 1u) << "after case " << k;
    }
  }
  EXPECT_EQ(book.mixed_chunks(), 0u);
  // Chunk 1 done case by case, codes that differ: it keeps its bytes, until one code replaces them.
  for (std::int64_t k = 0; k < 1000; ++k) book.set(1, 1000 + k, static_cast<std::int8_t>(1 + k % 2));
  EXPECT_EQ(book.mixed_chunks(), 1u);
  book.set_chunk_to(1, 3);
  EXPECT_EQ(book.mixed_chunks(), 0u);
  std::vector<std::int8_t> mixed(1000, 4);
  mixed[7] = kStatusNotRun;
  book.set_chunk(2, mixed);
  EXPECT_EQ(book.mixed_chunks(), 1u);
  // Every way of reading a code agrees with the whole list.
  const auto all = book.codes();
  ASSERT_EQ(all.size(), 4000u);
  for (std::size_t i = 0; i < all.size(); ++i) ASSERT_EQ(book[i], all[i]) << "case " << i;
  std::vector<std::int8_t> scratch;
  const auto two = book.chunk_codes(2, scratch);
  EXPECT_EQ(std::vector<std::int8_t>(two.begin(), two.end()), mixed);
  const auto three = book.chunk_codes(3, scratch);
  EXPECT_EQ(std::vector<std::int8_t>(three.begin(), three.end()), std::vector<std::int8_t>(1000, kStatusNotRun));
  expect_recounted(book, grid);
  // A cube read back: a code a chunk where its cases are alike.
  book.assign(std::vector<std::int8_t>(4000, 5));
  EXPECT_EQ(book.mixed_chunks(), 0u);
  expect_recounted(book, grid);
  EXPECT_THROW(StatusBook(grid, 3999), std::invalid_argument);
}

}  // namespace
}  // namespace pcrf::cube
