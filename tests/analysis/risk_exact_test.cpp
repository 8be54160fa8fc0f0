// The collapse-rate integral is exact per segment of the hazard curve: against Cornell's closed
// form to rounding, against an independent quadrature on curves of every steepness, and on
// segments so steep (two points 1e-6 apart, a decade of rate between them) that a grid in
// ln x cannot resolve them (issue 41: "the collapse-rate integral did not settle").
#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include "pcrf/analysis/risk.hpp"

namespace {

using pcrf::analysis::Lognormal;
using pcrf::risk::HazardCurve;
using pcrf::risk::Tail;

/// An independent reference: ∫ Φ(ln(x/θ)/β) k λ(x) du on each segment [x_i, x_{i+1}] (u = ln x)
/// by adaptive Gauss–Kronrod (61 points, to 1e-13, at most 12 halvings: smooth fragilities,
/// β ≥ 0.05), in long double, plus the cut-off's point
/// mass λ_n P(x_n). Cut-off curves only (the power-law tail is checked against Cornell).
double reference_rate(const HazardCurve& h, const Lognormal& f) {
  const auto& x = h.intensities();
  const auto& r = h.rates_per_yr();
  long double total = 0.0L;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const long double ua = std::log(static_cast<long double>(x[i])), ub = std::log(static_cast<long double>(x[i + 1]));
    const long double k = -std::log(static_cast<long double>(r[i + 1]) / r[i]) / (ub - ua);
    const long double lnm = std::log(static_cast<long double>(f.median)), beta = f.beta;
    auto g = [&](long double u) {
      const long double p = 0.5L * std::erfc(-(u - lnm) / beta / std::sqrt(2.0L));
      return p * k * r[i] * std::exp(-k * (u - ua));
    };
    total += boost::math::quadrature::gauss_kronrod<long double, 61>::integrate(g, ua, ub, 12, 1e-13L);
  }
  total += static_cast<long double>(r.back()) * 0.5L * std::erfc(-std::log(static_cast<long double>(x.back()) / f.median) /
                                                                   f.beta / std::sqrt(2.0L));
  return static_cast<double>(total);
}

TEST(RiskExact, PowerLawHazardGivesCornellsClosedFormToRounding) {
  const double k0 = 4e-4;
  for (const auto& [k, theta, beta] : std::vector<std::tuple<double, double, double>>{
           {2.5, 1.2, 0.5}, {1.5, 0.4, 0.3}, {3.5, 2.0, 0.8}, {2.0, 0.8, 0.1}, {3.0, 1.0, 0.05}, {6.0, 0.9, 1.2}}) {
    // The integrand P(C | x) k λ(x) in z = ln(x/θ)/β peaks at z = −kβ: the curve starts 12
    // below it, so that what its flat start leaves out is below 1e-30 of λ_c.
    const HazardCurve hazard =
        pcrf::risk::power_law_curve(k0, k, theta * std::exp(-beta * (k * beta + 12.0)), 3.0, 41, Tail::kPowerLaw);
    const Lognormal f{theta, beta};
    const double exact = pcrf::risk::cornell_collapse_rate(k0, k, f);
    EXPECT_NEAR(pcrf::risk::collapse_rate(hazard, f).lambda_per_yr / exact, 1.0, 1e-11)
        << "k " << k << " theta " << theta << " beta " << beta;
    // The same with bin edges splitting the segments: the pieces still add up to it.
    EXPECT_NEAR(pcrf::risk::collapse_rate(hazard, f, {0.01, 0.1, theta, 1.7}).lambda_per_yr / exact, 1.0, 1e-11);
  }
}

TEST(RiskExact, AgreesWithAnIndependentQuadratureOnRandomCurves) {
  std::mt19937_64 g(41);
  std::uniform_real_distribution<double> step(0.02, 1.0), fall(0.05, 3.0), median(-2.0, 1.0), spread(0.05, 1.2);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<double> x{0.01}, r{0.5};
    for (int i = 0; i < 12; ++i) {
      x.push_back(x.back() * std::exp(step(g)));
      r.push_back(r.back() * std::exp(-fall(g)));
    }
    const HazardCurve hazard(x, r, Tail::kCutOff);
    const Lognormal f{std::exp(median(g)), spread(g)};
    const double reference = reference_rate(hazard, f);
    ASSERT_GT(reference, 0.0);
    EXPECT_NEAR(pcrf::risk::collapse_rate(hazard, f).lambda_per_yr / reference, 1.0, 1e-10)
        << "trial " << trial << " theta " << f.median << " beta " << f.beta;
  }
}

// Issue 41: two hazard points 1e-6 apart with a decade of rate between them (k ≈ 2.3e6) made
// the Simpson grid give up with an internal error. Over so short a segment P(C | x) is constant
// to 1e-6, so its part is P(x) times the fall of the rate across it.
TEST(RiskExact, SteepSegmentHasItsExactPart) {
  const double a = 0.5, b = 0.5 * (1.0 + 1e-6);
  const HazardCurve hazard({0.1, a, b, 2.0}, {1e-2, 1e-3, 1e-4, 1e-6}, Tail::kCutOff);
  for (const Lognormal f : {Lognormal{0.5, 0.4}, Lognormal{3.0, 0.3}, Lognormal{0.05, 0.2}, Lognormal{0.5, 1e-3}}) {
    const auto result = pcrf::risk::collapse_rate(hazard, f);
    ASSERT_TRUE(std::isfinite(result.lambda_per_yr));
    const double p = pcrf::analysis::normal_cdf(std::log(a / f.median) / f.beta);
    const double p_b = pcrf::analysis::normal_cdf(std::log(b / f.median) / f.beta);
    double steep = 0.0;
    for (const auto& piece : result.pieces)
      if (piece.low == a) steep = piece.rate_per_yr;
    // Between P(a) and P(b) times the fall: bounds that are exact.
    EXPECT_GE(steep, p * 9e-4 * (1.0 - 1e-12)) << f.median << " " << f.beta;
    EXPECT_LE(steep, p_b * 9e-4 * (1.0 + 1e-12)) << f.median << " " << f.beta;
    // The whole curve against the quadrature (a fragility smooth enough for it).
    if (f.beta >= 0.05) {
      EXPECT_NEAR(result.lambda_per_yr / reference_rate(hazard, f), 1.0, 1e-9) << f.median << " " << f.beta;
    }
  }
  // Steeper still: a factor of 1e6 in rate over 1e-12 of intensity (k ≈ 1.4e13).
  const HazardCurve cliff({0.1, 1.0, 1.0 + 1e-12, 2.0}, {1e-1, 1e-2, 1e-8, 1e-9}, Tail::kPowerLaw);
  const auto result = pcrf::risk::collapse_rate(cliff, {1.0, 0.5});
  ASSERT_TRUE(std::isfinite(result.lambda_per_yr));
  double steep = 0.0;
  for (const auto& piece : result.pieces)
    if (piece.low == 1.0) steep = piece.rate_per_yr;
  EXPECT_NEAR(steep / (0.5 * (1e-2 - 1e-8)), 1.0, 1e-9);  // P(C | θ) = ½
}

// Each piece lies within [P(a), P(b)] times the rate's fall across it, whatever the segment's
// steepness and wherever the fragility's median lies (deep in either tail).
TEST(RiskExact, EveryPieceLiesWithinItsBounds) {
  for (double median : {1e-3, 0.05, 0.5, 3.0, 1e3})
    for (double beta : {0.01, 0.3, 2.0}) {
      const HazardCurve hazard({0.01, 0.1, 0.1000001, 0.3, 1.0, 1.0 + 1e-9, 5.0},
                               {3.0, 0.1, 1e-2, 1e-3, 1e-4, 1e-7, 1e-8}, Tail::kPowerLaw);
      const Lognormal f{median, beta};
      const auto result = pcrf::risk::collapse_rate(hazard, f, {0.05, 0.2, 2.0});
      double sum = 0.0;
      for (const auto& piece : result.pieces) {
        const double pa = pcrf::analysis::normal_cdf(std::log(piece.low / median) / beta);
        const double pb = pcrf::analysis::normal_cdf(std::log(piece.high / median) / beta);
        const double fall = hazard.rate_per_yr(piece.low) - (piece.high > piece.low ? hazard.rate_per_yr(piece.high) : 0.0);
        EXPECT_GE(piece.rate_per_yr, pa * fall * (1.0 - 1e-9) - 1e-300) << median << " " << beta << " at " << piece.low;
        EXPECT_LE(piece.rate_per_yr, pb * fall * (1.0 + 1e-9) + 1e-300) << median << " " << beta << " at " << piece.low;
        sum += piece.rate_per_yr;
      }
      EXPECT_TRUE(std::isfinite(result.lambda_per_yr));
      EXPECT_NEAR(sum, result.lambda_per_yr, 1e-14 * result.lambda_per_yr);
      EXPECT_LE(result.lambda_per_yr, 3.0 * (1.0 + 1e-12));  // never more than the rate of any shaking counted
    }
}

}  // namespace
