// Coordinates written during the run (issue 38; Coordinate::written_live): a sampled plan's
// parameters along `case` are chunked as the metrics are, made with the fill NaN and written by
// no one at the creation; a fold writes the chunks of the units it holds, close() every one
// still missing (found by HDF5's chunk query, so a --resume needs no record of them). A
// checkpoint's cube reads with NaN (no value) where a unit is not in it yet; the closed cube
// holds every value, the same as the plan's.
#include <gtest/gtest.h>

#include <hdf5.h>
#include <hdf5_hl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "pcrf/number_text.hpp"
#include "case_axis_layout.hpp"
#include "kill_points.hpp"
#include "worker_chunks.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

namespace fs = std::filesystem;

constexpr std::int64_t kCases = 40000;  // units of 16 384, 16 384 and 7 232 cases (an edge one)

double kappa_at(std::size_t i) { return 1.0 + 1.0 / static_cast<double>(i + 3); }  // no two alike

/// case_axis_layout with `kappa`, a computed parameter along `case` (long: written live).
CubeLayout live_layout(const std::string& fingerprint = "live") {
  CubeLayout l = case_axis_layout(kCases, fingerprint);
  Coordinate kappa{"kappa", "case", "1", "stiffness", {}, {}, false, false};
  kappa.number_at = kappa_at;
  kappa.computed_size = static_cast<std::size_t>(kCases);
  l.coordinates.push_back(std::move(kappa));
  return l;
}

std::vector<double> kappa_of(const fs::path& file) { return CubeReader(file).layout().find_coordinate("kappa")->numbers; }

/// The cases of units `units` hold their kappa, every other case NaN (not written yet).
void expect_kappa_of_units(const fs::path& file, const std::vector<std::size_t>& units) {
  const auto kappa = kappa_of(file);
  ASSERT_EQ(kappa.size(), static_cast<std::size_t>(kCases));
  const ChunkGrid grid(std::vector<std::size_t>{static_cast<std::size_t>(kCases)});
  std::size_t wrong = 0;
  for (std::size_t u = 0; u < grid.chunk_count(); ++u) {
    const bool in = std::find(units.begin(), units.end(), u) != units.end();
    const auto r = grid.range(u);
    for (std::int64_t i = r.first; i < r.first + r.count; ++i) {
      const double v = kappa[static_cast<std::size_t>(i)];
      wrong += in ? v != kappa_at(static_cast<std::size_t>(i)) : !std::isnan(v);
    }
  }
  EXPECT_EQ(wrong, 0u) << file;
}

TEST(LiveCoordinates, ALongParameterIsChunkedAsTheMetricsAndWrittenByNoneAtTheCreation) {
  const auto layout = live_layout();
  const Coordinate& kappa = layout.coordinates.back();
  ASSERT_TRUE(kappa.written_live());
  EXPECT_EQ(coordinate_chunk_values(layout, kappa), layout_grid(layout).chunk_shape()[0]);
  for (const auto& piece : coordinate_pieces(layout)) EXPECT_EQ(piece.coordinate, 0u) << "the case number's: kappa is no creation's piece";
  const auto file = test::scratch_dir("live_creation") / "c.h5";
  std::size_t asked = 0;
  CubeLayout counted = layout;
  counted.coordinates.back().number_at = [&asked](std::size_t i) { ++asked; return kappa_at(i); };
  {
    CubeWriter writer(file, counted, OpenMode::kCreate);
    EXPECT_EQ(asked, 0u) << "no value of it at the creation";
    expect_kappa_of_units(file, {});
    writer.close();
  }
  EXPECT_EQ(asked, static_cast<std::size_t>(kCases)) << "each value once, at close";
  expect_kappa_of_units(file, {0, 1, 2});
}

// A checkpoint's fold holds the coordinates of the units it holds, no other: `pcrf cube` and
// its selections read the others as no value (an empty field, never "nan"), then close() adds them.
TEST(LiveCoordinates, AFoldHoldsTheCoordinatesOfItsUnitsAndCloseTheRest) {
  const auto file = test::scratch_dir("live_fold") / "c.h5";
  CubeWriter writer(file, live_layout(), OpenMode::kCreate);
  for (std::int64_t i = 16384; i < 16390; ++i) writer.store(i, status_of(i), row_of(i));
  writer.fold();
  expect_kappa_of_units(file, {1});
  {
    const CubeReader reader(file);
    EXPECT_TRUE(reader.damage().empty());
    std::ostringstream csv;
    export_csv(reader, {"theta_max_rad"}, {}, csv, {});
    std::istringstream lines(csv.str());
    std::string header, first, line;
    std::getline(lines, header);
    std::getline(lines, first);
    EXPECT_EQ(header, "case,kappa,status,theta_max_rad");
    EXPECT_EQ(first, "0,,not_run,") << "a coordinate not written yet is no value";
    for (std::int64_t i = 1; i <= 16384; ++i) std::getline(lines, line);
    EXPECT_EQ(line, "16384," + pcrf::number_text(kappa_at(16384)) + ",at_rest," + pcrf::number_text(row_of(16384)[0]));
    const auto picked = select_cases(reader.layout(), {parse_selector("kappa=" + pcrf::number_text(kappa_at(20000)))});
    EXPECT_EQ(std::count(picked.begin(), picked.end(), true), 1);
    EXPECT_TRUE(picked[20000]);
  }
  writer.close();
  expect_kappa_of_units(file, {0, 1, 2});
}

// A run that ends without its close (killed after a fold; an error) leaves a cube whose
// coordinates are its units'; --resume finds the chunks missing in the file (no record of them
// kept) and its close writes them: the cube of the run never stopped.
TEST(LiveCoordinates, AResumedRunFillsWhatTheStoppedOneLacked) {
  const auto dir = test::scratch_dir("live_resume");
  {
    CubeWriter whole(dir / "whole.h5", live_layout(), OpenMode::kCreate);
    for (std::int64_t i = 0; i < kCases; ++i) whole.store(i, status_of(i), row_of(i));
    whole.close();
  }
  const auto file = dir / "stopped.h5";
  {
    CubeWriter stopped(file, live_layout(), OpenMode::kCreate);
    for (std::int64_t i = 0; i < 16384; ++i) stopped.store(i, status_of(i), row_of(i));
    stopped.fold();
    for (std::int64_t i = 16384; i < 20000; ++i) stopped.store(i, status_of(i), row_of(i));
  }  // not closed: the destructor appends to the journal
  expect_kappa_of_units(file, {0});
  {
    CubeWriter resumed(file, live_layout(), OpenMode::kResume);
    for (std::int64_t i = 20000; i < kCases; ++i) resumed.store(i, status_of(i), row_of(i));
    resumed.close();
  }
  EXPECT_EQ(kappa_of(file), kappa_of(dir / "whole.h5"));
  EXPECT_EQ(CubeReader(file).read_metric("theta_max_rad"), CubeReader(dir / "whole.h5").read_metric("theta_max_rad"));
  // A resume of a closed cube with nothing left writes nothing more and keeps every value.
  {
    CubeWriter again(file, live_layout(), OpenMode::kResume);
    again.close();
  }
  EXPECT_EQ(kappa_of(file), kappa_of(dir / "whole.h5"));
}

// A cube written before this change (its long coordinates written whole at the creation, in
// chunks of 65 536 values, without a fill value) reads as before, and a --resume of it adds
// no chunk of its own to them.
TEST(LiveCoordinates, ACubeOfAnEarlierVersionReadsAndResumesAsBefore) {
  const auto file = test::scratch_dir("live_old") / "old.h5";
  {
    CubeWriter writer(file, live_layout(), OpenMode::kCreate);
    for (std::int64_t i = 0; i < 100; ++i) writer.store(i, status_of(i), row_of(i));
    writer.close();
  }
  {  // kappa as an earlier version stored it: chunks of 65 536 values, no fill, every value written
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    ASSERT_GE(H5Ldelete(f, "kappa", H5P_DEFAULT), 0);
    const hsize_t n = static_cast<hsize_t>(kCases), chunk = 65536 > n ? n : 65536;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, &chunk);
    H5Pset_shuffle(dcpl);
    H5Pset_deflate(dcpl, 1);
    const hid_t d = H5Dcreate2(f, "kappa", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    ASSERT_GE(d, 0);
    std::vector<double> values(static_cast<std::size_t>(kCases));
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = kappa_at(i);
    ASSERT_GE(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    const hid_t scale = H5Dopen2(f, "case", H5P_DEFAULT);
    ASSERT_GE(H5DSattach_scale(d, scale, 0), 0);
    H5Dclose(scale);
    H5Dclose(d);
    H5Pclose(dcpl);
    H5Sclose(space);
    ASSERT_GE(H5Fclose(f), 0);
  }
  std::vector<double> expected(static_cast<std::size_t>(kCases));
  for (std::size_t i = 0; i < expected.size(); ++i) expected[i] = kappa_at(i);
  EXPECT_EQ(kappa_of(file), expected);
  {
    CubeWriter resumed(file, live_layout(), OpenMode::kResume);
    for (std::int64_t i = 100; i < 200; ++i) resumed.store(i, status_of(i), row_of(i));
    resumed.close();
  }
  EXPECT_EQ(kappa_of(file), expected);
  const CubeReader reader(file);
  EXPECT_TRUE(reader.damage().empty());
  EXPECT_EQ(reader.read_metric("theta_max_rad")[150], row_of(150)[0]);
}

/// Unit `unit` sealed as a worker seals it (worker_chunks.hpp), carrying its piece of each
/// coordinate the writer takes from the units (from the plan's values, as ChunkSealer does).
SealedChunk carrying(const CubeWriter& writer, std::size_t unit) {
  SealedChunk sealed = sealed_of(writer.grid(), unit);
  for (const auto& u : writer.unit_coordinates()) {
    const auto piece = unit_piece(writer.grid(), unit, u);
    if (!piece) continue;
    const std::size_t first = *piece * u.chunk_values;
    std::vector<double> values(std::min(u.chunk_values, static_cast<std::size_t>(kCases) - first));
    for (std::size_t k = 0; k < values.size(); ++k) values[k] = kappa_at(first + k);
    sealed.coordinates.push_back({u.coordinate, *piece, seal_coordinate_values(values, u.chunk_values)});
  }
  return sealed;
}

// What a unit's coordinate chunks hold counts in the results held until the next checkpoint
// (CubeWriter::pending_bytes, which bounds rank 0's memory: study_run.cpp checkpoints past
// kPendingResultsBytes): they wait in memory with the unit.
TEST(LiveCoordinates, AUnitsCoordinateChunksCountInTheBytesHeldUntilTheCheckpoint) {
  const auto file = test::scratch_dir("live_pending") / "c.h5";
  CubeWriter writer(file, live_layout(), OpenMode::kCreate);
  SealedChunk sealed = carrying(writer, 0);
  ASSERT_EQ(sealed.coordinates.size(), 1u);
  std::size_t held = sealed.status.size() + sealed.coordinates.front().filtered.size();
  for (const auto& f : sealed.filtered) held += f.size();
  writer.store_sealed(std::move(sealed));
  EXPECT_EQ(writer.pending_bytes(), held);
  writer.flush();
  EXPECT_EQ(writer.pending_bytes(), 0u);
}

/// A run of three ranks whose units carry their coordinates: unit 0 kept in rank 1's part and
/// streamed, unit 1 sent to rank 0 (its journal), unit 2 kept in rank 2's part and taken at the
/// end; `asked` counts the values rank 0's writer computes itself.
void carried_run(const fs::path& file, std::size_t* asked = nullptr) {
  CubeLayout layout = live_layout();
  if (asked != nullptr) layout.coordinates.back().number_at = [asked](std::size_t i) { ++*asked; return kappa_at(i); };
  CubeWriter writer(file, layout, OpenMode::kCreate);
  PartWriter one(part_path(file, 1), writer.part_header());
  one.add(carrying(writer, 0));
  writer.stream_kept(0, 1);
  writer.store_sealed(carrying(writer, 1));
  writer.flush();  // appends: the stream is open
  PartWriter(part_path(file, 2), writer.part_header()).add(carrying(writer, 2));
  writer.close();
}

// The units bring their coordinates' chunks wherever they go in (the streaming fold, the
// journal's sealed record, the parts at the end): rank 0 computes none of their values.
TEST(LiveCoordinates, UnitsCarryTheirCoordinatesIntoTheCubeWhereverTheyGoIn) {
  const auto file = test::scratch_dir("live_carried") / "c.h5";
  {
    CubeWriter writer(file, live_layout(), OpenMode::kCreate);
    ASSERT_EQ(writer.unit_coordinates().size(), 1u);
    const UnitCoordinate& u = writer.unit_coordinates().front();
    EXPECT_EQ(u.coordinate, 1u);
    EXPECT_EQ(u.name, "kappa");
    EXPECT_EQ(u.chunk_values, writer.grid().chunk_shape()[0]);
    EXPECT_EQ(unit_piece(writer.grid(), 2, u), std::optional<std::size_t>(2)) << "the edge unit carries the edge piece";
  }
  fs::remove(file);
  std::size_t asked = 0;
  carried_run(file, &asked);
  EXPECT_EQ(asked, 0u) << "rank 0 sealed no coordinate chunk: every unit brought its own";
  expect_kappa_of_units(file, {0, 1, 2});
  expect_chunks(file, {0, 1, 2});
}

// A kill at any step between a unit's part write and its fold (and through the folds), then
// --resume (computing what is missing, case by case), gives the cube of the run never killed:
// every coordinate, metric and status.
TEST(LiveCoordinates, AKillBetweenAUnitsPartAndItsFoldResumesToTheUninterruptedCube) {
  const auto dir = test::scratch_dir("live_kills");
  carried_run(dir / "whole.h5");
  const CubeReader whole(dir / "whole.h5");
  using S = CheckpointStep;
  for (const KillPoint k : {KillPoint{S::kStreamOpened, 1, "opened"}, {S::kChunkStreamed, 1, "streamed"},
                            {S::kJournalSynced, 1, "appended"}, {S::kFoldWritten, 2, "fold_written"},
                            {S::kFoldRenamed, 2, "renamed"}, {S::kJournalRemoved, 2, "journal_removed"},
                            {S::kPartsRemoved, 1, "parts_removed"}}) {
    const auto file = dir / (std::string(k.name) + ".h5");
    ASSERT_TRUE(killed(run_killed_at(k, [&] { carried_run(file); }))) << k.name << ": the run was not killed there";
    {
      CubeWriter resumed(file, live_layout(), OpenMode::kResume);
      for (std::size_t c = 0; c < resumed.grid().chunk_count(); ++c) {
        if (resumed.chunk_done(c) > 0) continue;
        const auto r = resumed.grid().range(c);
        for (std::int64_t i = r.first; i < r.first + r.count; ++i) {
          resumed.store(i, status_of(i), row_of(i));
          if (i % 997 == 0) resumed.store_note(i, "note of case " + std::to_string(i));
        }
      }
      resumed.close();
    }
    const CubeReader reader(file);
    EXPECT_TRUE(reader.damage().empty()) << k.name;
    EXPECT_EQ(kappa_of(file), kappa_of(dir / "whole.h5")) << k.name;
    EXPECT_EQ(reader.read_status(), whole.read_status()) << k.name;
    for (const char* metric : {"theta_max_rad", "impacts"})
      EXPECT_EQ(reader.read_metric(metric), whole.read_metric(metric)) << k.name << " " << metric;
  }
}

}  // namespace
}  // namespace pcrf::cube
