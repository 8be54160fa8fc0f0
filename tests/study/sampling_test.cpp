// Sampling plans: the Latin hypercube's strata, the Sobol' points against the Joe–Kuo
// reference sequence, scrambled points that keep the net property, and the Saltelli design's
// blocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <span>
#include <vector>

#include <boost/random/sobol.hpp>

#include "pcrf/study/sampling.hpp"

namespace pcrf::study {
namespace {

TEST(Sampling, LatinHypercubePutsOneValueInEachStratum) {
  const std::size_t n = 50, d = 8;
  const auto p = latin_hypercube(n, d, 7);
  for (std::size_t i = 0; i < d; ++i) {
    std::set<std::size_t> strata;
    for (std::size_t j = 0; j < n; ++j) strata.insert(static_cast<std::size_t>(p[j * d + i] * n));
    EXPECT_EQ(strata.size(), n) << "dimension " << i;
  }
  EXPECT_EQ(latin_hypercube(n, d, 7), p);
  EXPECT_NE(latin_hypercube(n, d, 8), p);
}

TEST(Sampling, IndexPermutationIsABijectionOfItsDomain) {
  for (std::uint64_t n : {1ull, 2ull, 3ull, 5ull, 16ull, 17ull, 1000ull, 4097ull, 65536ull}) {
    const IndexPermutation permutation(n, 12345);
    std::vector<char> hit(n, 0);
    for (std::uint64_t j = 0; j < n; ++j) {
      const std::uint64_t image = permutation(j);
      ASSERT_LT(image, n) << "n " << n;
      EXPECT_FALSE(hit[image]) << "n " << n << ": " << image << " taken twice";
      hit[image] = 1;
    }
  }
  // Another key, another permutation (of 1000! candidates, the same one would be a defect).
  const IndexPermutation a(1000, 1), b(1000, 2);
  std::size_t same = 0;
  for (std::uint64_t j = 0; j < 1000; ++j) same += a(j) == b(j);
  EXPECT_LT(same, 20u);
}

TEST(Sampling, IndexPermutationImagesAreItsValues) {
  // In runs from unaligned starts, longer than the lanes' block of 256, for sizes that walk
  // the cycles most (just above a power of 4) and least (a power of 4).
  for (std::uint64_t n : {1ull, 2ull, 5ull, 17ull, 257ull, 1000ull, 4096ull, 4097ull, 65537ull}) {
    const IndexPermutation permutation(n, 777);
    for (std::uint64_t first : {std::uint64_t{0}, std::uint64_t{1}, n / 3}) {
      std::vector<std::uint64_t> images(n - first);
      permutation.images(first, images);
      for (std::uint64_t j = first; j < n; ++j) ASSERT_EQ(images[j - first], permutation(j)) << "n " << n << " j " << j;
    }
  }
}

TEST(Sampling, ImagesOfOnePointUnderManyPermutationsAreTheirValues) {
  for (std::uint64_t n : {1ull, 5ull, 257ull, 4097ull, 65536ull}) {
    std::vector<IndexPermutation> permutations;
    for (std::uint64_t key = 0; key < 300; ++key) permutations.emplace_back(n, key);  // more than a block of lanes
    std::vector<std::uint64_t> images(permutations.size());
    for (std::uint64_t j = 0; j < n; j += 1 + n / 40) {
      IndexPermutation::images_of(j, permutations, images);
      for (std::size_t p = 0; p < permutations.size(); ++p) ASSERT_EQ(images[p], permutations[p](j)) << "n " << n << " key " << p;
    }
  }
}

TEST(Sampling, LatinHypercubeRowsAreItsValuesBitForBit) {
  for (std::uint64_t n : {2ull, 17ull, 4097ull, 65537ull}) {
    const std::size_t d = 40;  // past the 32 a sampled plan asks for at once
    const LatinHypercube design(n, d, 4);
    std::vector<double> row(d);
    for (std::uint64_t j = 0; j < n; j += 1 + n / 200) {
      design.row(j, 0, row);
      for (std::size_t i = 0; i < d; ++i) ASSERT_EQ(row[i], design.at(j, i)) << "n " << n << " j " << j << " column " << i;
      design.row(j, 3, std::span(row).first(5));
      for (std::size_t s = 0; s < 5; ++s) ASSERT_EQ(row[s], design.at(j, 3 + s)) << "from column 3";
    }
  }
}

TEST(Sampling, LatinHypercubeByIndexIsALatinHypercube) {
  // Each stratum of each dimension exactly once, the value inside its stratum, and the
  // whole-matrix function the same values.
  for (std::size_t n : {2u, 3u, 97u, 1000u, 4096u}) {
    const std::size_t d = 8;
    const LatinHypercube design(n, d, 1);
    const auto matrix = latin_hypercube(n, d, 1);
    for (std::size_t i = 0; i < d; ++i) {
      std::vector<char> taken(n, 0);
      for (std::size_t j = 0; j < n; ++j) {
        const std::uint64_t s = design.stratum(j, i);
        ASSERT_LT(s, n);
        EXPECT_FALSE(taken[s]) << "n " << n << " dimension " << i << " stratum " << s;
        taken[s] = 1;
        const double x = design.at(j, i);
        EXPECT_EQ(static_cast<std::uint64_t>(std::floor(x * static_cast<double>(n))), s);
        EXPECT_GE(x, 0.0);
        EXPECT_LT(x, 1.0);
        EXPECT_EQ(matrix[j * d + i], x);
      }
    }
  }
  // Uniform inside the strata: the positions within them average 1/2.
  const std::size_t n = 20000;
  const LatinHypercube design(n, 2, 3);
  double mean = 0.0;
  for (std::size_t j = 0; j < n; ++j)
    mean += design.at(j, 0) * static_cast<double>(n) - static_cast<double>(design.stratum(j, 0));
  EXPECT_NEAR(mean / static_cast<double>(n), 0.5, 0.01);  // 4.5 sigma of a mean of 20 000 uniforms
}

TEST(Sampling, SobolByIndexIsBoostsSequenceBitForBit) {
  // The sequence as the plans drew it before issue 38: Boost's engine stepped point by point.
  const std::size_t n = 5000, d = 16;
  boost::random::sobol_engine<std::uint32_t, 32> engine(d);
  const SobolSequence sequence(d, false, 0);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < d; ++i) {
      const std::uint32_t x = j == 0 ? 0u : static_cast<std::uint32_t>(engine());
      ASSERT_EQ(sequence.at(j, i), static_cast<double>(x) / 4294967296.0) << j << ", " << i;
    }
  // Far out, where stepping would take long: against Boost's own seek.
  boost::random::sobol_engine<std::uint32_t, 32> far(3);
  const SobolSequence three(3, false, 0);
  for (std::uint64_t j : {1ull << 20, (1ull << 31) + 12345, (1ull << 32) - 1}) {
    far.seed(static_cast<std::uint32_t>(j - 1));  // Boost's state after seed(s) is the sequence's point s + 1
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(three.at(j, i), static_cast<double>(far()) / 4294967296.0) << j;
  }
}

TEST(Sampling, SaltelliRowsAreTheDesignsRows) {
  const std::size_t n = 64, d = 4;
  for (bool scramble : {false, true}) {
    const auto design = saltelli_design(n, d, scramble, 9);
    const SaltelliRows rows(d, scramble, 9);
    for (std::size_t r = 0; r < n * (d + 2); ++r)
      for (std::size_t i = 0; i < d; ++i) ASSERT_EQ(rows.at(r, i), design.points[r * d + i]) << r << ", " << i;
  }
}

/// Every value of `design`'s column `i` over [0, n), filled in runs that start at `first`
/// and at unaligned offsets, is what at() gives for it, bit for bit.
template <class Design>
void expect_columns_match(const Design& design, std::uint64_t n, std::size_t i, std::uint64_t first = 0) {
  std::vector<double> whole(n - first);
  design.column(i, first, whole);
  for (std::uint64_t j = first; j < n; ++j) ASSERT_EQ(whole[j - first], design.at(j, i)) << "j " << j << " column " << i;
  for (std::uint64_t start : {first + 1, first + (n - first) / 3, n - 1}) {
    if (start >= n) continue;
    std::vector<double> run(std::min<std::uint64_t>(n - start, 37));
    design.column(i, start, run);
    for (std::size_t m = 0; m < run.size(); ++m) ASSERT_EQ(run[m], design.at(start + m, i)) << "from " << start;
  }
  design.column(i, first, std::span<double>());  // an empty run writes nothing
}

// What LatinHypercube::at computed when issue 38 defined it (two floor calls and the whole
// counter_hash a value): the faster forms must keep these bits.
double issue_38_lhs_value(std::uint64_t n, std::uint64_t seed, std::size_t i, std::uint64_t j) {
  const std::uint64_t key = counter_hash(seed, 0x4c4853ull, i);
  const double stratum = static_cast<double>(IndexPermutation(n, key)(j));
  const double u = static_cast<double>(counter_hash(key, seed, j) >> 11) * 0x1p-53;
  const double size = static_cast<double>(n);
  double x = (stratum + u) / size;
  while (x > 0.0 && std::floor(x * size) > stratum) x = std::nextafter(x, 0.0);
  while (std::floor(x * size) < stratum) x = std::nextafter(x, 1.0);
  return x;
}

TEST(Sampling, LatinHypercubeColumnsAreItsValuesBitForBit) {
  // Sizes just above a power of 4 walk the Feistel cycles most (the domain is 4^k, nearly 4n).
  for (std::uint64_t n : {2ull, 3ull, 5ull, 17ull, 65ull, 257ull, 1000ull, 4097ull, 16385ull, 65536ull, 65537ull}) {
    SCOPED_TRACE(n);
    const std::size_t d = 3;
    for (std::uint64_t seed : {0ull, 11ull}) {
      const LatinHypercube design(n, d, seed);
      for (std::size_t i = 0; i < d; ++i) {
        expect_columns_match(design, n, i);
        for (std::uint64_t j = 0; j < n; j += 1 + n / 500)
          ASSERT_EQ(design.at(j, i), issue_38_lhs_value(n, seed, i, j)) << "seed " << seed << " column " << i << " j " << j;
      }
    }
  }
}

TEST(Sampling, SobolColumnsAreItsValuesBitForBit) {
  for (bool scramble : {false, true}) {
    SCOPED_TRACE(scramble);
    const SobolSequence sequence(5, scramble, 3);
    for (std::uint64_t n : {2ull, 3ull, 1000ull, 4097ull, 65537ull})
      for (std::size_t i = 0; i < 5; ++i) expect_columns_match(sequence, n, i);
    // Far out, across the carry into bit 31 and up to the sequence's last point.
    for (std::size_t i = 0; i < 5; ++i) {
      expect_columns_match(sequence, (1ull << 31) + 1000, i, (1ull << 31) - 1000);
      expect_columns_match(sequence, 1ull << 32, i, (1ull << 32) - 300);
    }
  }
}

TEST(Sampling, SaltelliColumnsAreItsRowsBitForBit) {
  for (bool scramble : {false, true})
    for (std::size_t d : {2u, 3u, 8u}) {
      SCOPED_TRACE(d);
      const SaltelliRows rows(d, scramble, 9);
      for (std::uint64_t samples : {2ull, 5ull, 1000ull})
        for (std::size_t i = 0; i < d; ++i) expect_columns_match(rows, samples * (d + 2), i);
    }
}

TEST(Sampling, SobolPointsAreTheJoeKuoSequence) {
  // The first eight points of dimensions 1–3 (new-joe-kuo-6.21201), as published.
  const double reference[8][3] = {{0, 0, 0},       {0.5, 0.5, 0.5},       {0.75, 0.25, 0.25},   {0.25, 0.75, 0.75},
                                  {0.375, 0.375, 0.625}, {0.875, 0.875, 0.125}, {0.625, 0.125, 0.875}, {0.125, 0.625, 0.375}};
  const auto p = sobol_points(8, 3, false, 0);
  for (std::size_t j = 0; j < 8; ++j)
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(p[j * 3 + i], reference[j][i]) << j << ", " << i;
}

TEST(Sampling, ScrambledSobolPointsStayStratified) {
  const std::size_t n = 256, d = 6;
  const auto plain = sobol_points(n, d, false, 0);
  const auto scrambled = sobol_points(n, d, true, 42);
  EXPECT_NE(plain, scrambled);
  EXPECT_EQ(sobol_points(n, d, true, 42), scrambled);
  // 2^8 points of a (t, m, s)-net: every 1-D projection has one point per interval of 1/256,
  // and every 2-D projection (t = 0 for the first two dimensions) one per 1/16 × 1/16 box.
  for (std::size_t i = 0; i < d; ++i) {
    std::set<std::size_t> strata;
    for (std::size_t j = 0; j < n; ++j) strata.insert(static_cast<std::size_t>(scrambled[j * d + i] * n));
    EXPECT_EQ(strata.size(), n) << "dimension " << i;
  }
  std::set<std::pair<std::size_t, std::size_t>> boxes;
  for (std::size_t j = 0; j < n; ++j)
    boxes.insert({static_cast<std::size_t>(scrambled[j * d] * 16), static_cast<std::size_t>(scrambled[j * d + 1] * 16)});
  EXPECT_EQ(boxes.size(), n);
  // Not on the dyadic grid any more.
  EXPECT_NE(std::fmod(scrambled[d] * n, 1.0), 0.0);
}

TEST(Sampling, SaltelliBlocksMixAAndB) {
  const std::size_t n = 16, d = 3;
  const auto design = saltelli_design(n, d, false, 0);
  ASSERT_EQ(design.points.size(), n * (d + 2) * d);
  const auto base = sobol_points(n, 2 * d, false, 0);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t block = 0; block < d + 2; ++block) {
      const std::size_t row = j * (d + 2) + block;
      EXPECT_EQ(SaltelliDesign::sample(row, d), j);
      EXPECT_EQ(SaltelliDesign::block(row, d), block);
      for (std::size_t i = 0; i < d; ++i) {
        const double a = base[j * 2 * d + i], b = base[j * 2 * d + d + i];
        const double expected = block == 1 || (block >= 2 && block - 2 == i) ? b : a;
        EXPECT_EQ(design.points[row * d + i], expected);
      }
    }
  }
}

}  // namespace
}  // namespace pcrf::study
