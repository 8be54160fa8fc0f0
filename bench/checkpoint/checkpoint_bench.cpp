// pcrf_checkpoint_bench: what one checkpoint of a result cube costs against the cube's size.
// A cube of --cases cases and --metrics metrics is filled completely (--varying of them vary
// case to case with five digits, the others are 0), then each repeat stores one
// chunk's worth of changed cases (--changed) and times CubeWriter::flush(). Beside it, the
// time of a plain copy of the cube file: the part of a checkpoint that grows with the cube.
//
//   build/bench/checkpoint/pcrf_checkpoint_bench --cases 1000000 [--metrics 17] [--repeats 5] [--dir /tmp]
//
// Prints one line: cases, metrics, cube size [MB], median checkpoint [s], median copy [s].
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

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
  CLI::App app{"Checkpoint cost: one flush of a full cube against the cube's size"};
  long cases = 1'000'000, changed = 16384, fill_block = 1'000'000;
  int metrics = 17, varying = 17, repeats = 5;
  std::string dir = std::filesystem::temp_directory_path().string();
  app.add_option("--cases", cases, "cases in the cube")->capture_default_str();
  app.add_option("--metrics", metrics, "metrics stored per case")->capture_default_str();
  app.add_option("--varying", varying, "metrics that vary from case to case (the others are 0)")->capture_default_str();
  app.add_option("--changed", changed, "cases stored before each timed checkpoint")->capture_default_str();
  app.add_option("--repeats", repeats, "timed checkpoints (the median is printed)")->capture_default_str();
  app.add_option("--fill-block", fill_block, "cases stored between the checkpoints that fill the cube")->capture_default_str();
  app.add_option("--dir", dir, "folder for the cube")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const std::filesystem::path file = std::filesystem::path(dir) / ("checkpoint_bench_" + std::to_string(cases) + ".h5");
  std::vector<double> checkpoint_s, copy_s;
  double fill_s = 0.0;
  {
    CubeWriter writer(file, bench_layout(cases, metrics), OpenMode::kOverwrite);
    auto start = Clock::now();
    for (std::int64_t i = 0; i < cases; ++i) {
      writer.store(i, 0, row_of(i, metrics, varying, 0));
      if ((i + 1) % fill_block == 0 || i + 1 == cases) writer.flush();
    }
    fill_s = seconds_since(start);
    for (int r = 0; r < repeats; ++r) {
      const std::int64_t first = (static_cast<std::int64_t>(r) * 7919 * changed) % std::max<std::int64_t>(1, cases - changed);
      for (std::int64_t i = first; i < std::min<std::int64_t>(cases, first + changed); ++i)
        writer.store(i, 0, row_of(i, metrics, varying, static_cast<std::uint64_t>(r) + 1));
      start = Clock::now();
      writer.flush();
      checkpoint_s.push_back(seconds_since(start));
    }
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
  std::printf("cases %ld metrics %d cube_MB %.1f checkpoint_s %.4f copy_s %.4f fill_s %.2f changed %ld\n", cases, metrics,
              size_mb, median(checkpoint_s), median(copy_s), fill_s, changed);
  return 0;
}
