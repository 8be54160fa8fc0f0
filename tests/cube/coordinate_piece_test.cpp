// Coordinate pieces (issue 38: the cube's creation off rank 0's serial path): a chunked
// coordinate's chunk sealed anywhere (seal_coordinate_piece) is the bytes its variable stores,
// and a cube made from pieces another party sealed (a CoordinateSource: other ranks) reads
// back exactly as one that sealed them itself; a creation whose pieces fail leaves no cube,
// or the old one with --overwrite.
#include <gtest/gtest.h>

#include <hdf5.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "support/test_support.hpp"

namespace pcrf::cube {
namespace {

namespace fs = std::filesystem;

/// 150 000 cases: pieces of 16 384 values for a coordinate written live (the metrics' chunks
/// along `case`), the last of 2 544 (an edge chunk, stored padded); the case number, written
/// at the creation in chunks of up to kCreationCoordinateChunk values, is one piece.
constexpr std::size_t kCases = 150000;
constexpr std::size_t kPieces = 10;
/// A study of more cases than a creation's chunk: the case number in two pieces, cut evenly
/// (524 288 + 1 272 values each: no padding to seal).
constexpr std::size_t kLongCases = kCreationCoordinateChunk + 2544;
constexpr std::size_t kLongChunk = kLongCases / 2;

double kappa_at(std::size_t i) { return 1.0 + 1.0 / static_cast<double>(i + 3); }  // no two alike

/// A cube along `case`: the case number (an index: int32), a computed parameter, a held one
/// (long: written later, chunked), a short held one over `record` (in the image), and a
/// computed text label (written value by value).
CubeLayout piece_layout(std::size_t n = kCases) {
  CubeLayout l;
  l.dimensions = {{"record", 2}, {"case", n}};
  Coordinate record{"record", "record", "", "ground motion", {}, {"ER1", "ER2"}, true, false};
  Coordinate scale{"record_scale", "record", "1", "", {1.0, 0.5}, {}, false, false};
  Coordinate index{"case", "case", "", "frame number", {}, {}, false, true};
  index.number_at = [](std::size_t i) { return static_cast<double>(i); };
  index.computed_size = n;
  Coordinate kappa{"kappa", "case", "1", "", {}, {}, false, false};
  kappa.number_at = kappa_at;
  kappa.computed_size = n;
  Coordinate held{"lambda", "case", "1", "", {}, {}, false, false};
  for (std::size_t i = 0; i < n; ++i) held.numbers.push_back(2.0 - 1.0 / static_cast<double>(i + 7));
  Coordinate label{"case_label", "case", "", "frame label", {}, {}, true, false};
  label.text_at = [](std::size_t i) { return "s" + std::to_string(i); };
  label.computed_size = n;
  l.coordinates = {record, scale, index, kappa, held, label};
  l.metrics = {{"theta_max_rad", "rad", "peak"}};
  l.status_flags = {{0, "at_rest"}};
  l.attributes = {{kFingerprintName, std::string("pieces")}};
  return l;
}

/// A cube along `case` of `n` cases with the case number alone (an index: int32, "frame number").
CubeLayout case_number_layout(std::size_t n) {
  CubeLayout l;
  l.dimensions = {{"case", n}};
  Coordinate index{"case", "case", "", "frame number", {}, {}, false, true};
  index.number_at = [](std::size_t i) { return static_cast<double>(i); };
  index.computed_size = n;
  l.coordinates = {index};
  return l;
}

/// Pieces sealed here, as another rank would: each asked once, in order, and counted.
class CountingSource final : public CoordinateSource {
 public:
  explicit CountingSource(CubeLayout own, std::size_t fail_at = SIZE_MAX) : own_(std::move(own)), fail_at_(fail_at) {}
  std::span<const char> sealed(const CubeLayout& layout, const CoordinatePiece& piece) override {
    EXPECT_EQ(layout.coordinates.size(), own_.coordinates.size());
    asked.push_back(piece);
    if (asked.size() > fail_at_) throw CubeError("a worker is gone");
    last_ = seal_coordinate_piece(own_.coordinates[piece.coordinate], piece.chunk_values, piece.piece);
    return last_;
  }
  std::vector<CoordinatePiece> asked;

 private:
  std::vector<char> last_;
  CubeLayout own_;
  std::size_t fail_at_;
};

TEST(CoordinatePiece, PiecesAreEveryChunkOfTheLongCoordinatesInOrder) {
  const auto layout = piece_layout();
  const auto pieces = coordinate_pieces(layout);
  // The creation's: case (2), one chunk of all its values; kappa (3) and lambda (4) are written
  // live (with the units, and at close), cut as the metrics are; record_scale is short,
  // case_label text.
  const std::size_t chunk = coordinate_chunk_values(layout, layout.coordinates[3]);
  EXPECT_EQ(chunk, layout_grid(layout).chunk_shape()[1]) << "cut as the metrics are along `case`";
  EXPECT_EQ(piece_count(kCases, chunk), kPieces);
  EXPECT_EQ(coordinate_chunk_values(layout, layout.coordinates[2]), kCases) << "the case number: one chunk";
  EXPECT_EQ(pieces, (std::vector<CoordinatePiece>{{2, 0, kCases}}));
  // More cases than a creation's chunk: the case number in the fewest chunks of at most
  // kCreationCoordinateChunk, cut evenly, every one in order.
  const auto long_layout = piece_layout(kLongCases);
  EXPECT_EQ(coordinate_chunk_values(long_layout, long_layout.coordinates[2]), kLongChunk);
  EXPECT_EQ(coordinate_chunk_values(long_layout, long_layout.coordinates[3]), chunk) << "written live: as before";
  const std::vector<CoordinatePiece> expected = {{2, 0, kLongChunk}, {2, 1, kLongChunk}};
  EXPECT_EQ(coordinate_pieces(long_layout), expected);
  // The rule at its edges: one chunk up to kCreationCoordinateChunk, the last never short by a
  // chunk's worth of padding.
  for (const std::size_t n : {std::size_t{5000}, kCreationCoordinateChunk, kCreationCoordinateChunk + 1,
                              3 * kCreationCoordinateChunk - 1, 7 * kCreationCoordinateChunk + 12345}) {
    CubeLayout one = case_number_layout(n);
    const std::size_t values = coordinate_chunk_values(one, one.coordinates[0]);
    const std::size_t chunks = piece_count(n, values);
    EXPECT_LE(values, kCreationCoordinateChunk) << n;
    EXPECT_EQ(chunks, (n + kCreationCoordinateChunk - 1) / kCreationCoordinateChunk) << n;
    EXPECT_LT(chunks * values - n, chunks) << n << ": the padding of the last chunk";
  }
  EXPECT_TRUE(layout.coordinates[3].written_live() && layout.coordinates[4].written_live());
  EXPECT_FALSE(layout.coordinates[2].written_live()) << "the case number is an index: written at the creation";
  EXPECT_TRUE(coordinate_pieces(piece_layout(4000)).empty()) << "short coordinates stay contiguous";
  EXPECT_THROW(seal_coordinate_piece(layout.coordinates[3], chunk, kPieces), std::invalid_argument);
  EXPECT_THROW(seal_coordinate_piece(layout.coordinates[5], chunk, 0), std::invalid_argument);
}

TEST(CoordinatePiece, ASealedPieceInflatesToItsValuesPaddedWithZeros) {
  const auto layout = piece_layout();
  const Coordinate& kappa = layout.coordinates[3];
  const Coordinate& index = layout.coordinates[2];
  const std::size_t chunk = coordinate_chunk_values(layout, kappa);
  const std::size_t last = kPieces - 1, edge = kCases - last * chunk;
  const auto plain = unfilter(seal_coordinate_piece(kappa, chunk, last), chunk, sizeof(double), "kappa");
  std::vector<double> values(chunk);
  std::memcpy(values.data(), plain.data(), plain.size());
  for (std::size_t k = 0; k < chunk; ++k)
    ASSERT_EQ(values[k], k < edge ? kappa_at(last * chunk + k) : 0.0) << k;
  // The same piece from values a worker's cases computed: the same bytes.
  std::vector<double> own(edge);
  for (std::size_t k = 0; k < edge; ++k) own[k] = kappa_at(last * chunk + k);
  EXPECT_EQ(seal_coordinate_values(own, chunk), seal_coordinate_piece(kappa, chunk, last));
  const auto sealed_index = seal_coordinate_piece(index, chunk, 1);
  EXPECT_LT(sealed_index.size(), chunk / 8) << "0, 1, 2, … deflate to almost nothing";
  const auto ints = unfilter(sealed_index, chunk, sizeof(std::int32_t), "case");
  std::vector<std::int32_t> numbers(chunk);
  std::memcpy(numbers.data(), ints.data(), ints.size());
  for (std::size_t k = 0; k < chunk; ++k) ASSERT_EQ(numbers[k], static_cast<std::int32_t>(chunk + k));
  EXPECT_LE(seal_coordinate_piece(kappa, chunk, 0).size(), sealed_piece_bound(kappa, chunk));
}

// The cube a source's pieces make equals the one the writer seals itself, value for value,
// and the source is asked for each piece once, in order, during the creation only.
TEST(CoordinatePiece, ACubeFromAnotherPartysPiecesEqualsOneSealedHere) {
  const auto dir = test::scratch_dir("coordinate_pieces");
  {
    CubeWriter here(dir / "here.h5", piece_layout(), OpenMode::kOverwrite);
    here.close();
  }
  CountingSource source(piece_layout());
  {
    CubeWriter there(dir / "there.h5", piece_layout(), OpenMode::kOverwrite, &source);
    EXPECT_EQ(source.asked, coordinate_pieces(piece_layout()));
    there.store(0, 0, {0.5});
    there.close();
  }
  EXPECT_EQ(source.asked.size(), coordinate_pieces(piece_layout()).size()) << "never after the creation";
  CubeReader here(dir / "here.h5"), there(dir / "there.h5");
  for (const auto& c : piece_layout().coordinates) {
    const Coordinate* a = here.layout().find_coordinate(c.name);
    const Coordinate* b = there.layout().find_coordinate(c.name);
    ASSERT_TRUE(a != nullptr && b != nullptr) << c.name;
    EXPECT_EQ(a->numbers, b->numbers) << c.name;
    EXPECT_EQ(a->strings, b->strings) << c.name;
    EXPECT_EQ(a->is_index, b->is_index) << c.name;
    ASSERT_EQ(b->size(), c.size()) << c.name;
    for (std::size_t i = 0; i < c.size(); i += 997) EXPECT_EQ(b->label(i), c.label(i)) << c.name << " " << i;
  }
  EXPECT_EQ(there.read_metric("theta_max_rad")[0], 0.5);
  EXPECT_TRUE(there.damage().empty());
}

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// piece_layout with a second index along `case` (a sampled plan's sample number): two pieces
/// at the creation, the case number's, then the sample number's.
CubeLayout two_index_layout() {
  CubeLayout l = piece_layout();
  Coordinate sample{"sample", "case", "", "base sample", {}, {}, false, true};
  sample.number_at = [](std::size_t i) { return static_cast<double>(i / 10); };
  sample.computed_size = kCases;
  l.coordinates.push_back(sample);
  return l;
}

// A creation stopped while its pieces come in (a worker gone, bytes that are not a piece)
// leaves no cube, nor its temporary; with --overwrite the old cube stays as it was.
TEST(CoordinatePiece, ACreationWhosePiecesFailLeavesNoCubeOrTheOldOne) {
  const auto dir = test::scratch_dir("coordinate_pieces_fail");
  ASSERT_EQ(coordinate_pieces(two_index_layout()).size(), 2u);
  CountingSource failing(two_index_layout(), 1);  // the second fails, after the first was written
  EXPECT_THROW(CubeWriter(dir / "new.h5", two_index_layout(), OpenMode::kCreate, &failing), CubeError);
  EXPECT_EQ(failing.asked.size(), 2u);
  EXPECT_FALSE(fs::exists(dir / "new.h5"));
  EXPECT_FALSE(fs::exists(dir / "new.h5.partial"));

  {
    CubeWriter old(dir / "old.h5", piece_layout(5000), OpenMode::kOverwrite);
    old.store(3, 0, {0.25});
    old.close();
  }
  const std::string before = bytes_of(dir / "old.h5");
  struct Garbage final : CoordinateSource {
    std::span<const char> sealed(const CubeLayout&, const CoordinatePiece&) override { return {}; }
  } garbage;
  EXPECT_THROW(CubeWriter(dir / "old.h5", piece_layout(), OpenMode::kOverwrite, &garbage), CubeError);
  struct TooLarge final : CoordinateSource {
    std::span<const char> sealed(const CubeLayout& l, const CoordinatePiece& p) override {
      bytes.assign(sealed_piece_bound(l.coordinates[p.coordinate], p.chunk_values) + 1, 'x');
      return bytes;
    }
    std::vector<char> bytes;
  } too_large;
  EXPECT_THROW(CubeWriter(dir / "old.h5", piece_layout(), OpenMode::kOverwrite, &too_large), CubeError);
  EXPECT_EQ(bytes_of(dir / "old.h5"), before);
  EXPECT_FALSE(fs::exists(dir / "old.h5.partial"));
  EXPECT_EQ(CubeReader(dir / "old.h5").read_metric("theta_max_rad")[3], 0.25);
}

// A study of more cases than a creation's chunk: the case number written in two pieces by
// another party (the workers) reads back whole, the last piece's values included, and its
// variable is stored in chunks of that many values.
TEST(CoordinatePiece, ACaseNumberLongerThanACreationChunkReadsBackWhole) {
  const auto dir = test::scratch_dir("coordinate_pieces_long");
  CubeLayout layout = case_number_layout(kLongCases);
  layout.metrics = {{"theta_max_rad", "rad", "peak"}};
  layout.status_flags = {{0, "at_rest"}};
  layout.attributes = {{kFingerprintName, std::string("long")}};
  CountingSource source(layout);
  {
    CubeWriter writer(dir / "long.h5", layout, OpenMode::kOverwrite, &source);
    writer.store(static_cast<std::int64_t>(kLongCases - 1), 0, {0.25});
    writer.close();
  }
  EXPECT_EQ(source.asked.size(), 2u);
  CubeReader reader(dir / "long.h5");
  const Coordinate* read = reader.layout().find_coordinate("case");
  ASSERT_TRUE(read != nullptr);
  EXPECT_TRUE(read->is_index);
  ASSERT_EQ(read->numbers.size(), kLongCases);
  for (std::size_t i = 0; i < kLongCases; ++i) ASSERT_EQ(read->numbers[i], static_cast<double>(i)) << i;
  EXPECT_EQ(reader.read_metric("theta_max_rad")[kLongCases - 1], 0.25);
  EXPECT_TRUE(reader.damage().empty());
  const hid_t file = H5Fopen((dir / "long.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t set = H5Dopen2(file, "case", H5P_DEFAULT);
  const hid_t dcpl = H5Dget_create_plist(set);
  hsize_t chunk = 0;
  EXPECT_EQ(H5Pget_chunk(dcpl, 1, &chunk), 1);
  EXPECT_EQ(chunk, kLongChunk);
  H5Pclose(dcpl);
  H5Dclose(set);
  H5Fclose(file);
}

}  // namespace
}  // namespace pcrf::cube
