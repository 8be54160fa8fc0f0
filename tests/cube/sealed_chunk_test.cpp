// Sealed chunks (issue 38): a chunk a worker computed whole reaches the cube as the bytes the
// cube's filters make of it (one raw chunk write a variable), through a checkpoint's journal
// and --resume as well, and reads back bit for bit; cases stored after it are laid over it;
// a journal whose sealed chunk does not inflate is set aside, never folded.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "pcrf/io/record_log.hpp"
#include "support/test_support.hpp"
#include "worker_chunks.hpp"

namespace pcrf::cube {
namespace {

namespace fs = std::filesystem;

constexpr std::int64_t kCases = 40000;  // chunks of 16 384, 16 384 and 7 232 (an edge chunk, stored padded)

CubeLayout sealed_layout() {
  CubeLayout l;
  l.dimensions = {{"case", static_cast<std::size_t>(kCases)}};
  Coordinate index{"case", "case", "", "", {}, {}, false, true};
  for (std::int64_t i = 0; i < kCases; ++i) index.numbers.push_back(static_cast<double>(i));
  l.coordinates = {index};
  l.metrics = {{"theta_max_rad", "rad", ""}, {"impacts", "1", ""}, {"uplift_m", "m", ""}};
  l.status_flags = {{0, "at_rest"}, {3, "overturned"}};
  l.attributes = {{kFingerprintName, std::string("sealed-test")}};
  return l;
}

/// Case i's values as a run computes them (`round` 1: what a later run stores over them).
std::vector<double> row_of(std::int64_t i, int round = 0) {
  return {1e-5 * static_cast<double>(i) + round, static_cast<double>(i % 7), i % 5 == 0 ? std::nan("") : 0.0};
}

/// Chunk `chunk` of this file's cube (row_of's three metrics, worker_chunks.hpp's statuses)
/// computed whole and sealed, as a worker does it.
SealedChunk sealed_three_of(const ChunkGrid& grid, std::size_t chunk) {
  return sealed_from(grid, chunk, 3, [](std::int64_t i) { return row_of(i); }, status_of);
}

/// Every case of the cube holds what row_of and status_of say (cases in `over`: round 1).
void expect_cube(const fs::path& file, const std::vector<std::int64_t>& over = {}) {
  const CubeReader reader(file);
  const auto status = reader.read_status();
  std::vector<std::vector<double>> metric{reader.read_metric("theta_max_rad"), reader.read_metric("impacts"),
                                          reader.read_metric("uplift_m")};
  std::size_t wrong = 0;
  for (std::int64_t i = 0; i < kCases; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const bool later = std::find(over.begin(), over.end(), i) != over.end();
    const auto row = row_of(i, later ? 1 : 0);
    wrong += status[k] != status_of(i);
    for (std::size_t m = 0; m < 3; ++m)
      wrong += std::isnan(row[m]) ? !std::isnan(metric[m][k]) : metric[m][k] != row[m];
  }
  EXPECT_EQ(wrong, 0u) << file;
  std::size_t notes = 0;
  for (const auto& [index, text] : reader.read_notes()) {
    EXPECT_EQ(text, "note of case " + std::to_string(index));
    ++notes;
  }
  EXPECT_EQ(notes, static_cast<std::size_t>((kCases + 996) / 997));
}

TEST(SealedChunk, ASealedChunkFoldsRawAndReadsBackBitForBit) {
  const auto dir = test::scratch_dir("sealed_fold");
  const auto file = dir / "c.h5";
  {
    CubeWriter writer(file, sealed_layout(), OpenMode::kCreate);
    ASSERT_EQ(writer.grid().chunk_count(), 3u);
    writer.store_sealed(sealed_three_of(writer.grid(), 0));
    writer.store_sealed(sealed_three_of(writer.grid(), 2));  // the edge chunk
    for (std::int64_t i = 16384; i < 32768; ++i) {
      writer.store(i, status_of(i), row_of(i));
      if (i % 997 == 0) writer.store_note(i, "note of case " + std::to_string(i));
    }
    EXPECT_EQ(writer.done_count(), kCases);
    writer.close();
  }
  expect_cube(file);
  EXPECT_THROW(CubeWriter(dir / "d.h5", sealed_layout(), OpenMode::kCreate).store_sealed(SealedChunk{7, {}, {}, {}, {}}),
               CubeError);
}

// A chunk whose every value is the same (what frames that never lift make of most metrics)
// is deflated once and its stream reused: each reuse must still inflate to its own values,
// and values that compare equal but differ in their bits (0 and -0, two NaNs) must not share one.
TEST(SealedChunk, RepeatedValuesInflateToThemselvesEveryTime) {
  const ChunkGrid grid({static_cast<std::size_t>(kCases)});
  const std::size_t padded = padded_elements(grid);
  const double quiet = std::numeric_limits<double>::quiet_NaN();
  const double other_nan = -quiet;  // another NaN: its sign bit set
  const std::vector<double> constants{0.0, -0.0, 0.0, quiet, other_nan, 2.5, quiet};
  for (std::size_t round = 0; round < 2; ++round)  // the second round finds every stream kept
    for (const double c : constants) {
      const auto count = static_cast<std::size_t>(grid.range(0).count);
      const std::vector<double> values(count, c);
      const std::vector<std::int8_t> status(count, 0);
      const SealedChunk sealed = seal_chunk(grid, 0, 1, status, values, {});
      const auto plain = unfilter(sealed.filtered[0], padded, sizeof(double), "test");
      std::size_t wrong = 0;
      for (std::size_t k = 0; k < count; ++k) {
        double v = 0.0;
        std::memcpy(&v, plain.data() + k * sizeof(double), sizeof(double));
        wrong += std::memcmp(&v, &c, sizeof(double)) != 0;
      }
      EXPECT_EQ(wrong, 0u) << "the constant " << c << " (round " << round << ")";
      const auto codes = unfilter(sealed.filtered[1], padded, 1, "test");
      EXPECT_TRUE(std::all_of(codes.begin(), codes.begin() + static_cast<std::ptrdiff_t>(count), [](char s) { return s == 0; }));
    }
}

// Values whose low bytes are noise (a random frame's parameters and what follows from them)
// are sealed with those byte planes stored, not coded: the stream must still inflate to every
// value bit for bit, for every mix of noise and structure, and be no larger than coding every
// plane (zlib's run-length strategy at the cube's level, what sealing did before) but for a
// block's headers a plane.
TEST(SealedChunk, NoisyValuesInflateBitForBitAndNoLarger) {
  const ChunkGrid grid({static_cast<std::size_t>(kCases)});
  const std::size_t padded = padded_elements(grid);
  const auto count = static_cast<std::size_t>(grid.range(0).count);
  std::mt19937_64 random(38);
  std::uniform_real_distribution<double> uniform(0.05, 0.2);
  std::vector<double> values(4 * count);
  for (std::size_t k = 0; k < count; ++k) {
    values[k] = uniform(random);                                   // noise below the exponent
    values[count + k] = std::bit_cast<double>(random());            // every byte noise (NaNs too)
    values[2 * count + k] = k % 3 == 0 ? uniform(random) : 0.0;     // noise in a third of the cases
    values[3 * count + k] = 1e-5 * static_cast<double>(k);          // a smooth ramp
  }
  const SealedChunk sealed = seal_chunk(grid, 0, 4, std::vector<std::int8_t>(count, 0), values, {});
  for (std::size_t m = 0; m < 4; ++m) {
    const auto plain = unfilter(sealed.filtered[m], padded, sizeof(double), "test");
    EXPECT_EQ(std::memcmp(plain.data(), values.data() + m * count, count * sizeof(double)), 0) << "metric " << m;
    // The same chunk shuffled and coded whole by zlib at the cube's level, for comparison.
    std::vector<double> column(padded, std::numeric_limits<double>::quiet_NaN());
    std::memcpy(column.data(), values.data() + m * count, count * sizeof(double));
    std::vector<unsigned char> planes(padded * sizeof(double));
    for (std::size_t b = 0; b < sizeof(double); ++b)
      for (std::size_t k = 0; k < padded; ++k) planes[b * padded + k] = reinterpret_cast<const unsigned char*>(column.data())[k * sizeof(double) + b];
    z_stream z{};
    ASSERT_EQ(deflateInit2(&z, static_cast<int>(kDeflateLevel), Z_DEFLATED, 15, 8, Z_RLE), Z_OK);
    std::vector<unsigned char> all(deflateBound(&z, static_cast<uLong>(planes.size())));
    z.next_in = planes.data();
    z.avail_in = static_cast<uInt>(planes.size());
    z.next_out = all.data();
    z.avail_out = static_cast<uInt>(all.size());
    ASSERT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
    const auto coded = z.total_out;
    deflateEnd(&z);
    // At most one block's headers more a byte plane (a switch between coded and stored ends a block).
    EXPECT_LE(sealed.filtered[m].size(), coded + 32 * sizeof(double)) << "metric " << m;
  }
}

TEST(SealedChunk, AJournaledSealedChunkResumesAndLaterCasesLieOverIt) {
  const auto dir = test::scratch_dir("sealed_journal");
  const auto file = dir / "c.h5";
  {
    CubeWriter writer(file, sealed_layout(), OpenMode::kCreate);
    for (std::int64_t i = 16384; i < 32768; ++i) {
      writer.store(i, status_of(i), row_of(i));
      if (i % 997 == 0) writer.store_note(i, "note of case " + std::to_string(i));
    }
    writer.flush();  // the first results fold
    writer.store_sealed(sealed_three_of(writer.grid(), 0));
    writer.append();  // the sealed chunk goes to the journal
    writer.store(5, status_of(5), row_of(5, 1));  // a case of it stored again, later
    writer.append();
  }
  const CubeReader folded(file);
  const JournalReader journal(file, folded.layout(), journal_id_of(folded.layout()));
  ASSERT_TRUE(journal.current());
  EXPECT_EQ(journal.results(), 16384 + 1);
  ASSERT_EQ(journal.sealed_chunks().size(), 1u);
  journal.check_all();  // inflates the sealed chunk
  {
    CubeWriter resumed(file, sealed_layout(), OpenMode::kResume);
    EXPECT_EQ(resumed.done_count(), 2 * 16384);
    const auto theta = resumed.read_values("theta_max_rad");
    EXPECT_EQ(theta[5], row_of(5, 1)[0]);
    EXPECT_EQ(theta[6], row_of(6)[0]);
    resumed.store_sealed(sealed_three_of(resumed.grid(), 2));
    resumed.close();
  }
  expect_cube(file, {5});
}

TEST(SealedChunk, ASealedRecordThatDoesNotInflateIsSetAside) {
  const auto dir = test::scratch_dir("sealed_forged");
  const auto file = dir / "c.h5";
  {
    CubeWriter writer(file, sealed_layout(), OpenMode::kCreate);
    for (std::int64_t i = 16384; i < 32768; ++i) writer.store(i, status_of(i), row_of(i));
    writer.flush();
    SealedChunk forged = sealed_three_of(writer.grid(), 0);
    forged.filtered[1][forged.filtered[1].size() / 2] ^= 0x5a;  // its CRC will hold: the journal frames it as it is
    writer.store_sealed(std::move(forged));
    writer.append();
  }
  std::vector<std::string> notes;
  {
    CubeWriter resumed(file, sealed_layout(), OpenMode::kResume);
    notes = resumed.resume_notes();
    EXPECT_EQ(resumed.done_count(), 16384) << "nothing of a journal set aside is used";
  }
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("does not inflate"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("set aside"), std::string::npos) << notes[0];
}

TEST(SealedChunk, BytesRoundTripAndForeignBytesAreRefused) {
  const ChunkGrid grid({static_cast<std::size_t>(kCases)});
  const SealedChunk sealed = sealed_three_of(grid, 2);
  const auto bytes = to_bytes(sealed);
  const SealedChunk back = sealed_from_bytes(bytes, grid, 3, "test");
  EXPECT_EQ(back.chunk, 2u);
  EXPECT_EQ(back.status, sealed.status);
  EXPECT_EQ(back.filtered, sealed.filtered);
  EXPECT_EQ(back.notes, sealed.notes);
  // The filters undo to the chunk at its full shape: the values, then the fill.
  const auto plain = unfilter(back.filtered[0], padded_elements(grid), sizeof(double), "test");
  const auto* theta = reinterpret_cast<const double*>(plain.data());
  EXPECT_EQ(theta[0], row_of(32768)[0]);
  EXPECT_TRUE(std::isnan(theta[padded_elements(grid) - 1]));
  EXPECT_THROW(sealed_from_bytes(bytes, grid, 4, "test"), CubeError);
  EXPECT_THROW(sealed_from_bytes(bytes, ChunkGrid({10}), 3, "test"), CubeError);
  auto cut = bytes;
  cut.resize(cut.size() - 3);
  EXPECT_THROW(sealed_from_bytes(cut, grid, 3, "test"), CubeError);
}

}  // namespace
}  // namespace pcrf::cube

namespace pcrf::cube {
namespace {

// A whole chunk whose cases all ended alike has the one status stream uniform_status_stream
// makes (a reader knows it by one comparison); a mixed chunk, or one at the cube's edge
// (padded with not run), has another; the stream inflates to the chunk of that code.
TEST(SealedChunk, AWholeChunkOfOneCodeHasTheUniformStatusStream) {
  const ChunkGrid grid(sealed_layout().shape());
  const std::size_t padded = padded_elements(grid);
  for (const std::int8_t code : {std::int8_t{0}, std::int8_t{3}}) {
    const auto r = grid.range(0);
    const auto count = static_cast<std::size_t>(r.count);
    const std::vector<std::int8_t> status(count, code);
    const std::vector<double> values(3 * count, 0.0);
    const SealedChunk alike = seal_chunk(grid, 0, 3, status, values, {});
    EXPECT_EQ(alike.filtered.back(), uniform_status_stream(padded, code)) << int{code};
    const std::vector<char> codes = unfilter(uniform_status_stream(padded, code), padded, 1, "test");
    EXPECT_TRUE(std::all_of(codes.begin(), codes.end(), [code](char c) { return c == static_cast<char>(code); }));
    const auto e = grid.range(2);  // the edge chunk: 7 232 cases, padded to 16 384
    const SealedChunk edge = seal_chunk(grid, 2, 3, std::vector<std::int8_t>(static_cast<std::size_t>(e.count), code),
                                        std::vector<double>(3 * static_cast<std::size_t>(e.count), 0.0), {});
    EXPECT_NE(edge.filtered.back(), uniform_status_stream(padded, code));
  }
  EXPECT_NE(sealed_three_of(grid, 0).filtered.back(), uniform_status_stream(padded, 0)) << "a mixed chunk";
}

}  // namespace
}  // namespace pcrf::cube

namespace pcrf::cube {
namespace {

/// Bytes drawn at random from `values` values (0 .. values - 1).
unsigned char random_byte(std::mt19937_64& random, unsigned values) {
  return static_cast<unsigned char>(std::uniform_int_distribution<unsigned>(0, values - 1)(random));
}

// A chunk of any length (the shuffle takes 16 values at a time, the rest one by one) and of
// int32 or float64 values seals to what inflates to its values bit for bit: a coordinate of
// 5 003 values, one piece, padded to none.
TEST(SealedChunk, ValuesOfAnyCountAndWidthInflateBitForBit) {
  constexpr std::size_t kValues = 5003;  // 312 groups of 16, and 11 more
  std::mt19937_64 random(5003);
  Coordinate noisy{"kappa", "case", "1", "", {}, {}, false, false};
  Coordinate index{"case", "case", "", "", {}, {}, false, true};
  for (std::size_t i = 0; i < kValues; ++i) {
    noisy.numbers.push_back(std::uniform_real_distribution<double>(1.2, 2.4)(random));
    index.numbers.push_back(static_cast<double>(3 * i + 1));
  }
  ASSERT_TRUE(noisy.chunked());
  ASSERT_EQ(piece_count(noisy.size(), kValues), 1u);
  const auto doubles = unfilter(seal_coordinate_piece(noisy, kValues, 0), kValues, sizeof(double), "kappa");
  const auto ints = unfilter(seal_coordinate_piece(index, kValues, 0), kValues, sizeof(std::int32_t), "case");
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < kValues; ++i) {
    double d = 0.0;
    std::int32_t n = 0;
    std::memcpy(&d, doubles.data() + i * sizeof(double), sizeof(double));
    std::memcpy(&n, ints.data() + i * sizeof(std::int32_t), sizeof(std::int32_t));
    wrong += std::bit_cast<std::uint64_t>(d) != std::bit_cast<std::uint64_t>(noisy.numbers[i]);
    wrong += n != static_cast<std::int32_t>(3 * i + 1);
  }
  EXPECT_EQ(wrong, 0u);
}

// The worst a chunk's planes can be for the stream's size: noise (stored) alternating with
// planes that barely compress (coded; each after stored planes starts zlib's window over, a
// flush and its empty block). The stream still fits filtered_bound, which every reader of a
// sealed chunk checks (zlib's compressBound), and inflates to the values.
TEST(SealedChunk, PlanesThatBarelyCompressBetweenNoiseStayWithinTheBound) {
  const ChunkGrid grid({4096}, 4096);
  ASSERT_EQ(padded_elements(grid), 4096u);
  std::mt19937_64 random(38);
  std::vector<double> values(4096);
  for (double& v : values) {
    std::array<unsigned char, 8> bytes{};
    for (std::size_t b = 0; b < 8; ++b) bytes[b] = random_byte(random, b % 2 == 0 ? 256 : 239);  // 8 and 7.90 bits
    std::memcpy(&v, bytes.data(), sizeof(double));
  }
  const SealedChunk sealed = seal_chunk(grid, 0, 1, std::vector<std::int8_t>(4096, 0), values, {});
  EXPECT_LE(sealed.filtered[0].size(), filtered_bound(4096, sizeof(double)));
  const auto plain = unfilter(sealed.filtered[0], 4096, sizeof(double), "test");
  EXPECT_EQ(std::memcmp(plain.data(), values.data(), plain.size()), 0);
}


// A metric whose cases follow a short pattern along the cube's inner axis (here: every fourth
// case noise, the others 0, as where one of four intensities lifts a frame) is coded, not
// stored: what decides a plane's coding reads stretches of consecutive bytes, which see the
// pattern whole (a sample of every fourth byte would see noise alone, and store it).
TEST(SealedChunk, APatternAlongTheInnerAxisIsCodedNotStored) {
  const ChunkGrid grid({16384});
  const std::size_t count = padded_elements(grid);
  ASSERT_EQ(count, 16384u);
  std::mt19937_64 random(4);
  std::vector<double> values(count, 0.0);
  for (std::size_t k = 0; k < count; k += 4) values[k] = std::bit_cast<double>(random());
  const SealedChunk sealed = seal_chunk(grid, 0, 1, std::vector<std::int8_t>(count, 0), values, {});
  // Stored, its planes would take the whole chunk; coded, under 2/5 of it.
  EXPECT_LT(sealed.filtered[0].size(), count * sizeof(double) * 2 / 5);
  const auto plain = unfilter(sealed.filtered[0], count, sizeof(double), "test");
  EXPECT_EQ(std::memcmp(plain.data(), values.data(), plain.size()), 0);
}

}  // namespace
}  // namespace pcrf::cube
