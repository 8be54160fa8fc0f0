// pcrf_index_close: what closing a fold's file costs as the cube grows (issue 38, item 5). Not a
// test; run by bench/master/index_close_cost.py under callgrind.
//
//   build/bench/master/pcrf_index_close FILE VARIABLES CHUNKS
//
// Makes FILE (refused if it exists) with VARIABLES float64 datasets of CHUNKS chunks of 16 384
// values each, stored as the cube stores its variables (HDF5 1.10 file format bounds, so a fixed
// array indexes the chunks; shuffle, then deflate; NaN fill), writes every chunk raw
// (H5Dwrite_chunk, as CubeWriter's stream writes a unit's sealed chunks: a chunk of each
// variable in turn), then closes it. The chunks' bytes are not a valid stream: nothing reads
// them; HDF5 stores and indexes them as they are.
#include <hdf5.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s FILE VARIABLES CHUNKS\n", argv[0]);
    return 2;
  }
  const std::string file = argv[1];
  const long variables = std::atol(argv[2]), chunks = std::atol(argv[3]);
  if (variables < 1 || variables > 1000 || chunks < 1 || chunks > (1L << 20) || std::filesystem::exists(file)) {
    std::fprintf(stderr, "%s: VARIABLES in [1, 1000], CHUNKS in [1, 2^20], FILE new\n", argv[0]);
    return 2;
  }
  constexpr hsize_t kChunkValues = 16384;  // the cube's unit of cases (cube::ChunkGrid)
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_small_data_block_size(fapl, 0);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110);
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl);
  if (f < 0) return 1;
  const hsize_t values = kChunkValues * static_cast<hsize_t>(chunks);
  const hid_t space = H5Screate_simple(1, &values, nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  const hsize_t chunk = kChunkValues;
  H5Pset_chunk(dcpl, 1, &chunk);
  H5Pset_shuffle(dcpl);
  H5Pset_deflate(dcpl, 1);
  const double fill = std::numeric_limits<double>::quiet_NaN();
  H5Pset_fill_value(dcpl, H5T_NATIVE_DOUBLE, &fill);
  std::vector<hid_t> sets;
  for (long v = 0; v < variables; ++v)
    sets.push_back(H5Dcreate2(f, ("v" + std::to_string(v)).c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT));
  std::vector<char> bytes(4096, 7);
  for (long c = 0; c < chunks; ++c) {
    const hsize_t offset = static_cast<hsize_t>(c) * kChunkValues;
    for (long v = 0; v < variables; ++v) {
      const std::size_t size = 1500 + static_cast<std::size_t>((c * 37 + v * 11) % 1000);  // a sealed chunk's size [bytes]
      if (H5Dwrite_chunk(sets[static_cast<std::size_t>(v)], H5P_DEFAULT, 0, &offset, size, bytes.data()) < 0) return 1;
    }
  }
  for (const hid_t d : sets) H5Dclose(d);
  H5Sclose(space);
  H5Pclose(dcpl);
  H5Pclose(fapl);
  return H5Fclose(f) < 0 ? 1 : 0;
}
