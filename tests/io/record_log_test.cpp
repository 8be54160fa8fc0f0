// A log's records (io/record_log.hpp): framed as kind, size, payload and the CRC-32 that zlib
// computes (libdeflate computes it here: the same value, checked against zlib's own on the
// bytes written), whether the payload is written whole or in pieces.
#include <gtest/gtest.h>
#include <zlib.h>

#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/io/record_log.hpp"
#include "support/test_support.hpp"

namespace pcrf::io {
namespace {

namespace fs = std::filesystem;

/// `n` bytes drawn from a seeded generator.
std::string random_bytes(std::size_t n, unsigned seed) {
  std::mt19937 draw(seed);
  std::string bytes(n, '\0');
  for (char& b : bytes) b = static_cast<char>(draw() & 0xff);
  return bytes;
}

/// zlib's CRC-32 of `bytes`.
std::uint32_t zlib_crc(std::string_view bytes) {
  return static_cast<std::uint32_t>(::crc32(::crc32(0, nullptr, 0), reinterpret_cast<const Bytef*>(bytes.data()),
                                            static_cast<uInt>(bytes.size())));
}

TEST(RecordLog, EveryRecordEndsWithZlibsCrcOfItsFrameAndPayload) {
  const auto log = test::scratch_dir("record_log_crc") / "c.h5.journal";
  // Lengths around the vectorised paths' blocks (16, 64, 128 bytes and more), and none.
  const std::vector<std::size_t> lengths{0, 1, 7, 15, 16, 17, 63, 64, 65, 127, 128, 129, 255, 1000, 4096, 65537, 1 << 20};
  {
    LogWriter w(log, 0);
    for (std::size_t k = 0; k < lengths.size(); ++k) w.add(static_cast<std::uint32_t>(k + 1), random_bytes(lengths[k], static_cast<unsigned>(k)));
    w.sync();
  }
  const std::string file = test::read_file(log);
  std::size_t at = 8;  // the magic
  for (std::size_t k = 0; k < lengths.size(); ++k) {
    ASSERT_LE(at + 16 + lengths[k], file.size());
    EXPECT_EQ(load_le(file.data() + at, 4), k + 1);
    ASSERT_EQ(load_le(file.data() + at + 4, 8), lengths[k]);
    const std::string_view framed(file.data() + at, 12 + lengths[k]);
    EXPECT_EQ(load_le(file.data() + at + 12 + lengths[k], 4), zlib_crc(framed)) << lengths[k] << " bytes";
    EXPECT_EQ(framed.substr(12), random_bytes(lengths[k], static_cast<unsigned>(k)));
    at += 16 + lengths[k];
  }
  EXPECT_EQ(at, file.size());
  const LogReader read(log);
  EXPECT_EQ(read.records().size(), lengths.size());
}

TEST(RecordLog, ARecordWrittenInPiecesIsTheRecordOfItsPiecesJoined) {
  const auto dir = test::scratch_dir("record_log_pieces");
  // Empty pieces, short ones, and more pieces than one pwritev takes (64).
  std::vector<std::string> parts;
  for (unsigned k = 0; k < 150; ++k) parts.push_back(random_bytes(k % 5 == 0 ? 0 : (k * 37) % 300, k));
  std::string joined;
  std::vector<std::string_view> pieces;
  for (const auto& p : parts) {
    joined += p;
    pieces.emplace_back(p);
  }
  {
    LogWriter whole(dir / "whole", 0), split(dir / "split", 0);
    for (int r = 0; r < 3; ++r) {
      whole.add(7, joined);
      split.add_pieces(7, pieces);
    }
    whole.add(8, "");
    split.add_pieces(8, {});
    whole.sync();
    split.sync();
  }
  EXPECT_EQ(test::read_file(dir / "split"), test::read_file(dir / "whole"));
  const LogReader read(dir / "split");
  ASSERT_EQ(read.records().size(), 4u);
  EXPECT_EQ(read.payload(read.records()[2]), joined);
}

}  // namespace
}  // namespace pcrf::io
