// Damaged and foreign cubes (issue 29, "Fuzzing"): each is crafted with the HDF5 C API, one
// fault at a time, and must be refused with a CubeError naming the file and the variable,
// before any buffer is sized by what the file declares; on the command line, one line and
// exit 2. The reproducers of the audit's findings, each a test.
#include <gtest/gtest.h>

#include <hdf5.h>
#include <hdf5_hl.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pcrf/cube/cube_reader.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

/// What a crafted cube declares: one dimension `x` (a coordinate of `coordinate` values),
/// `status` over `cases` cases, and the metric `theta_max_rad` of `metric` values.
struct Craft {
  hsize_t cases = 3;
  hsize_t coordinate = 3;
  hsize_t metric = 3;
  bool chunked_coordinate = false;   ///< chunked, unwritten: takes no room in the file
  bool write_coordinate = true;      ///< a contiguous coordinate left unwritten holds no bytes
  hsize_t message_texts = 0;         ///< with messages: case_index of 1 value, text of this many
  hsize_t text_chunk = 0;            ///< with messages: the text's chunk length (0: as make_set)
};

hid_t make_set(hid_t where, const char* name, hid_t type, hsize_t n, bool chunked) {
  const hsize_t chunk = std::min<hsize_t>(n, 1024);
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (chunked && n > 0) H5Pset_chunk(dcpl, 1, &chunk);
  const hid_t set = H5Dcreate2(where, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Pclose(dcpl);
  H5Sclose(space);
  return set;
}

void text_attribute(hid_t object, const char* name, const std::string& text) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, text.size());
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, text.data());
  H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
}

/// A cube as `c` declares it, written at `file`: all values stored where their length is
/// small, nothing stored (HDF5 then reads the fill) where it is huge.
std::filesystem::path craft(const std::filesystem::path& file, const Craft& c) {
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t x = make_set(f, "x", H5T_IEEE_F64LE, c.coordinate, c.chunked_coordinate);
  if (c.write_coordinate && c.coordinate <= 1024) {
    std::vector<double> values(c.coordinate);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.5 * static_cast<double>(i + 1);
    H5Dwrite(x, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  }
  H5DSset_scale(x, "x");
  const hid_t status = make_set(f, "status", H5T_STD_I8LE, c.cases, true);
  if (c.cases <= 1024) {
    const std::vector<std::int8_t> values(c.cases, 0);
    H5Dwrite(status, H5T_NATIVE_INT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  }
  H5DSattach_scale(status, x, 0);
  const std::int8_t flags[2] = {0, -1};
  const hsize_t two = 2;
  const hid_t flag_space = H5Screate_simple(1, &two, nullptr);
  const hid_t a = H5Acreate2(status, "flag_values", H5T_STD_I8LE, flag_space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_INT8, flags);
  H5Aclose(a);
  H5Sclose(flag_space);
  text_attribute(status, "flag_meanings", "at_rest not_run");
  const hid_t metric = make_set(f, "theta_max_rad", H5T_IEEE_F64LE, c.metric, true);
  if (c.metric <= 1024) {
    const std::vector<double> values(c.metric, 0.01);
    H5Dwrite(metric, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  }
  if (c.message_texts > 0) {
    const hid_t group = H5Gcreate2(f, "messages", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dclose(make_set(group, "case_index", H5T_STD_I64LE, 1, true));
    const hid_t text = H5Tcopy(H5T_C_S1);
    H5Tset_size(text, H5T_VARIABLE);
    if (c.text_chunk == 0) {
      H5Dclose(make_set(group, "text", text, c.message_texts, true));
    } else {  // extendible, so that a chunk may be longer than the variable
      const hsize_t unlimited = H5S_UNLIMITED;
      const hid_t space = H5Screate_simple(1, &c.message_texts, &unlimited);
      const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
      H5Pset_chunk(dcpl, 1, &c.text_chunk);
      H5Dclose(H5Dcreate2(group, "text", text, space, H5P_DEFAULT, dcpl, H5P_DEFAULT));
      H5Pclose(dcpl);
      H5Sclose(space);
    }
    H5Tclose(text);
    H5Gclose(group);
  }
  for (const hid_t id : {x, status, metric}) H5Dclose(id);
  H5Fclose(f);
  return file;
}

/// The CubeError of reading a cube whole as `cube info` does ("" when it reads).
std::string refusal(const std::filesystem::path& file) {
  try {
    const CubeReader reader(file);
    (void)reader.read_status();
    for (const auto& m : reader.layout().metrics) (void)reader.read_metric(m.name);
    (void)reader.read_notes();
  } catch (const CubeError& e) {
    return e.what();
  }
  return "";
}

void expect_refused(const std::filesystem::path& file, const std::string& names) {
  const std::string message = refusal(file);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find(names), std::string::npos) << message;
}

/// `pcrf cube COMMAND FILE`, ended after 60 s (a read that blocks fails the test, not the run).
test::CommandResult cube_command(const std::string& command, const std::filesystem::path& file) {
  return test::run_command("timeout 60 " + test::pcrf_executable().string() + " cube " + command + " '" +
                           file.string() + "'");
}

/// One line on stderr naming the file, exit 2, and no "internal error".
void expect_one_line_refusal(const test::CommandResult& r, const std::filesystem::path& file) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(file.filename().string()), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

TEST(CubeDamage, AWholeCraftedCubeReads) {  // the baseline every other test changes one thing of
  const auto file = craft(test::scratch_dir("damage_none") / "c.h5", {});
  EXPECT_EQ(refusal(file), "");
  const CubeReader reader(file);
  EXPECT_EQ(reader.read_metric("theta_max_rad"), std::vector<double>(3, 0.01));
  const auto r = cube_command("export", file);
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// Finding 1: read_metric sized its buffer from `status` and let HDF5 write the metric's own
// length into it (a heap overflow; 10^12 values: SIGSEGV).
TEST(CubeDamage, AMetricLongerThanStatusIsRefusedBeforeItIsRead) {
  const auto dir = test::scratch_dir("damage_long_metric");
  for (const hsize_t length : {hsize_t{5}, hsize_t{1000000000000}}) {
    Craft c;
    c.metric = length;
    const auto file = craft(dir / ("m" + std::to_string(length) + ".h5"), c);
    expect_refused(file, "theta_max_rad");
    expect_one_line_refusal(cube_command("export", file), file);
  }
}

// Finding 7: a metric shorter than `status` was exported as zeros, exit 0.
TEST(CubeDamage, AMetricShorterThanStatusIsRefused) {
  Craft c;
  c.metric = 2;
  const auto file = craft(test::scratch_dir("damage_short_metric") / "c.h5", c);
  expect_refused(file, "theta_max_rad");
  const auto r = cube_command("export", file);
  expect_one_line_refusal(r, file);
  EXPECT_EQ(r.out, "");
}

// Finding 3: a 6 KB cube declaring 10^12 cases made `cube info` end in std::bad_alloc.
TEST(CubeDamage, ACubeDeclaringMoreCasesThanMemoryIsRefused) {
  Craft c;
  c.cases = c.coordinate = c.metric = 1000000000000;
  c.chunked_coordinate = true;
  const auto file = craft(test::scratch_dir("damage_huge") / "c.h5", c);
  ASSERT_LT(std::filesystem::file_size(file), 100000u);
  expect_refused(file, "status");
  expect_one_line_refusal(cube_command("info", file), file);
}

// The file's own storage bounds what a coordinate stored whole may declare.
TEST(CubeDamage, ACoordinateDeclaringMoreBytesThanTheFileIsRefused) {
  Craft c;
  c.cases = c.coordinate = c.metric = 1000000;  // 8 MB of coordinate in a file of a few kB
  c.write_coordinate = false;
  const auto file = craft(test::scratch_dir("damage_unstored") / "c.h5", c);
  ASSERT_LT(std::filesystem::file_size(file), 1000000u);
  expect_refused(file, "'x'");
  expect_one_line_refusal(cube_command("info", file), file);
}

// Finding 4: a coordinate shorter than its dimension gave `internal error:
// vector::_M_range_check` in `cube export`.
TEST(CubeDamage, ACoordinateShorterThanItsDimensionIsRefused) {
  Craft c;
  c.coordinate = 2;
  const auto file = craft(test::scratch_dir("damage_short_coordinate") / "c.h5", c);
  expect_refused(file, "'x'");
  expect_one_line_refusal(cube_command("export", file), file);
}

TEST(CubeDamage, MessagesOfTwoLengthsAreRefused) {
  Craft c;
  c.message_texts = 1000000000000;  // one case index, 10^12 texts: pointers for every one
  const auto file = craft(test::scratch_dir("damage_messages") / "c.h5", c);
  expect_refused(file, "messages/text");
}

// Issue 41: a damaged chunk size of a text variable made every reader allocate a chunk
// buffer of GBs (HDF5 reads a chunk whole) before refusing; the size is checked first.
TEST(CubeDamage, AChunkLargerThanAReaderAllowsIsRefusedBeforeItIsRead) {
  Craft c;
  c.message_texts = 1;
  c.text_chunk = hsize_t{1} << 27;  // 2^27 texts of 16 bytes a chunk: 2.1 GB (HDF5 allows < 4 GiB)
  const auto file = craft(test::scratch_dir("damage_chunk") / "c.h5", c);
  expect_refused(file, "'messages/text' declares chunks of");
  expect_one_line_refusal(cube_command("info", file), file);
}

// Finding 5: `cube info` on a symbolic-link loop ended in an uncaught filesystem_error.
TEST(CubeDamage, ALinkLoopIsRefusedInOneLine) {
  const auto dir = test::scratch_dir("damage_loop");
  std::filesystem::create_symlink(dir / "loop.h5", dir / "loop.h5");
  expect_refused(dir / "loop.h5", "loop.h5");
  expect_one_line_refusal(cube_command("info", dir / "loop.h5"), dir / "loop.h5");
}

// Finding 6: `cube info` on a FIFO blocked forever.
TEST(CubeDamage, AFifoIsRefusedAsNotARegularFile) {
  const auto dir = test::scratch_dir("damage_fifo");
  ASSERT_EQ(::mkfifo((dir / "pipe.h5").c_str(), 0600), 0);
  expect_refused(dir / "pipe.h5", "not a regular file");
  const auto r = cube_command("info", dir / "pipe.h5");
  expect_one_line_refusal(r, dir / "pipe.h5");
}

}  // namespace
}  // namespace pcrf::cube
