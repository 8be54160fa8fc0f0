// The streaming fold (issue 38: the parts' chunks go into the cube while the run goes on):
// each chunk a worker reports kept is written from its part into the next fold's <cube>.partial
// at once (CubeWriter::stream_kept), and the end's fold writes only the rest. The cube equals the
// one assembled at the end; a checkpoint meanwhile only appends; a kill at any streaming step
// leaves the last fold, its journal and the parts, which --resume assembles; a streaming write
// that fails (a file size limit, as a full disk) drops the .partial and the end's fold assembles
// every chunk as before.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "case_axis_layout.hpp"
#include "kill_points.hpp"
#include "worker_chunks.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

namespace fs = std::filesystem;

constexpr std::int64_t kCases = 40000;  // chunks of 16 384, 16 384 and 7 232 (an edge chunk)

CubeLayout stream_layout() { return case_axis_layout(kCases, "stream-test"); }

fs::path partial_of(const fs::path& file) { return file.string() + ".partial"; }

int streamed_chunks = 0;
void count_streamed(CheckpointStep step) { streamed_chunks += step == CheckpointStep::kChunkStreamed; }

/// Two cubes hold the same status and the same metrics, case by case (NaN equal to NaN).
void expect_same_statuses_and_metrics(const CubeReader& a, const CubeReader& b) {
  EXPECT_EQ(a.read_status(), b.read_status());
  for (const char* metric : {"theta_max_rad", "impacts"}) {
    const auto x = a.read_metric(metric), y = b.read_metric(metric);
    ASSERT_EQ(x.size(), y.size());
    for (std::size_t k = 0; k < x.size(); ++k)
      ASSERT_TRUE(x[k] == y[k] || (std::isnan(x[k]) && std::isnan(y[k]))) << metric << " " << k;
  }
}

/// A run of three ranks as rank 0's writer sees it: rank 1 keeps chunk 0, rank 2 chunk 2 (every
/// case overturned), each reported and streamed; rank 0 stores chunk 1 case by case between
/// them and checkpoints; then the run closes.
void streamed_run(const fs::path& file) {
  CubeWriter writer(file, stream_layout(), OpenMode::kCreate);
  PartWriter one(part_path(file, 1), writer.part_header());
  PartWriter two(part_path(file, 2), writer.part_header());
  one.add(sealed_of(writer.grid(), 0));
  writer.stream_kept(0, 1);
  for (std::int64_t i = 16384; i < 32768; ++i) {
    writer.store(i, status_of(i), row_of(i));
    if (i % 997 == 0) writer.store_note(i, "note of case " + std::to_string(i));
  }
  writer.flush();  // a fold would be due (the cube holds nothing yet): it only appends
  two.add(sealed_of(writer.grid(), 2, 3));
  writer.stream_kept(2, 2);
  writer.close();
}

TEST(CubeStream, ChunksStreamedDuringTheRunGoInWithTheLastFold) {
  const auto dir = test::scratch_dir("stream_close");
  const auto file = dir / "c.h5";
  CubeWriter writer(file, stream_layout(), OpenMode::kCreate);
  PartWriter one(part_path(file, 1), writer.part_header());
  PartWriter two(part_path(file, 2), writer.part_header());
  one.add(sealed_of(writer.grid(), 0));
  streamed_chunks = 0;
  observe_checkpoints(count_streamed);
  writer.stream_kept(0, 1);
  EXPECT_EQ(streamed_chunks, 1);
  EXPECT_TRUE(fs::is_regular_file(partial_of(file))) << "the streaming fold is open";
  writer.stream_kept(0, 1);  // reported twice: written once
  writer.stream_kept(1, 1);  // not in the part: left to the end's fold
  EXPECT_EQ(streamed_chunks, 1);
  EXPECT_EQ(writer.done_count(), 0) << "the statuses join at the fold, as before";
  EXPECT_EQ(CubeReader(file).read_status(), std::vector<std::int8_t>(kCases, kStatusNotRun)) << "the cube is untouched";
  for (std::int64_t i = 16384; i < 32768; ++i) {
    writer.store(i, status_of(i), row_of(i));
    if (i % 997 == 0) writer.store_note(i, "note of case " + std::to_string(i));
  }
  writer.flush();
  EXPECT_TRUE(fs::exists(journal_path(file))) << "a checkpoint appends while the stream is open";
  EXPECT_TRUE(fs::is_regular_file(partial_of(file)));
  // A part read during the run is read on: the records its worker committed since.
  two.add(sealed_of(writer.grid(), 2, 3));
  writer.stream_kept(2, 2);
  one.add(sealed_of(writer.grid(), 1));  // a stray record of a chunk done (the journal's): never used
  EXPECT_EQ(streamed_chunks, 2);
  EXPECT_TRUE(writer.take_stream_note().empty());
  writer.close();
  observe_checkpoints(nullptr);
  EXPECT_EQ(streamed_chunks, 2) << "the end's fold writes what was streamed once";
  EXPECT_FALSE(fs::exists(partial_of(file)));
  EXPECT_FALSE(fs::exists(journal_path(file)));
  EXPECT_FALSE(fs::exists(part_path(file, 1)));
  EXPECT_FALSE(fs::exists(part_path(file, 2)));
  expect_chunks(file, {0, 1, 2}, 2);
  const auto status = CubeReader(file).read_status();
  EXPECT_EQ(writer.status(), status);
  EXPECT_EQ(writer.status_counts(), count_statuses(status));
  EXPECT_EQ(writer.done_count(), kCases);
  for (std::size_t c = 0; c < writer.grid().chunk_count(); ++c) EXPECT_EQ(writer.chunk_done(c), writer.grid().range(c).count);
}

// A part the stream read during the run is read on at the end from where the stream stopped:
// a chunk its worker kept after that and never reported (a run stopping) goes in at the close,
// written there, with the streamed one written once; the cube is the one assembled at the end.
TEST(CubeStream, AChunkKeptAfterTheStreamLastReadItsPartGoesInAtTheClose) {
  const auto dir = test::scratch_dir("stream_read_on");
  const auto file = dir / "c.h5";
  {
    CubeWriter writer(file, stream_layout(), OpenMode::kCreate);
    PartWriter one(part_path(file, 1), writer.part_header());
    one.add(sealed_of(writer.grid(), 0));
    streamed_chunks = 0;
    observe_checkpoints(count_streamed);
    writer.stream_kept(0, 1);
    one.add(sealed_of(writer.grid(), 2, 3));  // kept, not reported
    one.add(sealed_of(writer.grid(), 1));
    writer.close();
    observe_checkpoints(nullptr);
    EXPECT_EQ(streamed_chunks, 1);
    EXPECT_EQ(writer.done_count(), kCases);
    EXPECT_EQ(writer.status(), CubeReader(file).read_status());
  }
  EXPECT_FALSE(fs::exists(part_path(file, 1)));
  expect_chunks(file, {0, 1, 2}, 2);
  const auto end = dir / "end.h5";  // the same part, assembled at the end only
  {
    CubeWriter writer(end, stream_layout(), OpenMode::kCreate);
    PartWriter one(part_path(end, 1), writer.part_header());
    one.add(sealed_of(writer.grid(), 0));
    one.add(sealed_of(writer.grid(), 2, 3));
    one.add(sealed_of(writer.grid(), 1));
    writer.close();
  }
  const CubeReader a(file), b(end);
  expect_same_statuses_and_metrics(a, b);
}

// The same run without streaming (the parts taken at the end) gives the same cube.
TEST(CubeStream, TheStreamedCubeIsTheOneAssembledAtTheEnd) {
  const auto dir = test::scratch_dir("stream_same");
  streamed_run(dir / "streamed.h5");
  {
    const auto file = dir / "end.h5";
    CubeWriter writer(file, stream_layout(), OpenMode::kCreate);
    PartWriter(part_path(file, 1), writer.part_header()).add(sealed_of(writer.grid(), 0));
    for (std::int64_t i = 16384; i < 32768; ++i) {
      writer.store(i, status_of(i), row_of(i));
      if (i % 997 == 0) writer.store_note(i, "note of case " + std::to_string(i));
    }
    writer.flush();
    PartWriter(part_path(file, 2), writer.part_header()).add(sealed_of(writer.grid(), 2, 3));
    writer.close();
  }
  const CubeReader a(dir / "streamed.h5"), b(dir / "end.h5");
  expect_same_statuses_and_metrics(a, b);
  // The same notes; their order follows the folds (at several ranks, the scheduling) and is no answer.
  auto notes_a = a.read_notes(), notes_b = b.read_notes();
  std::sort(notes_a.begin(), notes_a.end());
  std::sort(notes_b.begin(), notes_b.end());
  EXPECT_EQ(notes_a, notes_b);
}

// A kill at each step of a streamed run (the new ones, and the end's fold through the stream)
// leaves the last fold whole, its journal and the parts (a stray .partial at most); --resume
// assembles every chunk kept, from the parts, and the journal's.
TEST(CubeStream, AKillAtEveryStreamingStepResumesToTheSameCube) {
  const auto dir = test::scratch_dir("stream_kills");
  using S = CheckpointStep;
  for (const KillPoint k : {KillPoint{S::kStreamOpened, 1, "opened"}, {S::kChunkStreamed, 1, "first"},
                            {S::kJournalSynced, 1, "appended"}, {S::kChunkStreamed, 2, "second"},
                            {S::kFoldWritten, 2, "fold_written"}, {S::kFoldRenamed, 2, "renamed"},
                            {S::kJournalRemoved, 2, "journal_removed"}, {S::kPartsRemoved, 1, "parts_removed"}}) {
    const auto file = dir / (std::string(k.name) + ".h5");
    ASSERT_TRUE(killed(run_killed_at(k, [&] { streamed_run(file); }))) << k.name << ": the run was not killed there";
    {
      const CubeReader reader(file);
      EXPECT_TRUE(reader.damage().empty()) << k.name;
    }
    const bool streaming = k.step == S::kStreamOpened || k.step == S::kChunkStreamed;
    if (streaming) {
      EXPECT_TRUE(fs::exists(partial_of(file))) << k.name << ": the streaming fold is left as it was";
    }
    {
      CubeWriter resumed(file, stream_layout(), OpenMode::kResume);
      resumed.close();
    }
    EXPECT_FALSE(fs::exists(partial_of(file))) << k.name;
    EXPECT_FALSE(fs::exists(part_path(file, 1))) << k.name;
    EXPECT_FALSE(fs::exists(part_path(file, 2))) << k.name;
    std::vector<std::size_t> chunks{0};
    const bool ended = k.occurrence == 2 || k.step == S::kPartsRemoved;  // chunk 2 kept and reported
    if (ended || k.step == S::kJournalSynced) chunks = {0, 1};
    if (ended) chunks.push_back(2);
    expect_chunks(file, chunks, 2);
  }
}

/// Writes beyond `bytes` fail in this process (EFBIG, as a full disk fails them) until reset.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &old_);
    old_handler_ = ::signal(SIGXFSZ, SIG_IGN);
    rlimit limited = old_;
    limited.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &limited);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &old_);
    ::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit old_{};
  sighandler_t old_handler_ = SIG_DFL;
};

// A streaming write that fails drops the .partial, says why once and stops the streaming; the
// end's fold then assembles every part's chunk as before: nothing is lost, nothing reported
// written that was not.
TEST(CubeStream, AStreamThatFailsFallsBackToTheAssemblyAtTheEnd) {
  const auto dir = test::scratch_dir("stream_fails");
  const auto file = dir / "c.h5";
  CubeWriter writer(file, stream_layout(), OpenMode::kCreate);
  PartWriter(part_path(file, 1), writer.part_header()).add(sealed_of(writer.grid(), 0));
  PartWriter(part_path(file, 2), writer.part_header()).add(sealed_of(writer.grid(), 2, 3));
  {
    const FileSizeLimit limit(fs::file_size(file));  // the copy fits, a chunk more does not
    writer.stream_kept(0, 1);
  }
  const std::string note = writer.take_stream_note();
  EXPECT_NE(note.find("at the end of the run instead"), std::string::npos) << note;
  EXPECT_TRUE(writer.take_stream_note().empty()) << "said once";
  EXPECT_FALSE(fs::exists(partial_of(file))) << "the failed streaming fold is dropped";
  writer.stream_kept(2, 2);  // streaming stopped for this run
  EXPECT_FALSE(fs::exists(partial_of(file)));
  for (std::int64_t i = 16384; i < 32768; ++i) {
    writer.store(i, status_of(i), row_of(i));
    if (i % 997 == 0) writer.store_note(i, "note of case " + std::to_string(i));
  }
  writer.close();
  expect_chunks(file, {0, 1, 2}, 2);
  EXPECT_EQ(writer.status(), CubeReader(file).read_status());
  EXPECT_EQ(writer.done_count(), kCases);
  EXPECT_FALSE(fs::exists(part_path(file, 1)));
}

/// Chunk 0 streamed from part 1, then `meanwhile` done to the streaming fold's .partial, then
/// chunk 2 (every status 3) streamed from part 2 and chunk 1's cases stored with their notes,
/// and the writer closed: the cube holds every chunk and the writer's statuses, and the
/// .partial is gone. Returns what the writer said of its stream.
std::string close_after(const fs::path& file, const std::function<void(const fs::path&)>& meanwhile) {
  CubeWriter writer(file, stream_layout(), OpenMode::kCreate);
  PartWriter(part_path(file, 1), writer.part_header()).add(sealed_of(writer.grid(), 0));
  writer.stream_kept(0, 1);
  EXPECT_TRUE(fs::exists(partial_of(file)));
  meanwhile(partial_of(file));
  PartWriter(part_path(file, 2), writer.part_header()).add(sealed_of(writer.grid(), 2, 3));
  writer.stream_kept(2, 2);
  for (std::int64_t i = 16384; i < 32768; ++i) {
    writer.store(i, status_of(i), row_of(i));
    if (i % 997 == 0) writer.store_note(i, "note of case " + std::to_string(i));
  }
  writer.close();
  EXPECT_FALSE(fs::exists(partial_of(file)));
  expect_chunks(file, {0, 1, 2}, 2);
  EXPECT_EQ(writer.status(), CubeReader(file).read_status());
  EXPECT_EQ(writer.status_counts(), count_statuses(writer.status()));
  return writer.take_stream_note();
}

// The end's fold through the streaming fold fails before its rename (its .partial was removed
// meanwhile: the sync by its name fails): it falls back to a fold from a new copy, which writes
// every chunk, the streamed one included, and says why once.
TEST(CubeStream, AStreamedFoldThatFailsFallsBackToANewCopy) {
  const auto file = test::scratch_dir("stream_fold_fails") / "c.h5";
  const std::string note = close_after(file, [](const fs::path& partial) { fs::remove(partial); });
  EXPECT_NE(note.find("at the end of the run instead"), std::string::npos);
}

// The streaming fold's .partial replaced during the run by another regular file (a copy: the
// same bytes, another inode, which a sync by the name would not tell): the last fold does not
// rename that file into the cube's place (the chunk streamed after, the cases stored after
// and the parts removed with the rename would be lost); it falls back to a new copy.
TEST(CubeStream, AStreamedFoldReplacedDuringTheRunIsNotRenamedIntoPlace) {
  const auto file = test::scratch_dir("stream_fold_replaced") / "c.h5";
  const std::string note = close_after(file, [](const fs::path& partial) {
    const fs::path other = partial.parent_path() / "other.h5";
    fs::copy_file(partial, other);
    fs::rename(other, partial);
  });
  EXPECT_NE(note.find("was replaced by another file"), std::string::npos);
}

// take_parts (an IDA's producer, before the last fold) after chunks were streamed: the
// statuses count at once and read_values sees every part's chunk, streamed or not.
TEST(CubeStream, TakenPartsReadEveryChunkStreamedOrNot) {
  const auto dir = test::scratch_dir("stream_take");
  const auto file = dir / "c.h5";
  CubeWriter writer(file, stream_layout(), OpenMode::kCreate);
  PartWriter(part_path(file, 1), writer.part_header()).add(sealed_of(writer.grid(), 0));
  writer.stream_kept(0, 1);
  PartWriter(part_path(file, 2), writer.part_header()).add(sealed_of(writer.grid(), 2, 3));
  writer.take_parts();
  EXPECT_EQ(writer.done_count(), 16384 + 7232);
  const auto theta = writer.read_values("theta_max_rad");
  EXPECT_EQ(theta[5], row_of(5)[0]);
  EXPECT_EQ(theta[32768 + 5], row_of(32768 + 5)[0]);
  EXPECT_TRUE(std::isnan(theta[16384 + 5]));
  writer.close();
  expect_chunks(file, {0, 2}, 2);
  EXPECT_EQ(writer.status(), CubeReader(file).read_status());
  EXPECT_EQ(writer.status_counts(), count_statuses(writer.status()));
}

}  // namespace
}  // namespace pcrf::cube
