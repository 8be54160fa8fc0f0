// Modelling uncertainty measured: the split of a pooled fragility's dispersion into the
// frames' record-to-record part and the parameters' part, against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "pcrf/analysis/fragility.hpp"
#include "pcrf/analysis/model_dispersion.hpp"

namespace {

using pcrf::analysis::Lognormal;

/// n values evenly spread over [−a, a] (mean 0), and their standard deviation (divisor n).
std::vector<double> spread(std::size_t n, double a, double& sd) {
  std::vector<double> z(n);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    z[i] = -a + 2.0 * a * static_cast<double>(i) / static_cast<double>(n - 1);
    sum2 += z[i] * z[i];
  }
  sd = std::sqrt(sum2 / static_cast<double>(n));
  return z;
}

TEST(ModelDispersion, SplitsALognormalMixtureIntoItsTwoKnownDispersions) {
  // Frame i's collapse intensities: exp(ln θ0 + β_m z_i + β_r u_j), z and u spread evenly with
  // mean 0. Each frame's MLE is then (θ0 exp(β_m z_i), β_r s_u); the pooled one has
  // β² = β_m² s_z² + β_r² s_u² (total variance), so β_model = β_medians = β_m s_z.
  const double theta0 = 1.2, beta_m = 0.3, beta_r = 0.45;
  double s_z = 0.0, s_u = 0.0;
  const auto z = spread(15, 1.6, s_z);
  const auto u = spread(41, 2.0, s_u);
  std::vector<Lognormal> frames;
  std::vector<double> all;
  for (double zi : z) {
    std::vector<double> frame;
    for (double uj : u) frame.push_back(theta0 * std::exp(beta_m * zi + beta_r * uj));
    const auto fit = pcrf::analysis::fit_censored(frame, {});
    ASSERT_TRUE(fit);
    EXPECT_NEAR(fit->median, theta0 * std::exp(beta_m * zi), 1e-8);
    EXPECT_NEAR(fit->beta, beta_r * s_u, 1e-8);
    frames.push_back(*fit);
    all.insert(all.end(), frame.begin(), frame.end());
  }
  const auto pooled = pcrf::analysis::fit_censored(all, {});
  ASSERT_TRUE(pooled);
  EXPECT_NEAR(pooled->beta, std::hypot(beta_m * s_z, beta_r * s_u), 1e-8);
  const auto d = pcrf::analysis::measured_dispersion(*pooled, frames);
  EXPECT_EQ(d.frames, 15u);
  EXPECT_NEAR(d.beta_rtr, beta_r * s_u, 1e-8);
  EXPECT_NEAR(d.beta_model, beta_m * s_z, 1e-7);
  EXPECT_NEAR(d.beta_medians, beta_m * s_z, 1e-12);
  // The totals of P-695 Eq. 7-5 with the modelling term measured or rated (B = 0.2, C = 0.35).
  EXPECT_NEAR(d.total_measured(0.2, 0.2), std::sqrt(pooled->beta * pooled->beta + 0.08), 1e-15);
  EXPECT_NEAR(d.total_rated(0.2, 0.2, 0.35), std::sqrt(beta_r * beta_r * s_u * s_u + 0.08 + 0.35 * 0.35), 1e-8);
}

TEST(ModelDispersion, IdenticalFramesAddNothingAndCensoringIsKeptApart) {
  // Identical frames: the pooled fit is each frame's, β_model is 0 (not the root of a
  // rounding error below 0).
  const Lognormal one{0.8, 0.4};
  const auto same = pcrf::analysis::measured_dispersion(one, {one, one, one});
  EXPECT_EQ(same.beta_model, 0.0);
  EXPECT_EQ(same.beta_medians, 0.0);
  EXPECT_NEAR(same.beta_rtr, 0.4, 1e-15);
  EXPECT_THROW(pcrf::analysis::measured_dispersion(one, {one}), std::invalid_argument);
  EXPECT_THROW(pcrf::analysis::measured_dispersion(one, {one, {0.8, 0.0}}), std::invalid_argument);

  // Drawn lognormal data, right-censored at a cap as an IDA's max_intensity censors it:
  // 300 frames with ln θ_i ~ N(0, 0.25²), 40 records each with β_RTR = 0.4. The censored
  // fits recover both parts (a fit that took the cap for a collapse would shrink them).
  std::mt19937_64 g(7);
  std::normal_distribution<double> normal;
  const double beta_m = 0.25, beta_r = 0.4, cap = 1.6;
  std::vector<Lognormal> frames;
  std::vector<double> observed, censored;
  for (int i = 0; i < 300; ++i) {
    const double log_median = beta_m * normal(g);
    std::vector<double> frame_observed, frame_censored;
    for (int j = 0; j < 40; ++j) {
      const double x = std::exp(log_median + beta_r * normal(g));
      (x < cap ? frame_observed : frame_censored).push_back(x < cap ? x : cap);
    }
    const auto fit = pcrf::analysis::fit_censored(frame_observed, frame_censored);
    ASSERT_TRUE(fit);
    frames.push_back(*fit);
    observed.insert(observed.end(), frame_observed.begin(), frame_observed.end());
    censored.insert(censored.end(), frame_censored.begin(), frame_censored.end());
  }
  ASSERT_GT(censored.size(), 1000u);  // about a tenth of the 12000 curves
  const auto pooled = pcrf::analysis::fit_censored(observed, censored);
  ASSERT_TRUE(pooled);
  const auto d = pcrf::analysis::measured_dispersion(*pooled, frames);
  // Standard errors: β_RTR over 300 × 40 values ~0.003; β_model from 300 medians ~0.012.
  EXPECT_NEAR(d.beta_rtr, beta_r, 0.015);
  EXPECT_NEAR(d.beta_model, beta_m, 0.04);
  EXPECT_NEAR(pooled->beta, std::hypot(beta_m, beta_r), 0.015);
}

}  // namespace
