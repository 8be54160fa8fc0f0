// Sampling plans over the unit hypercube (see sampling.hpp).
#include "pcrf/study/sampling.hpp"

#include <boost/random/sobol.hpp>

#include <algorithm>
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

/// splitmix64's finaliser (Steele, Lea and Flood 2014): a bijective 64-bit mixer.
std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  x ^= x >> 31;
  return x;
}

}  // namespace

std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ull;  // splitmix64's increment
  std::uint64_t h = mix64(seed + kGolden);
  h = mix64(h ^ (a + 2 * kGolden));
  return mix64(h ^ (b + 3 * kGolden));
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
  std::uint64_t left = x >> half_bits_, right = x & half_mask_;
  for (const std::uint64_t k : round_keys_) {
    const std::uint64_t next = (left ^ mix64(right ^ k)) & half_mask_;
    left = right;
    right = next;
  }
  return (left << half_bits_) | right;
}

std::uint64_t IndexPermutation::operator()(std::uint64_t j) const {
  std::uint64_t x = encrypt(j);
  while (x >= n_) x = encrypt(x);  // cycle-walking: ends, as j < n lies on x's cycle
  return x;
}

LatinHypercube::LatinHypercube(std::uint64_t n, std::size_t d, std::uint64_t seed) : n_(n), seed_(seed) {
  for (std::size_t i = 0; i < d; ++i) {
    keys_.push_back(counter_hash(seed, 0x4c4853ull, i));  // "LHS"
    permutations_.emplace_back(n, keys_.back());
  }
}

double LatinHypercube::at(std::uint64_t j, std::size_t i) const {
  const std::uint64_t stratum = permutations_[i](j);
  const double u = static_cast<double>(counter_hash(keys_[i], seed_, j) >> 11) * 0x1p-53;  // [0, 1)
  const double n = static_cast<double>(n_), s = static_cast<double>(stratum);
  double x = (s + u) / n;
  // Rounding must not carry the value out of its stratum (as floor(x N) reads it back).
  while (x > 0.0 && std::floor(x * n) > s) x = std::nextafter(x, 0.0);
  while (std::floor(x * n) < s) x = std::nextafter(x, 1.0);
  return x;
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

double SobolSequence::at(std::uint64_t j, std::size_t i) const {
  std::uint64_t gray = j ^ (j >> 1);
  std::uint32_t x = 0;
  for (unsigned r = 0; gray != 0; ++r, gray >>= 1)
    if (gray & 1u) x ^= directions_[i][r];
  if (scramble_) x = owen_scramble(x, seeds_[i]);
  return static_cast<double>(x) / kTwoTo32;
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
