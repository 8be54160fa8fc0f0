// The annual collapse rate against closed forms (Cornell et al. 2002), the risk-targeted
// intensity against its closed form under a power-law hazard, and a textbook example.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <utility>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "pcrf/analysis/risk.hpp"

namespace {

using pcrf::analysis::Lognormal;
using pcrf::risk::HazardCurve;
using pcrf::risk::Tail;

TEST(Risk, HazardCurveInterpolatesLogLogAndExtendsItsTailAsAsked) {
  const HazardCurve power = pcrf::risk::power_law_curve(2e-4, 2.5, 0.05, 2.0, 5, Tail::kPowerLaw);
  for (double x : {0.05, 0.07, 0.3, 1.9, 2.0, 3.5, 10.0})
    EXPECT_NEAR(power.rate_per_yr(x) / (2e-4 * std::pow(x, -2.5)), 1.0, 1e-12) << x;
  EXPECT_NEAR(power.slope(5.0), 2.5, 1e-12);
  EXPECT_NEAR(power.intensity_at_rate(2e-4 * std::pow(0.4, -2.5)), 0.4, 1e-12);
  EXPECT_NEAR(power.intensity_at_rate(2e-4 * std::pow(7.0, -2.5)), 7.0, 1e-12);  // on the extension
  EXPECT_EQ(power.rate_per_yr(0.01), power.rate_per_yr(0.05));                      // flat below the first point
  EXPECT_TRUE(std::isnan(power.intensity_at_rate(1.0)));                            // above the first rate

  const HazardCurve cut = pcrf::risk::power_law_curve(2e-4, 2.5, 0.05, 2.0, 5, Tail::kCutOff);
  EXPECT_EQ(cut.rate_per_yr(2.0001), 0.0);
  EXPECT_GT(cut.rate_per_yr(2.0), 0.0);
  EXPECT_TRUE(std::isnan(cut.intensity_at_rate(1e-9)));
  EXPECT_EQ(pcrf::risk::parse_tail("cutoff"), Tail::kCutOff);
  EXPECT_THROW(pcrf::risk::parse_tail("linear"), std::invalid_argument);
}

TEST(Risk, HazardCurveRefusesARateThatDoesNotDecreaseOrIsNotPositive) {
  EXPECT_THROW(HazardCurve({0.1, 0.2, 0.3}, {1e-2, 1e-2, 1e-3}, Tail::kCutOff), std::invalid_argument);
  EXPECT_THROW(HazardCurve({0.1, 0.2, 0.3}, {1e-2, 2e-2, 1e-3}, Tail::kCutOff), std::invalid_argument);
  EXPECT_THROW(HazardCurve({0.1, 0.2}, {1e-2, 0.0}, Tail::kCutOff), std::invalid_argument);
  EXPECT_THROW(HazardCurve({0.1, 0.2}, {1e-2, -1e-3}, Tail::kCutOff), std::invalid_argument);
  EXPECT_THROW(HazardCurve({0.2, 0.1}, {1e-2, 1e-3}, Tail::kCutOff), std::invalid_argument);
  EXPECT_THROW(HazardCurve({0.0, 0.1}, {1e-2, 1e-3}, Tail::kCutOff), std::invalid_argument);
  EXPECT_THROW(HazardCurve({0.1}, {1e-2}, Tail::kCutOff), std::invalid_argument);
  try {
    HazardCurve({0.1, 0.2, 0.3}, {1e-2, 1e-3, 1e-3}, Tail::kCutOff);
    FAIL() << "accepted a flat rate";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("point 2"), std::string::npos) << e.what();
  }
}

// Cornell, Jalayer, Hamburger & Foutch (2002), J. Struct. Eng. 128(4), Eq. 11 with no demand
// term: a power-law hazard λ(x) = k₀ x^−k and a lognormal capacity (θ, β) give
// λ_c = k₀ θ^−k exp(k² β² / 2).
TEST(Risk, CollapseRateMatchesCornellClosedForm) {
  const double k0 = 4e-4;
  for (const auto& [k, theta, beta] : std::vector<std::tuple<double, double, double>>{
           {2.5, 1.2, 0.5}, {1.5, 0.4, 0.3}, {3.5, 2.0, 0.8}, {2.0, 0.8, 0.1}, {3.0, 1.0, 0.05}}) {
    const HazardCurve hazard = pcrf::risk::power_law_curve(k0, k, 1e-5, 3.0, 41, Tail::kPowerLaw);
    const Lognormal f{theta, beta};
    const auto result = pcrf::risk::collapse_rate(hazard, f);
    const double exact = pcrf::risk::cornell_collapse_rate(k0, k, f);
    EXPECT_NEAR(result.lambda_per_yr / exact, 1.0, 1e-4) << "k " << k << " theta " << theta << " beta " << beta;
    EXPECT_LT(result.relative_change, 1e-7);  // settled, not stopped at the step limit
    double sum = 0.0;
    for (const auto& p : result.pieces) sum += p.rate_per_yr;
    EXPECT_NEAR(sum, result.lambda_per_yr, 1e-12 * exact);
    EXPECT_LT(result.fragility_at_lowest, 1e-10);
  }
}

TEST(Risk, CutOffCountsTheLastRateAtTheLastIntensityABound) {
  const double k0 = 4e-4, k = 2.5;
  const Lognormal f{1.2, 0.5};
  const auto cut = pcrf::risk::collapse_rate(pcrf::risk::power_law_curve(k0, k, 1e-4, 1.5, 31, Tail::kCutOff), f);
  const auto power = pcrf::risk::collapse_rate(pcrf::risk::power_law_curve(k0, k, 1e-4, 1.5, 31, Tail::kPowerLaw), f);
  EXPECT_LT(cut.lambda_per_yr, power.lambda_per_yr);  // P(C | x) grows beyond the last point
  // The cut-off's mass: λ(1.5) P(C | 1.5) at the last point.
  const double mass = k0 * std::pow(1.5, -k) * pcrf::analysis::normal_cdf(std::log(1.5 / 1.2) / 0.5);
  EXPECT_NEAR(cut.beyond_last_per_yr / mass, 1.0, 1e-12);
  EXPECT_GT(power.beyond_last_per_yr, cut.beyond_last_per_yr);
  // Below the last point the two agree.
  EXPECT_NEAR(cut.rate_below(1.5) / power.rate_below(1.5), 1.0, 1e-7);  // each settled to 1e-7
  EXPECT_LT(cut.relative_change, 1e-7);  // the integrand keeps its value at the cut-off point
}

// A fragility that starts at zero (a frame that cannot collapse at the curve's intensities;
// an empirical fraction of 0 at the first stripes) gives a rate of 0 or a tiny one, never NaN.
TEST(Risk, FragilityStartingAtZeroGivesAFiniteRate) {
  const HazardCurve hazard({0.1, 0.2, 0.4, 0.8}, {1e-2, 2e-3, 3e-4, 2e-5}, Tail::kCutOff);
  const auto far = pcrf::risk::collapse_rate(hazard, {1e6, 0.3});
  EXPECT_TRUE(std::isfinite(far.lambda_per_yr));
  EXPECT_EQ(far.lambda_per_yr, 0.0);
  const auto steps = pcrf::risk::collapse_rate_steps(hazard, {0.1, 0.2, 0.4}, {0.0, 0.0, 0.0});
  EXPECT_EQ(steps.lambda_per_yr, 0.0);
  const auto rising = pcrf::risk::collapse_rate_steps(hazard, {0.1, 0.2, 0.4}, {0.0, 0.0, 0.5});
  EXPECT_DOUBLE_EQ(rising.lambda_per_yr, 0.5 * 3e-4);  // 0.5 (λ(0.4) − λ(0.8)) + 0.5 λ(0.8)
  EXPECT_EQ(pcrf::risk::probability_in_years(0.0, 50.0), 0.0);
  EXPECT_THROW(pcrf::risk::collapse_rate_steps(hazard, {0.1, 0.2}, {0.0, 1.5}), std::invalid_argument);
  EXPECT_THROW(pcrf::risk::collapse_rate(hazard, {0.0, 0.3}), std::invalid_argument);
}

// Baker, Bradley & Stafford (2021), "Seismic Hazard and Risk Analysis", Cambridge University
// Press, Chapter 9, the discrete exceedance example (Eq. 9.x, "risk_exceedance_probability_
// curve_discrete"; the book's supporting calculation chapter9/risk_metrics.m in
// github.com/bakerjw/seismic-hazard-and-risk): IM = 0.1, 0.2, 0.3 g with rates of exceedance
// 0.06, 0.016, 0.003 /yr and P(failure | IM) = 0.1, 0.4, 0.6 give λ(F) = Σ P_i |Δλ_i| = 0.0114
// /yr, and in one year 1 − exp(−0.0114) = 0.0113. The discrete sum is the integral of the step
// fragility P = P_i from IM_i on with the curve cut off beyond 0.3 g.
TEST(Risk, TextbookDiscreteExampleGivesItsRate) {
  const HazardCurve hazard({0.1, 0.2, 0.3}, {0.06, 0.016, 0.003}, Tail::kCutOff);
  const auto result = pcrf::risk::collapse_rate_steps(hazard, {0.1, 0.2, 0.3}, {0.1, 0.4, 0.6});
  EXPECT_NEAR(result.lambda_per_yr, 0.0114, 0.00005);
  EXPECT_NEAR(pcrf::risk::probability_in_years(result.lambda_per_yr, 1.0), 0.0113, 0.00005);
  // Its rate deaggregated as the book's table does, P_i |Δλ_i| per IM: 0.0044, 0.0052 and 0.0018 /yr.
  ASSERT_EQ(result.pieces.size(), 3u);
  EXPECT_NEAR(result.pieces[0].rate_per_yr, 0.0044, 1e-15);
  EXPECT_NEAR(result.pieces[1].rate_per_yr, 0.0052, 1e-15);
  EXPECT_NEAR(result.pieces[2].rate_per_yr, 0.0018, 1e-15);
  // And over bins, the bin edges splitting the pieces: [0.1, 0.15) holds half of the first
  // piece in ln-rate terms, λ(0.1) − λ(0.15), times 0.1.
  const auto split = pcrf::risk::collapse_rate_steps(hazard, {0.1, 0.2, 0.3}, {0.1, 0.4, 0.6}, {0.15, 0.25});
  EXPECT_NEAR(split.lambda_per_yr, result.lambda_per_yr, 1e-15);
  const auto bins = pcrf::risk::deaggregate(split.pieces, {0.1, 0.15, 0.2, 0.3, 1.0});
  EXPECT_NEAR(bins[0], 0.1 * (0.06 - hazard.rate_per_yr(0.15)), 1e-15);
  EXPECT_NEAR(bins[1], 0.1 * (hazard.rate_per_yr(0.15) - 0.016), 1e-15);
  EXPECT_NEAR(bins[3], 0.0018, 1e-15);
}

// Luco et al. (2007): the intensity whose generic fragility (β, 10 % at it) gives 1 % in 50
// years. Under a power law, θ = (k₀ exp(k² β² / 2) / λ_t)^{1/k} and x_RT = θ exp(Φ⁻¹(0.1) β).
TEST(Risk, RiskTargetedIntensityMatchesItsClosedFormUnderAPowerLaw) {
  for (const auto& [k0, k, beta] : std::vector<std::tuple<double, double, double>>{
           {4e-4, 2.5, 0.6}, {1e-4, 1.8, 0.6}, {2e-3, 3.2, 0.8}}) {
    const HazardCurve hazard = pcrf::risk::power_law_curve(k0, k, 1e-5, 2.0, 41, Tail::kPowerLaw);
    pcrf::risk::RiskTarget target;
    target.beta = beta;
    const double numeric = pcrf::risk::risk_targeted_intensity(hazard, target);
    const double exact = pcrf::risk::cornell_risk_targeted_intensity(k0, k, target);
    EXPECT_NEAR(numeric / exact, 1.0, 1e-4) << k0 << " " << k << " " << beta;
    // At that intensity the generic fragility is 10 % and its λ_c the target's rate.
    const auto f = target.fragility_at(numeric);
    EXPECT_NEAR(pcrf::analysis::normal_cdf(std::log(numeric / f.median) / f.beta), 0.1, 1e-12);
    EXPECT_NEAR(pcrf::risk::collapse_rate(hazard, f).lambda_per_yr / target.rate_per_yr(), 1.0, 1e-6);
  }
  EXPECT_NEAR(pcrf::risk::RiskTarget{}.rate_per_yr(), -std::log(0.99) / 50.0, 1e-18);
}

TEST(Risk, HazardFactorIsWhereTheFrameMeetsTheTarget) {
  const double k0 = 4e-4, k = 2.5;
  const HazardCurve hazard = pcrf::risk::power_law_curve(k0, k, 1e-5, 2.0, 41, Tail::kPowerLaw);
  const Lognormal f{1.5, 0.4};
  const pcrf::risk::RiskTarget target;
  // λ_c(θ / s) = k₀ (θ / s)^−k exp(k² β² / 2) = λ_t.
  const double exact = std::pow(target.rate_per_yr() / pcrf::risk::cornell_collapse_rate(k0, k, f), 1.0 / k);
  EXPECT_NEAR(pcrf::risk::hazard_factor_at_target(hazard, f, target) / exact, 1.0, 1e-4);
}

/// Collapse intensities at the lognormal's (i − ½)/n quantiles: a sample with no scatter of its own.
std::vector<double> quantile_sample(const Lognormal& f, std::size_t n) {
  std::vector<double> x;
  for (std::size_t i = 0; i < n; ++i) {
    const double p = (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    double lo = -10.0, hi = 10.0;  // Φ⁻¹(p) by bisection
    for (int k = 0; k < 100; ++k) (pcrf::analysis::normal_cdf(0.5 * (lo + hi)) < p ? lo : hi) = 0.5 * (lo + hi);
    x.push_back(f.median * std::exp(f.beta * 0.5 * (lo + hi)));
  }
  return x;
}

TEST(Risk, BootstrapIntervalOfTheRateNarrowsAsOneOverRootN) {
  const HazardCurve hazard = pcrf::risk::power_law_curve(4e-4, 2.5, 1e-3, 3.0, 21, Tail::kPowerLaw);
  auto interval = [&](std::size_t n) {
    const auto sample = quantile_sample({1.0, 0.4}, n);
    const auto fit = pcrf::analysis::fit_censored(sample, {});
    const auto rate = pcrf::risk::collapse_rate(hazard, *fit).lambda_per_yr;
    const auto result = pcrf::risk::rate_interval(hazard, [&](std::mt19937_64& g) {
      std::uniform_int_distribution<std::size_t> pick(0, n - 1);
      std::vector<double> drawn;
      for (std::size_t i = 0; i < n; ++i) drawn.push_back(sample[pick(g)]);
      return pcrf::analysis::fit_censored(drawn, {});
    }, 400);
    EXPECT_LT(result.low, rate);
    EXPECT_GT(result.high, rate);
    EXPECT_EQ(result.fits, 400u);
    return std::make_pair(rate, result);
  };
  const auto [rate20, i20] = interval(20);
  const auto [rate80, i80] = interval(80);
  const double ratio = (i20.high - i20.low) / rate20 / ((i80.high - i80.low) / rate80);
  EXPECT_GT(ratio, 1.5);  // 2 for a width ∝ 1/√n
  EXPECT_LT(ratio, 2.7);
  // The size for ±10 %: more than the 20 curves used, and about what 80 curves' width implies.
  const double need20 = i20.size_for(rate20, 20, 0.1), need80 = i80.size_for(rate80, 80, 0.1);
  EXPECT_GT(need20, 20.0);
  EXPECT_NEAR(need20 / need80, 1.0, 0.5);
  // A refit that never changes gives a point.
  const auto fixed = pcrf::risk::rate_interval(hazard, [](std::mt19937_64&) { return std::optional<Lognormal>(Lognormal{1.0, 0.4}); }, 10);
  EXPECT_DOUBLE_EQ(fixed.low, fixed.high);
}

TEST(Risk, EmpiricalIdaStepsCountEveryCurve) {
  std::vector<double> x, p;
  pcrf::risk::empirical_ida_steps({0.5, 0.3, 0.5, 0.9}, 5, x, p);
  EXPECT_EQ(x, (std::vector<double>{0.3, 0.5, 0.9}));
  EXPECT_EQ(p, (std::vector<double>{0.2, 0.6, 0.8}));
}

}  // namespace
