// The cube file on its own: chunk ranges, write/flush/read back, resume, refusals, queries.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <set>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "chunk_tiling.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

TEST(ChunkGrid, ChunksAreContiguousRangesThatCoverTheCubeOnce) {
  for (const auto& [shape, target] : std::vector<std::pair<std::vector<std::size_t>, std::size_t>>{
           {{3, 4, 5}, 7}, {{13, 1, 9, 1, 1, 1, 1, 1, 1, 11}, 40}, {{2, 3}, 1000}, {{5}, 2}, {{1, 1, 100}, 30}}) {
    const ChunkGrid grid(shape, target);
    expect_tiles(grid, shape);
  }
}

CubeLayout test_layout(const std::string& fingerprint = "f1") {
  CubeLayout l;
  l.dimensions = {{"record", 2}, {"scale", 3}, {"case", 4}};
  Coordinate record{"record", "record", "", "ground motion", {}, {"ER1", "ER2 ü"}, true, false};
  Coordinate scale{"scale", "scale", "1", "factor", {0.5, 1.0, 2.0}, {}, false, false};
  Coordinate index{"case", "case", "", "frame number", {0, 1, 2, 3}, {}, false, true};
  Coordinate varied{"varied_parameter", "case", "", "", {}, {"none", "kappa", "kappa", "lambda"}, true, false};
  Coordinate kappa{"kappa", "case", "1", "", {1.8, 1.0, 3.0, 1.8}, {}, false, false};
  l.coordinates = {record, scale, index, varied, kappa};
  l.metrics = {{"theta_max_rad", "rad", "peak"}, {"impacts", "1", "count"}};
  l.status_flags = {{0, "at_rest"}, {4, "solver_failure"}};
  l.attributes = {{kFingerprintName, fingerprint}, {"plan", std::string("one-at-a-time")},
                  {"solver_rtol", 1e-8}, {"solver_max_steps", std::int64_t{2000000}}, {"empty", std::string()}};
  return l;
}

TEST(CubeFile, WritesFlushesAndReadsBack) {
  const auto file = test::scratch_dir("cube_roundtrip") / "c.h5";
  {
    CubeWriter writer(file, test_layout(), OpenMode::kCreate);
    writer.store(0, 0, {0.01, 3});
    writer.store(23, 4, {NAN, NAN});
    writer.store_note(23, "solver failed: step size too small");
    HistoryTable h{"one", {{"case_index", std::int64_t{0}}}, {{"t_s", "s", "time"}, {"theta1_rad", "rad", ""}},
                   {{0.0, 0.5, 1.0}, {0.0, 0.1, 0.0}}};
    writer.store_history(h);
    writer.close();
  }
  CubeReader reader(file);
  const auto& l = reader.layout();
  ASSERT_EQ(l.dimensions.size(), 3u);
  EXPECT_EQ(l.dimensions[2].name, "case");
  EXPECT_EQ(l.shape(), (std::vector<std::size_t>{2, 3, 4}));
  EXPECT_EQ(l.find_coordinate("record")->strings[1], "ER2 ü");
  EXPECT_EQ(l.find_coordinate("scale")->numbers[2], 2.0);
  EXPECT_EQ(l.find_coordinate("varied_parameter")->dimension, "case");
  EXPECT_TRUE(l.find_coordinate("case")->is_index);
  ASSERT_EQ(l.metrics.size(), 2u);
  EXPECT_EQ(l.metrics[0].units, "rad");
  EXPECT_EQ(l.text_attribute(kFingerprintName), "f1");
  EXPECT_EQ(l.text_attribute("empty"), "");
  const auto status = reader.read_status();
  EXPECT_EQ(status[0], 0);
  EXPECT_EQ(status[23], 4);
  EXPECT_EQ(std::count(status.begin(), status.end(), kStatusNotRun), 22);
  const auto theta = reader.read_metric("theta_max_rad");
  EXPECT_EQ(theta[0], 0.01);
  EXPECT_TRUE(std::isnan(theta[1]));  // fill value
  EXPECT_EQ(reader.read_metric("impacts")[0], 3.0);
  ASSERT_EQ(reader.read_notes().size(), 1u);
  EXPECT_EQ(reader.read_notes()[0].first, 23);
  EXPECT_EQ(reader.history_names(), std::vector<std::string>{"one"});
  EXPECT_THROW(reader.read_metric("nope"), CubeError);
}

/// A cube along one `case` dimension of n frames: the case number, a parameter and, as every
/// cube of a sampled plan had before issue 38 (the old layout), a text label per case.
CubeLayout case_layout(std::size_t n, bool labels) {
  CubeLayout l;
  l.dimensions = {{"record", 1}, {"case", n}};
  Coordinate record{"record", "record", "", "ground motion", {}, {"ER1"}, true, false};
  Coordinate index{"case", "case", "", "frame number", {}, {}, false, true};
  Coordinate kappa{"kappa", "case", "1", "", {}, {}, false, false};
  Coordinate label{"case_label", "case", "", "frame label", {}, {}, true, false};
  for (std::size_t i = 0; i < n; ++i) {
    index.numbers.push_back(static_cast<double>(i));
    kappa.numbers.push_back(1.0 + 1.0 / static_cast<double>(i + 3));  // no two alike, not short decimals
    label.strings.push_back("s" + std::to_string(i));
  }
  l.coordinates = {record, index};
  if (labels) l.coordinates.push_back(label);
  l.coordinates.push_back(kappa);
  l.metrics = {{"theta_max_rad", "rad", "peak"}};
  l.status_flags = {{0, "at_rest"}};
  l.attributes = {{kFingerprintName, std::string("f")}};
  return l;
}

// Coordinates longer than a few thousand values are chunked and deflated (issue 38), shorter
// ones stay contiguous as every coordinate was before: both read back exactly, with and
// without the per-case text labels that cubes written before issue 38 hold.
TEST(CubeFile, CoordinatesReadBackChunkedOrNotWithOrWithoutLabels) {
  for (const std::size_t n : {std::size_t{100}, std::size_t{70000}}) {
    for (const bool labels : {true, false}) {
      const auto file = test::scratch_dir("cube_coordinates") / ("c" + std::to_string(n) + std::to_string(labels) + ".h5");
      const auto layout = case_layout(n, labels);
      {
        CubeWriter writer(file, layout, OpenMode::kOverwrite);
        writer.store(static_cast<std::int64_t>(n - 1), 0, {0.25});
        writer.close();
      }
      CubeReader reader(file);
      const auto& read = reader.layout();
      EXPECT_EQ(read.find_coordinate("kappa")->numbers, layout.find_coordinate("kappa")->numbers) << n;
      EXPECT_EQ(read.find_coordinate("case")->numbers, layout.find_coordinate("case")->numbers) << n;
      EXPECT_TRUE(read.find_coordinate("case")->is_index);
      ASSERT_EQ(read.find_coordinate("case_label") != nullptr, labels) << n;
      if (labels) {
        EXPECT_EQ(read.find_coordinate("case_label")->strings[n - 1], "s" + std::to_string(n - 1));
      }
      EXPECT_EQ(reader.read_metric("theta_max_rad")[n - 1], 0.25);
      EXPECT_TRUE(reader.damage().empty());
      const auto picked = select_cases(read, {parse_selector("kappa=" + layout.find_coordinate("kappa")->label(0))});
      EXPECT_EQ(std::count(picked.begin(), picked.end(), true), 1);
      EXPECT_TRUE(picked[0]);
    }
  }
}

// A plan's coordinates along `case` are computed from the case number (issue 38): the writer
// asks for them chunk by chunk while it creates the cube, and they read back exactly, the same
// as the held ones, short (contiguous) or long (chunked, in several pieces and a partial one).
TEST(CubeFile, ComputedCoordinatesReadBackAsHeldOnes) {
  for (const std::size_t n : {std::size_t{100}, std::size_t{150000}}) {
    const auto file = test::scratch_dir("cube_computed") / ("c" + std::to_string(n) + ".h5");
    const auto held = case_layout(n, true);
    CubeLayout computed = held;
    std::size_t asked = 0, highest = 0;
    for (auto& c : computed.coordinates) {
      if (c.dimension != "case") continue;
      c.computed_size = n;
      if (c.is_text) {
        c.text_at = [&asked](std::size_t i) { ++asked; return "s" + std::to_string(i); };
        c.strings.clear();
      } else {
        const bool index = c.is_index;
        c.number_at = [&asked, &highest, index](std::size_t i) {
          ++asked;
          highest = std::max(highest, i);
          return index ? static_cast<double>(i) : 1.0 + 1.0 / static_cast<double>(i + 3);
        };
        c.numbers.clear();
      }
    }
    // A long kappa is written live (issue 38): none of its values at the creation, each once
    // by the end (the last case's chunk at the fold that holds that case, the others at close).
    const bool live = computed.find_coordinate("kappa")->written_live();
    EXPECT_EQ(live, n > kContiguousCoordinateMax);
    {
      CubeWriter writer(file, computed, OpenMode::kOverwrite);
      EXPECT_EQ(asked, (live ? 2 : 3) * n) << "each value once, at creation (but a live coordinate's)";
      EXPECT_EQ(highest, n - 1);
      writer.store(static_cast<std::int64_t>(n - 1), 0, {0.25});
      writer.close();
      EXPECT_EQ(asked, 3 * n) << "each value once in all";
    }
    CubeReader reader(file);
    const auto& read = reader.layout();
    EXPECT_EQ(read.find_coordinate("kappa")->numbers, held.find_coordinate("kappa")->numbers) << n;
    EXPECT_EQ(read.find_coordinate("case")->numbers, held.find_coordinate("case")->numbers) << n;
    EXPECT_TRUE(read.find_coordinate("case")->is_index);
    EXPECT_EQ(read.find_coordinate("case_label")->strings, held.find_coordinate("case_label")->strings) << n;
    EXPECT_EQ(reader.read_metric("theta_max_rad")[n - 1], 0.25);
    EXPECT_TRUE(reader.damage().empty());
  }
}

TEST(CubeFile, ResumeKeepsDoneCasesAndRefusesAnotherStudy) {
  const auto file = test::scratch_dir("cube_resume") / "c.h5";
  {
    CubeWriter writer(file, test_layout(), OpenMode::kCreate);
    writer.store(5, 0, {0.02, 1});
    writer.store_note(5, "first");
    writer.flush();
  }  // the destructor closes without losing what was flushed
  EXPECT_THROW(CubeWriter(file, test_layout(), OpenMode::kCreate), CubeError);
  try {
    CubeWriter other(file, test_layout("f2"), OpenMode::kResume);
    FAIL() << "resumed another study's cube";
  } catch (const CubeError& e) {
    EXPECT_NE(std::string(e.what()).find("was made by a different study"), std::string::npos) << e.what();
  }
  {
    CubeWriter writer(file, test_layout(), OpenMode::kResume);
    EXPECT_TRUE(writer.resumed());
    EXPECT_EQ(writer.done_count(), 1);
    EXPECT_EQ(writer.status()[5], 0);
    writer.store(6, 0, {0.03, 2});
    writer.store_note(6, "second");
    writer.close();
  }
  {
    CubeReader reader(file);
    const auto theta = reader.read_metric("theta_max_rad");
    EXPECT_EQ(theta[5], 0.02);
    EXPECT_EQ(theta[6], 0.03);
    ASSERT_EQ(reader.read_notes().size(), 2u);
    EXPECT_EQ(reader.read_notes()[1].second, "second");
  }  // HDF5 cannot truncate a file this process still has open
  CubeWriter fresh(file, test_layout("f3"), OpenMode::kOverwrite);
  EXPECT_EQ(fresh.done_count(), 0);
}

// The writer holds only what came since the last checkpoint: a chunk finished over several
// checkpoints keeps every value (each checkpoint lays the new ones over the file's), and
// read_values() sees both.
TEST(CubeFile, ChunksFinishedOverSeveralCheckpointsKeepEveryValue) {
  const auto file = test::scratch_dir("cube_pending") / "c.h5";
  CubeWriter writer(file, test_layout(), OpenMode::kCreate);
  EXPECT_EQ(writer.pending_bytes(), 0u);
  for (std::int64_t i = 0; i < 24; i += 2) writer.store(i, 0, {0.001 * static_cast<double>(i), 1});
  EXPECT_GT(writer.pending_bytes(), 0u);
  writer.flush();
  EXPECT_EQ(writer.pending_bytes(), 0u);
  for (std::int64_t i = 1; i < 24; i += 2) writer.store(i, 0, {0.001 * static_cast<double>(i), 2});
  writer.store_note(3, "late");
  const auto seen = writer.read_values("theta_max_rad");
  for (std::size_t i = 0; i < 24; ++i) EXPECT_EQ(seen[i], 0.001 * static_cast<double>(i)) << i;
  writer.flush();
  writer.store_note(5, "later");
  writer.close();
  CubeReader reader(file);
  const auto theta = reader.read_metric("theta_max_rad");
  const auto impacts = reader.read_metric("impacts");
  for (std::size_t i = 0; i < 24; ++i) {
    EXPECT_EQ(theta[i], 0.001 * static_cast<double>(i)) << i;
    EXPECT_EQ(impacts[i], i % 2 == 0 ? 1.0 : 2.0) << i;
  }
  const auto status = reader.read_status();
  EXPECT_EQ(std::count(status.begin(), status.end(), kStatusNotRun), 0);
  const auto notes = reader.read_notes();
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_EQ(notes[0].second, "late");
  EXPECT_EQ(notes[1].second, "later");
}

TEST(CubeFile, ReaderRejectsFilesThatAreNotCubes) {
  const auto dir = test::scratch_dir("cube_not");
  test::write_file(dir, "text.h5", "hello");
  EXPECT_THROW(CubeReader(dir / "text.h5"), CubeError);
  EXPECT_THROW(CubeReader(dir / "missing.h5"), CubeError);
}

TEST(CubeQuery, SelectorsMatchDimensionAndAuxiliaryCoordinates) {
  const CubeLayout l = test_layout();
  const auto by_scale = select_cases(l, {parse_selector("scale=1")});
  EXPECT_EQ(std::count(by_scale.begin(), by_scale.end(), true), 2 * 4);
  const auto by_varied = select_cases(l, {parse_selector("varied_parameter=kappa"), parse_selector("record=ER1")});
  EXPECT_EQ(std::count(by_varied.begin(), by_varied.end(), true), 3 * 2);
  EXPECT_TRUE(by_varied[1]);
  EXPECT_FALSE(by_varied[0]);
  EXPECT_THROW(select_cases(l, {parse_selector("scale=7")}), CubeError);
  EXPECT_THROW(select_cases(l, {parse_selector("mass=1")}), CubeError);
  EXPECT_THROW(parse_selector("scale"), CubeError);
}

// Repeated messages are counted by kind (their numbers set aside), in order of first case.
TEST(MessageKinds, RepeatedMessagesAreCountedNotListed) {
  const auto kinds = message_kinds({{3, "tendon strain reached the fracture strain"},
                                    {5, "non-finite state at t = 3.200000 s"},
                                    {7, "tendon strain reached the fracture strain"},
                                    {9, "non-finite state at t = 1e-05 s"},
                                    {11, "more than max_steps steps"}});
  ASSERT_EQ(kinds.size(), 3u);
  EXPECT_EQ(kinds[0].text, "tendon strain reached the fracture strain");
  EXPECT_EQ(kinds[0].count, 2);
  EXPECT_EQ(kinds[0].first_case, 3);
  EXPECT_EQ(kinds[1].text, "non-finite state at t = 3.200000 s");
  EXPECT_EQ(kinds[1].count, 2);
  EXPECT_EQ(kinds[2].count, 1);
  EXPECT_EQ(kinds[2].first_case, 11);
}

}  // namespace
}  // namespace pcrf::cube
