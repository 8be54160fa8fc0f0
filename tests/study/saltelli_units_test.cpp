// Saltelli studies in whole chunks (issue 38: Saltelli base samples stay whole within one
// chunk). A Saltelli cube is cut into chunks of whole base samples; its chunks go out as units
// column by column (a piece of the frame axis for every record), so that a stopped cube holds
// whole base samples; the cube equals the one of the case-by-case, frame-by-frame hand-out
// (--batch-size) at one rank, at three and in shards; a stopped cube's Sobol' indices use only
// its whole base samples; a cube of an earlier version, cut otherwise, resumes case by case in
// its own chunks.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "pcrf/analysis/sobol_indices.hpp"
#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/run/unit_order.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

constexpr std::size_t kGroup = 5;  // d + 2 frames a base sample, d = 3 varied parameters

/// Two records, `samples` base samples of three parameters (5 frames each); `pga` sets how
/// many frames lift: 0.026 g none (a few µs a case), 0.75 g some (about 15 µs a case on average).
std::string saltelli_study(std::size_t samples, double pga1_g = 0.026, double pga2_g = 0.02) {
  std::ostringstream s;
  s << "[study]\nname = \"salt\"\n[[records]]\nsynthetic = [\"stochastic:seed=1,pga_g=" << pga1_g
    << ",duration_s=2,dt_s=0.01\", \"stochastic:seed=2,pga_g=" << pga2_g << ",duration_s=2,dt_s=0.01\"]\n"
    << "[plan]\nkind = \"saltelli\"\nsamples = " << samples << "\nseed = 7\n"
    << "[axes]\nkappa = {from = 1.26, to = 2.34}\ntan_alpha = {from = 0.14, to = 0.26}\n"
       "lambda_h = {from = 0.14, to = 0.26}\n";
  return s.str();
}

study::Study parse(const std::string& text) { return study::parse_study(text, "s.toml", test::source_dir()); }

test::CommandResult study_in(const std::filesystem::path& dir, const std::string& args, const std::string& launcher = "") {
  return test::run_command("cd " + quoted(dir) + " && " + launcher + pcrf() + " study s.toml --progress-interval 0 " + args);
}

const std::vector<std::string> kTimes{"wall_time_s", "cpu_time_s"};

TEST(SaltelliUnits, ChunksHoldWholeBaseSamplesAndGoOutColumnByColumn) {
  const study::Study s = parse(saltelli_study(32768));
  const study::CaseSpace space(s);
  ASSERT_EQ(space.shape(), (std::vector<std::size_t>{2, 1, 163840}));
  EXPECT_EQ(space.chunk_multiples(), (std::vector<std::size_t>{1, 1, kGroup}));
  const cube::ChunkGrid grid(space.shape(), cube::kChunkCases, space.chunk_multiples());
  const run::FrameColumns columns = run::frame_columns(grid, space);
  ASSERT_TRUE(columns);
  EXPECT_EQ(columns.columns, 11u);
  EXPECT_EQ(columns.excitations, 2u);
  const auto order = run::unit_order(grid, space);
  ASSERT_EQ(order.size(), grid.chunk_count());
  std::set<std::size_t> seen;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto r = grid.range(order[k]);
    const auto frame = static_cast<std::size_t>(r.first % 163840), record = static_cast<std::size_t>(r.first / 163840);
    // Column k / 2, record k % 2: the same frames for both records, one column after another.
    EXPECT_EQ(record, k % 2);
    EXPECT_EQ(frame, (k / 2) * 16380);
    EXPECT_EQ(frame % kGroup, 0u);
    EXPECT_EQ(static_cast<std::size_t>(r.count) % kGroup, 0u);
    // Its hand-out positions (frame by frame: every record of frame f, then f + 1) are column k / 2's.
    const auto [first, end] = columns.positions(grid, columns.column_of(order[k]));
    EXPECT_GE(space.handout_position(r.first), first);
    EXPECT_LT(space.handout_position(r.first + r.count - 1), end);
    seen.insert(order[k]);
  }
  EXPECT_EQ(seen.size(), grid.chunk_count());
  for (std::int64_t p = 0; p < space.size(); p += 997) EXPECT_EQ(space.handout_position(space.handout_index(p)), p);
  // A cube of an earlier version (16 384 frames a chunk: base samples split) has no columns:
  // its cases go case by case, frame by frame, as before.
  const cube::ChunkGrid earlier(space.shape());
  EXPECT_FALSE(run::frame_columns(earlier, space));
  EXPECT_TRUE(run::unit_order(earlier, space).empty());
  // A frame axis short enough that a chunk holds it whole for several records: no columns
  // (no chunk order keeps base samples whole as the frame-by-frame order does).
  const study::CaseSpace small(parse(saltelli_study(1000)));
  EXPECT_TRUE(run::unit_order(cube::ChunkGrid(small.shape(), cube::kChunkCases, small.chunk_multiples()), small).empty());
  // Other plans: storage order.
  const study::CaseSpace lhs(parse(saltelli_study(40000).replace(saltelli_study(40000).find("saltelli"), 8, "lhs")));
  const cube::ChunkGrid lhs_grid(lhs.shape(), cube::kChunkCases, lhs.chunk_multiples());
  EXPECT_EQ(lhs_grid, cube::ChunkGrid(lhs.shape()));
  const auto lhs_order = run::unit_order(lhs_grid, lhs);
  ASSERT_EQ(lhs_order.size(), lhs_grid.chunk_count());
  for (std::size_t c = 0; c < lhs_order.size(); ++c) EXPECT_EQ(lhs_order[c], c);
}

TEST(SaltelliUnits, WholeChunksGiveTheCubeOfTheFrameByFrameHandOut) {
  const auto dir = test::scratch_dir("saltelli_units");
  test::write_file(dir, "s.toml", saltelli_study(32768));
  const auto one_by_one = study_in(dir, "--batch-size 64 -o cases.h5");
  ASSERT_EQ(one_by_one.exit_code, 0) << one_by_one.err;
  const auto units = study_in(dir, "-o units.h5");
  ASSERT_EQ(units.exit_code, 0) << units.err;
  EXPECT_NE(units.err.find("327680 cases computed, 0 failed"), std::string::npos) << units.err;
  expect_same_cube(dir / "cases.h5", dir / "units.h5", kTimes);
  EXPECT_EQ(cube::CubeReader(dir / "units.h5").layout().chunk_shape, (std::vector<std::size_t>{1, 1, 16380}));
  if (have_mpirun()) {
    const auto three = study_in(dir, "-o three.h5", mpirun(3));
    ASSERT_EQ(three.exit_code, 0) << three.err;
    EXPECT_EQ(three.err.find("instead of its part"), std::string::npos) << three.err;
    expect_same_cube(dir / "cases.h5", dir / "three.h5", kTimes);
  }
  // Shards own runs of hand-out positions (frames of every record): a chunk whole inside
  // one is a unit of it; the merge is the whole cube.
  for (const char* k : {"1", "2", "3"})
    ASSERT_EQ(study_in(dir, std::string("--shard ") + k + "/3 -o part" + k + ".h5").exit_code, 0);
  const auto merged =
      test::run_command("cd " + quoted(dir) + " && " + pcrf() + " cube merge part1.h5 part2.h5 part3.h5 -o all.h5");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  expect_same_cube(dir / "cases.h5", dir / "all.h5", kTimes);
}

/// Base samples whose every frame has a status other than not_run for every record.
std::vector<bool> whole_base_samples(const std::vector<std::int8_t>& status, std::size_t records, std::size_t frames) {
  std::vector<bool> whole(frames / kGroup, true);
  for (std::size_t r = 0; r < records; ++r)
    for (std::size_t f = 0; f < frames; ++f)
      if (status[r * frames + f] == cube::kStatusNotRun) whole[f / kGroup] = false;
  return whole;
}

/// The rows of `pcrf cube sensitivity --csv -`: parameter → its columns.
std::map<std::string, std::map<std::string, std::string>> sensitivity_rows(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::stringstream header(line); std::getline(header, line, ',');) names.push_back(line);
  std::map<std::string, std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::map<std::string, std::string> row;
    std::stringstream cells(line);
    for (std::size_t k = 0; k < names.size() && std::getline(cells, line, ','); ++k) row[names[k]] = line;
    rows[row["parameter"]] = row;
  }
  return rows;
}

TEST(SaltelliUnits, AStoppedCubeHoldsWholeColumnsAndItsSobolIndicesUseOnlyWholeBaseSamples) {
  const auto dir = test::scratch_dir("saltelli_units_stop");
  // 16 384 base samples (81 920 frames, six columns of two records) of which some frames lift.
  test::write_file(dir, "s.toml", saltelli_study(16384, 0.76, 0.74));
  const auto err = dir / "s.err";
  const pid_t pid = spawn_shell("cd " + quoted(dir) + " && exec " + pcrf() +
                                " study s.toml -o s.h5 --progress-interval-s 0.02 2>" + quoted(err));
  ASSERT_GT(pid, 0);
  std::pair<long, long> progress{0, 0};  // stop past a third: two columns done at least, most likely
  for (int i = 0; i < 1500 && !(progress.second > 0 && 3 * progress.first >= progress.second); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    progress = last_progress(err);
  }
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int wstatus = 0;
  ::waitpid(pid, &wstatus, 0);
  const cube::CubeReader reader(dir / "s.h5");
  const auto status = reader.read_status();
  const std::size_t frames = 81920, records = 2;
  const auto done = static_cast<std::size_t>(
      std::count_if(status.begin(), status.end(), [](std::int8_t s) { return s != cube::kStatusNotRun; }));
  if (done == status.size()) GTEST_SKIP() << "the run ended before the signal";
  ASSERT_GT(done, 0u);
  // Units go out column by column, computed whole one after another by rank 0's one worker:
  // whole chunks in column order, then at most the one in hand when the signal came, in part.
  const cube::ChunkGrid grid = cube::layout_grid(reader.layout());
  const study::CaseSpace space(parse(saltelli_study(16384, 0.76, 0.74)));
  const auto order = run::unit_order(grid, space);
  ASSERT_FALSE(order.empty());
  std::size_t k = 0;
  auto done_in = [&](std::size_t chunk) {
    const auto r = grid.range(chunk);
    return static_cast<std::size_t>(std::count_if(status.begin() + r.first, status.begin() + r.first + r.count,
                                                  [](std::int8_t s) { return s != cube::kStatusNotRun; }));
  };
  while (k < order.size() && done_in(order[k]) == static_cast<std::size_t>(grid.range(order[k]).count)) ++k;
  if (k < order.size()) ++k;  // the chunk in hand, done in part (or not at all)
  for (; k < order.size(); ++k) EXPECT_EQ(done_in(order[k]), 0u) << "chunk " << order[k] << ", unit " << k;
  // The whole base samples: every column done for both records, at least.
  const auto whole = whole_base_samples(status, records, frames);
  const auto whole_count = static_cast<std::size_t>(std::count(whole.begin(), whole.end(), true));
  const auto column_cases = grid.range(0).count * static_cast<std::int64_t>(records);
  EXPECT_GE(static_cast<std::int64_t>(whole_count * kGroup * records), static_cast<std::int64_t>(done) - column_cases)
      << "a column at most is in part";
  // Sobol' indices of the stopped cube: from its whole base samples alone.
  const auto sensitivity =
      test::run_command(pcrf() + " cube sensitivity " + quoted(dir / "s.h5") + " --metric lambda_g --csv -");
  ASSERT_EQ(sensitivity.exit_code, 0) << sensitivity.err;
  const auto rows = sensitivity_rows(sensitivity.out);
  ASSERT_EQ(rows.size(), 3u) << sensitivity.out;
  analysis::SaltelliOutputs outputs{{}, {}, std::vector<std::vector<double>>(3)};
  const auto values = reader.read_metric("lambda_g");
  for (std::size_t j = 0; j < whole.size(); ++j) {
    if (!whole[j]) continue;
    auto mean = [&](std::size_t block) { return (values[j * kGroup + block] + values[frames + j * kGroup + block]) / 2.0; };
    outputs.f_a.push_back(mean(0));
    outputs.f_b.push_back(mean(1));
    for (std::size_t p = 0; p < 3; ++p) outputs.f_ab[p].push_back(mean(2 + p));
  }
  const auto expected = analysis::sobol_indices(outputs);
  const char* names[] = {"kappa", "tan_alpha", "lambda_h"};
  for (std::size_t p = 0; p < 3; ++p) {
    const auto& row = rows.at(names[p]);
    EXPECT_EQ(std::stoul(row.at("samples")), whole_count);
    EXPECT_DOUBLE_EQ(std::stod(row.at("S1")), expected[p].s1) << names[p];
    EXPECT_DOUBLE_EQ(std::stod(row.at("ST")), expected[p].st) << names[p];
  }
  // Resumed (at three ranks: the rest in units, the chunk in part case by case, frame by
  // frame), it is the cube of the frame-by-frame hand-out.
  const auto resumed = study_in(dir, "-o s.h5 --resume", have_mpirun() ? mpirun(3) : "");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  ASSERT_EQ(study_in(dir, "--batch-size 64 -o cases.h5").exit_code, 0);
  expect_same_cube(dir / "cases.h5", dir / "s.h5", kTimes);
}

/// A cube as an earlier version left it when killed: its chunks by the rule without groups
/// (16 384 frames), the first `folded` cases in hand-out order (frame by frame) from `whole`
/// in the cube, the next `journaled` in its journal (chunks numbered by those chunks).
void write_earlier_cube(const std::filesystem::path& whole, const std::filesystem::path& file, std::int64_t folded,
                        std::int64_t journaled, const study::CaseSpace& space) {
  const cube::CubeReader reader(whole);
  cube::CubeLayout layout = reader.layout();
  layout.chunk_shape.clear();
  const auto status = reader.read_status();
  std::vector<std::vector<double>> metrics;
  for (const auto& m : layout.metrics) metrics.push_back(reader.read_metric(m.name));
  cube::CubeWriter writer(file, layout, cube::OpenMode::kCreate);
  std::vector<double> row(metrics.size());
  auto store = [&](std::int64_t from, std::int64_t to) {
    for (std::int64_t p = from; p < to; ++p) {
      const auto i = static_cast<std::size_t>(space.handout_index(p));
      for (std::size_t m = 0; m < row.size(); ++m) row[m] = metrics[m][i];
      writer.store(static_cast<std::int64_t>(i), status[i], row);
    }
  };
  store(0, folded);
  writer.flush();  // a new cube's first checkpoint: a fold
  store(folded, folded + journaled);
  writer.flush();  // under a quarter of the folded results: appended to the journal
}  // not closed, as a killed run: the journal stays

// A cube of an earlier version keeps its chunks: --resume reads them from the file (its
// journal, parts and the workers' units count them so). Three parameters: 16 384 frames split
// base samples of 5, so no columns: case by case, frame by frame, as before. Two parameters:
// 16 384 frames are whole base samples of 4, so its own chunks go out as units by column.
TEST(SaltelliUnits, ACubeOfAnEarlierVersionResumesInItsOwnChunks) {
  const auto dir = test::scratch_dir("saltelli_units_earlier");
  for (const bool two_parameters : {false, true}) {
    std::string text = saltelli_study(two_parameters ? 32768 : 16384);
    if (two_parameters) text = text.substr(0, text.find("lambda_h"));
    test::write_file(dir, "s.toml", text);
    const study::CaseSpace space(parse(text));
    ASSERT_EQ(study_in(dir, "-o whole.h5 --overwrite").exit_code, 0);
    const std::vector<std::size_t> earlier_chunks{1, 1, 16384};
    std::filesystem::remove(dir / "earlier.h5");
    const std::int64_t folded = space.size() / 10, journaled = space.size() / 50;
    write_earlier_cube(dir / "whole.h5", dir / "earlier.h5", folded, journaled, space);
    EXPECT_EQ(cube::CubeReader(dir / "earlier.h5").layout().chunk_shape, earlier_chunks);
    ASSERT_TRUE(std::filesystem::exists(dir / "earlier.h5.journal"));
    EXPECT_EQ(static_cast<bool>(run::frame_columns(cube::ChunkGrid(space.shape()), space)), two_parameters);
    const auto resumed = study_in(dir, "-o earlier.h5 --resume", have_mpirun() ? mpirun(3) : "");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    // The journal's chunks are the cube's: it replays whole (nothing set aside, recomputed).
    EXPECT_NE(resumed.err.find("(" + std::to_string(folded + journaled) + " already done)"), std::string::npos) << resumed.err;
    EXPECT_EQ(resumed.err.find("set aside"), std::string::npos) << resumed.err;
    expect_same_cube(dir / "whole.h5", dir / "earlier.h5", kTimes);
    EXPECT_EQ(cube::CubeReader(dir / "earlier.h5").layout().chunk_shape, earlier_chunks);
    // This version cuts 16 380 frames (whole base samples of 5); 16 384 are whole ones of 4.
    const std::vector<std::size_t> this_version = two_parameters ? earlier_chunks : std::vector<std::size_t>{1, 1, 16380};
    EXPECT_EQ(cube::CubeReader(dir / "whole.h5").layout().chunk_shape, this_version);
  }
}

}  // namespace
}  // namespace pcrf::study_test
