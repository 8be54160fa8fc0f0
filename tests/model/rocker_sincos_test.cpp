// The rigid rockers' sin/cos (pcrf/model/rocker_sincos.hpp): within 2 ulp of the true values
// (long double's sinl/cosl as the reference) over the rockers' arguments and far beyond, the
// quadrants' signs right, exact where it must be, NaN where it must be.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "pcrf/model/rocker_sincos.hpp"

namespace pcrf {
namespace {

struct Ops {
  static double select(bool m, double a, double b) { return m ? a : b; }
};

/// |v − reference| in units of the last place of the reference (as a double).
double ulps(double v, long double reference) {
  const double r = static_cast<double>(reference);
  const double ulp = std::nextafter(std::abs(r), std::numeric_limits<double>::infinity()) - std::abs(r);
  return static_cast<double>(std::abs(static_cast<long double>(v) - reference) / ulp);
}

TEST(RockerSinCos, WithinTwoUlpOfTheTrueValuesFromTinyToLargeArguments) {
  std::mt19937_64 rng(17);
  double worst_sin = 0.0, worst_cos = 0.0;
  for (const double range : {1e-6, 0.8, 4.0, 100.0, 1e5}) {
    std::uniform_real_distribution<double> u(-range, range);
    for (int i = 0; i < 50000; ++i) {
      const double x = u(rng);
      double s, c;
      rocker_sincos<Ops>(x, s, c);
      worst_sin = std::max(worst_sin, ulps(s, std::sin(static_cast<long double>(x))));
      worst_cos = std::max(worst_cos, ulps(c, std::cos(static_cast<long double>(x))));
    }
  }
  EXPECT_LE(worst_sin, 2.0);
  EXPECT_LE(worst_cos, 2.0);
  EXPECT_GT(worst_sin + worst_cos, 0.0);  // a reference that agreed everywhere would test nothing
}

TEST(RockerSinCos, QuadrantsZeroAndNonFiniteArguments) {
  double s, c;
  rocker_sincos<Ops>(0.0, s, c);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(c, 1.0);
  for (int k = -8; k <= 8; ++k) {  // the sign of each quadrant, a little inside it
    const double x = (k + 0.5) * 0.5 * std::numbers::pi;
    rocker_sincos<Ops>(x, s, c);
    EXPECT_NEAR(s, std::sin(x), 1e-15) << k;
    EXPECT_NEAR(c, std::cos(x), 1e-15) << k;
  }
  for (const double bad : {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()}) {
    rocker_sincos<Ops>(bad, s, c);
    EXPECT_TRUE(std::isnan(s) && std::isnan(c)) << bad;
  }
}

}  // namespace
}  // namespace pcrf
