// pcrf_cube_filters: what each variable of a cube costs on disk under other deflate levels and
// with or without the shuffle filter (issue 38, "a smaller cube"). Not a test.
//
//   build/bench/master/pcrf_cube_filters CUBE.h5 [CHUNK_CASES]
//
// Every 1-D and N-D numeric variable is read whole and cut into pieces of CHUNK_CASES values
// (default: the variable's own chunk, or 65 536 values where it has none), each piece shuffled
// or not and deflated as HDF5's filters do (zlib's compress2 on the piece); the sum over pieces,
// divided by the number of cases, is printed per variable and for the whole cube in bytes a
// case, beside what the file stores now. Variable-length text is left out (listed as such).
#include <hdf5.h>
#include <zlib.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

struct Row {
  std::string name;
  double stored = 0.0;      // bytes in the file now
  double cost[2][3] = {};   // [shuffle][level 1, 4, 9]
  bool text = false;
};

constexpr int kLevels[3] = {1, 4, 9};

std::vector<unsigned char> shuffled(const unsigned char* data, std::size_t count, std::size_t width) {
  std::vector<unsigned char> out(count * width);
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t b = 0; b < width; ++b) out[b * count + i] = data[i * width + b];
  return out;
}

double deflated(const std::vector<unsigned char>& bytes, int level) {
  uLongf size = compressBound(bytes.size());
  std::vector<unsigned char> out(size);
  if (compress2(out.data(), &size, bytes.data(), bytes.size(), level) != Z_OK) std::abort();
  return static_cast<double>(size);
}

std::vector<Row> rows;
std::size_t chunk_override = 0;

herr_t visit(hid_t location, const char* name, const H5O_info_t* info, void*) {
  if (info->type != H5O_TYPE_DATASET) return 0;
  const hid_t set = H5Dopen2(location, name, H5P_DEFAULT);
  const hid_t type = H5Dget_type(set);
  Row row{name, static_cast<double>(H5Dget_storage_size(set))};
  if (H5Tget_class(type) == H5T_STRING || H5Tis_variable_str(type) > 0) {
    row.text = true;
  } else {
    const hid_t space = H5Dget_space(set);
    const auto count = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
    const std::size_t width = H5Tget_size(type);
    std::vector<unsigned char> data(count * width);
    const hid_t native = H5Tget_native_type(type, H5T_DIR_DEFAULT);
    H5Dread(set, native, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data());
    std::size_t piece = 65536;
    const hid_t plist = H5Dget_create_plist(set);
    if (H5Pget_layout(plist) == H5D_CHUNKED) {
      hsize_t dims[8];
      const int rank = H5Pget_chunk(plist, 8, dims);
      piece = 1;
      for (int d = 0; d < rank; ++d) piece *= dims[d];
    }
    if (chunk_override > 0) piece = chunk_override;
    for (std::size_t first = 0; first < count; first += piece) {
      const std::size_t n = std::min(piece, count - first);
      const unsigned char* p = data.data() + first * width;
      const std::vector<unsigned char> plain(p, p + n * width), mixed = shuffled(p, n, width);
      for (int l = 0; l < 3; ++l) {
        row.cost[0][l] += deflated(plain, kLevels[l]);
        row.cost[1][l] += deflated(mixed, kLevels[l]);
      }
    }
    H5Pclose(plist);
    H5Tclose(native);
    H5Sclose(space);
  }
  H5Tclose(type);
  H5Dclose(set);
  rows.push_back(row);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s CUBE.h5 [CHUNK_CASES]\n", argv[0]);
    return 2;
  }
  if (argc > 2) chunk_override = std::strtoull(argv[2], nullptr, 10);
  const hid_t file = H5Fopen(argv[1], H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return 1;
  const hid_t status = H5Dopen2(file, "status", H5P_DEFAULT);
  const hid_t space = H5Dget_space(status);
  const double cases = static_cast<double>(H5Sget_simple_extent_npoints(space));
  H5Sclose(space);
  H5Dclose(status);
  H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_NATIVE, visit, nullptr, H5O_INFO_BASIC);
  H5Fclose(file);
  std::printf("bytes a case, %.0f cases (deflate level 1, 4, 9; without and with shuffle)\n", cases);
  std::printf("| variable | stored now | l1 | l4 | l9 | shuffle l1 | shuffle l4 | shuffle l9 |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
  Row total{"all numeric"};
  for (const auto& r : rows) {
    if (r.text) {
      std::printf("| %s | %.2f | text, not recompressed |||||| \n", r.name.c_str(), r.stored / cases);
      continue;
    }
    std::printf("| %s | %.2f", r.name.c_str(), r.stored / cases);
    total.stored += r.stored;
    for (int s = 0; s < 2; ++s)
      for (int l = 0; l < 3; ++l) {
        std::printf(" | %.2f", r.cost[s][l] / cases);
        total.cost[s][l] += r.cost[s][l];
      }
    std::printf(" |\n");
  }
  std::printf("| **%s** | %.2f", total.name.c_str(), total.stored / cases);
  for (int s = 0; s < 2; ++s)
    for (int l = 0; l < 3; ++l) std::printf(" | %.2f", total.cost[s][l] / cases);
  std::printf(" |\n");
  return 0;
}
