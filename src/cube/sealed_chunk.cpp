// Sealed chunks (see sealed_chunk.hpp): the cube's filter pipeline run by the rank that
// computed the chunk. HDF5 applies a dataset's filters in the order they were set
// (H5Pset_shuffle, then H5Pset_deflate: cube_writer.cpp), so a chunk is shuffled (byte k of
// every value together, as H5Z's shuffle filter does), then deflated by zlib's compress2 at
// the cube's level (H5Z's deflate filter, the same zlib format); reading it back runs the same
// filters in reverse.
#include "pcrf/cube/sealed_chunk.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

#include "pcrf/cube/cube_layout.hpp"

namespace pcrf::cube {
namespace {

std::vector<char> shuffled(const char* data, std::size_t elements, std::size_t element_bytes) {
  std::vector<char> out(elements * element_bytes);
  if (element_bytes == 1) {
    std::memcpy(out.data(), data, out.size());
    return out;
  }
  for (std::size_t b = 0; b < element_bytes; ++b)
    for (std::size_t i = 0; i < elements; ++i) out[b * elements + i] = data[i * element_bytes + b];
  return out;
}

std::vector<char> unshuffled(const std::vector<char>& data, std::size_t elements, std::size_t element_bytes) {
  if (element_bytes == 1) return data;
  std::vector<char> out(data.size());
  for (std::size_t b = 0; b < element_bytes; ++b)
    for (std::size_t i = 0; i < elements; ++i) out[i * element_bytes + b] = data[b * elements + i];
  return out;
}

/// Shannon entropy of a byte plane [bits a byte] above which the plane is noise: stored in
/// the stream as it is rather than coded (a random value's low mantissa bytes: coding them
/// gains nothing and costs most of a chunk's deflate).
constexpr double kNoiseBitsPerByte = 7.9;
/// Planes shorter than this [bytes] are always coded (their entropy cannot show noise).
constexpr std::size_t kNoiseMinBytes = 4096;

bool is_noise(const unsigned char* plane, std::size_t bytes) {
  if (bytes < kNoiseMinBytes) return false;
  std::array<std::uint32_t, 256> count{};
  for (std::size_t i = 0; i < bytes; ++i) ++count[plane[i]];
  double bits = 0.0;
  for (const std::uint32_t c : count)
    if (c > 0) {
      const double p = static_cast<double>(c) / static_cast<double>(bytes);
      bits -= p * std::log2(p);
    }
  return bits > kNoiseBitsPerByte;
}

/// How a chunk's byte planes are coded: each by runs, a noise plane stored (metrics, float64
/// coordinates), or all by zlib's default strategy, which finds repeats at any distance (an
/// index 0, 1, 2, ...: its low plane repeats at distance 256, noise to a count of its bytes).
enum class Coding { kRunsOrStored, kRepeats };

/// A zlib stream, as H5Z's deflate filter reads it. Its strategy is zlib's run-length one
/// (Z_RLE: matches at distance 1 only), which HDF5's own filter cannot choose: on the shuffled
/// metrics of a non-lifting LHS (16 384 cases, 17 metrics) 36.9 B a case in 296 ns, against
/// 37.6 B in 685 ns with the default strategy at the same level (zlib via Python on this
/// machine): the byte planes of a shuffled chunk are runs and skewed bytes, not repeats.
/// A plane that is noise (is_noise) goes in as stored blocks (zlib's level 0, switched by
/// deflateParams between planes; one stream of mixed blocks, which any inflate reads): the
/// same size within a few bytes, at a copy's cost (zlib via Python: 31-39 ns a random value
/// coded, 5-9 stored). Coding::kRepeats: every plane coded, by the default strategy.
std::vector<char> deflated(const char* data, std::size_t elements, std::size_t element_bytes,
                           Coding coding = Coding::kRunsOrStored) {
  std::vector<char> plain = shuffled(data, elements, element_bytes);
  z_stream z{};
  int level = static_cast<int>(kDeflateLevel);
  const int strategy = coding == Coding::kRepeats ? Z_DEFAULT_STRATEGY : Z_RLE;
  if (deflateInit2(&z, level, Z_DEFLATED, 15, 8, strategy) != Z_OK) throw std::runtime_error("cannot deflate a chunk");
  // Stored blocks add 5 bytes a block of at most 64 KiB, and each switch ends a block.
  std::vector<char> out(deflateBound(&z, static_cast<uLong>(plain.size())) + 64 * (element_bytes + plain.size() / 65535 + 1));
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  bool failed = false;
  for (std::size_t b = 0; b < element_bytes && !failed; ++b) {
    auto* plane = reinterpret_cast<unsigned char*>(plain.data() + b * elements);
    const int want = coding == Coding::kRunsOrStored && is_noise(plane, elements) ? 0 : static_cast<int>(kDeflateLevel);
    // A switch that zlib declines (Z_BUF_ERROR: never with this much room) keeps the level:
    // the stream is the same data either way.
    if (want != level && deflateParams(&z, want, strategy) == Z_OK) level = want;
    z.next_in = plane;
    z.avail_in = static_cast<uInt>(elements);
    while (z.avail_in > 0 && !failed) failed = deflate(&z, Z_NO_FLUSH) != Z_OK;
  }
  const int done = failed ? Z_STREAM_ERROR : deflate(&z, Z_FINISH);
  const auto size = z.total_out;
  deflateEnd(&z);
  if (done != Z_STREAM_END) throw std::runtime_error("cannot deflate a chunk");
  out.resize(size);
  return out;
}

/// True when every element of `data` has the same bytes (a chunk equal to its shift by one
/// element is periodic in it).
bool every_element_same(const char* data, std::size_t elements, std::size_t element_bytes) {
  return elements < 2 || std::memcmp(data, data + element_bytes, (elements - 1) * element_bytes) == 0;
}

/// The stream of a chunk, as `deflated` makes it. A chunk of one repeated element (a metric
/// that is 0 or NaN for every case where frames never lift, a status that is the same for
/// all) is deflated once per thread and element, and its stream reused: the same bytes, at
/// the cost of a comparison (about a third of a worker's sealing on a non-lifting study).
std::vector<char> filtered(const char* data, std::size_t elements, std::size_t element_bytes) {
  if (element_bytes > sizeof(std::uint64_t) || !every_element_same(data, elements, element_bytes))
    return deflated(data, elements, element_bytes);
  struct Repeated {
    std::uint64_t element = 0;
    std::size_t elements = 0, element_bytes = 0;
    std::vector<char> stream;
  };
  constexpr std::size_t kRepeatedKept = 64;  // distinct repeated chunks a thread keeps [chunks]
  thread_local std::vector<Repeated> kept;
  std::uint64_t element = 0;
  std::memcpy(&element, data, element_bytes);
  for (const Repeated& r : kept)
    if (r.element == element && r.elements == elements && r.element_bytes == element_bytes) return r.stream;
  std::vector<char> stream = deflated(data, elements, element_bytes);
  if (kept.size() < kRepeatedKept) kept.push_back({element, elements, element_bytes, stream});
  return stream;
}

void put_bytes(std::vector<char>& out, const void* data, std::size_t n) {
  if (n == 0) return;
  const std::size_t at = out.size();
  out.resize(at + n);
  std::memcpy(out.data() + at, data, n);
}

template <class T>
void put(std::vector<char>& out, T value) {
  put_bytes(out, &value, sizeof(T));
}

class Reader {
 public:
  Reader(const std::vector<char>& bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}
  template <class T>
  T get() {
    T value{};
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  const char* take(std::uint64_t n) {
    if (n > bytes_.size() - at_) fail("ends early");
    const char* p = bytes_.data() + at_;
    at_ += static_cast<std::size_t>(n);
    return p;
  }
  std::size_t left() const { return bytes_.size() - at_; }
  [[noreturn]] void fail(const std::string& problem) const { throw CubeError(what_ + ": a sealed chunk " + problem); }

 private:
  const std::vector<char>& bytes_;
  std::string what_;
  std::size_t at_ = 0;
};

}  // namespace

std::size_t padded_elements(const ChunkGrid& grid) {
  std::size_t n = 1;
  for (const auto extent : grid.chunk_shape()) n *= extent;
  return n;
}

std::size_t filtered_bound(std::size_t elements, std::size_t element_bytes) {
  return static_cast<std::size_t>(compressBound(static_cast<uLong>(elements * element_bytes)));
}

SealedChunk seal_chunk(const ChunkGrid& grid, std::size_t chunk, std::size_t metrics, std::span<const std::int8_t> status,
                       std::span<const double> values, std::vector<std::pair<std::int64_t, std::string>> notes) {
  if (chunk >= grid.chunk_count()) throw std::invalid_argument("seal_chunk: no chunk " + std::to_string(chunk));
  const auto count = static_cast<std::size_t>(grid.range(chunk).count);
  if (status.size() != count || values.size() != metrics * count)
    throw std::invalid_argument("seal_chunk: the chunk has " + std::to_string(count) + " cases");
  const std::size_t padded = padded_elements(grid);  // an edge chunk is stored at full shape, filled
  SealedChunk sealed;
  sealed.chunk = chunk;
  sealed.status.assign(status.begin(), status.end());
  sealed.notes = std::move(notes);
  std::vector<double> column(padded, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t m = 0; m < metrics; ++m) {
    std::memcpy(column.data(), values.data() + m * count, count * sizeof(double));
    sealed.filtered.push_back(filtered(reinterpret_cast<const char*>(column.data()), padded, sizeof(double)));
  }
  std::vector<std::int8_t> codes(padded, kStatusNotRun);
  std::memcpy(codes.data(), status.data(), count);
  sealed.filtered.push_back(filtered(reinterpret_cast<const char*>(codes.data()), padded, 1));
  return sealed;
}

const std::vector<char>& uniform_status_stream(std::size_t padded, std::int8_t code) {
  thread_local std::map<std::pair<std::size_t, std::int8_t>, std::vector<char>> streams;
  auto [it, fresh] = streams.try_emplace({padded, code});
  if (fresh) {  // seal_chunk's own path: the status codes of the padded chunk, filtered
    const std::vector<std::int8_t> codes(padded, code);
    it->second = filtered(reinterpret_cast<const char*>(codes.data()), padded, 1);
  }
  return it->second;
}

std::vector<CoordinatePiece> coordinate_pieces(const CubeLayout& layout) {
  std::vector<CoordinatePiece> pieces;
  for (std::size_t k = 0; k < layout.coordinates.size(); ++k) {
    const Coordinate& c = layout.coordinates[k];
    if (!c.written_later() || !c.chunked()) continue;
    for (std::size_t p = 0; p < c.piece_count(); ++p) pieces.push_back({k, p});
  }
  return pieces;
}

std::size_t sealed_piece_bound(const Coordinate& c) {
  return filtered_bound(c.chunk_values(), c.is_index ? sizeof(std::int32_t) : sizeof(double));
}

std::vector<char> seal_coordinate_piece(const Coordinate& c, std::size_t piece) {
  static_assert(std::endian::native == std::endian::little, "a sealed piece holds the file's little-endian values");
  if (!c.chunked() || piece >= c.piece_count())
    throw std::invalid_argument("seal_coordinate_piece: '" + c.name + "' has no chunk " + std::to_string(piece));
  const std::size_t chunk = c.chunk_values();
  const std::size_t first = piece * kCoordinateChunk;
  const std::size_t count = std::min(chunk, c.size() - first);
  if (c.is_index) {  // whole numbers, stored as int32 (the conversion H5Dwrite made from int32 memory)
    std::vector<std::int32_t> values(chunk, 0);
    for (std::size_t k = 0; k < count; ++k) values[k] = static_cast<std::int32_t>(c.number(first + k));
    return deflated(reinterpret_cast<const char*>(values.data()), chunk, sizeof(std::int32_t), Coding::kRepeats);
  }
  std::vector<double> values(chunk, 0.0);
  c.numbers_into(first, std::span<double>(values.data(), count));
  return deflated(reinterpret_cast<const char*>(values.data()), chunk, sizeof(double));
}

std::vector<char> to_bytes(const SealedChunk& sealed) {
  std::vector<char> out;
  std::size_t size = 8 * 4 + sealed.status.size();
  for (const auto& f : sealed.filtered) size += 8 + f.size();
  for (const auto& [index, text] : sealed.notes) size += 16 + text.size();
  out.reserve(size);
  put<std::uint64_t>(out, sealed.chunk);
  put<std::uint64_t>(out, sealed.status.size());
  put_bytes(out, sealed.status.data(), sealed.status.size());
  put<std::uint64_t>(out, sealed.filtered.size());
  for (const auto& f : sealed.filtered) {
    put<std::uint64_t>(out, f.size());
    put_bytes(out, f.data(), f.size());
  }
  put<std::uint64_t>(out, sealed.notes.size());
  for (const auto& [index, text] : sealed.notes) {
    put<std::int64_t>(out, index);
    put<std::uint64_t>(out, text.size());
    put_bytes(out, text.data(), text.size());
  }
  return out;
}

SealedChunk sealed_from_bytes(const std::vector<char>& bytes, const ChunkGrid& grid, std::size_t metrics,
                              const std::string& what) {
  Reader in(bytes, what);
  SealedChunk sealed;
  sealed.chunk = static_cast<std::size_t>(in.get<std::uint64_t>());
  if (sealed.chunk >= grid.chunk_count()) in.fail("names chunk " + std::to_string(sealed.chunk) + " of " + std::to_string(grid.chunk_count()));
  const auto r = grid.range(sealed.chunk);
  if (in.get<std::uint64_t>() != static_cast<std::uint64_t>(r.count)) in.fail("has another number of cases than its chunk");
  const auto* status = reinterpret_cast<const std::int8_t*>(in.take(static_cast<std::uint64_t>(r.count)));
  sealed.status.assign(status, status + r.count);
  if (in.get<std::uint64_t>() != metrics + 1) in.fail("has another number of variables than the cube");
  const std::size_t padded = padded_elements(grid);
  for (std::size_t v = 0; v <= metrics; ++v) {
    const auto size = in.get<std::uint64_t>();
    if (size == 0 || size > filtered_bound(padded, v < metrics ? sizeof(double) : 1)) in.fail("has a variable of a wrong size");
    const char* p = in.take(size);
    sealed.filtered.emplace_back(p, p + size);
  }
  const auto notes = in.get<std::uint64_t>();
  if (notes > in.left() / 16) in.fail("declares more notes than it holds");
  for (std::uint64_t k = 0; k < notes; ++k) {
    const auto index = in.get<std::int64_t>();
    if (index < r.first || index >= r.first + r.count) in.fail("has a note of a case outside its chunk");
    const auto size = in.get<std::uint64_t>();
    const char* p = in.take(size);
    sealed.notes.emplace_back(index, std::string(p, static_cast<std::size_t>(size)));
  }
  if (in.left() != 0) in.fail("has trailing bytes");
  return sealed;
}

std::vector<char> unfilter(const std::vector<char>& filtered, std::size_t elements, std::size_t element_bytes,
                           const std::string& what) {
  std::vector<char> plain(elements * element_bytes);
  uLongf size = static_cast<uLongf>(plain.size());
  uLong used = static_cast<uLong>(filtered.size());
  if (uncompress2(reinterpret_cast<Bytef*>(plain.data()), &size, reinterpret_cast<const Bytef*>(filtered.data()), &used) != Z_OK ||
      size != plain.size() || used != filtered.size())
    throw CubeError(what + ": a sealed chunk's variable does not inflate to its chunk");
  return unshuffled(plain, elements, element_bytes);
}

}  // namespace pcrf::cube
