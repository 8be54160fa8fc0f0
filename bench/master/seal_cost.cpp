// pcrf_seal_cost: what a worker's sealing costs, on a real cube's values (issue 38, item 5:
// a worker's instructions per case beyond its own cases). Not a test.
//
//   build/bench/master/pcrf_seal_cost CUBE.h5 [ROUNDS]
//   valgrind --tool=callgrind build/bench/master/pcrf_seal_cost CUBE.h5   (instructions)
//
// Reads the cube's metrics, status and coordinates, then seals every chunk of the metrics
// (cube::seal_chunk, as a worker does with each chunk it computed) and every piece of each
// chunked coordinate (cube::seal_coordinate_piece, as the cube's creation does), ROUNDS times
// (default 1), and checks that each sealed variable inflates back to its values. Prints the
// sealed bytes a case per variable and in all: what the cube stores of them, and the CRC-32 of
// every sealed byte in order (two builds that print the same one sealed the same bytes). Callgrind's
// inclusive counts of seal_chunk and seal_coordinate_piece, divided by the cases and rounds,
// are their instructions a case.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <zlib.h>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/sealed_chunk.hpp"

namespace {

using namespace pcrf::cube;

/// CRC-32 of every sealed byte, in the order sealed.
uLong digest = crc32(0L, Z_NULL, 0);

void add_to_digest(const std::vector<char>& sealed) {
  digest = crc32_z(digest, reinterpret_cast<const Bytef*>(sealed.data()), sealed.size());
}

/// Seals every chunk of the cube's metrics; adds each variable's sealed bytes to `bytes`.
void seal_metrics(const CubeReader& reader, std::vector<double>& bytes) {
  const CubeLayout& layout = reader.layout();
  const ChunkGrid grid(layout.shape());
  const std::size_t metrics = layout.metrics.size();
  std::vector<std::vector<double>> columns;
  for (const auto& m : layout.metrics) columns.push_back(reader.read_metric(m.name));
  const std::vector<std::int8_t> status = reader.read_status();
  const std::size_t padded = padded_elements(grid);
  for (std::size_t chunk = 0; chunk < grid.chunk_count(); ++chunk) {
    const auto r = grid.range(chunk);
    const auto count = static_cast<std::size_t>(r.count);
    const auto first = static_cast<std::size_t>(r.first);
    std::vector<double> values(metrics * count);
    for (std::size_t m = 0; m < metrics; ++m)
      std::memcpy(values.data() + m * count, columns[m].data() + first, count * sizeof(double));
    const std::span<const std::int8_t> codes(status.data() + first, count);
    const SealedChunk sealed = seal_chunk(grid, chunk, metrics, codes, values, {});
    for (std::size_t v = 0; v <= metrics; ++v) {
      bytes[v] += static_cast<double>(sealed.filtered[v].size());
      add_to_digest(sealed.filtered[v]);
      const std::size_t width = v < metrics ? sizeof(double) : 1;
      const auto plain = unfilter(sealed.filtered[v], padded, width, "bench");
      const void* want = v < metrics ? static_cast<const void*>(columns[v].data() + first) : codes.data();
      if (std::memcmp(plain.data(), want, count * width) != 0) {
        std::fprintf(stderr, "variable %zu of chunk %zu does not inflate to its values\n", v, chunk);
        std::exit(1);
      }
    }
  }
}

/// Seals every piece of each chunked coordinate; adds each one's sealed bytes to `bytes`.
void seal_coordinates(const CubeReader& reader, std::vector<double>& bytes) {
  const CubeLayout& layout = reader.layout();
  for (std::size_t k = 0; k < layout.coordinates.size(); ++k) {
    const Coordinate& c = layout.coordinates[k];
    if (!c.chunked()) continue;
    const std::size_t values = coordinate_chunk_values(layout, c);
    for (std::size_t p = 0; p < piece_count(c.size(), values); ++p) {
      const std::vector<char> sealed = seal_coordinate_piece(c, values, p);
      bytes[k] += static_cast<double>(sealed.size());
      add_to_digest(sealed);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s CUBE.h5 [ROUNDS]\n", argv[0]);
    return 2;
  }
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 1;
  const CubeReader reader(argv[1]);
  const CubeLayout& layout = reader.layout();
  double cases = 1.0;
  for (const auto& d : layout.dimensions) cases *= static_cast<double>(d.size);
  std::vector<double> metric_bytes(layout.metrics.size() + 1), coordinate_bytes(layout.coordinates.size());
  for (int round = 0; round < rounds; ++round) {
    seal_metrics(reader, metric_bytes);
    seal_coordinates(reader, coordinate_bytes);
  }
  const double per_case = cases * rounds;
  double total = 0.0;
  std::printf("%-24s %12s\n", "variable", "B/case");
  for (std::size_t m = 0; m <= layout.metrics.size(); ++m) {
    const std::string name = m < layout.metrics.size() ? layout.metrics[m].name : kStatusName;
    std::printf("%-24s %12.4f\n", name.c_str(), metric_bytes[m] / per_case);
    total += metric_bytes[m];
  }
  for (std::size_t k = 0; k < layout.coordinates.size(); ++k) {
    if (!layout.coordinates[k].chunked()) continue;
    std::printf("%-24s %12.4f\n", layout.coordinates[k].name.c_str(), coordinate_bytes[k] / per_case);
    total += coordinate_bytes[k];
  }
  std::printf("%-24s %12.4f\n", "sealed, in all", total / per_case);
  std::printf("%-24s %12.8lx\n", "CRC-32 of sealed bytes", digest);
  return 0;
}
