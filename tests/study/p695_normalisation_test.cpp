/// \file p695_normalisation_test.cpp
/// \brief FEMA P-695 Appendix A's normalisation of a record set (p695_set_intensities),
/// against the definition worked by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "pcrf/study/record_source.hpp"

namespace pcrf::study {
namespace {

TEST(P695Normalisation, StationsByNameAndTheSetScaledByItsMedian) {
  EXPECT_EQ(station_of("RSN1111_KOBE_NIS000"), "RSN1111_KOBE");
  EXPECT_EQ(station_of("NGA_no_829_RIO270"), "NGA_no_829");
  // Three stations: PGV_pair = √(1·4) = 2, √(2·2) = 2... chosen so the factors are simple.
  const std::vector<std::string> stations{"A", "A", "B", "B", "C", "C"};
  const std::vector<double> pgv{1.0, 4.0, 1.0, 1.0, 4.0, 4.0};    // pairs: 2, 1, 4 → median 2
  const std::vector<double> sa{1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
  // NM: A 1, B 2, C 0.5; normalised Sa: 1, 2, 6, 8, 2.5, 3 → median (2.5 + 3)/2 = 2.75.
  const auto s = p695_set_intensities(stations, pgv, sa);
  const std::vector<double> nm{1.0, 1.0, 2.0, 2.0, 0.5, 0.5};
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_DOUBLE_EQ(s[i], 2.75 / nm[i]) << i;
  // At set intensity I each record gets I / s = NM I / 2.75: the scaled set's median is I.
  std::vector<double> scaled;
  for (std::size_t i = 0; i < s.size(); ++i) scaled.push_back(sa[i] * 5.0 / s[i]);
  std::sort(scaled.begin(), scaled.end());
  EXPECT_NEAR(0.5 * (scaled[2] + scaled[3]), 5.0, 1e-12);
  EXPECT_THROW((void)p695_set_intensities({"A", "A", "B"}, {1, 1, 1}, {1, 1, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace pcrf::study
