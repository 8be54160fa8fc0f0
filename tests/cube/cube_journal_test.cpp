// The cube's journal (docs/checkpoint.md): checkpoints append to <cube>.journal and folds
// replace the cube; a torn or damaged journal is cut at its last good record, a forged one is
// a clear error; a process killed at every kill point of a checkpoint leaves a cube that
// resumes to the same results as an uninterrupted run.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <sys/stat.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_merge.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/io/record_log.hpp"
#include "kill_points.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

namespace fs = std::filesystem;

/// 5 × 10 000 cases: five chunks of 10 000 (ChunkGrid), so records of several chunks.
CubeLayout journal_layout() {
  CubeLayout l;
  l.dimensions = {{"row", 5}, {"case", 10000}};
  Coordinate row{"row", "row", "1", "", {0, 1, 2, 3, 4}, {}, false, true};
  Coordinate index{"case", "case", "", "", {}, {}, false, true};
  for (int i = 0; i < 10000; ++i) index.numbers.push_back(i);
  l.coordinates = {row, index};
  l.metrics = {{"theta_max_rad", "rad", ""}, {"impacts", "1", ""}, {"uplift_m", "m", ""}};
  l.status_flags = {{0, "at_rest"}, {3, "overturned"}};
  l.attributes = {{kFingerprintName, std::string("journal-test")}};
  return l;
}

constexpr std::int64_t kCases = 50000;
constexpr std::int64_t kHistoryCase = 30500;

/// Case i's result, the same whichever run computes it: two metrics that vary, one that is 0
/// for every case (journaled as one value per record).
std::vector<double> row_of(std::int64_t i) { return {1e-5 * static_cast<double>(i), static_cast<double>(i % 7), 0.0}; }
std::int8_t status_of(std::int64_t i) { return i % 11 == 0 ? 3 : 0; }

HistoryTable history_of(std::int64_t i) {
  return {"h" + std::to_string(i), {{"case_index", i}}, {{"t_s", "s", "time"}, {"theta1_rad", "rad", ""}},
          {{0.0, 0.5, 1.0}, {0.0, 1e-3 * static_cast<double>(i % 5), 0.0}}};
}

/// Stores cases [first, last) as any run would: values, a note every 97th, the history of one.
void store_cases(CubeWriter& writer, std::int64_t first, std::int64_t last) {
  for (std::int64_t i = first; i < last; ++i) {
    writer.store(i, status_of(i), row_of(i));
    if (i % 97 == 0) writer.store_note(i, "note of case " + std::to_string(i));
    if (i == kHistoryCase) writer.store_history(history_of(i));
  }
}

/// Resumes `file` and computes every case not done, then closes (folds).
void finish(const fs::path& file) {
  CubeWriter writer(file, journal_layout(), OpenMode::kResume);
  const auto status = writer.status();
  for (std::int64_t i = 0; i < kCases; ++i)
    if (status[static_cast<std::size_t>(i)] == kStatusNotRun) store_cases(writer, i, i + 1);
  writer.close();
}

/// The cube's results equal those of an uninterrupted run.
void expect_complete(const fs::path& file) {
  const CubeReader reader(file);
  EXPECT_TRUE(reader.damage().empty());
  const auto status = reader.read_status();
  const auto theta = reader.read_metric("theta_max_rad");
  const auto impacts = reader.read_metric("impacts");
  const auto uplift = reader.read_metric("uplift_m");
  std::size_t wrong = 0;
  for (std::int64_t i = 0; i < kCases; ++i) {
    const auto k = static_cast<std::size_t>(i);
    wrong += status[k] != status_of(i) || theta[k] != row_of(i)[0] || impacts[k] != row_of(i)[1] || uplift[k] != 0.0;
  }
  EXPECT_EQ(wrong, 0u) << file;
  auto notes = reader.read_notes();
  std::sort(notes.begin(), notes.end());
  ASSERT_EQ(notes.size(), static_cast<std::size_t>((kCases + 96) / 97)) << file;
  for (std::size_t n = 0; n < notes.size(); ++n) EXPECT_EQ(notes[n].second, "note of case " + std::to_string(97 * n));
  EXPECT_EQ(reader.history_names(), std::vector<std::string>{"h" + std::to_string(kHistoryCase)});
  EXPECT_EQ(reader.read_history("h" + std::to_string(kHistoryCase)).values, history_of(kHistoryCase).values);
  EXPECT_FALSE(fs::exists(journal_path(file))) << "a finished cube keeps no journal";
}

std::int64_t done_in(const std::vector<std::int8_t>& status) {
  return std::count_if(status.begin(), status.end(), [](std::int8_t s) { return s != kStatusNotRun; });
}

/// A cube folded with cases [0, 20000), then three appends of 1000 cases each (a record of
/// cases, one of notes and a commit each). Returns the journal's size after each
/// append (index 0: after the fold, when it has none).
std::vector<std::uintmax_t> journaled_cube(const fs::path& file) {
  std::vector<std::uintmax_t> sizes{0};
  CubeWriter writer(file, journal_layout(), OpenMode::kCreate);
  store_cases(writer, 0, 20000);
  writer.flush();  // the first results fold (nothing was folded yet)
  EXPECT_FALSE(fs::exists(journal_path(file)));
  for (std::int64_t first = 20000; first < 23000; first += 1000) {
    store_cases(writer, first, first + 1000);
    writer.flush();  // 1000 to 3000 results: below a quarter of the 20 000 folded
    sizes.push_back(fs::file_size(journal_path(file)));
  }
  return sizes;  // the writer's destructor has nothing left to write
}

TEST(CubeJournal, ChecksumsStoreResultsThatResumeAndFold) {
  const auto dir = test::scratch_dir("journal_roundtrip");
  const auto file = dir / "c.h5";
  journaled_cube(file);
  // Readers see the last fold; the journal holds the rest.
  const CubeReader folded(file);
  EXPECT_EQ(done_in(folded.read_status()), 20000);
  const JournalReader journal(file, folded.layout(), journal_id_of(folded.layout()));
  ASSERT_TRUE(journal.current());
  EXPECT_EQ(journal.results(), 3000);
  EXPECT_EQ(journal.dropped_bytes(), 0u);
  std::int64_t seen = 0;
  journal.for_each_cases([&](const JournalCases& c) {
    for (std::size_t j = 0; j < c.offsets.size(); ++j) {
      const std::int64_t i = static_cast<std::int64_t>(c.chunk) * 10000 + c.offsets[j];
      EXPECT_EQ(c.status[j], status_of(i));
      EXPECT_EQ(c.values[j], row_of(i)[0]);
      EXPECT_EQ(c.values[c.offsets.size() + j], row_of(i)[1]);
      EXPECT_EQ(c.values[2 * c.offsets.size() + j], 0.0);
      ++seen;
    }
  });
  EXPECT_EQ(seen, 3000);
  const auto notes = journal.notes();
  ASSERT_FALSE(notes.empty());
  EXPECT_EQ(notes.front().first, 20079);  // the first multiple of 97 from 20 000
  EXPECT_EQ(notes.front().second, "note of case 20079");
  // A journal that belongs to another fold (another id) is stale: it holds nothing for this cube.
  EXPECT_FALSE(JournalReader(file, folded.layout(), journal_id_of(folded.layout()) + 1).current());
  {
    CubeWriter resumed(file, journal_layout(), OpenMode::kResume);
    EXPECT_EQ(resumed.done_count(), 23000);
    const auto theta = resumed.read_values("theta_max_rad");
    EXPECT_EQ(theta[22999], row_of(22999)[0]);
    EXPECT_TRUE(std::isnan(theta[23000]));
    // append() never folds (a stopping run's checkpoint), though a fold is due here.
    store_cases(resumed, 23000, 33000);
    resumed.append();
    EXPECT_EQ(done_in(CubeReader(file).read_status()), 20000);
    EXPECT_EQ(JournalReader(file, folded.layout(), journal_id_of(folded.layout())).results(), 13000);
  }
  finish(file);
  expect_complete(file);
}

// What a reader shows is the last fold; it says how many results wait in the journal, and a
// merge refuses a part whose journal holds results rather than leave them out.
TEST(CubeJournal, ReadersNameTheResultsWaitingInTheJournal) {
  const auto dir = test::scratch_dir("journal_readers");
  const auto file = dir / "c.h5";
  journaled_cube(file);
  const auto info = test::run_command("'" + test::pcrf_executable().string() + "' cube info '" + file.string() + "'");
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("completion: 20000/50000"), std::string::npos) << info.out;
  EXPECT_NE(info.err.find(file.string() + ": 3000 results wait in its journal " + journal_path(file).string()),
            std::string::npos) << info.err;
  try {
    merge_cubes({file}, dir / "merged.h5", false, {}, true);
    ADD_FAILURE() << "merged a part whose journal holds results";
  } catch (const CubeError& e) {
    EXPECT_NE(std::string(e.what()).find("3000 results wait in its journal"), std::string::npos) << e.what();
  }
  finish(file);  // folded: nothing waits, nothing is said
  EXPECT_EQ(test::run_command("'" + test::pcrf_executable().string() + "' cube info '" + file.string() + "'")
                .err.find("journal"), std::string::npos);
}

/// A copy of `from` (cube and journal) in `dir`, its journal cut to `bytes`.
fs::path torn_copy(const fs::path& from, const fs::path& dir, std::uintmax_t bytes) {
  fs::create_directories(dir);
  const auto file = dir / "c.h5";
  fs::copy_file(from, file, fs::copy_options::overwrite_existing);
  fs::copy_file(journal_path(from), journal_path(file), fs::copy_options::overwrite_existing);
  fs::resize_file(journal_path(file), bytes);
  return file;
}

TEST(CubeJournal, ATornTailIsDroppedAndItsCasesComputedAgain) {
  const auto dir = test::scratch_dir("journal_torn");
  const auto sizes = journaled_cube(dir / "whole.h5");
  // Cut inside the last record's frame, its payload and its CRC: two appends remain.
  for (const std::uintmax_t cut : {sizes[2] + 1, sizes[2] + 12, (sizes[2] + sizes[3]) / 2, sizes[3] - 1}) {
    const auto file = torn_copy(dir / "whole.h5", dir / ("cut" + std::to_string(cut)), cut);
    const CubeReader reader(file);
    const JournalReader journal(file, reader.layout(), journal_id_of(reader.layout()));
    EXPECT_EQ(journal.results(), 2000) << cut;
    EXPECT_EQ(journal.dropped_bytes(), cut - sizes[2]) << cut;
    {
      CubeWriter resumed(file, journal_layout(), OpenMode::kResume);
      EXPECT_EQ(resumed.done_count(), 22000) << cut;
      store_cases(resumed, 22000, 22500);
      resumed.flush();  // continues the journal after its last good record
    }
    const JournalReader continued(file, reader.layout(), journal_id_of(reader.layout()));
    EXPECT_EQ(continued.results(), 2500) << cut;
    EXPECT_EQ(continued.dropped_bytes(), 0u) << cut;
    finish(file);
    expect_complete(file);
  }
  // A journal cut inside its header, or left empty, holds nothing.
  for (const std::uintmax_t cut : {std::uintmax_t{0}, std::uintmax_t{5}, std::uintmax_t{20}}) {
    const auto file = torn_copy(dir / "whole.h5", dir / ("head" + std::to_string(cut)), cut);
    EXPECT_EQ(CubeWriter(file, journal_layout(), OpenMode::kResume).done_count(), 20000) << cut;
    finish(file);
    expect_complete(file);
  }
}

/// Flips one byte of a file.
void flip_byte(const fs::path& file, std::uintmax_t at) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(static_cast<std::streamoff>(at));
  const char c = static_cast<char>(f.get() ^ 0x5a);
  f.seekp(static_cast<std::streamoff>(at));
  f.put(c);
}

TEST(CubeJournal, ADamagedRecordEndsWhatIsTrusted) {
  const auto dir = test::scratch_dir("journal_crc");
  const auto sizes = journaled_cube(dir / "whole.h5");
  // A byte of the second append's records: the first append is kept, nothing after.
  auto file = torn_copy(dir / "whole.h5", dir / "middle", sizes[3]);
  flip_byte(journal_path(file), (sizes[1] + sizes[2]) / 2);
  EXPECT_EQ(CubeWriter(file, journal_layout(), OpenMode::kResume).done_count(), 21000);
  finish(file);
  expect_complete(file);
  // A byte of the header (its id): the journal is not this cube's.
  file = torn_copy(dir / "whole.h5", dir / "header", sizes[3]);
  flip_byte(journal_path(file), 24);
  EXPECT_EQ(CubeWriter(file, journal_layout(), OpenMode::kResume).done_count(), 20000);
  finish(file);
  expect_complete(file);
}

/// Appends a record of `kind` to a copy's journal, with a valid CRC, and commits it.
void forge(const fs::path& file, std::uint32_t kind, const std::string& payload) {
  const CubeReader reader(file);
  const JournalReader journal(file, reader.layout(), journal_id_of(reader.layout()));
  io::LogWriter log(journal_path(file), journal.valid_bytes());
  log.add(kind, payload);
  log.add(kJournalCommit, {});
  log.sync();
}

/// What resuming `file` says about its journal: the error, or the notes (a journal that
/// cannot be replayed is set aside, and the notes say why).
std::string resume_error(const fs::path& file) {
  try {
    CubeWriter writer(file, journal_layout(), OpenMode::kResume);
    std::string notes;
    for (const auto& note : writer.resume_notes()) notes += note + "\n";
    return notes;
  } catch (const CubeError& e) {
    return e.what();
  }
}

TEST(CubeJournal, AForgedRecordIsAClearErrorAndAHugeSizeATornTail) {
  const auto dir = test::scratch_dir("journal_forged");
  const auto sizes = journaled_cube(dir / "whole.h5");
  std::string chunk_999;
  io::append_le(chunk_999, 999, 8);
  io::append_le(chunk_999, 0, 4);
  auto file = torn_copy(dir / "whole.h5", dir / "chunk", sizes[3]);
  forge(file, kJournalCases, chunk_999);
  const std::string chunk_error = resume_error(file);  // sets the journal aside: asked once
  EXPECT_NE(chunk_error.find(journal_path(file).string() + ": record 10 (at byte "), std::string::npos) << chunk_error;
  EXPECT_NE(chunk_error.find("names chunk 999 of a cube of 5"), std::string::npos) << chunk_error;
  // Issue 41: no longer "remove the journal": --resume sets it aside itself and says so.
  EXPECT_NE(chunk_error.find("set aside as " + journal_path(file).string() + ".set-aside-1"), std::string::npos) << chunk_error;
  // A note's text declared longer than its record: refused before anything is allocated.
  std::string note;
  io::append_le(note, 1, 4);
  io::append_le(note, 7, 8);
  io::append_le(note, 0xffffffffu, 4);
  file = torn_copy(dir / "whole.h5", dir / "note", sizes[3]);
  forge(file, kJournalNotes, note);
  EXPECT_NE(resume_error(file).find("ends "), std::string::npos);
  // A cases record whose declared count disagrees with its size.
  std::string short_cases;
  io::append_le(short_cases, 1, 8);
  io::append_le(short_cases, 10000, 4);
  file = torn_copy(dir / "whole.h5", dir / "short", sizes[3]);
  forge(file, kJournalCases, short_cases);
  EXPECT_NE(resume_error(file).find("not the 10000 cases it declares"), std::string::npos);
  // A frame declaring 2^60 bytes: more than the file holds, so a torn tail, not an allocation.
  file = torn_copy(dir / "whole.h5", dir / "huge", sizes[3]);
  {
    std::ofstream out(journal_path(file), std::ios::app | std::ios::binary);
    std::string frame;
    io::append_le(frame, kJournalCases, 4);
    io::append_le(frame, std::uint64_t{1} << 60, 8);
    out << frame << std::string(64, 'x');
  }
  EXPECT_EQ(CubeWriter(file, journal_layout(), OpenMode::kResume).done_count(), 23000);
  finish(file);
  expect_complete(file);
}

/// The payload of a record of cases of chunk 2 (cases 20 000 …) with `statuses`, every
/// metric the same value.
std::string cases_payload(const std::vector<std::int8_t>& statuses) {
  std::string out;
  io::append_le(out, 2, 8);
  io::append_le(out, statuses.size(), 4);
  for (std::size_t j = 0; j < statuses.size(); ++j) io::append_le(out, 5000 + j, 4);  // offsets not yet journaled
  for (const auto s : statuses) out.push_back(static_cast<char>(s));
  for (int m = 0; m < 3; ++m) {
    out.push_back(1);  // one value for every case
    io::append_le(out, std::bit_cast<std::uint64_t>(0.25), 8);
  }
  return out;
}

void put_text(std::string& out, const std::string& text) {
  io::append_le(out, text.size(), 4);
  out += text;
}

/// The payload of a history record named `name`, of one column `column` of `rows` rows.
std::string history_payload(const std::string& name, const std::string& column, std::size_t rows) {
  std::string out;
  put_text(out, name);
  io::append_le(out, 0, 4);  // no attribute
  io::append_le(out, 1, 4);  // one column
  put_text(out, column);
  put_text(out, "s");
  put_text(out, "time");
  io::append_le(out, rows, 8);
  for (std::size_t k = 0; k < rows; ++k) io::append_le(out, std::bit_cast<std::uint64_t>(0.5 * static_cast<double>(k)), 8);
  return out;
}

// Issue 41: a journal forged with valid checksums writes nothing the cube's layout does not
// allow (status 99 or -128, a history name that is no group name), and does not make every
// --resume fail: it is set aside (never over a file there) with a note, and its cases are
// computed again.
TEST(CubeJournal, AForgedJournalIsSetAsideAndItsCasesComputedAgain) {
  const auto dir = test::scratch_dir("journal_set_aside");
  const auto sizes = journaled_cube(dir / "whole.h5");
  struct Forgery {
    const char* name;
    std::uint32_t kind;
    std::string payload;
    const char* problem;
  };
  for (const Forgery& f : {Forgery{"status99", kJournalCases, cases_payload({0, 99}), "has the status code 99"},
                           Forgery{"status128", kJournalCases, cases_payload({-128}), "has the status code -128"},
                           Forgery{"not_run", kJournalCases, cases_payload({kStatusNotRun}), "has the status code -1"},
                           Forgery{"slash", kJournalHistory, history_payload("a/b", "t_s", 2), "history named \"a/b\""},
                           Forgery{"dotdot", kJournalHistory, history_payload("..", "t_s", 2), "history named \"..\""},
                           Forgery{"column", kJournalHistory, history_payload("h1", "", 2), "history column named"}}) {
    const auto file = torn_copy(dir / "whole.h5", dir / f.name, sizes[3]);
    // A file already at the first set-aside name is kept as it is: the next name is taken.
    test::write_file(file.parent_path(), "c.h5.journal.set-aside-1", "the user's");
    forge(file, f.kind, f.payload);
    std::vector<std::string> notes;
    {
      CubeWriter resumed(file, journal_layout(), OpenMode::kResume);
      notes = resumed.resume_notes();
      EXPECT_EQ(resumed.done_count(), 20000) << f.name << ": nothing of a journal set aside is used";
    }
    ASSERT_EQ(notes.size(), 1u) << f.name;
    EXPECT_NE(notes[0].find(f.problem), std::string::npos) << notes[0];
    EXPECT_NE(notes[0].find("set aside as " + journal_path(file).string() + ".set-aside-2"), std::string::npos) << notes[0];
    EXPECT_NE(notes[0].find("computed again (the cube's last fold holds 20000 of 50000 cases)"), std::string::npos) << notes[0];
    EXPECT_EQ(test::read_file(journal_path(file).string() + ".set-aside-1"), "the user's");
    EXPECT_TRUE(fs::exists(journal_path(file).string() + ".set-aside-2"));
    finish(file);
    expect_complete(file);
    const auto status = CubeReader(file).read_status();
    EXPECT_EQ(std::count_if(status.begin(), status.end(), [](std::int8_t s) { return s != 0 && s != 3; }), 0) << f.name;
  }
}

// UBSan (issue 41): a history of zero rows read back from a journal copied from a null
// pointer; it replays and folds as the history of no rows it is.
TEST(CubeJournal, AHistoryOfNoRowsReplays) {
  const auto dir = test::scratch_dir("journal_empty_history");
  const auto sizes = journaled_cube(dir / "whole.h5");
  const auto file = torn_copy(dir / "whole.h5", dir / "empty", sizes[3]);
  forge(file, kJournalHistory, history_payload("h_empty", "t_s", 0));
  {
    CubeWriter resumed(file, journal_layout(), OpenMode::kResume);
    EXPECT_TRUE(resumed.resume_notes().empty());
    EXPECT_EQ(resumed.done_count(), 23000);
  }
  finish(file);
  const CubeReader reader(file);
  const auto empty = reader.read_history("h_empty");
  ASSERT_EQ(empty.values.size(), 1u);
  EXPECT_TRUE(empty.values[0].empty());
}

// Issue 41 item 9: a resume that drops a torn tail says how much it dropped.
TEST(CubeJournal, AResumeThatDropsRecordsSaysHowMany) {
  const auto dir = test::scratch_dir("journal_dropped_note");
  const auto sizes = journaled_cube(dir / "whole.h5");
  // The third append's records complete but its commit cut off: 1 record of 1000 cases and
  // one of notes, dropped.
  auto file = torn_copy(dir / "whole.h5", dir / "uncommitted", sizes[3] - 16);
  {
    CubeWriter resumed(file, journal_layout(), OpenMode::kResume);
    ASSERT_EQ(resumed.resume_notes().size(), 1u);
    const auto& note = resumed.resume_notes()[0];
    EXPECT_NE(note.find(journal_path(file).string() + ": its last " + std::to_string(sizes[3] - 16 - sizes[2]) + " bytes are dropped"),
              std::string::npos) << note;
    EXPECT_NE(note.find("2 complete records of a checkpoint never closed (1000 results)"), std::string::npos) << note;
    EXPECT_NE(note.find("computed again"), std::string::npos) << note;
  }
  // A byte of the second append damaged: its records and all after are dropped, uncounted.
  file = torn_copy(dir / "whole.h5", dir / "damaged", sizes[3]);
  flip_byte(journal_path(file), (sizes[1] + sizes[2]) / 2);
  {
    CubeWriter resumed(file, journal_layout(), OpenMode::kResume);
    ASSERT_EQ(resumed.resume_notes().size(), 1u);
    EXPECT_NE(resumed.resume_notes()[0].find("a record that is torn or damaged"), std::string::npos) << resumed.resume_notes()[0];
  }
  finish(file);
  expect_complete(file);
}

// Issue 41 item 1: the files beside a cube are never followed: a symbolic link at the
// journal or the .partial (to the study file, say) is refused before anything is written,
// and so is a FIFO (without waiting on it).
TEST(CubeJournal, ALinkOrAFifoBesideTheCubeIsRefusedNeverFollowed) {
  const auto dir = test::scratch_dir("journal_sidecar_links");
  const auto sizes = journaled_cube(dir / "whole.h5");
  for (const char* sidecar : {".journal", ".partial"})
    for (const OpenMode mode : {OpenMode::kResume, OpenMode::kOverwrite}) {
      const auto file = torn_copy(dir / "whole.h5", dir / (std::string("link") + sidecar + std::to_string(int(mode))), sizes[3]);
      const auto study = test::write_file(file.parent_path(), "study.toml", "precious");
      fs::remove(file.string() + sidecar);
      fs::create_symlink(study, file.string() + sidecar);
      try {
        CubeWriter writer(file, journal_layout(), mode);
        ADD_FAILURE() << sidecar << ": opened with a link beside the cube";
      } catch (const CubeError& e) {
        EXPECT_NE(std::string(e.what()).find(file.string() + sidecar + ": is a symbolic link"), std::string::npos) << e.what();
      }
      EXPECT_EQ(test::read_file(study), "precious");
    }
  const auto file = torn_copy(dir / "whole.h5", dir / "fifo", sizes[3]);
  fs::remove(journal_path(file));
  ASSERT_EQ(::mkfifo(journal_path(file).c_str(), 0600), 0);
  alarm(20);  // a regression blocks: end it rather than hang the suite
  EXPECT_THROW(CubeWriter(file, journal_layout(), OpenMode::kResume), CubeError);
  const CubeReader reader(file);
  EXPECT_THROW(JournalReader(file, reader.layout(), journal_id_of(reader.layout())), CubeError);
  alarm(0);
}

// ---- kills ----

/// The child's run: resumes the journaled cube, appends (continuing the journal), folds,
/// appends again (a new journal), then closes (folds).
void killed_run(const fs::path& file) {
  CubeWriter writer(file, journal_layout(), OpenMode::kResume);
  store_cases(writer, 23000, 24000);
  writer.flush();  // append
  store_cases(writer, 24000, 31000);
  writer.fold();
  store_cases(writer, 31000, 32000);
  writer.flush();  // append, to a new journal
  store_cases(writer, 32000, 33000);
  writer.close();
}

TEST(CubeJournal, AKillAtEveryStepOfACheckpointLeavesACubeThatResumesToTheSameResults) {
  const auto dir = test::scratch_dir("journal_kills");
  const auto sizes = journaled_cube(dir / "whole.h5");
  using S = CheckpointStep;
  for (const KillPoint k : {KillPoint{S::kJournalWritten, 1, "append_written"}, {S::kJournalSynced, 1, "append_synced"},
                            {S::kFoldCopied, 1, "fold_copied"}, {S::kFoldWritten, 1, "fold_written"},
                            {S::kFoldRenamed, 1, "fold_renamed"}, {S::kJournalRemoved, 1, "journal_removed"},
                            {S::kJournalWritten, 2, "new_journal_written"}, {S::kJournalSynced, 2, "new_journal_synced"},
                            {S::kFoldRenamed, 2, "last_fold_renamed"}}) {
    const auto file = torn_copy(dir / "whole.h5", dir / k.name, sizes[3]);
    ASSERT_TRUE(killed(run_killed_at(k, [&] { killed_run(file); }))) << k.name << ": the run was not killed there";
    // The cube is whole and readable as it is; its journal, when current, reads too.
    const CubeReader reader(file);
    EXPECT_TRUE(reader.damage().empty()) << k.name;
    const JournalReader journal(file, reader.layout(), journal_id_of(reader.layout()));
    const auto done = done_in(reader.read_status()) + journal.results();
    EXPECT_GE(done, 23000) << k.name << ": a checkpoint's results were lost";
    if (k.step == S::kFoldRenamed) {
      EXPECT_FALSE(journal.current()) << k.name << ": the old journal must be stale";
    }
    finish(file);
    expect_complete(file);
  }
}

}  // namespace
}  // namespace pcrf::cube
