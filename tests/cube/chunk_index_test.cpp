// How a cube indexes its chunks (issue 38 item 5): a new cube's chunked variables take HDF5
// 1.10's fixed array (one entry a chunk, set in place), not a version-1 B-tree, under a
// version-0 superblock (the one H5Fget_file_image copies correctly before HDF5 2.0); a cube
// written before, whose variables have version-1 B-trees, reads and resumes as a new one does.
#include <gtest/gtest.h>

#include <hdf5.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

// Five chunks of the grid (16 384 cases each, the last one partial), and as many of kappa (a
// coordinate written live, cut as the grid): each of those variables has more than one chunk.
// The case number, written at the creation in chunks of up to kCreationCoordinateChunk values,
// is one chunk (HDF5's single-chunk index).
constexpr std::size_t kCases = 70000;
const std::vector<std::string> kChunked = {"case", "kappa", "theta_max_rad", "impacts", "status"};

CubeLayout layout() {
  CubeLayout l;
  l.dimensions = {{"record", 1}, {"case", kCases}};
  Coordinate record{"record", "record", "", "ground motion", {}, {"ER1"}, true, false};
  Coordinate index{"case", "case", "", "frame number", {}, {}, false, true};
  Coordinate kappa{"kappa", "case", "1", "", {}, {}, false, false};
  for (std::size_t i = 0; i < kCases; ++i) {
    index.numbers.push_back(static_cast<double>(i));
    kappa.numbers.push_back(1.0 + 1.0 / static_cast<double>(i + 3));
  }
  l.coordinates = {record, index, kappa};
  l.metrics = {{"theta_max_rad", "rad", "peak"}, {"impacts", "1", "count"}};
  l.status_flags = {{0, "at_rest"}, {4, "solver_failure"}};
  l.attributes = {{kFingerprintName, std::string("f")}};
  return l;
}

double theta_of(std::size_t i) { return 1e-3 * std::sin(static_cast<double>(i)); }

/// Chunk `chunk` whole, sealed as a worker seals it (written raw at the fold), and the first
/// cases of chunk `chunk + 1` one by one (written value by value).
void store_round(CubeWriter& writer, std::size_t chunk) {
  const auto r = writer.grid().range(chunk);
  const auto count = static_cast<std::size_t>(r.count);
  std::vector<std::int8_t> status(count, 0);
  std::vector<double> values(2 * count);
  for (std::size_t k = 0; k < count; ++k) {
    values[k] = theta_of(r.first + k);
    values[count + k] = static_cast<double>(k % 3);
  }
  status[7] = 4;
  writer.store_sealed(seal_chunk(writer.grid(), chunk, 2, status, values, {}));
  const auto next = writer.grid().range(chunk + 1).first;
  for (std::size_t k = 0; k < 5; ++k)
    writer.store(static_cast<std::int64_t>(next + k), 0, {theta_of(next + k), 1.0});
}

H5D_chunk_index_t index_of(const std::filesystem::path& file, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  H5D_chunk_index_t index = H5D_CHUNK_IDX_NTYPES;
  EXPECT_GE(H5Dget_chunk_index_type(d, &index), 0) << name;
  H5Dclose(d);
  H5Fclose(f);
  return index;
}

unsigned superblock_version(const std::filesystem::path& file) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  H5F_info2_t info{};
  EXPECT_GE(H5Fget_info2(f, &info), 0);
  H5Fclose(f);
  return info.super.version;
}

/// What a cube written before issue 38 item 5 has: every chunked variable indexed by a
/// version-1 B-tree (H5Dformat_convert: the layout HDF5 1.8 writes).
void convert_to_btree(const std::filesystem::path& file) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  for (const auto& name : kChunked) {
    const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
    EXPECT_GE(H5Dformat_convert(d), 0) << name;
    H5Dclose(d);
  }
  H5Fclose(f);
}

struct Values {
  std::vector<std::int8_t> status;
  std::vector<std::vector<double>> metrics;
  std::vector<double> kappa, index;
};

Values read(const std::filesystem::path& file) {
  CubeReader reader(file);
  EXPECT_TRUE(reader.damage().empty()) << file;
  return {reader.read_status(),
          {reader.read_metric("theta_max_rad"), reader.read_metric("impacts")},
          reader.layout().find_coordinate("kappa")->numbers,
          reader.layout().find_coordinate("case")->numbers};
}

void expect_same(const Values& a, const Values& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.kappa, b.kappa);
  EXPECT_EQ(a.index, b.index);
  ASSERT_EQ(a.metrics.size(), b.metrics.size());
  for (std::size_t m = 0; m < a.metrics.size(); ++m) {
    ASSERT_EQ(a.metrics[m].size(), b.metrics[m].size());
    for (std::size_t i = 0; i < a.metrics[m].size(); ++i)
      ASSERT_TRUE(a.metrics[m][i] == b.metrics[m][i] || (std::isnan(a.metrics[m][i]) && std::isnan(b.metrics[m][i])))
          << "metric " << m << ", case " << i;
  }
}

TEST(CubeChunkIndex, ANewCubeIndexesItsChunksWithAFixedArrayUnderAVersion0Superblock) {
  const auto file = test::scratch_dir("chunk_index_new") / "c.h5";
  {
    CubeWriter writer(file, layout(), OpenMode::kOverwrite);
    store_round(writer, 0);
    writer.close();
  }
  EXPECT_EQ(superblock_version(file), 0u);
  for (const auto& name : kChunked)
    EXPECT_EQ(index_of(file, name), name == "case" ? H5D_CHUNK_IDX_SINGLE : H5D_CHUNK_IDX_FARRAY) << name;
  const Values v = read(file);
  EXPECT_EQ(v.index, layout().find_coordinate("case")->numbers);
  EXPECT_EQ(v.kappa, layout().find_coordinate("kappa")->numbers);
  EXPECT_EQ(v.status[7], 4);
  EXPECT_EQ(v.metrics[0][16384 + 4], theta_of(16384 + 4));
  EXPECT_EQ(v.status[16384 + 5], kStatusNotRun);
}

TEST(CubeChunkIndex, ACubeWithVersion1BTreesReadsAndResumesAsANewOne) {
  const auto dir = test::scratch_dir("chunk_index_old");
  const auto now = dir / "now.h5";
  const auto before = dir / "before.h5";
  {
    CubeWriter writer(now, layout(), OpenMode::kOverwrite);
    store_round(writer, 0);
    writer.close();
  }
  std::filesystem::remove(before);
  std::filesystem::copy_file(now, before);
  convert_to_btree(before);
  for (const auto& name : kChunked) ASSERT_EQ(index_of(before, name), H5D_CHUNK_IDX_BTREE) << name;
  expect_same(read(now), read(before));
  for (const auto& file : {now, before}) {  // chunks sealed and stored case by case, folded into each
    CubeWriter writer(file, layout(), OpenMode::kResume);
    EXPECT_TRUE(writer.resumed());
    EXPECT_EQ(writer.done_count(), 16384 + 5);
    store_round(writer, 2);
    writer.close();
  }
  for (const auto& name : kChunked) EXPECT_EQ(index_of(before, name), H5D_CHUNK_IDX_BTREE) << name;
  const Values v = read(before);
  expect_same(read(now), v);
  EXPECT_EQ(v.metrics[0][2 * 16384 + 9], theta_of(2 * 16384 + 9));
  EXPECT_EQ(v.status[2 * 16384 + 7], 4);
  EXPECT_EQ(v.metrics[1][3 * 16384 + 4], 1.0);
  EXPECT_EQ(v.status[3 * 16384 + 5], kStatusNotRun);
}

}  // namespace
}  // namespace pcrf::cube
