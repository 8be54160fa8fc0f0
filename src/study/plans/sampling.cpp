// Sampling plans over the unit hypercube (see sampling.hpp).
#include "pcrf/study/sampling.hpp"

#include <boost/random/sobol.hpp>

#include <algorithm>
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

}  // namespace

UnitPoints latin_hypercube(std::size_t n, std::size_t d, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> inside(0.0, 1.0);
  UnitPoints points(n * d);
  std::vector<std::size_t> strata(n);
  for (std::size_t i = 0; i < d; ++i) {
    std::iota(strata.begin(), strata.end(), 0);
    std::shuffle(strata.begin(), strata.end(), random);
    for (std::size_t j = 0; j < n; ++j)
      points[j * d + i] = (static_cast<double>(strata[j]) + inside(random)) / static_cast<double>(n);
  }
  return points;
}

UnitPoints sobol_points(std::size_t n, std::size_t d, bool scramble, std::uint64_t seed) {
  boost::random::sobol_engine<std::uint32_t, 32> engine(d);
  std::vector<std::uint32_t> seeds(d, 0);
  if (scramble) {
    std::mt19937_64 random(seed);
    for (auto& s : seeds) s = static_cast<std::uint32_t>(random());
  }
  UnitPoints points(n * d);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t i = 0; i < d; ++i) {
      // Boost's engine starts after the origin; the sequence itself starts at it.
      std::uint32_t x = j == 0 ? 0u : static_cast<std::uint32_t>(engine());
      if (scramble) x = owen_scramble(x, seeds[i]);
      points[j * d + i] = static_cast<double>(x) / kTwoTo32;
    }
  }
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
