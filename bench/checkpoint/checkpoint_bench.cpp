// pcrf_checkpoint_bench: what a checkpoint of a result cube costs against the cube's size,
// by journal append (flush) and by fold (docs/checkpoint.md). A cube of --cases cases and
// --metrics metrics is filled completely (--varying of them vary case to case with five
// digits, the others are 0) and folded. Then each repeat stores one chunk's worth of changed
// cases (--changed), times CubeWriter::flush() (an append to the journal: the new
// checkpoint) and then CubeWriter::fold() of that one chunk (a copy of the cube with the
// chunk written into it, renamed: the checkpoint before the journal). Last, a quarter of the
// cube's cases (less --changed) is stored anew through appends of --append-block cases (as a
// run's checkpoints append a flush interval's results, or 256 MiB) and one fold() is timed:
// the fold at kFoldJournalShare. Beside them, the time of a plain copy of the cube file.
//
//   build/bench/checkpoint/pcrf_checkpoint_bench --cases 1000000 [--metrics 17] [--repeats 5] [--dir /tmp]
//
// Prints one line: cases, metrics, cube size [MB], median append [s], median fold of one
// chunk [s], fold at a quarter [s], the journal then [MB], the appends that filled it [s] and
// their results, median copy [s], fill [s].
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_writer.hpp"

namespace {

using namespace pcrf::cube;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

CubeLayout bench_layout(std::int64_t cases, int metrics) {
  CubeLayout l;
  l.dimensions = {{"case", static_cast<std::size_t>(cases)}};
  Coordinate index{"case", "case", "", "case number", {}, {}, false, true};
  index.numbers.resize(static_cast<std::size_t>(cases));
  for (std::size_t i = 0; i < index.numbers.size(); ++i) index.numbers[i] = static_cast<double>(i);
  l.coordinates = {std::move(index)};
  for (int m = 0; m < metrics; ++m) l.metrics.push_back({"metric_" + std::to_string(m), "1", ""});
  l.status_flags = {{0, "done"}};
  l.attributes = {{kFingerprintName, std::string("checkpoint-bench")}};
  return l;
}

/// A result row: `varying` values with about five significant digits (a deterministic hash
/// of the case), the others 0 (a metric of a frame that never lifts).
std::vector<double> row_of(std::int64_t index, int metrics, int varying, std::uint64_t salt) {
  std::vector<double> row(static_cast<std::size_t>(metrics), 0.0);
  std::uint64_t x = static_cast<std::uint64_t>(index) * 0x9E3779B97F4A7C15ull + salt;
  for (int m = 0; m < std::min(varying, metrics); ++m) {
    x ^= x >> 31;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 29;
    row[static_cast<std::size_t>(m)] = static_cast<double>(x % 100000) * 1e-4;
  }
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Checkpoint cost: journal appends and folds of a full cube against the cube's size"};
  long cases = 1'000'000, changed = 16384, fill_block = 1'000'000, append_block = 1'000'000;
  int metrics = 17, varying = 17, repeats = 5;
  std::string dir = std::filesystem::temp_directory_path().string();
  app.add_option("--cases", cases, "cases in the cube")->capture_default_str();
  app.add_option("--metrics", metrics, "metrics stored per case")->capture_default_str();
  app.add_option("--varying", varying, "metrics that vary from case to case (the others are 0)")->capture_default_str();
  app.add_option("--changed", changed, "cases stored before each timed checkpoint")->capture_default_str();
  app.add_option("--repeats", repeats, "timed appends and folds of one chunk (their medians are printed)")->capture_default_str();
  app.add_option("--fill-block", fill_block, "cases stored between the checkpoints that fill the cube")->capture_default_str();
  app.add_option("--append-block", append_block, "cases per append that fills the journal to a quarter")->capture_default_str();
  app.add_option("--dir", dir, "folder for the cube")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const std::filesystem::path file = std::filesystem::path(dir) / ("checkpoint_bench_" + std::to_string(cases) + ".h5");
  const auto journal = journal_path(file);
  std::vector<double> append_s, fold_s, copy_s;
  double fill_s = 0.0, quarter_s = 0.0, quarter_mb = 0.0, quarter_appends_s = 0.0;
  // A journal just under the fold's threshold: a quarter of the cube's cases, less a chunk.
  const auto quarter = static_cast<std::int64_t>(kFoldJournalShare * static_cast<double>(cases)) - changed;
  auto store_block = [&](CubeWriter& writer, std::int64_t first, std::int64_t count, std::uint64_t salt) {
    for (std::int64_t i = first; i < std::min<std::int64_t>(cases, first + count); ++i)
      writer.store(i, 0, row_of(i, metrics, varying, salt));
  };
  {
    CubeWriter writer(file, bench_layout(cases, metrics), OpenMode::kOverwrite);
    auto start = Clock::now();
    for (std::int64_t first = 0; first < cases; first += fill_block) {
      store_block(writer, first, fill_block, 0);
      writer.flush();
    }
    writer.fold();
    fill_s = seconds_since(start);
    for (int r = 0; r < repeats; ++r) {
      const std::int64_t first = (static_cast<std::int64_t>(r) * 7919 * changed) % std::max<std::int64_t>(1, cases - changed);
      store_block(writer, first, changed, static_cast<std::uint64_t>(r) + 1);
      start = Clock::now();
      writer.flush();
      append_s.push_back(seconds_since(start));
      if (!std::filesystem::exists(journal)) {
        std::fprintf(stderr, "the flush folded: --changed must be under a quarter of --cases\n");
        return 1;
      }
      start = Clock::now();
      writer.fold();
      fold_s.push_back(seconds_since(start));
    }
    // The journal filled to just under the fold's threshold, then the fold.
    for (std::int64_t first = 0; first < quarter; first += append_block) {
      store_block(writer, first, std::min<std::int64_t>(append_block, quarter - first), 99);
      start = Clock::now();
      writer.flush();
      quarter_appends_s += seconds_since(start);
    }
    quarter_mb = static_cast<double>(std::filesystem::file_size(journal)) / 1e6;
    start = Clock::now();
    writer.fold();
    quarter_s = seconds_since(start);
    writer.close();
  }
  const std::filesystem::path copy = file.string() + ".copy";
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    std::filesystem::copy_file(file, copy, std::filesystem::copy_options::overwrite_existing);
    copy_s.push_back(seconds_since(start));
  }
  const double size_mb = static_cast<double>(std::filesystem::file_size(file)) / 1e6;
  std::filesystem::remove(copy);
  std::filesystem::remove(file);
  std::printf("cases %ld metrics %d cube_MB %.1f append_s %.4f fold_chunk_s %.4f fold_quarter_s %.4f journal_quarter_MB %.1f "
              "quarter_appends_s %.3f quarter_results %ld copy_s %.4f fill_s %.2f changed %ld\n",
              cases, metrics, size_mb, median(append_s), median(fold_s), quarter_s, quarter_mb, quarter_appends_s,
              static_cast<long>(std::max<std::int64_t>(quarter, 0)), median(copy_s), fill_s, changed);
  return 0;
}
