// Ranks' parts (issue 38): a worker rank's sealed chunks kept beside the cube in its own part
// go into the cube at the writer's last fold, or at the first fold of a --resume, and the parts
// go; a part is untrusted input: a forged or foreign one is set aside (its cases computed
// again), a torn tail dropped and said, a chunk the cube holds already skipped; a symbolic
// link at a part name is refused before anything is written.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "case_axis_layout.hpp"
#include "worker_chunks.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

namespace fs = std::filesystem;

constexpr std::int64_t kCases = 40000;  // chunks of 16 384, 16 384 and 7 232 (an edge chunk)

CubeLayout part_layout() { return case_axis_layout(kCases, "part-test"); }

/// A cube whose middle chunk (1) was stored case by case and folded.
void make_cube(const fs::path& file) {
  CubeWriter writer(file, part_layout(), OpenMode::kCreate);
  for (std::int64_t i = 16384; i < 32768; ++i) {
    writer.store(i, status_of(i), row_of(i));
    if (i % 997 == 0) writer.store_note(i, "note of case " + std::to_string(i));
  }
  writer.close();
}

PartHeader header_of(const fs::path& file) { return part_header_of(CubeReader(file).layout()); }

TEST(CubePart, ThePartsOfARunGoInAtItsLastFoldAndGo) {
  const auto dir = test::scratch_dir("part_close");
  const auto file = dir / "c.h5";
  CubeWriter writer(file, part_layout(), OpenMode::kCreate);
  EXPECT_NE(writer.part_header().id, 0);
  {  // two workers keep a chunk each while rank 0 stores the middle one case by case
    PartWriter one(part_path(file, 1), writer.part_header());
    one.add(sealed_of(writer.grid(), 0));
    PartWriter two(part_path(file, 2), writer.part_header());
    two.add(sealed_of(writer.grid(), 2));
    EXPECT_THROW(PartWriter(part_path(file, 2), writer.part_header()), CubeError) << "made exclusively";
  }
  for (std::int64_t i = 16384; i < 32768; ++i) {
    writer.store(i, status_of(i), row_of(i));
    if (i % 997 == 0) writer.store_note(i, "note of case " + std::to_string(i));
  }
  writer.flush();  // an in-run fold leaves the parts alone
  EXPECT_TRUE(fs::exists(part_path(file, 1)));
  EXPECT_EQ(writer.done_count(), 16384);
  writer.close();
  EXPECT_EQ(writer.done_count(), kCases);
  EXPECT_FALSE(fs::exists(part_path(file, 1)));
  EXPECT_FALSE(fs::exists(part_path(file, 2)));
  expect_chunks(file, {0, 1, 2});
}

TEST(CubePart, AStoppedRunsPartsResumeAndAChunkTheCubeHoldsIsSkipped) {
  const auto dir = test::scratch_dir("part_resume");
  const auto file = dir / "c.h5";
  make_cube(file);
  const ChunkGrid grid(part_layout().shape());
  {
    PartWriter part(part_path(file, 3), header_of(file));
    part.add(sealed_of(grid, 0));
    part.add(sealed_of(grid, 1, 3));  // chunk 1 is in the cube already: this record is not used
  }
  {
    CubeWriter resumed(file, part_layout(), OpenMode::kResume);
    EXPECT_EQ(resumed.done_count(), 2 * 16384);
    EXPECT_TRUE(resumed.resume_notes().empty());
    EXPECT_FALSE(fs::exists(part_path(file, 3))) << "taken by the first fold of the resume";
    resumed.close();
  }
  expect_chunks(file, {0, 1});
}

/// A resume's first fold killed at kFoldWritten and kJournalRemoved, with rank `rank`'s part.
void expect_kill_after_fold_skips_and_removes(int rank) {
  const auto dir = test::scratch_dir("part_kill_" + std::to_string(rank));
  const auto file = dir / "c.h5";
  make_cube(file);
  {
    PartWriter part(part_path(file, rank), header_of(file));
    part.add(sealed_of(ChunkGrid(part_layout().shape()), 2));
  }
  for (const auto step : {CheckpointStep::kFoldWritten, CheckpointStep::kJournalRemoved}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      static CheckpointStep at;
      at = step;
      observe_checkpoints([](CheckpointStep s) {
        if (s == at) ::_exit(7);
      });
      CubeWriter resumed(file, part_layout(), OpenMode::kResume);  // its first fold takes the part
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 7);
    EXPECT_TRUE(fs::exists(part_path(file, rank)));
    expect_chunks(file, step == CheckpointStep::kFoldWritten ? std::vector<std::size_t>{1} : std::vector<std::size_t>{1, 2});
  }
  {
    CubeWriter resumed(file, part_layout(), OpenMode::kResume);
    EXPECT_EQ(resumed.done_count(), 16384 + 7232);
    EXPECT_FALSE(fs::exists(part_path(file, rank)));
    resumed.close();
  }
  expect_chunks(file, {1, 2});
}

TEST(CubePart, AKillAfterTheFoldLeavesPartsTheResumeSkipsAndRemoves) {
  expect_kill_after_fold_skips_and_removes(1);
  expect_kill_after_fold_skips_and_removes(0);  // rank 0's own worker thread's part
}

/// Rank `forged`'s part holds a status code 99 (its CRC holds), rank 2's is another cube's.
void expect_forged_part_set_aside(int forged) {
  const auto dir = test::scratch_dir("part_forged_" + std::to_string(forged));
  const auto file = dir / "c.h5";
  make_cube(file);
  const ChunkGrid grid(part_layout().shape());
  {
    PartWriter part(part_path(file, forged), header_of(file));
    part.add(sealed_of(grid, 0));
    part.add(sealed_of(grid, 2, 99));  // its CRC holds; the status code 99 is none of the cube's
  }
  {
    PartHeader other = header_of(file);
    other.id += 1;  // another cube's
    PartWriter part(part_path(file, 2), other);
    part.add(sealed_of(grid, 2));
  }
  {
    CubeWriter resumed(file, part_layout(), OpenMode::kResume);
    EXPECT_EQ(resumed.done_count(), 16384);
    ASSERT_EQ(resumed.resume_notes().size(), 2u);
    EXPECT_NE(resumed.resume_notes()[0].find("status code 99"), std::string::npos) << resumed.resume_notes()[0];
    EXPECT_NE(resumed.resume_notes()[0].find("set aside as " + part_path(file, forged).string() + ".set-aside-1"),
              std::string::npos);
    EXPECT_NE(resumed.resume_notes()[1].find("is not a part of this cube"), std::string::npos) << resumed.resume_notes()[1];
    resumed.close();
  }
  EXPECT_TRUE(fs::exists(part_path(file, forged).string() + ".set-aside-1"));
  EXPECT_TRUE(fs::exists(part_path(file, 2).string() + ".set-aside-1"));
  EXPECT_FALSE(fs::exists(part_path(file, forged)));
  expect_chunks(file, {1});
}

TEST(CubePart, AForgedPartIsSetAsideAndItsCasesComputedAgain) {
  expect_forged_part_set_aside(1);
  expect_forged_part_set_aside(0);  // rank 0's own worker thread's part
}

/// Rank `rank`'s part cut in the middle of its last chunk.
void expect_torn_tail_dropped(int rank) {
  const auto dir = test::scratch_dir("part_torn_" + std::to_string(rank));
  const auto file = dir / "c.h5";
  make_cube(file);
  const ChunkGrid grid(part_layout().shape());
  {
    PartWriter part(part_path(file, rank), header_of(file));
    part.add(sealed_of(grid, 0));
    part.add(sealed_of(grid, 2));
  }
  fs::resize_file(part_path(file, rank), fs::file_size(part_path(file, rank)) - 9);  // a kill in the middle of the last append
  {
    CubeWriter resumed(file, part_layout(), OpenMode::kResume);
    EXPECT_EQ(resumed.done_count(), 2 * 16384);
    ASSERT_EQ(resumed.resume_notes().size(), 1u);
    EXPECT_NE(resumed.resume_notes()[0].find("are dropped"), std::string::npos) << resumed.resume_notes()[0];
    resumed.close();
  }
  expect_chunks(file, {0, 1});
}

TEST(CubePart, ATornTailIsDroppedAndSaid) {
  expect_torn_tail_dropped(1);
  expect_torn_tail_dropped(0);
}

// A fold holds one part open at a time: a part released after it was read is reopened only
// when it is still the file read (not replaced, not cut).
TEST(CubePart, AReleasedPartIsReopenedOnlyWhenItIsTheFileRead) {
  const auto dir = test::scratch_dir("part_reopen");
  const auto file = dir / "c.h5";
  make_cube(file);
  const ChunkGrid grid(part_layout().shape());
  {
    PartWriter part(part_path(file, 1), header_of(file));
    part.add(sealed_of(grid, 0));
    PartWriter other(dir / "other", header_of(file));
    other.add(sealed_of(grid, 2));
  }
  const std::string header = part_header_payload(header_of(file));
  JournalReader read(part_path(file, 1), CubeReader(file).layout(), header);
  ASSERT_TRUE(read.current());
  const std::size_t record = read.sealed_chunks().at(0).front();
  read.release_file();
  read.reopen_file();
  EXPECT_EQ(read.sealed(record).status, sealed_of(grid, 0).status);
  read.release_file();
  fs::rename(dir / "other", part_path(file, 1));  // another file at its name since
  EXPECT_THROW(read.reopen_file(), CubeError);
}

TEST(CubePart, OverwriteRemovesTheOldParts) {
  const auto dir = test::scratch_dir("part_overwrite");
  const auto file = dir / "c.h5";
  make_cube(file);
  const auto old_id = header_of(file).id;
  {
    PartWriter part(part_path(file, 1), header_of(file));
    part.add(sealed_of(ChunkGrid(part_layout().shape()), 0));
  }
  {
    CubeWriter fresh(file, part_layout(), OpenMode::kOverwrite);
    EXPECT_EQ(fresh.done_count(), 0);
    EXPECT_NE(fresh.part_header().id, old_id) << "a new cube, a new part id";
    EXPECT_FALSE(fs::exists(part_path(file, 1)));
    fresh.close();
  }
  expect_chunks(file, {});
}

TEST(CubePart, ALinkAtAPartNameIsRefusedBeforeAnythingIsWritten) {
  const auto dir = test::scratch_dir("part_link");
  const auto file = dir / "c.h5";
  { std::ofstream(dir / "mine.txt") << "the user's"; }
  fs::create_symlink(dir / "mine.txt", part_path(file, 1));
  try {
    CubeWriter writer(file, part_layout(), OpenMode::kCreate);
    ADD_FAILURE() << "a symbolic link at a part name was accepted";
  } catch (const CubeError& e) {
    EXPECT_NE(std::string(e.what()).find(part_path(file, 1).string() + ": is a symbolic link"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(file));
  EXPECT_TRUE(fs::is_symlink(part_path(file, 1)));
  std::ifstream in(dir / "mine.txt");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "the user's");
  EXPECT_THROW(PartWriter(part_path(file, 1), PartHeader{1, kCases, 2, "part-test"}), CubeError);
  fs::remove(part_path(file, 1));
  fs::create_directory(part_path(file, 2));
  EXPECT_THROW(CubeWriter(file, part_layout(), OpenMode::kCreate), CubeError);
  fs::remove(part_path(file, 2));
  fs::create_symlink(dir / "mine.txt", part_path(file, 0));  // rank 0's part name too
  EXPECT_THROW(CubeWriter(file, part_layout(), OpenMode::kCreate), CubeError);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_TRUE(fs::is_symlink(part_path(file, 0)));
}

TEST(CubePart, APartIsNamedByItsRankFromZeroWithoutLeadingZeros) {
  const auto dir = test::scratch_dir("part_names");
  const auto file = dir / "c.h5";
  for (const char* name : {"c.h5.part-0", "c.h5.part-00", "c.h5.part-01", "c.h5.part-10", "c.h5.part-2", "c.h5.part-x",
                           "c.h5.part-", "d.h5.part-1"})
    std::ofstream(dir / name) << "x";
  EXPECT_EQ(part_files(file), (std::vector<fs::path>{part_path(file, 0), part_path(file, 2), part_path(file, 10)}));
}

// The rank a part's name gives (what the end's fold matches with the rank a chunk was streamed
// from) follows part_files' rule, and is nothing for a name that rule refuses.
TEST(CubePart, APartsRankIsTheOneItsNameGives) {
  const fs::path file = fs::path("dir") / "c.h5";
  for (const int rank : {0, 2, 10, 999999}) EXPECT_EQ(part_rank(file, part_path(file, rank)), rank);
  EXPECT_EQ(part_rank(file, fs::path("elsewhere") / "c.h5.part-7"), 7) << "by its name, as part_files finds it";
  for (const char* name : {"c.h5.part-00", "c.h5.part-01", "c.h5.part-x", "c.h5.part-", "d.h5.part-1", "c.h5.part-1000000",
                           "c.h5.part--1", "c.h5.part-+1", "c.h5.part-1 "})
    EXPECT_FALSE(part_rank(file, fs::path("dir") / name).has_value()) << name;
}

/// The sealed records of rank `rank`'s part of `file`, each chunk's statuses as a raw write
/// takes them: the code of a chunk whose status variable says one for all, else -2.
std::map<std::size_t, int> statuses_as_written(const fs::path& file, int rank) {
  const JournalReader read(part_path(file, rank), CubeReader(file).layout(), part_header_payload(header_of(file)), false);
  std::map<std::size_t, int> found;
  for (const auto& [chunk, records] : read.sealed_chunks())
    read.with_sealed(
        records.front(), [&, chunk = chunk](const SealedStatuses& s) { found[chunk] = s.alike ? s.code : -2; },
        [](std::size_t, const char*, std::size_t) {});
  return found;
}

// Rank 0's own worker thread keeps a part as the worker ranks do (at two ranks or more): it goes
// in at the run's last fold like theirs. The assembly counts a whole chunk whose cases all ended
// alike by its status variable, one comparison and one memset (a mixed chunk, or one at the
// cube's edge, case by case): the writer's statuses, counts per code and per chunk are then
// those of the cube.
TEST(CubePart, RankZerosPartGoesInAndAChunkOfOneCodeIsCountedWhole) {
  const auto dir = test::scratch_dir("part_zero");
  const auto file = dir / "c.h5";
  CubeWriter writer(file, part_layout(), OpenMode::kCreate);
  {
    PartWriter zero(part_path(file, 0), writer.part_header());
    zero.add(sealed_of(writer.grid(), 0, 0));  // every case at rest
    PartWriter one(part_path(file, 1), writer.part_header());
    one.add(sealed_of(writer.grid(), 1));     // mixed
    one.add(sealed_of(writer.grid(), 2, 3));  // one code, at the cube's edge
  }
  EXPECT_EQ(statuses_as_written(file, 0), (std::map<std::size_t, int>{{0, 0}}));
  EXPECT_EQ(statuses_as_written(file, 1), (std::map<std::size_t, int>{{1, -2}, {2, -2}}));
  EXPECT_EQ(writer.done_count(), 0) << "nothing counted before the parts go in";
  writer.close();
  EXPECT_FALSE(fs::exists(part_path(file, 0)));
  EXPECT_FALSE(fs::exists(part_path(file, 1)));
  const auto status = CubeReader(file).read_status();
  EXPECT_EQ(writer.status(), status);
  EXPECT_EQ(writer.status_counts(), count_statuses(status));
  EXPECT_EQ(writer.done_count(), kCases);
  for (std::size_t c = 0; c < writer.grid().chunk_count(); ++c) EXPECT_EQ(writer.chunk_done(c), writer.grid().range(c).count);
  std::int64_t overturned_in_1 = 0;  // chunk 1's mixed statuses: status_of
  for (std::int64_t i = 16384; i < 32768; ++i) overturned_in_1 += status_of(i) == 3;
  EXPECT_EQ(count_of(writer.status_counts(), 0), 2 * 16384 - overturned_in_1);
  EXPECT_EQ(count_of(writer.status_counts(), 3), overturned_in_1 + 7232);
}

// take_parts (a producer that reads every result before the last fold: an IDA's replay) counts
// the parts' statuses at once, each case's; close() then writes them without counting again.
TEST(CubePart, TakenPartsCountTheirStatusesAtOnce) {
  const auto dir = test::scratch_dir("part_take");
  const auto file = dir / "c.h5";
  CubeWriter writer(file, part_layout(), OpenMode::kCreate);
  PartWriter(part_path(file, 0), writer.part_header()).add(sealed_of(writer.grid(), 1));  // mixed
  PartWriter(part_path(file, 1), writer.part_header()).add(sealed_of(writer.grid(), 0, 0));
  writer.take_parts();
  EXPECT_EQ(writer.done_count(), 2 * 16384);
  for (std::int64_t i = 0; i < 2 * 16384; ++i)
    ASSERT_EQ(writer.status()[static_cast<std::size_t>(i)], i < 16384 ? 0 : status_of(i)) << i;
  EXPECT_EQ(writer.read_values("theta_max_rad")[16384 + 5], row_of(16384 + 5)[0]);
  writer.close();
  EXPECT_EQ(writer.done_count(), 2 * 16384);
  EXPECT_EQ(writer.status(), CubeReader(file).read_status());
  EXPECT_EQ(writer.status_counts(), count_statuses(writer.status()));
}

// At the run's end the writer counts what the cube receives: a record whose status variable
// says one code for every case while its statuses (its head) say otherwise is counted as its
// variable, which is what is written; a mixed record with a code the cube's flags do not name
// fails the assembly (the run reports it), as before.
TEST(CubePart, TheAssemblyCountsTheStatusesTheCubeReceives) {
  const auto dir = test::scratch_dir("part_close_forged");
  const auto file = dir / "c.h5";
  {
    CubeWriter writer(file, part_layout(), OpenMode::kCreate);
    SealedChunk forged = sealed_of(writer.grid(), 0, 0);
    forged.status[5] = 3;  // the head says one case overturned; the variable, all at rest
    PartWriter(part_path(file, 0), writer.part_header()).add(forged);
    writer.close();
    EXPECT_EQ(writer.status(), CubeReader(file).read_status());
    EXPECT_EQ(count_of(writer.status_counts(), 3), 0);
    EXPECT_EQ(writer.status()[5], 0);
  }
  const auto other = dir / "d.h5";
  CubeWriter writer(other, part_layout(), OpenMode::kCreate);
  PartWriter(part_path(other, 2), writer.part_header()).add(sealed_of(writer.grid(), 1, 99));
  try {
    writer.close();
    ADD_FAILURE() << "a status code 99 reached the cube";
  } catch (const CubeError& e) {
    EXPECT_NE(std::string(e.what()).find("status code 99"), std::string::npos) << e.what();
  }
  EXPECT_EQ(CubeReader(other).read_status(), std::vector<std::int8_t>(kCases, kStatusNotRun)) << "the last fold stays";
}

}  // namespace
}  // namespace pcrf::cube
