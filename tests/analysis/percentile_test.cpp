// The engine's one percentile, against numpy's default (linear between order statistics).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pcrf/analysis/percentile.hpp"

namespace {

using pcrf::analysis::percentile;
using pcrf::analysis::percentile_sorted;

TEST(Percentile, InterpolatesLikeNumpy) {
  const std::vector<double> v = {1, 2, 3, 4, 10};
  EXPECT_DOUBLE_EQ(percentile_sorted(v, 0.50), 3.0);
  EXPECT_DOUBLE_EQ(percentile_sorted(v, 0.16), 1.64);  // numpy.percentile([1,2,3,4,10], 16)
  EXPECT_DOUBLE_EQ(percentile_sorted(v, 0.84), 6.16);  // numpy.percentile([1,2,3,4,10], 84)
  EXPECT_DOUBLE_EQ(percentile_sorted({7.0}, 0.84), 7.0);
  EXPECT_TRUE(std::isnan(percentile_sorted({}, 0.5)));
}

TEST(Percentile, SortsAndLeavesOutNans) {
  EXPECT_DOUBLE_EQ(percentile({10, NAN, 3, 1, 4, 2}, 0.16), 1.64);
  EXPECT_TRUE(std::isnan(percentile({NAN, NAN}, 0.5)));
}

}  // namespace
