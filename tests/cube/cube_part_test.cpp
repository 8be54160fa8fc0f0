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
#include <string>
#include <vector>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

namespace fs = std::filesystem;

constexpr std::int64_t kCases = 40000;  // chunks of 16 384, 16 384 and 7 232 (an edge chunk)

CubeLayout part_layout() {
  CubeLayout l;
  l.dimensions = {{"case", static_cast<std::size_t>(kCases)}};
  Coordinate index{"case", "case", "", "", {}, {}, false, true};
  for (std::int64_t i = 0; i < kCases; ++i) index.numbers.push_back(static_cast<double>(i));
  l.coordinates = {index};
  l.metrics = {{"theta_max_rad", "rad", ""}, {"impacts", "1", ""}};
  l.status_flags = {{0, "at_rest"}, {3, "overturned"}};
  l.attributes = {{kFingerprintName, std::string("part-test")}};
  return l;
}

std::vector<double> row_of(std::int64_t i) { return {1e-5 * static_cast<double>(i), static_cast<double>(i % 7)}; }
std::int8_t status_of(std::int64_t i) { return i % 11 == 0 ? 3 : 0; }

/// Chunk `chunk` computed whole and sealed, as a worker does it (`code`: every status, when set).
SealedChunk sealed_of(const ChunkGrid& grid, std::size_t chunk, int code = -1) {
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

/// The cases of `chunks` hold what row_of and status_of say, the others are not run; every
/// note of a case stored is there once.
void expect_chunks(const fs::path& file, const std::vector<std::size_t>& chunks) {
  const CubeReader reader(file);
  const ChunkGrid grid(reader.layout().shape());
  const auto status = reader.read_status();
  const auto theta = reader.read_metric("theta_max_rad");
  std::size_t wrong = 0, notes_expected = 0;
  for (std::size_t c = 0; c < grid.chunk_count(); ++c) {
    const bool stored = std::find(chunks.begin(), chunks.end(), c) != chunks.end();
    const auto r = grid.range(c);
    for (std::int64_t i = r.first; i < r.first + r.count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (stored) {
        wrong += status[k] != status_of(i) || theta[k] != row_of(i)[0];
        notes_expected += i % 997 == 0;
      } else {
        wrong += status[k] != kStatusNotRun || !std::isnan(theta[k]);
      }
    }
  }
  EXPECT_EQ(wrong, 0u) << file;
  EXPECT_EQ(reader.read_notes().size(), notes_expected);
}

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

TEST(CubePart, AKillAfterTheFoldLeavesPartsTheResumeSkipsAndRemoves) {
  const auto dir = test::scratch_dir("part_kill");
  const auto file = dir / "c.h5";
  make_cube(file);
  {
    PartWriter part(part_path(file, 1), header_of(file));
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
    EXPECT_TRUE(fs::exists(part_path(file, 1)));
    expect_chunks(file, step == CheckpointStep::kFoldWritten ? std::vector<std::size_t>{1} : std::vector<std::size_t>{1, 2});
  }
  {
    CubeWriter resumed(file, part_layout(), OpenMode::kResume);
    EXPECT_EQ(resumed.done_count(), 16384 + 7232);
    EXPECT_FALSE(fs::exists(part_path(file, 1)));
    resumed.close();
  }
  expect_chunks(file, {1, 2});
}

TEST(CubePart, AForgedPartIsSetAsideAndItsCasesComputedAgain) {
  const auto dir = test::scratch_dir("part_forged");
  const auto file = dir / "c.h5";
  make_cube(file);
  const ChunkGrid grid(part_layout().shape());
  {
    PartWriter part(part_path(file, 1), header_of(file));
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
    EXPECT_NE(resumed.resume_notes()[0].find("set aside as " + part_path(file, 1).string() + ".set-aside-1"),
              std::string::npos);
    EXPECT_NE(resumed.resume_notes()[1].find("is not a part of this cube"), std::string::npos) << resumed.resume_notes()[1];
    resumed.close();
  }
  EXPECT_TRUE(fs::exists(part_path(file, 1).string() + ".set-aside-1"));
  EXPECT_TRUE(fs::exists(part_path(file, 2).string() + ".set-aside-1"));
  EXPECT_FALSE(fs::exists(part_path(file, 1)));
  expect_chunks(file, {1});
}

TEST(CubePart, ATornTailIsDroppedAndSaid) {
  const auto dir = test::scratch_dir("part_torn");
  const auto file = dir / "c.h5";
  make_cube(file);
  const ChunkGrid grid(part_layout().shape());
  {
    PartWriter part(part_path(file, 1), header_of(file));
    part.add(sealed_of(grid, 0));
    part.add(sealed_of(grid, 2));
  }
  fs::resize_file(part_path(file, 1), fs::file_size(part_path(file, 1)) - 9);  // a kill in the middle of the last append
  {
    CubeWriter resumed(file, part_layout(), OpenMode::kResume);
    EXPECT_EQ(resumed.done_count(), 2 * 16384);
    ASSERT_EQ(resumed.resume_notes().size(), 1u);
    EXPECT_NE(resumed.resume_notes()[0].find("are dropped"), std::string::npos) << resumed.resume_notes()[0];
    resumed.close();
  }
  expect_chunks(file, {0, 1});
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
}

}  // namespace
}  // namespace pcrf::cube
