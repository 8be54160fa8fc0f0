// Sealed chunks (see sealed_chunk.hpp): the cube's filter pipeline run by the rank that
// computed the chunk. HDF5 applies a dataset's filters in the order they were set
// (H5Pset_shuffle, then H5Pset_deflate: cube_writer.cpp), so a chunk is shuffled (byte k of
// every value together, as H5Z's shuffle filter does), then deflated by zlib at the cube's
// level into one zlib stream (what H5Z's deflate filter makes with compress2 and reads back
// with inflate; a plane at a time here, see Deflater); reading it back runs the same filters
// in reverse.
#include "pcrf/cube/sealed_chunk.hpp"

#include <libdeflate.h>
#include <zlib.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>

#include "pcrf/cube/cube_layout.hpp"

namespace pcrf::cube {
namespace {

#if defined(__SSE2__)
/// One round of a byte transpose of 16 values of `W` bytes held in W registers (register r:
/// bytes 16 r .. 16 r + 15 of the values): register k is interleaved byte by byte with
/// register k + W/2. A byte's position (its register, then its byte in it: log2(W) + 4 bits)
/// is rotated left by one bit, so 4 rounds take the values' bytes (value, then byte) to their
/// planes (byte, then value): the shuffle; log2(W) rounds undo it.
template <std::size_t W>
void interleave_round(__m128i (&x)[W]) {
  __m128i next[W];
  for (std::size_t k = 0; k < W / 2; ++k) {
    next[2 * k] = _mm_unpacklo_epi8(x[k], x[k + W / 2]);
    next[2 * k + 1] = _mm_unpackhi_epi8(x[k], x[k + W / 2]);
  }
  for (std::size_t k = 0; k < W; ++k) x[k] = next[k];
}

/// The shuffle of the first values of `W` bytes, 16 at a time by SSE2 (every x86-64 CPU has
/// it): 0.56 instructions a byte, against 6 for a byte loop (callgrind, 8-byte values).
/// Returns how many values it did (a multiple of 16); the caller does the rest.
template <std::size_t W>
std::size_t shuffle_sse2(const char* data, std::size_t elements, char* planes) {
  std::size_t i = 0;
  for (; i + 16 <= elements; i += 16) {
    __m128i x[W];
    for (std::size_t r = 0; r < W; ++r) x[r] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(data + i * W) + r);
    for (int round = 0; round < 4; ++round) interleave_round(x);
    for (std::size_t b = 0; b < W; ++b) _mm_storeu_si128(reinterpret_cast<__m128i*>(planes + b * elements + i), x[b]);
  }
  return i;
}

/// Inverse of shuffle_sse2: log2(W) rounds.
template <std::size_t W>
std::size_t unshuffle_sse2(const char* planes, std::size_t elements, char* data) {
  constexpr int kRounds = std::countr_zero(W);
  std::size_t i = 0;
  for (; i + 16 <= elements; i += 16) {
    __m128i x[W];
    for (std::size_t b = 0; b < W; ++b) x[b] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(planes + b * elements + i));
    for (int round = 0; round < kRounds; ++round) interleave_round(x);
    for (std::size_t r = 0; r < W; ++r) _mm_storeu_si128(reinterpret_cast<__m128i*>(data + i * W) + r, x[r]);
  }
  return i;
}
#endif

/// H5Z's shuffle filter: byte b of value i of `data` goes to planes[b * elements + i]. By SSE2
/// for float64 and int32 values where the CPU is x86-64, byte by byte otherwise (and for the
/// last values, fewer than 16).
void shuffle(const char* data, std::size_t elements, std::size_t element_bytes, char* planes) {
  if (element_bytes == 1) {
    std::memcpy(planes, data, elements);
    return;
  }
  std::size_t first = 0;  // values not done yet
#if defined(__SSE2__)
  if (element_bytes == 8) first = shuffle_sse2<8>(data, elements, planes);
  if (element_bytes == 4) first = shuffle_sse2<4>(data, elements, planes);
#endif
  for (std::size_t b = 0; b < element_bytes; ++b)
    for (std::size_t i = first; i < elements; ++i) planes[b * elements + i] = data[i * element_bytes + b];
}

std::vector<char> unshuffled(const std::vector<char>& planes, std::size_t elements, std::size_t element_bytes) {
  if (element_bytes == 1) return planes;
  std::vector<char> out(planes.size());
  std::size_t first = 0;
#if defined(__SSE2__)
  if (element_bytes == 8) first = unshuffle_sse2<8>(planes.data(), elements, out.data());
  if (element_bytes == 4) first = unshuffle_sse2<4>(planes.data(), elements, out.data());
#endif
  for (std::size_t b = 0; b < element_bytes; ++b)
    for (std::size_t i = first; i < elements; ++i) out[i * element_bytes + b] = planes[b * elements + i];
  return out;
}

/// Shannon entropy of a byte plane [bits a byte] above which the plane is noise: stored in
/// the stream as it is rather than coded (a random value's low mantissa bytes: coding them
/// gains nothing and costs most of a chunk's deflate).
constexpr double kNoiseBitsPerByte = 7.9;
/// Entropy of a byte plane [bits a byte] above which, when it has no runs either, it is coded
/// by Huffman codes alone (Z_HUFFMAN_ONLY), not by runs. On a non-lifting LHS (zlib via
/// Python) each such plane takes within 0.0002 B a case of what runs make of it, and its coding
/// costs 4 instructions a byte fewer (callgrind); below (a value's exponent byte, at 0-1.3
/// bits) runs save up to 0.015 B a case.
constexpr double kHuffmanBitsPerByte = 2.0;
/// Share of a plane's bytes equal to the next above which the plane has runs: it is coded by
/// runs whatever its entropy (a smooth ramp's middle bytes take every value, in runs; bytes
/// drawn at random from 16 values repeat 1/16 of the time, noise 1/256).
constexpr double kRunsRepeatShare = 1.0 / 8.0;
/// Bytes of a plane that plane_measure reads: 64 stretches of 64 consecutive bytes, evenly
/// spaced, and in each 8 pairs of neighbours for its runs. A histogram of every byte cost 590
/// instructions a case, this sample 100 (callgrind, pcrf_seal_cost on a non-lifting LHS of
/// 262 144 cases). Consecutive bytes see whole any pattern
/// of the cube's inner axes up to 64 values long (an evenly strided sample can see one phase
/// of it: noise where the plane is half constant). On seven cubes (a non-lifting LHS, the
/// large LHS, grid, IDA and Saltelli studies of same_answers.py, LHS of 5 000 and 9 000) it
/// stores the same planes as a histogram of every byte, but for planes in runs (Saltelli's
/// repeated coordinates: coded now) and three planes of 5 000 bytes whose whole histogram
/// reads 7.89 bits (low by 0.04 at that count; 7.93 at 65 536 values): stored now.
constexpr std::size_t kSampleStretches = 64;
constexpr std::size_t kStretchBytes = 64;
constexpr std::size_t kBytesPerPair = 8;
/// Planes shorter than this [bytes] are always coded by runs (their entropy cannot show noise).
constexpr std::size_t kMeasuredMinBytes = kSampleStretches * kStretchBytes;

struct PlaneMeasure {
  double bits = 0.0;          ///< entropy [bits a byte]
  double repeat_share = 0.0;  ///< of bytes equal to the next
};

/// c log2(c) for each count c a histogram of a sample can hold [bits]: a table, as log2 of
/// each of 256 counts was 37 instructions a case.
const std::vector<double>& count_bits() {
  static const std::vector<double> table = [] {
    std::vector<double> t(kMeasuredMinBytes + 1, 0.0);
    for (std::size_t k = 1; k < t.size(); ++k) t[k] = static_cast<double>(k) * std::log2(static_cast<double>(k));
    return t;
  }();
  return table;
}

/// A plane's entropy, estimated from a sample (kSampleStretches) by its histogram, and its
/// runs. The histogram's entropy is low by about (K - 1) / (2 n ln 2) bits for K distinct
/// bytes in n samples (Miller and Madow; 0.045 bits for noise in 4 096), which is added back.
/// `bytes` is at least kMeasuredMinBytes.
PlaneMeasure plane_measure(const unsigned char* plane, std::size_t bytes) {
  const std::size_t step = bytes / kSampleStretches;
  std::array<std::uint32_t, 256> count{};
  std::size_t equal = 0;
  for (std::size_t s = 0; s < kSampleStretches; ++s) {
    const unsigned char* stretch = plane + s * step;
    for (std::size_t i = 0; i < kStretchBytes; ++i) ++count[stretch[i]];
    for (std::size_t i = 0; i < kStretchBytes; i += kBytesPerPair) equal += stretch[i] == stretch[i + 1];
  }
  const double* const c_log2_c = count_bits().data();
  double sum = 0.0;  // the entropy is log2(n) - sum / n
  std::uint32_t distinct = 0;
  for (const std::uint32_t c : count) {
    sum += c_log2_c[c];
    distinct += c > 0 ? 1 : 0;
  }
  constexpr double n = kMeasuredMinBytes;
  constexpr double pairs = n / kBytesPerPair;
  const double bits = std::log2(n) - sum / n + (static_cast<double>(distinct) - 1.0) / (2.0 * n * std::numbers::ln2);
  return {bits, static_cast<double>(equal) / pairs};
}

/// How one byte plane goes into a stream: as it is (noise), by Huffman codes alone, by runs
/// (Z_RLE: matches at distance 1 only), or by zlib's default strategy, which finds repeats at
/// any distance (an index 0, 1, 2, ...: its low plane repeats at distance 256, noise to a
/// count of its bytes).
enum class PlaneCoding { kStored, kHuffman, kRuns, kRepeats };

PlaneCoding metric_plane_coding(const unsigned char* plane, std::size_t bytes) {
  if (bytes < kMeasuredMinBytes) return PlaneCoding::kRuns;
  const PlaneMeasure m = plane_measure(plane, bytes);
  if (m.repeat_share >= kRunsRepeatShare) return PlaneCoding::kRuns;
  return m.bits > kNoiseBitsPerByte ? PlaneCoding::kStored : m.bits > kHuffmanBitsPerByte ? PlaneCoding::kHuffman : PlaneCoding::kRuns;
}

/// zlib's level and strategy for a plane coding.
std::pair<int, int> zlib_parameters(PlaneCoding coding) {
  const auto level = static_cast<int>(kDeflateLevel);
  switch (coding) {
    case PlaneCoding::kStored: return {0, Z_DEFAULT_STRATEGY};
    case PlaneCoding::kHuffman: return {level, Z_HUFFMAN_ONLY};
    case PlaneCoding::kRuns: return {level, Z_RLE};
    case PlaneCoding::kRepeats: break;
  }
  return {level, Z_DEFAULT_STRATEGY};
}

/// How a chunk's byte planes are coded: each as metric_plane_coding says (metrics, float64
/// coordinates); each by repeats (an index); or all as one run by runs, as compress2 would
/// make it (a chunk of one repeated element: a few bytes whatever is done, made once a thread).
enum class Coding { kPlanes, kRepeats, kRunsWhole };

/// zlib's window: 2^15 bytes, what H5Z's deflate filter (compress2) uses.
constexpr int kWindowBits = 15;
constexpr std::size_t kWindowBytes = std::size_t{1} << kWindowBits;
/// A zlib stream's framing around its deflate data (RFC 1950) [bytes]: a header (CMF, FLG),
/// and the Adler-32 of the data, most significant byte first.
constexpr std::size_t kZlibHeaderBytes = 2;
constexpr std::size_t kZlibTrailerBytes = 4;

/// The header zlib's deflate writes for a stream begun at `level` and `strategy` (deflate.c):
/// method 8 with the window's size (CMF), the level class FLEVEL, no preset dictionary, and
/// FCHECK making the two bytes, most significant first, a multiple of 31. Inflate checks all
/// but FLEVEL, which is written as zlib writes it: the streams are zlib's own, byte for byte.
std::array<unsigned char, kZlibHeaderBytes> zlib_header(int level, int strategy) {
  const unsigned level_class = strategy >= Z_HUFFMAN_ONLY || level < 2 ? 0 : level < 6 ? 1 : level == 6 ? 2 : 3;
  unsigned header = (Z_DEFLATED + ((kWindowBits - 8) << 4)) << 8 | level_class << 6;
  header += 31 - header % 31;
  return {static_cast<unsigned char>(header >> 8), static_cast<unsigned char>(header & 0xff)};
}

/// Coded bytes a stream takes between full flushes. zlib slides its window (2 x 32 KiB) once
/// it holds 64 KiB less 262 bytes (MIN_LOOKAHEAD): a copy of 32 KiB and a rebase of both hash
/// tables (slide_hash: 64 Ki entries), which run-length coding never reads. Slides and the
/// hashing of stored bytes before a coded plane (fill_window's `insert`) were 1 080 of a
/// worker's 4 700 sealing instructions a case (callgrind, pcrf_seal_cost on a non-lifting LHS);
/// a full flush instead starts the window over (deflate.c: strstart = 0) for an empty stored
/// block (5 bytes) and a clear of the hash heads (CLEAR_HASH: 64 KiB).
constexpr std::size_t kCodedBytesPerWindow = 2 * kWindowBytes - 4096;

/// A zlib stream of the cube's filters (H5Z's deflate of the shuffled chunk), made by one
/// thread's deflate state and buffers, kept from one chunk to the next (deflateInit2 allocates
/// 256 KiB and clears 64 KiB each time; a chunk's buffers would be cleared and freed).
///
/// Each plane has a coding of its own (PlaneCoding, switched by deflateParams: one stream of
/// mixed blocks, which any inflate reads), which HDF5's own filter cannot choose: on the
/// shuffled metrics of a non-lifting LHS (16 384 cases, 17 metrics) runs take 36.9 B a case in
/// 296 ns, against 37.6 B in 685 ns with the default strategy at the same level (zlib via
/// Python on this machine): the byte planes of a shuffled chunk are runs and skewed bytes, not
/// repeats. A plane of noise goes in stored (zlib's level 0): the same size within a few
/// bytes, at a copy's cost (zlib via Python: 31-39 ns a random value coded, 5-9 stored).
///
/// Consecutive planes coded alike go to zlib as one run (its shuffled bytes are contiguous): a
/// run of stored planes of 32 KiB or more is copied straight to the output (deflate_stored);
/// a coded plane ends a block (its own Huffman codes: cpu_time_s of a non-lifting LHS takes
/// 3.75 B a case so, 3.80 coded as one run), and full flushes (kCodedBytesPerWindow) keep the
/// window from sliding. A stream is never longer than filtered_bound, which readers check:
/// were the flushes' empty blocks to take it past (only planes that barely compress,
/// alternating with noise), the chunk is deflated again as one run by runs, which zlib keeps
/// within it (deflateBound).
///
/// zlib makes the deflate data raw (negative windowBits: no checksum of its own); the Deflater
/// frames it as zlib would (zlib_header, then the Adler-32 of the shuffled chunk), with
/// libdeflate's Adler-32, vectorised where the CPU allows (SSE2, AVX2, ...): 33 instructions a
/// case against zlib's scalar 446, of the 2 982 that sealing a non-lifting LHS's chunks and
/// coordinate pieces took (callgrind, pcrf_seal_cost). Every byte is the one zlib's own framing
/// made (pcrf_seal_cost prints a digest of them; sealed_framing_test).
class Deflater {
 public:
  Deflater() {
    if (deflateInit2(&z_, static_cast<int>(kDeflateLevel), Z_DEFLATED, -kWindowBits, 8, Z_RLE) != Z_OK)
      throw std::runtime_error("cannot deflate a chunk");
  }
  ~Deflater() { deflateEnd(&z_); }
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;

  /// The stream of the chunk, in this deflater's buffer (valid until its next call).
  std::span<const char> operator()(const char* data, std::size_t elements, std::size_t element_bytes, Coding coding) {
    const std::size_t bytes = elements * element_bytes;
    if (planes_.size() < bytes) planes_.resize(bytes);
    shuffle(data, elements, element_bytes, planes_.data());
    // A run, a cut or a flush adds at most 10 bytes of block headers.
    const std::size_t room = filtered_bound(elements, element_bytes) + 64 * (element_bytes + bytes / (kWindowBytes / 2) + 2);
    if (out_.size() < room) out_.resize(room);
    plane_bytes_ = elements;
    stream_bytes_ = bytes;
    // Planes too short to measure are all coded by runs, as one run (a block a plane would
    // cost more in headers than its own codes gain).
    const bool whole = coding == Coding::kRunsWhole || (coding == Coding::kPlanes && elements < kMeasuredMinBytes);
    std::size_t size = whole ? deflate_whole() : deflate_planes(element_bytes, coding);
    if (size > filtered_bound(elements, element_bytes)) size = deflate_whole();
    return {out_.data(), size};
  }

 private:
  /// The stream of planes_, its planes in runs coded alike; its size [bytes].
  std::size_t deflate_planes(std::size_t element_bytes, Coding coding) {
    start(Z_RLE);
    std::size_t first = 0;  // the run's first plane
    PlaneCoding run = plane_coding(0, coding);
    for (std::size_t b = 1; b <= element_bytes; ++b) {
      const PlaneCoding next = b < element_bytes ? plane_coding(b, coding) : run;
      if (b < element_bytes && next == run) continue;
      put_run(planes_.data() + first * plane_bytes_, (b - first) * plane_bytes_, run);
      first = b;
      run = next;
    }
    return finish();
  }

  /// The stream of planes_ as one run by runs, all of it in one call (as compress2 makes it).
  std::size_t deflate_whole() {
    start(Z_RLE);
    put(planes_.data(), stream_bytes_, Z_NO_FLUSH);
    return finish();
  }

  PlaneCoding plane_coding(std::size_t b, Coding coding) const {
    if (coding == Coding::kRepeats) return PlaneCoding::kRepeats;
    return metric_plane_coding(reinterpret_cast<const unsigned char*>(planes_.data() + b * plane_bytes_), plane_bytes_);
  }

  void put_run(const char* run, std::size_t bytes, PlaneCoding coding) {
    // A switch that zlib declines (Z_BUF_ERROR: never with this much room) keeps the last
    // parameters: the stream is the same data either way.
    const auto [level, strategy] = zlib_parameters(coding);
    if ((level != level_ || strategy != strategy_) && deflateParams(&z_, level, strategy) == Z_OK) {
      level_ = level;
      strategy_ = strategy;
    }
    if (level_ == 0) put_stored(run, bytes);
    else put_coded(run, bytes);
  }

  void start(int strategy) {
    if (deflateReset(&z_) != Z_OK || deflateParams(&z_, static_cast<int>(kDeflateLevel), strategy) != Z_OK)
      throw std::runtime_error("cannot deflate a chunk");
    level_ = static_cast<int>(kDeflateLevel);
    strategy_ = strategy;
    z_.next_out = reinterpret_cast<Bytef*>(out_.data() + kZlibHeaderBytes);
    z_.avail_out = static_cast<uInt>(out_.size() - kZlibHeaderBytes - kZlibTrailerBytes);
    window_bytes_ = 0;
    stored_since_flush_ = false;
    begun_ = false;
  }

  /// One call of zlib's deflate. The stream's header is the one zlib writes at its first call,
  /// from the parameters it then has (a deflateParams before it calls no deflate).
  int step(int flush) {
    if (!begun_) {
      const auto header = zlib_header(level_, strategy_);
      std::memcpy(out_.data(), header.data(), header.size());
      begun_ = true;
    }
    return deflate(&z_, flush);
  }

  /// Stored bytes, copied to the output at once (Z_BLOCK). zlib keeps the last 32 KiB of them
  /// in its window; fewer that would overflow it first make it slide, so the window starts over.
  void put_stored(const char* run, std::size_t bytes) {
    if (bytes < kWindowBytes && window_bytes_ + bytes >= 2 * kWindowBytes) full_flush();
    put(run, bytes, Z_BLOCK);
    window_bytes_ = bytes >= kWindowBytes ? kWindowBytes : window_bytes_ + bytes;
    stored_since_flush_ = true;
  }

  /// Coded planes, each ending a block, in pieces of at most kWindowBytes; the window is
  /// started over before zlib would hash the stored bytes in it or slide it.
  void put_coded(const char* run, std::size_t bytes) {
    const char* const end = run + bytes;
    while (run < end) {
      const auto plane_left = static_cast<std::size_t>(plane_bytes_ - static_cast<std::size_t>(run - planes_.data()) % plane_bytes_);
      const std::size_t take = std::min(plane_left, kWindowBytes);
      if (stored_since_flush_ || window_bytes_ + take > kCodedBytesPerWindow) full_flush();
      // The stream's last bytes are ended by Z_FINISH alone (a one-plane chunk, the status:
      // the stream it always had, which uniform_status_stream's readers compare).
      const bool block_ends = take == plane_left && run + take != planes_.data() + stream_bytes_;
      put(run, take, block_ends ? Z_BLOCK : Z_NO_FLUSH);
      window_bytes_ += take;
      run += take;
    }
  }

  void full_flush() {
    if (step(Z_FULL_FLUSH) != Z_OK) throw std::runtime_error("cannot deflate a chunk");
    window_bytes_ = 0;
    stored_since_flush_ = false;
  }

  void put(const char* bytes, std::size_t n, int flush) {
    z_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes));
    z_.avail_in = static_cast<uInt>(n);
    while (z_.avail_in > 0)
      if (step(flush) != Z_OK) throw std::runtime_error("cannot deflate a chunk");
  }

  /// Ends the deflate data and frames it; the stream's size [bytes].
  std::size_t finish() {
    if (step(Z_FINISH) != Z_STREAM_END) throw std::runtime_error("cannot deflate a chunk");
    const std::uint32_t adler = libdeflate_adler32(1, planes_.data(), stream_bytes_);
    unsigned char* const trailer = reinterpret_cast<unsigned char*>(out_.data()) + kZlibHeaderBytes + z_.total_out;
    for (std::size_t k = 0; k < kZlibTrailerBytes; ++k)
      trailer[k] = static_cast<unsigned char>(adler >> (8 * (kZlibTrailerBytes - 1 - k)));
    return kZlibHeaderBytes + static_cast<std::size_t>(z_.total_out) + kZlibTrailerBytes;
  }

  z_stream z_{};
  int level_ = 0, strategy_ = 0;     ///< zlib's parameters now
  std::size_t window_bytes_ = 0;     ///< bytes zlib's window may hold since the last full flush
  bool stored_since_flush_ = false;  ///< stored bytes zlib would hash before coding more
  bool begun_ = false;               ///< deflate called since start: the header is written
  std::size_t plane_bytes_ = 1, stream_bytes_ = 0;  ///< of the chunk being deflated
  std::vector<char> planes_, out_;   ///< the shuffled chunk; its stream
};

/// The stream of a chunk in this thread's deflater (valid until the thread's next deflate).
std::span<const char> deflated_view(const char* data, std::size_t elements, std::size_t element_bytes, Coding coding) {
  thread_local Deflater deflater;
  return deflater(data, elements, element_bytes, coding);
}

std::vector<char> deflated(const char* data, std::size_t elements, std::size_t element_bytes, Coding coding) {
  const std::span<const char> stream = deflated_view(data, elements, element_bytes, coding);
  return {stream.begin(), stream.end()};
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
/// Valid until the thread's next deflate (a view of its deflater's stream, or of the one kept).
std::span<const char> filtered_view(const char* data, std::size_t elements, std::size_t element_bytes) {
  if (element_bytes > sizeof(std::uint64_t) || !every_element_same(data, elements, element_bytes))
    return deflated_view(data, elements, element_bytes, Coding::kPlanes);
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
  const std::span<const char> stream = deflated_view(data, elements, element_bytes, Coding::kRunsWhole);
  if (kept.size() < kRepeatedKept) kept.push_back({element, elements, element_bytes, {stream.begin(), stream.end()}});
  return stream;
}

std::vector<char> filtered(const char* data, std::size_t elements, std::size_t element_bytes) {
  const std::span<const char> stream = filtered_view(data, elements, element_bytes);
  return {stream.begin(), stream.end()};
}

/// The stream of a chunk of `padded` values whose first are `values`, the rest `fill` (a chunk
/// at the cube's edge, stored at its full shape); a whole chunk's values as they are (a copy
/// of each metric was 140 instructions a case).
template <class T>
std::span<const char> filtered_padded_view(std::span<const T> values, std::size_t padded, T fill) {
  if (values.size() == padded) return filtered_view(reinterpret_cast<const char*>(values.data()), padded, sizeof(T));
  std::vector<T> chunk(padded, fill);
  std::copy(values.begin(), values.end(), chunk.begin());
  return filtered_view(reinterpret_cast<const char*>(chunk.data()), padded, sizeof(T));
}

template <class T>
std::vector<char> filtered_padded(std::span<const T> values, std::size_t padded, T fill) {
  const std::span<const char> stream = filtered_padded_view(values, padded, fill);
  return {stream.begin(), stream.end()};
}

void put_bytes(std::vector<char>& out, const void* data, std::size_t n) {
  if (n == 0) return;
  const std::size_t at = out.size();
  out.resize(at + n);
  std::memcpy(out.data() + at, data, n);
}

/// A variable's stream or a chunk's status codes, copied once (put_bytes clears them first:
/// 55 instructions a case, a non-lifting LHS's chunk). put_bytes keeps its resize and copy for
/// a scalar's few bytes: an insert there makes GCC 12 warn falsely (-Wstringop-overflow, an
/// error in this build) of a write into a region of size 0 after to_bytes's reserve.
void put_span(std::vector<char>& out, std::span<const char> bytes) { out.insert(out.end(), bytes.begin(), bytes.end()); }

template <class T>
void put(std::vector<char>& out, T value) {
  put_bytes(out, &value, sizeof(T));
}

/// The cases of chunk `chunk`, checked against what seal_chunk and sealed_bytes are given.
/// \throws std::invalid_argument for a chunk the grid lacks, or statuses and values not its cases'.
std::size_t chunk_cases(const ChunkGrid& grid, std::size_t chunk, std::size_t metrics, std::span<const std::int8_t> status,
                        std::span<const double> values) {
  if (chunk >= grid.chunk_count()) throw std::invalid_argument("seal_chunk: no chunk " + std::to_string(chunk));
  const auto count = static_cast<std::size_t>(grid.range(chunk).count);
  if (status.size() != count || values.size() != metrics * count)
    throw std::invalid_argument("seal_chunk: the chunk has " + std::to_string(count) + " cases");
  return count;
}

// A sealed chunk's bytes (to_bytes, sealed_bytes; read by sealed_view_of_bytes), in order: the
// head (put_head), `variables` streams (put_stream), the notes (put_notes), the coordinate
// pieces' count, then each piece's head (put_piece_head) and stream.

/// The chunk's number, its case count and statuses, and how many variables' streams follow.
void put_head(std::vector<char>& out, std::size_t chunk, std::span<const std::int8_t> status, std::size_t variables) {
  put<std::uint64_t>(out, chunk);
  put<std::uint64_t>(out, status.size());
  put_span(out, {reinterpret_cast<const char*>(status.data()), status.size()});
  put<std::uint64_t>(out, variables);
}

/// A stream: its size, then its bytes.
void put_stream(std::vector<char>& out, std::span<const char> stream) {
  put<std::uint64_t>(out, stream.size());
  put_span(out, stream);
}

/// The notes' count, then each note's case, size and text.
void put_notes(std::vector<char>& out, std::span<const std::pair<std::int64_t, std::string>> notes) {
  put<std::uint64_t>(out, notes.size());
  for (const auto& [index, text] : notes) {
    put<std::int64_t>(out, index);
    put<std::uint64_t>(out, text.size());
    put_bytes(out, text.data(), text.size());
  }
}

/// A coordinate piece's coordinate and number, before its stream.
void put_piece_head(std::vector<char>& out, std::size_t coordinate, std::size_t piece) {
  put<std::uint64_t>(out, coordinate);
  put<std::uint64_t>(out, piece);
}

class Reader {
 public:
  Reader(std::span<const char> bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}
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
  std::span<const char> bytes_;
  std::string what_;
  std::size_t at_ = 0;
};

}  // namespace

std::size_t padded_elements(const ChunkGrid& grid) {
  std::size_t n = 1;
  for (const auto extent : grid.chunk_shape()) n *= extent;
  return n;
}

std::size_t sealed_piece_size_bound(const ChunkGrid& grid) { return filtered_bound(padded_elements(grid), sizeof(double)); }

std::optional<std::size_t> unit_piece(const ChunkGrid& grid, std::size_t unit, const UnitCoordinate& c) {
  if (unit >= grid.chunk_count() || c.dimension >= grid.shape().size() || c.chunk_values == 0) return std::nullopt;
  const auto r = grid.range(unit);
  for (std::size_t d = 0; d < r.start.size(); ++d)
    if (d != c.dimension && r.start[d] != 0) return std::nullopt;  // not the first along the others
  const std::size_t first = r.start[c.dimension], count = r.extent[c.dimension];
  if (first % c.chunk_values != 0) return std::nullopt;
  if (count != c.chunk_values && first + count != grid.shape()[c.dimension]) return std::nullopt;
  if (count > c.chunk_values) return std::nullopt;
  return first / c.chunk_values;
}

std::size_t filtered_bound(std::size_t elements, std::size_t element_bytes) {
  return static_cast<std::size_t>(compressBound(static_cast<uLong>(elements * element_bytes)));
}

SealedChunk seal_chunk(const ChunkGrid& grid, std::size_t chunk, std::size_t metrics, std::span<const std::int8_t> status,
                       std::span<const double> values, std::vector<std::pair<std::int64_t, std::string>> notes) {
  const std::size_t count = chunk_cases(grid, chunk, metrics, status, values);
  const std::size_t padded = padded_elements(grid);  // an edge chunk is stored at full shape, filled
  SealedChunk sealed;
  sealed.chunk = chunk;
  sealed.status.assign(status.begin(), status.end());
  sealed.notes = std::move(notes);
  sealed.filtered.reserve(metrics + 1);
  for (std::size_t m = 0; m < metrics; ++m) {
    const std::span<const double> metric = values.subspan(m * count, count);
    sealed.filtered.push_back(filtered_padded(metric, padded, std::numeric_limits<double>::quiet_NaN()));
  }
  sealed.filtered.push_back(filtered_padded(status, padded, kStatusNotRun));
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
    if (!c.written_later() || !c.chunked() || c.written_live()) continue;
    const std::size_t values = coordinate_chunk_values(layout, c);
    for (std::size_t p = 0; p < piece_count(c.size(), values); ++p) pieces.push_back({k, p, values});
  }
  return pieces;
}

std::size_t sealed_piece_bound(const Coordinate& c, std::size_t chunk_values) {
  return filtered_bound(chunk_values, c.is_index ? sizeof(std::int32_t) : sizeof(double));
}

namespace {

static_assert(std::endian::native == std::endian::little, "a sealed piece holds the file's little-endian values");

/// A float64 chunk of `chunk_values` values of a coordinate, in a thread's buffer, kept (a new
/// one, cleared, was 70 instructions a case for 8 coordinates): its first values are the
/// piece's, written there by the caller.
std::span<double> piece_buffer(std::size_t chunk_values) {
  thread_local std::vector<double> buffer;
  if (buffer.size() < chunk_values) buffer.resize(chunk_values);
  return {buffer.data(), chunk_values};
}

/// The stream of a float64 chunk whose first `count` values hold the piece's: the rest padded
/// with zeros (never read), then each byte plane coded as a metric's.
/// Valid until the thread's next deflate.
std::span<const char> sealed_float64_chunk_view(std::span<double> chunk, std::size_t count) {
  std::fill(chunk.begin() + static_cast<std::ptrdiff_t>(count), chunk.end(), 0.0);
  return deflated_view(reinterpret_cast<const char*>(chunk.data()), chunk.size(), sizeof(double), Coding::kPlanes);
}

std::vector<char> sealed_float64_chunk(std::span<double> chunk, std::size_t count) {
  const std::span<const char> stream = sealed_float64_chunk_view(chunk, count);
  return {stream.begin(), stream.end()};
}

/// The stream of a piece of `values` (seal_coordinate_values' checks and bytes), valid until
/// the thread's next deflate.
std::span<const char> sealed_values_view(std::span<const double> values, std::size_t chunk_values) {
  if (values.empty() || values.size() > chunk_values) throw std::invalid_argument("seal_coordinate_values: not a piece");
  const std::span<double> chunk = piece_buffer(chunk_values);
  std::copy(values.begin(), values.end(), chunk.begin());
  return sealed_float64_chunk_view(chunk, values.size());
}

}  // namespace

std::vector<char> seal_coordinate_values(std::span<const double> values, std::size_t chunk_values) {
  const std::span<const char> stream = sealed_values_view(values, chunk_values);
  return {stream.begin(), stream.end()};
}

std::vector<char> seal_coordinate_piece(const Coordinate& c, std::size_t chunk_values, std::size_t piece) {
  if (!c.chunked() || chunk_values == 0 || piece >= piece_count(c.size(), chunk_values))
    throw std::invalid_argument("seal_coordinate_piece: '" + c.name + "' has no chunk " + std::to_string(piece));
  const std::size_t chunk = chunk_values;
  const std::size_t first = piece * chunk;
  const std::size_t count = std::min(chunk, c.size() - first);
  if (c.is_index) {  // whole numbers, stored as int32 (the conversion H5Dwrite made from int32 memory)
    std::vector<std::int32_t> values(chunk, 0);
    for (std::size_t k = 0; k < count; ++k) values[k] = static_cast<std::int32_t>(c.number(first + k));
    return deflated(reinterpret_cast<const char*>(values.data()), chunk, sizeof(std::int32_t), Coding::kRepeats);
  }
  const std::span<double> values = piece_buffer(chunk);
  c.numbers_into(first, values.first(count));
  return sealed_float64_chunk(values, count);
}

std::vector<char> to_bytes(const SealedChunk& sealed) {
  std::vector<char> out;
  std::size_t size = 8 * 4 + sealed.status.size();
  for (const auto& f : sealed.filtered) size += 8 + f.size();
  for (const auto& [index, text] : sealed.notes) size += 16 + text.size();
  out.reserve(size);
  put_head(out, sealed.chunk, sealed.status, sealed.filtered.size());
  for (const auto& f : sealed.filtered) put_stream(out, f);
  put_notes(out, sealed.notes);
  put<std::uint64_t>(out, sealed.coordinates.size());
  for (const auto& piece : sealed.coordinates) {
    put_piece_head(out, piece.coordinate, piece.piece);
    put_stream(out, piece.filtered);
  }
  return out;
}

std::vector<char> sealed_bytes(const ChunkGrid& grid, std::size_t chunk, std::size_t metrics,
                               std::span<const std::int8_t> status, std::span<const double> values,
                               std::span<const std::pair<std::int64_t, std::string>> notes,
                               std::span<const PieceValues> pieces) {
  const std::size_t count = chunk_cases(grid, chunk, metrics, status, values);
  const std::size_t padded = padded_elements(grid);  // an edge chunk is stored at full shape, filled
  // Room for what the thread's last chunk took, and a quarter more: the bytes grow in place
  // (a reallocation would copy them again).
  thread_local std::size_t last_bytes = 0;
  std::vector<char> out;
  out.reserve(last_bytes + last_bytes / 4 + 4096 + count);
  put_head(out, chunk, status, metrics + 1);
  for (std::size_t m = 0; m < metrics; ++m)
    put_stream(out, filtered_padded_view(values.subspan(m * count, count), padded, std::numeric_limits<double>::quiet_NaN()));
  put_stream(out, filtered_padded_view(status, padded, kStatusNotRun));
  put_notes(out, notes);
  put<std::uint64_t>(out, pieces.size());
  for (const PieceValues& piece : pieces) {
    put_piece_head(out, piece.coordinate, piece.piece);
    const bool in_place = !piece.values.empty() && piece.room.size() == piece.chunk_values &&
                          piece.room.data() == piece.values.data() && piece.values.size() <= piece.chunk_values;
    put_stream(out, in_place ? sealed_float64_chunk_view(piece.room, piece.values.size())
                             : sealed_values_view(piece.values, piece.chunk_values));
  }
  last_bytes = out.size();
  return out;
}

SealedChunkView view_of(const SealedChunk& sealed) {
  SealedChunkView view;
  view.chunk = sealed.chunk;
  view.status = sealed.status;
  for (const auto& f : sealed.filtered) view.filtered.emplace_back(f);
  for (const auto& [index, text] : sealed.notes) view.notes.emplace_back(index, text);
  for (const auto& piece : sealed.coordinates) view.coordinates.push_back({piece.coordinate, piece.piece, piece.filtered});
  return view;
}

SealedChunkView sealed_view_of_bytes(std::span<const char> bytes, const ChunkGrid& grid, std::size_t metrics,
                                     const std::string& what) {
  Reader in(bytes, what);
  SealedChunkView sealed;
  sealed.chunk = static_cast<std::size_t>(in.get<std::uint64_t>());
  if (sealed.chunk >= grid.chunk_count()) in.fail("names chunk " + std::to_string(sealed.chunk) + " of " + std::to_string(grid.chunk_count()));
  const auto r = grid.range(sealed.chunk);
  if (in.get<std::uint64_t>() != static_cast<std::uint64_t>(r.count)) in.fail("has another number of cases than its chunk");
  sealed.status = {reinterpret_cast<const std::int8_t*>(in.take(static_cast<std::uint64_t>(r.count))), static_cast<std::size_t>(r.count)};
  if (in.get<std::uint64_t>() != metrics + 1) in.fail("has another number of variables than the cube");
  const std::size_t padded = padded_elements(grid);
  sealed.filtered.reserve(metrics + 1);
  for (std::size_t v = 0; v <= metrics; ++v) {
    const auto size = in.get<std::uint64_t>();
    if (size == 0 || size > filtered_bound(padded, v < metrics ? sizeof(double) : 1)) in.fail("has a variable of a wrong size");
    sealed.filtered.emplace_back(in.take(size), static_cast<std::size_t>(size));
  }
  const auto notes = in.get<std::uint64_t>();
  if (notes > in.left() / 16) in.fail("declares more notes than it holds");
  for (std::uint64_t k = 0; k < notes; ++k) {
    const auto index = in.get<std::int64_t>();
    if (index < r.first || index >= r.first + r.count) in.fail("has a note of a case outside its chunk");
    const auto size = in.get<std::uint64_t>();
    sealed.notes.emplace_back(index, std::string_view(in.take(size), static_cast<std::size_t>(size)));
  }
  const auto pieces = in.get<std::uint64_t>();
  if (pieces > in.left() / 24) in.fail("declares more coordinate pieces than it holds");
  for (std::uint64_t k = 0; k < pieces; ++k) {
    SealedChunkView::Piece piece;
    piece.coordinate = static_cast<std::size_t>(in.get<std::uint64_t>());
    piece.piece = static_cast<std::size_t>(in.get<std::uint64_t>());
    const auto size = in.get<std::uint64_t>();
    if (size == 0 || size > sealed_piece_size_bound(grid)) in.fail("has a coordinate piece of a wrong size");
    piece.filtered = {in.take(size), static_cast<std::size_t>(size)};
    sealed.coordinates.push_back(piece);
  }
  if (in.left() != 0) in.fail("has trailing bytes");
  return sealed;
}

SealedChunk sealed_from_bytes(const std::vector<char>& bytes, const ChunkGrid& grid, std::size_t metrics,
                              const std::string& what) {
  const SealedChunkView view = sealed_view_of_bytes(bytes, grid, metrics, what);
  SealedChunk sealed;
  sealed.chunk = view.chunk;
  sealed.status.assign(view.status.begin(), view.status.end());
  sealed.filtered.reserve(view.filtered.size());
  for (const auto f : view.filtered) sealed.filtered.emplace_back(f.begin(), f.end());
  for (const auto& [index, text] : view.notes) sealed.notes.emplace_back(index, std::string(text));
  for (const auto& piece : view.coordinates)
    sealed.coordinates.push_back({piece.coordinate, piece.piece, {piece.filtered.begin(), piece.filtered.end()}});
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
