/// \file test_ground_motion.cpp
/// \brief GroundMotion: constructor checks, exact values at t = i·dt, linear interpolation
/// between samples, zero outside the record, scaling and PGA.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "pcrf/record/ground_motion.hpp"

namespace {

using pcrf::GroundMotion;

/// Irregular but reproducible samples: no two neighbours equal, mixed signs.
std::vector<double> wiggly_samples(std::size_t n) {
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i);
    a[i] = 3.0 * std::sin(0.37 * x) + 0.5 * std::cos(1.91 * x) + 1e-3 * x;
  }
  return a;
}

// Sample intervals that are not exact binary fractions (0.01, 0.0066, 1/3 …) are where
// floor(t / dt) or floor(t · (1/dt)) lands one below i for some t = i·dt.
const double kAwkwardSteps_s[] = {0.01, 0.005, 0.02, 0.0066, 0.1, 1.0 / 3.0, 0.007, 0.3, 1e-4};

TEST(GroundMotion, ReturnsEverySampleExactlyAtItsTime) {
  constexpr std::size_t kN = 20001;
  const std::vector<double> a = wiggly_samples(kN);
  std::size_t naive_misses = 0;  // how often the obvious index formula would pick the wrong sample
  for (double dt_s : kAwkwardSteps_s) {
    const GroundMotion g("wiggly", dt_s, a);
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < kN; ++i) {
      const double t_s = static_cast<double>(i) * dt_s;
      if (g.accel_m_s2(t_s) != a[i]) ++mismatches;
      if (static_cast<std::size_t>(std::floor(t_s * (1.0 / dt_s))) != i) ++naive_misses;
    }
    EXPECT_EQ(mismatches, 0u) << "dt_s = " << dt_s;
  }
  // The step set really exercises the rounding trap the implementation guards against.
  EXPECT_GT(naive_misses, 0u);
}

TEST(GroundMotion, InterpolatesLinearlyBetweenSamples) {
  constexpr std::size_t kN = 5001;
  const std::vector<double> a = wiggly_samples(kN);
  for (double dt_s : kAwkwardSteps_s) {
    const GroundMotion g("wiggly", dt_s, a);
    for (std::size_t i = 0; i + 1 < kN; ++i) {
      const double mid_s = (static_cast<double>(i) + 0.5) * dt_s;
      const double quarter_s = (static_cast<double>(i) + 0.25) * dt_s;
      const double tol = 1e-12 * (std::abs(a[i]) + std::abs(a[i + 1]) + 1.0);
      ASSERT_NEAR(g.accel_m_s2(mid_s), 0.5 * (a[i] + a[i + 1]), tol) << "i = " << i;
      ASSERT_NEAR(g.accel_m_s2(quarter_s), 0.75 * a[i] + 0.25 * a[i + 1], tol) << "i = " << i;
    }
  }
}

TEST(GroundMotion, IsContinuousAcrossSamples) {
  const std::vector<double> a = wiggly_samples(1000);
  const GroundMotion g("wiggly", 0.01, a);
  for (std::size_t i = 1; i + 1 < a.size(); ++i) {
    const double t_s = static_cast<double>(i) * 0.01;
    const double just_before_s = std::nextafter(t_s, 0.0);
    const double just_after_s = std::nextafter(t_s, 1e9);
    EXPECT_NEAR(g.accel_m_s2(just_before_s), a[i], 1e-10);
    EXPECT_NEAR(g.accel_m_s2(just_after_s), a[i], 1e-10);
  }
}

TEST(GroundMotion, IsZeroOutsideTheRecordAndExactAtBothEnds) {
  const std::vector<double> a = {0.7, -1.2, 2.5, -0.4};
  const GroundMotion g("four", 0.02, a);
  EXPECT_DOUBLE_EQ(g.duration_s(), 0.06);
  EXPECT_EQ(g.accel_m_s2(0.0), 0.7);
  EXPECT_EQ(g.accel_m_s2(g.duration_s()), -0.4);
  EXPECT_EQ(g.accel_m_s2(-1e-300), 0.0);
  EXPECT_EQ(g.accel_m_s2(-0.01), 0.0);
  EXPECT_EQ(g.accel_m_s2(std::nextafter(g.duration_s(), 1.0)), 0.0);
  EXPECT_EQ(g.accel_m_s2(1.0), 0.0);
  EXPECT_EQ(g.accel_m_s2(std::numeric_limits<double>::infinity()), 0.0);
  EXPECT_EQ(g.accel_m_s2(-std::numeric_limits<double>::infinity()), 0.0);
  EXPECT_TRUE(std::isnan(g.accel_m_s2(std::numeric_limits<double>::quiet_NaN())));
  // Just inside the end still interpolates towards the last sample.
  EXPECT_NEAR(g.accel_m_s2(std::nextafter(g.duration_s(), 0.0)), -0.4, 1e-12);
}

TEST(GroundMotion, SingleSampleRecord) {
  const GroundMotion g("one", 0.01, {0.3});
  EXPECT_EQ(g.size(), 1u);
  EXPECT_EQ(g.duration_s(), 0.0);
  EXPECT_EQ(g.accel_m_s2(0.0), 0.3);
  EXPECT_EQ(g.accel_m_s2(1e-9), 0.0);
  EXPECT_EQ(g.accel_m_s2(-1e-9), 0.0);
  EXPECT_EQ(g.pga_m_s2(), 0.3);
}

TEST(GroundMotion, RejectsBadConstruction) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(GroundMotion("x", 0.0, {1.0}), std::invalid_argument);
  EXPECT_THROW(GroundMotion("x", -0.01, {1.0}), std::invalid_argument);
  EXPECT_THROW(GroundMotion("x", nan, {1.0}), std::invalid_argument);
  EXPECT_THROW(GroundMotion("x", inf, {1.0}), std::invalid_argument);
  EXPECT_THROW(GroundMotion("x", 0.01, {}), std::invalid_argument);
  EXPECT_THROW(GroundMotion("x", 0.01, {1.0, nan}), std::invalid_argument);
  EXPECT_THROW(GroundMotion("x", 0.01, {inf, 1.0}), std::invalid_argument);
  try {
    GroundMotion("ER7", 0.01, {1.0, 2.0, -inf});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ER7"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("sample 2"), std::string::npos) << e.what();
  }
}

TEST(GroundMotion, KeepsNameStepAndSamples) {
  const std::vector<double> a = wiggly_samples(17);
  const GroundMotion g("rec", 0.005, a);
  EXPECT_EQ(g.name(), "rec");
  EXPECT_EQ(g.dt_s(), 0.005);
  EXPECT_EQ(g.size(), 17u);
  EXPECT_EQ(g.samples_m_s2(), a);
  EXPECT_DOUBLE_EQ(g.duration_s(), 16 * 0.005);
}

TEST(GroundMotion, PgaIsPeakAbsoluteSample) {
  EXPECT_EQ(GroundMotion("a", 0.01, {0.1, -0.7, 0.3}).pga_m_s2(), 0.7);
  EXPECT_EQ(GroundMotion("b", 0.01, {0.1, 0.65, -0.3}).pga_m_s2(), 0.65);
  EXPECT_EQ(GroundMotion("z", 0.01, {0.0, 0.0}).pga_m_s2(), 0.0);
}

TEST(GroundMotion, ScaledMinusOneMirrorsTheRecord) {
  const std::vector<double> a = wiggly_samples(801);
  const GroundMotion g("rec", 0.01, a);
  const GroundMotion m = g.scaled(-1.0);
  EXPECT_EQ(m.name(), g.name());
  EXPECT_EQ(m.dt_s(), g.dt_s());
  ASSERT_EQ(m.size(), g.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(m.samples_m_s2()[i], -a[i]);
  EXPECT_EQ(m.pga_m_s2(), g.pga_m_s2());
  for (double t_s = -0.5; t_s < 9.0; t_s += 0.00731) {
    EXPECT_EQ(m.accel_m_s2(t_s), -g.accel_m_s2(t_s)) << "t = " << t_s;
  }
}

TEST(GroundMotion, ScaledMultipliesEverySample) {
  const std::vector<double> a = wiggly_samples(300);
  const GroundMotion g("rec", 0.02, a);
  const GroundMotion s = g.scaled(2.5);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(s.samples_m_s2()[i], 2.5 * a[i]);
  EXPECT_EQ(s.pga_m_s2(), 2.5 * g.pga_m_s2());
  EXPECT_EQ(g.scaled(0.0).pga_m_s2(), 0.0);
  // The original is untouched.
  EXPECT_EQ(g.samples_m_s2(), a);
}

TEST(GroundMotion, ScaledRejectsNonFiniteFactorAndOverflow) {
  const GroundMotion g("rec", 0.01, {1.0, -2.0});
  EXPECT_THROW((void)g.scaled(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW((void)g.scaled(std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW((void)g.scaled(1e308), std::invalid_argument);  // −2e308 overflows
}

}  // namespace
