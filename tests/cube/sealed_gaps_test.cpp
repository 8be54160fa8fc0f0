// A sealed chunk with cases not run (issue 38: an IDA's chunk searched whole by its worker, the
// points past each curve's last run not run): journaled by rank 0 or kept in a worker's part, it
// reaches the cube with those cases not run and NaN; --resume reads it from the journal and the
// part (its statuses, and its values through read_values) instead of setting either aside; the
// parts of a run are taken before its end when asked (take_parts), so that a producer of side
// variables reads their values. A record of cases still never holds not_run
// (cube_journal_test's forgeries).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "case_axis_layout.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

namespace fs = std::filesystem;

constexpr std::int64_t kCases = 40000;  // chunks of 16 384, 16 384 and 7 232

CubeLayout gaps_layout() { return case_axis_layout(kCases, "gaps-test"); }

/// Case i is run unless i % 4 == 3 (a curve of four points whose last is never run).
bool run_case(std::int64_t i) { return i % 4 != 3; }
std::int8_t status_of(std::int64_t i) { return i % 8 == 2 ? 3 : 0; }
double theta_of(std::int64_t i) { return 1e-5 * static_cast<double>(i); }

/// Chunk `chunk` sealed with its cases not run left out (status not_run, NaN).
SealedChunk sealed_with_gaps(const ChunkGrid& grid, std::size_t chunk) {
  const auto r = grid.range(chunk);
  const auto count = static_cast<std::size_t>(r.count);
  std::vector<std::int8_t> status(count, kStatusNotRun);
  std::vector<double> values(2 * count, std::nan(""));
  for (std::size_t k = 0; k < count; ++k) {
    const std::int64_t i = r.first + static_cast<std::int64_t>(k);
    if (!run_case(i)) continue;
    status[k] = status_of(i);
    values[k] = theta_of(i);
    values[count + k] = static_cast<double>(i % 5);
  }
  return seal_chunk(grid, chunk, 2, status, values, {});
}

/// Every case of `chunks` as sealed_with_gaps made it; the others not run.
void expect_gaps(const std::vector<std::int8_t>& status, const std::vector<double>& theta, const ChunkGrid& grid,
                 const std::vector<std::size_t>& chunks) {
  std::size_t wrong = 0, not_run = 0;
  for (std::size_t c = 0; c < grid.chunk_count(); ++c) {
    const bool stored = std::find(chunks.begin(), chunks.end(), c) != chunks.end();
    const auto r = grid.range(c);
    for (std::int64_t i = r.first; i < r.first + r.count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (stored && run_case(i)) {
        wrong += status[k] != status_of(i) || theta[k] != theta_of(i);
      } else {
        wrong += status[k] != kStatusNotRun || !std::isnan(theta[k]);
        ++not_run;
      }
    }
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(not_run, 0u);
}

TEST(SealedGaps, AChunkWithCasesNotRunReachesTheCubeFromThePartAndTheJournal) {
  const auto dir = test::scratch_dir("sealed_gaps");
  const auto file = dir / "c.h5";
  const ChunkGrid grid(gaps_layout().shape());
  {
    CubeWriter writer(file, gaps_layout(), OpenMode::kCreate);
    writer.flush();  // the new cube's first fold: later checkpoints append to the journal
    {
      PartWriter part(part_path(file, 1), writer.part_header());  // a worker rank's chunk
      part.add(sealed_with_gaps(grid, 0));
    }
    writer.store_sealed(sealed_with_gaps(grid, 2));  // rank 0's own worker thread's chunk
    writer.append();                                 // journaled as a sealed record
    EXPECT_EQ(writer.done_count(), 7232 - 7232 / 4);
    // A run killed here: the journal and the part hold the two chunks; --resume replays both.
  }
  ASSERT_TRUE(fs::exists(journal_path(file)));
  {
    CubeWriter resumed(file, gaps_layout(), OpenMode::kResume);
    EXPECT_TRUE(resumed.resume_notes().empty()) << resumed.resume_notes().front();
    expect_gaps(resumed.status(), resumed.read_values("theta_max_rad"), grid, {0, 2});
    resumed.close();
  }
  EXPECT_FALSE(fs::exists(part_path(file, 1)));
  const CubeReader reader(file);
  expect_gaps(reader.read_status(), reader.read_metric("theta_max_rad"), grid, {0, 2});
}

TEST(SealedGaps, TheRunsPartsAreTakenBeforeItsEndWhenAsked) {
  const auto dir = test::scratch_dir("sealed_gaps_take");
  const auto file = dir / "c.h5";
  const ChunkGrid grid(gaps_layout().shape());
  CubeWriter writer(file, gaps_layout(), OpenMode::kCreate);
  {
    PartWriter part(part_path(file, 2), writer.part_header());
    part.add(sealed_with_gaps(grid, 1));
  }
  EXPECT_EQ(writer.done_count(), 0) << "a part of this run is the writer's only once taken";
  writer.take_parts();
  expect_gaps(writer.status(), writer.read_values("theta_max_rad"), grid, {1});
  writer.close();  // takes no part twice
  EXPECT_FALSE(fs::exists(part_path(file, 2)));
  const CubeReader reader(file);
  expect_gaps(reader.read_status(), reader.read_metric("theta_max_rad"), grid, {1});
}

}  // namespace
}  // namespace pcrf::cube
