// RotD50 and RotD100 (Boore 2010) against a motion along one direction and against an
// independent computation that rotates the records themselves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/rotd.hpp"
#include "pcrf/record/synthetic.hpp"
#include "support/test_support.hpp"

namespace {

using pcrf::GroundMotion;
using pcrf::HorizontalPair;
using pcrf::IntensityMeasure;
using pcrf::IntensitySpec;

double radians(double deg) { return deg * std::numbers::pi / 180.0; }

GroundMotion stochastic(std::uint64_t seed) {
  pcrf::StochasticSpec s;
  s.seed = seed;
  s.duration_s = 8.0;
  return pcrf::make_stochastic(s);
}

std::vector<IntensitySpec> measures() {
  return {{IntensityMeasure::kPga, 0.0, 0.05}, {IntensityMeasure::kPgv, 0.0, 0.05},
          {IntensityMeasure::kSa, 0.2, 0.05}, {IntensityMeasure::kSa, 1.0, 0.05}};
}

TEST(RotD, AMotionAlongOneDirectionHasRotD100ItsPeakAndRotD50ItsPeakTimesCos45) {
  const GroundMotion a = stochastic(5);
  for (const auto& [az1, az2] : std::vector<std::pair<double, double>>{{0, 90}, {140, 230}, {260, 345}}) {
    // Along ψ = az₁ + 30° (on the 1° grid): the components are a cos(ψ − az).
    const double psi = az1 + 30.0;
    const GroundMotion h1 = a.scaled(std::cos(radians(psi - az1))), h2 = a.scaled(std::cos(radians(psi - az2)));
    for (const IntensitySpec& spec : measures()) {
      SCOPED_TRACE(std::to_string(az2 - az1) + "° apart, " + pcrf::to_string(spec.measure) + " " +
                   std::to_string(spec.period_s));
      const double peak = pcrf::intensity_of(a, spec);
      const pcrf::RotD r = pcrf::rotd(HorizontalPair{h1, az1, h2, az2}, spec);
      EXPECT_NEAR(r.rotd100, peak, 1e-9 * peak);
      EXPECT_NEAR(r.rotd50, peak * std::cos(radians(45.0)), 1e-9 * peak);
    }
  }
}

/// Brute force: rotate the records to every azimuth and measure each rotated record alone.
pcrf::RotD brute_force(const HorizontalPair& pair, const IntensitySpec& spec) {
  std::vector<double> peaks;
  for (int k = 0; k < 180; ++k) peaks.push_back(pcrf::intensity_of(pcrf::project(pair, pair.az1_deg + k), spec));
  std::sort(peaks.begin(), peaks.end());
  return {0.5 * (peaks[89] + peaks[90]), peaks.back()};
}

void expect_brute_force(const HorizontalPair& pair) {
  for (const IntensitySpec& spec : measures()) {
    SCOPED_TRACE(pcrf::to_string(spec.measure) + " " + std::to_string(spec.period_s));
    const pcrf::RotD fast = pcrf::rotd(pair, spec), slow = brute_force(pair, spec);
    EXPECT_NEAR(fast.rotd50, slow.rotd50, 1e-6 * slow.rotd50);
    EXPECT_NEAR(fast.rotd100, slow.rotd100, 1e-6 * slow.rotd100);
    EXPECT_LT(fast.rotd50, fast.rotd100);
  }
}

TEST(RotD, AgreesWithRotatingTheRecordsThemselves) {
  const GroundMotion h1 = stochastic(6), h2 = stochastic(7);
  expect_brute_force(HorizontalPair{h1, 0.0, h2, 90.0});
  expect_brute_force(HorizontalPair{h1, 260.0, h2, 345.0});
}

TEST(RotD, AgreesWithRotatingTheRecordsOfLucerne) {
  PCRF_REQUIRE_RECORDS(records);
  // RSN879 Landers, Lucerne: LCN260 and LCN345, 85° apart.
  const auto dir = records / "nearfault_sehyeon9121";
  const GroundMotion h1 = pcrf::read_at2(dir / "RSN879_LANDERS_LCN260.AT2");
  const GroundMotion h2 = pcrf::read_at2(dir / "RSN879_LANDERS_LCN345.AT2");
  expect_brute_force(HorizontalPair{h1, 260.0, h2, 345.0});
}

}  // namespace
