// A sealed chunk's zlib framing (issue 38, item 5): zlib deflates raw and the Deflater writes
// the stream's header and its Adler-32 trailer itself, the checksum by libdeflate. The
// checksum is zlib's on any length (its modulo reductions fall every 5 552 bytes in zlib); a
// chunk too short to measure is byte for byte the stream zlib frames itself; a chunk of every
// plane coding (stored, Huffman codes, runs, repeats) inflates with plain zlib, whose inflate
// checks the trailer, and reads back through HDF5's filters bit for bit.
#include <gtest/gtest.h>
#include <libdeflate.h>
#include <zlib.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "case_axis_layout.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "support/test_support.hpp"
#include "worker_chunks.hpp"

namespace pcrf::cube {
namespace {

/// zlib's own Adler-32 of `bytes`.
std::uint32_t zlib_adler32(const std::vector<unsigned char>& bytes, std::size_t from, std::size_t n) {
  return static_cast<std::uint32_t>(adler32_z(adler32_z(0L, Z_NULL, 0), bytes.data() + from, n));
}

// libdeflate's Adler-32 equals zlib's: empty, one byte, either side of zlib's 5 552-byte
// blocks, large, from any alignment, on random bytes and on all 0xff (the largest sums before
// a reduction), and as a running checksum over pieces.
TEST(SealedFraming, LibdeflatesAdler32IsZlibsOnEveryLength) {
  std::mt19937_64 random(5552);
  std::vector<unsigned char> noise((std::size_t{1} << 21) + 64);
  for (auto& b : noise) b = static_cast<unsigned char>(random());
  const std::vector<unsigned char> ones(noise.size(), 0xff);
  const std::vector<std::size_t> lengths{0, 1, 2, 15, 16, 31, 32, 33, 63, 64, 65, 5551, 5552, 5553, 11104, 11105,
                                         65536, 65537, (std::size_t{1} << 21) + 7};
  for (const auto* bytes : std::array<const std::vector<unsigned char>*, 2>{&noise, &ones})
    for (const std::size_t n : lengths)
      for (const std::size_t from : {0, 1, 7, 31}) {
        const std::uint32_t want = zlib_adler32(*bytes, from, n);
        EXPECT_EQ(libdeflate_adler32(1, bytes->data() + from, n), want) << n << " bytes from " << from;
      }
  // Running: pieces of uneven length, carried from one call to the next.
  std::uint32_t running = libdeflate_adler32(0, nullptr, 0);
  EXPECT_EQ(running, 1u);
  std::size_t at = 0;
  for (const std::size_t piece : {std::size_t{3}, std::size_t{5553}, std::size_t{100000}, std::size_t{5552}}) {
    running = libdeflate_adler32(running, noise.data() + at, piece);
    at += piece;
  }
  EXPECT_EQ(running, zlib_adler32(noise, 0, at));
}

/// H5Z's shuffle of `values`, byte by byte: byte b of value i at b * count + i.
std::vector<unsigned char> shuffled(const std::vector<double>& values) {
  std::vector<unsigned char> planes(values.size() * sizeof(double));
  for (std::size_t i = 0; i < values.size(); ++i)
    for (std::size_t b = 0; b < sizeof(double); ++b)
      planes[b * values.size() + i] = reinterpret_cast<const unsigned char*>(&values[i])[b];
  return planes;
}

/// The zlib stream zlib itself makes of `bytes` in one call, by runs at the cube's level: what
/// the Deflater makes of a chunk too short to measure.
std::vector<char> zlib_stream(const std::vector<unsigned char>& bytes) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, static_cast<int>(kDeflateLevel), Z_DEFLATED, 15, 8, Z_RLE), Z_OK);
  std::vector<char> out(deflateBound(&z, static_cast<uLong>(bytes.size())));
  z.next_in = const_cast<Bytef*>(bytes.data());
  z.avail_in = static_cast<uInt>(bytes.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

// A chunk too short to measure (fewer than 4 096 values: one run by runs) seals to exactly the
// bytes zlib's own framing makes: its header, the same deflate data, its Adler-32.
TEST(SealedFraming, AShortChunkIsByteForByteTheStreamZlibFrames) {
  const ChunkGrid grid({1000}, 1000);
  ASSERT_EQ(padded_elements(grid), 1000u);
  std::mt19937_64 random(1000);
  std::vector<double> values(1000);
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = i % 3 == 0 ? std::bit_cast<double>(random()) : 1e-3 * static_cast<double>(i / 10);
  const SealedChunk sealed = seal_chunk(grid, 0, 1, std::vector<std::int8_t>(1000, 0), values, {});
  EXPECT_EQ(sealed.filtered[0], zlib_stream(shuffled(values)));
}

/// Case i's four metrics, one of each plane coding a sealed chunk has: noise (its planes stored),
/// bytes drawn from 16 values (Huffman codes alone), runs of 1 000 cases (runs), and a smooth
/// ramp whose low bytes take every value; every value from i alone.
std::vector<double> coded_row(std::int64_t i) {
  std::mt19937_64 random(static_cast<std::uint64_t>(i));
  const std::uint64_t bits = random();
  std::uint64_t sixteen = 0;  // each byte one of 16 values
  for (int b = 0; b < 8; ++b) sixteen |= ((random() & 0xf) * 17) << (8 * b);
  return {std::bit_cast<double>(bits), std::bit_cast<double>(sixteen), static_cast<double>(i / 1000),
          1.0 + 1e-6 * static_cast<double>(i)};
}

CubeLayout coded_layout(std::int64_t cases) {
  CubeLayout l = case_axis_layout(cases, "sealed-framing");
  l.metrics = {{"noise", "1", ""}, {"sixteen", "1", ""}, {"runs", "1", ""}, {"ramp", "1", ""}};
  return l;
}

/// `stream` is a zlib stream of `plain`: zlib's header (78 01: deflate, a 32 KiB window, the
/// fastest levels' class), raw deflate data that inflates to `plain` and ends exactly before
/// the last four bytes, and zlib's Adler-32 of `plain` there, most significant byte first;
/// plain zlib's uncompress, which checks that trailer, gives `plain` back.
void expect_zlib_stream(const std::vector<char>& stream, const std::vector<unsigned char>& plain, const std::string& what) {
  ASSERT_GT(stream.size(), 6u) << what;
  const auto* s = reinterpret_cast<const unsigned char*>(stream.data());
  EXPECT_EQ(s[0], 0x78) << what;
  EXPECT_EQ(s[1], 0x01) << what;
  EXPECT_EQ((s[0] * 256u + s[1]) % 31u, 0u) << what;
  const std::uint32_t want = zlib_adler32(plain, 0, plain.size());
  const std::uint32_t trailer = std::uint32_t{s[stream.size() - 4]} << 24 | std::uint32_t{s[stream.size() - 3]} << 16 |
                                std::uint32_t{s[stream.size() - 2]} << 8 | s[stream.size() - 1];
  EXPECT_EQ(trailer, want) << what;

  z_stream raw{};  // the deflate data alone, as a raw stream
  ASSERT_EQ(inflateInit2(&raw, -15), Z_OK);
  std::vector<unsigned char> out(plain.size() + 1);
  raw.next_in = const_cast<Bytef*>(s + 2);
  raw.avail_in = static_cast<uInt>(stream.size() - 6);
  raw.next_out = out.data();
  raw.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(inflate(&raw, Z_FINISH), Z_STREAM_END) << what;
  EXPECT_EQ(raw.avail_in, 0u) << what;
  EXPECT_EQ(raw.total_out, plain.size()) << what;
  inflateEnd(&raw);
  out.resize(plain.size());
  EXPECT_EQ(out, plain) << what;

  uLongf size = static_cast<uLongf>(out.size());
  EXPECT_EQ(uncompress(out.data(), &size, s, static_cast<uLong>(stream.size())), Z_OK) << what;
  EXPECT_EQ(size, plain.size()) << what;
  EXPECT_EQ(out, plain) << what;
}

// Every variable of a chunk of each plane coding, and a piece of an index coordinate (zlib's
// default strategy: repeats), is a zlib stream of its shuffled values with zlib's framing; a
// trailer off by one bit is refused by inflate.
TEST(SealedFraming, EveryCodingIsFramedAsZlibFramesIt) {
  constexpr std::int64_t kCases = 20000;  // chunks of 16 384 and 3 616 (padded with NaN)
  const ChunkGrid grid(coded_layout(kCases).shape());
  const std::size_t padded = padded_elements(grid);
  for (std::size_t chunk = 0; chunk < grid.chunk_count(); ++chunk) {
    const SealedChunk sealed = sealed_from(grid, chunk, 4, coded_row, status_of);
    const auto r = grid.range(chunk);
    for (std::size_t m = 0; m < 4; ++m) {
      std::vector<double> values(padded, std::numeric_limits<double>::quiet_NaN());
      for (std::int64_t k = 0; k < r.count; ++k) values[static_cast<std::size_t>(k)] = coded_row(r.first + k)[m];
      expect_zlib_stream(sealed.filtered[m], shuffled(values), "chunk " + std::to_string(chunk) + " metric " + std::to_string(m));
    }
    std::vector<unsigned char> codes(padded, static_cast<unsigned char>(kStatusNotRun));
    for (std::int64_t k = 0; k < r.count; ++k) codes[static_cast<std::size_t>(k)] = static_cast<unsigned char>(status_of(r.first + k));
    expect_zlib_stream(sealed.filtered[4], codes, "chunk " + std::to_string(chunk) + " status");

    std::vector<char> damaged = sealed.filtered[0];
    damaged.back() = static_cast<char>(damaged.back() ^ 1);
    EXPECT_THROW(unfilter(damaged, padded, sizeof(double), "test"), CubeError) << "chunk " << chunk;
  }

  Coordinate index{"case", "case", "", "", {}, {}, false, true};
  for (std::int64_t i = 0; i < 70000; ++i) index.numbers.push_back(static_cast<double>(3 * i));
  ASSERT_TRUE(index.chunked());
  // Its chunks as a cube of 70 000 cases along `case` cuts them (coordinate_chunk_values).
  const std::size_t values = coordinate_chunk_values(ChunkGrid(std::vector<std::size_t>{70000}), 0);
  for (std::size_t p = 0; p < piece_count(index.size(), values); ++p) {
    std::vector<unsigned char> plain(values * sizeof(std::int32_t), 0);
    const std::size_t first = p * values;
    for (std::size_t k = 0; k < values && first + k < index.size(); ++k)
      for (std::size_t b = 0; b < sizeof(std::int32_t); ++b)
        plain[b * values + k] = static_cast<unsigned char>(static_cast<std::uint32_t>(3 * (first + k)) >> (8 * b));
    expect_zlib_stream(seal_coordinate_piece(index, values, p), plain, "index piece " + std::to_string(p));
  }
}

// Such chunks, written raw into a cube, read back through HDF5's filters (whose inflate checks
// the trailer) bit for bit.
TEST(SealedFraming, ChunksOfEveryCodingReadBackThroughHdf5BitForBit) {
  constexpr std::int64_t kCases = 20000;
  const auto file = test::scratch_dir("sealed_framing") / "c.h5";
  {
    CubeWriter writer(file, coded_layout(kCases), OpenMode::kCreate);
    for (std::size_t chunk = 0; chunk < writer.grid().chunk_count(); ++chunk)
      writer.store_sealed(sealed_from(writer.grid(), chunk, 4, coded_row, status_of));
    writer.close();
  }
  const CubeReader reader(file);
  EXPECT_TRUE(reader.damage().empty());
  const auto status = reader.read_status();
  const std::vector<std::string> names{"noise", "sixteen", "runs", "ramp"};
  std::size_t wrong = 0;
  for (std::size_t m = 0; m < names.size(); ++m) {
    const auto metric = reader.read_metric(names[m]);
    ASSERT_EQ(metric.size(), static_cast<std::size_t>(kCases));
    for (std::int64_t i = 0; i < kCases; ++i)
      wrong += std::bit_cast<std::uint64_t>(metric[static_cast<std::size_t>(i)]) != std::bit_cast<std::uint64_t>(coded_row(i)[m]);
  }
  for (std::int64_t i = 0; i < kCases; ++i) wrong += status[static_cast<std::size_t>(i)] != status_of(i);
  EXPECT_EQ(wrong, 0u);
}

}  // namespace
}  // namespace pcrf::cube
