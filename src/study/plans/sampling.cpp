// Sampling plans over the unit hypercube (see sampling.hpp).
#include "pcrf/study/sampling.hpp"

#include "study/plans/feistel.hpp"

#include <boost/random/sobol.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <random>

namespace pcrf::study {
namespace {

constexpr double kTwoTo32 = 4294967296.0;

std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

/// The Laine–Karras permutation with Burley's (2020) constants: a hash in which each bit
/// depends only on the bits below it, so applied to the bit-reversed value it flips each
/// dyadic interval's halves by a hash of the digits above (a nested uniform, i.e. Owen,
/// scramble).
std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
  return reverse_bits(laine_karras(reverse_bits(x), seed));
}

using detail::mix64;

constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ull;  // splitmix64's increment

/// counter_hash's state after (seed, a), which its last word b only mixes into.
std::uint64_t counter_hash_state(std::uint64_t seed, std::uint64_t a) {
  return mix64(mix64(seed + kGolden) ^ (a + 2 * kGolden));
}

std::uint64_t counter_hash_last(std::uint64_t state, std::uint64_t b) { return mix64(state ^ (b + 3 * kGolden)); }

}  // namespace

std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  return counter_hash_last(counter_hash_state(seed, a), b);
}

IndexPermutation::IndexPermutation(std::uint64_t n, std::uint64_t key) : n_(n == 0 ? 1 : n) {
  unsigned bits = 2;
  while (bits < 64 && (std::uint64_t{1} << bits) < n_) ++bits;
  bits += bits % 2;
  half_bits_ = bits / 2;
  half_mask_ = (std::uint64_t{1} << half_bits_) - 1;
  for (int r = 0; r < kRounds; ++r) round_keys_[static_cast<std::size_t>(r)] = counter_hash(key, 0x5045524dull, static_cast<std::uint64_t>(r));
}

std::uint64_t IndexPermutation::encrypt(std::uint64_t x) const {
  return detail::feistel_encrypt(x, round_keys_, half_bits_, half_mask_);
}

std::uint64_t IndexPermutation::operator()(std::uint64_t j) const {
  std::uint64_t x = encrypt(j);
  while (x >= n_) x = encrypt(x);  // cycle-walking: ends, as j < n lies on x's cycle
  return x;
}

namespace {

using EncryptEach = void (*)(std::span<std::uint64_t>, const detail::FeistelKeys&, unsigned, std::uint64_t);
using EncryptKeyed = void (*)(std::span<std::uint64_t>, const detail::FeistelKeys*, unsigned, std::uint64_t);

void encrypt_each_portable(std::span<std::uint64_t> x, const detail::FeistelKeys& keys, unsigned half_bits,
                           std::uint64_t half_mask) {
  detail::feistel_encrypt_each(x, keys, half_bits, half_mask);
}

void encrypt_keyed_portable(std::span<std::uint64_t> x, const detail::FeistelKeys* keys, unsigned half_bits,
                            std::uint64_t half_mask) {
  detail::feistel_encrypt_keyed(x, keys, half_bits, half_mask);
}

/// The lanes' kernels with the widest instruction set this CPU runs, chosen once.
EncryptEach encrypt_each() {
#ifdef PCRF_FEISTEL_AVX2
  static const EncryptEach chosen =
      __builtin_cpu_supports("avx2") ? &detail::feistel_encrypt_each_avx2 : &encrypt_each_portable;
  return chosen;
#else
  return &encrypt_each_portable;
#endif
}

EncryptKeyed encrypt_keyed() {
#ifdef PCRF_FEISTEL_AVX2
  static const EncryptKeyed chosen =
      __builtin_cpu_supports("avx2") ? &detail::feistel_encrypt_keyed_avx2 : &encrypt_keyed_portable;
  return chosen;
#else
  return &encrypt_keyed_portable;
#endif
}

/// Values whose cycle-walks are stepped together [values]: a few kB on the stack.
constexpr std::size_t kWalkedTogether = 256;

}  // namespace

void IndexPermutation::images(std::uint64_t first, std::span<std::uint64_t> out) const {
  const EncryptEach encrypt_all = encrypt_each();
  std::array<std::uint64_t, kWalkedTogether> walking;
  std::array<std::size_t, kWalkedTogether> position;
  for (std::size_t start = 0; start < out.size(); start += kWalkedTogether) {
    const auto block = out.subspan(start, std::min(kWalkedTogether, out.size() - start));
    for (std::size_t m = 0; m < block.size(); ++m) block[m] = first + start + m;
    encrypt_all(block, round_keys_, half_bits_, half_mask_);
    // Cycle-walking as operator() does it, the values still outside [0, n) gathered and
    // encrypted again together, until none is left.
    std::size_t pending = 0;
    for (std::size_t m = 0; m < block.size(); ++m)
      if (block[m] >= n_) walking[pending] = block[m], position[pending++] = m;
    while (pending > 0) {
      encrypt_all(std::span(walking.data(), pending), round_keys_, half_bits_, half_mask_);
      std::size_t still = 0;
      for (std::size_t p = 0; p < pending; ++p) {
        if (walking[p] < n_) block[position[p]] = walking[p];
        else walking[still] = walking[p], position[still++] = position[p];
      }
      pending = still;
    }
  }
}

void IndexPermutation::images_of(std::uint64_t j, std::span<const IndexPermutation> permutations,
                                 std::span<std::uint64_t> out) {
  if (out.empty()) return;
  const EncryptKeyed encrypt_all = encrypt_keyed();
  const IndexPermutation& any = permutations[0];  // every one of the same domain
  std::array<detail::FeistelKeys, kWalkedTogether> keys;
  for (std::size_t start = 0; start < out.size(); start += kWalkedTogether) {
    const auto block = out.subspan(start, std::min(kWalkedTogether, out.size() - start));
    for (std::size_t m = 0; m < block.size(); ++m) block[m] = j, keys[m] = permutations[start + m].round_keys_;
    encrypt_all(block, keys.data(), any.half_bits_, any.half_mask_);
    // The few that walk on, one by one: lanes called again for one or two values cost more
    // than they save (measured with callgrind: 1265 instructions a point of 8 dimensions at
    // N = 2^17, against 1107 so).
    for (std::size_t m = 0; m < block.size(); ++m)
      while (block[m] >= any.n_) block[m] = permutations[start + m].encrypt(block[m]);
  }
}

LatinHypercube::LatinHypercube(std::uint64_t n, std::size_t d, std::uint64_t seed) : n_(n) {
  for (std::size_t i = 0; i < d; ++i) {
    const std::uint64_t key = counter_hash(seed, 0x4c4853ull, i);  // "LHS"
    permutations_.emplace_back(n, key);
    jitter_states_.push_back(counter_hash_state(key, seed));
  }
}

namespace {

/// A point's position inside its stratum, in [0, 1), from its dimension's jitter state.
double unit_jitter(std::uint64_t state, std::uint64_t j) {
  return static_cast<double>(counter_hash_last(state, j) >> 11) * 0x1p-53;
}

/// (stratum + u) / n, moved by ulps until floor(x n) reads the stratum back: rounding must
/// not carry the value out of its stratum. floor(y) > s is y >= s + 1 and floor(y) < s is
/// y < s for a whole s below 2^53: the same tests without two calls to floor (the baseline
/// x86-64 has no rounding instruction) for each value.
double place_in_stratum(std::uint64_t stratum, double u, double n) {
  const double s = static_cast<double>(stratum);
  double x = (s + u) / n;
  while (x > 0.0 && x * n >= s + 1.0) x = std::nextafter(x, 0.0);
  while (x * n < s) x = std::nextafter(x, 1.0);
  return x;
}

}  // namespace

double LatinHypercube::at(std::uint64_t j, std::size_t i) const {
  return place_in_stratum(permutations_[i](j), unit_jitter(jitter_states_[i], j), static_cast<double>(n_));
}

void LatinHypercube::row(std::uint64_t j, std::size_t first, std::span<double> out) const {
  const double n = static_cast<double>(n_);
  std::array<std::uint64_t, kWalkedTogether> strata;
  for (std::size_t start = 0; start < out.size(); start += strata.size()) {
    const std::size_t count = std::min(strata.size(), out.size() - start);
    IndexPermutation::images_of(j, std::span(permutations_).subspan(first + start, count), std::span(strata.data(), count));
    for (std::size_t s = 0; s < count; ++s)
      out[start + s] = place_in_stratum(strata[s], unit_jitter(jitter_states_[first + start + s], j), n);
  }
}

void LatinHypercube::column(std::size_t i, std::uint64_t first, std::span<double> out) const {
  const double n = static_cast<double>(n_);
  const std::uint64_t jitter_state = jitter_states_[i];
  std::array<std::uint64_t, kWalkedTogether> strata;
  for (std::size_t start = 0; start < out.size(); start += strata.size()) {
    const std::size_t count = std::min(strata.size(), out.size() - start);
    permutations_[i].images(first + start, std::span(strata.data(), count));
    for (std::size_t m = 0; m < count; ++m)
      out[start + m] = place_in_stratum(strata[m], unit_jitter(jitter_state, first + start + m), n);
  }
}

SobolSequence::SobolSequence(std::size_t d, bool scramble, std::uint64_t seed)
    : directions_(d), seeds_(d, 0), scramble_(scramble) {
  boost::random::sobol_engine<std::uint32_t, 32> engine(d);
  for (unsigned r = 0; r < 32; ++r) {
    // Boost's state after seed(s) is its point s + 1 (the sequence's point, the origin being
    // point 0), the XOR of v_k over the bits k of gray(s + 1): for s + 1 = 2^(r+1) - 1,
    // gray(s + 1) = 2^r, and the state is v_r.
    engine.seed(static_cast<std::uint32_t>((std::uint64_t{1} << (r + 1)) - 2));
    for (std::size_t i = 0; i < d; ++i) directions_[i][r] = static_cast<std::uint32_t>(engine());
  }
  if (scramble) {
    std::mt19937_64 random(seed);
    for (auto& s : seeds_) s = static_cast<std::uint32_t>(random());
  }
}

std::uint32_t SobolSequence::unscrambled(std::uint64_t j, std::size_t i) const {
  std::uint64_t gray = j ^ (j >> 1);
  std::uint32_t x = 0;
  for (unsigned r = 0; gray != 0; ++r, gray >>= 1)
    if (gray & 1u) x ^= directions_[i][r];
  return x;
}

double SobolSequence::unit(std::uint32_t x, std::size_t i) const {
  if (scramble_) x = owen_scramble(x, seeds_[i]);
  return static_cast<double>(x) / kTwoTo32;
}

double SobolSequence::at(std::uint64_t j, std::size_t i) const { return unit(unscrambled(j, i), i); }

void SobolSequence::column(std::size_t i, std::uint64_t first, std::span<double> out) const {
  if (out.empty()) return;
  // Antonov and Saleev's recurrence: gray(j) = gray(j - 1) ^ 2^r, r the lowest set bit of j,
  // so point j is point j - 1 with v_r toggled: one XOR a value instead of one per bit of j.
  std::uint32_t x = unscrambled(first, i);
  out[0] = unit(x, i);
  for (std::size_t m = 1; m < out.size(); ++m) {
    x ^= directions_[i][static_cast<std::size_t>(std::countr_zero(first + m))];
    out[m] = unit(x, i);
  }
}

void SaltelliRows::column(std::size_t i, std::uint64_t first, std::span<double> out) const {
  if (out.empty()) return;
  // Row r is base sample r / (d + 2): its A value (column i) or B value (column d + i), both
  // computed once a sample as Sobol' columns over the samples the rows span.
  const std::uint64_t rows_per_sample = d_ + 2, first_sample = first / rows_per_sample;
  const std::uint64_t samples = (first + out.size() - 1) / rows_per_sample - first_sample + 1;
  std::vector<double> a(samples), b(samples);
  base_.column(i, first_sample, a);
  base_.column(d_ + i, first_sample, b);
  std::uint64_t sample = 0, block = first % rows_per_sample;
  for (double& value : out) {
    const bool from_b = block == 1 || block == i + 2;
    value = from_b ? b[sample] : a[sample];
    if (++block == rows_per_sample) block = 0, ++sample;
  }
}

UnitPoints latin_hypercube(std::size_t n, std::size_t d, std::uint64_t seed) {
  const LatinHypercube design(n, d, seed);
  UnitPoints points(n * d);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < d; ++i) points[j * d + i] = design.at(j, i);
  return points;
}

UnitPoints sobol_points(std::size_t n, std::size_t d, bool scramble, std::uint64_t seed) {
  const SobolSequence sequence(d, scramble, seed);
  UnitPoints points(n * d);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < d; ++i) points[j * d + i] = sequence.at(j, i);
  return points;
}

SaltelliDesign saltelli_design(std::size_t n, std::size_t d, bool scramble, std::uint64_t seed) {
  const UnitPoints base = sobol_points(n, 2 * d, scramble, seed);
  SaltelliDesign design{n, d, UnitPoints(n * (d + 2) * d)};
  for (std::size_t j = 0; j < n; ++j) {
    const double* a = &base[j * 2 * d];
    const double* b = a + d;
    for (std::size_t block = 0; block < d + 2; ++block) {
      double* row = &design.points[(j * (d + 2) + block) * d];
      for (std::size_t i = 0; i < d; ++i) {
        if (block == 1) row[i] = b[i];
        else row[i] = (block >= 2 && i == block - 2) ? b[i] : a[i];
      }
    }
  }
  return design;
}

}  // namespace pcrf::study
