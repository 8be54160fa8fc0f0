// Sampling plans: the Latin hypercube's strata, the Sobol' points against the Joe–Kuo
// reference sequence, scrambled points that keep the net property, and the Saltelli design's
// blocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

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
