// The terms of Eq. (31) are consistent with the energies they come from, the kinematics
// derivatives with the positions, and the two branches are odd mirrors of each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/record/ground_motion.hpp"

namespace pcrf {
namespace {

// A spread of frames around the basic model, including the corners of the grid.
std::vector<FrameParameters> frames() {
  std::vector<FrameParameters> out;
  out.push_back(FrameParameters{});
  FrameParameters p;
  p.kappa = 0.1; p.lambda = 1.0; p.tan_alpha = 0.05; p.lambda_h = 0.05; out.push_back(p);
  p = FrameParameters{};
  p.kappa = 10; p.lambda = 5.0; p.tan_alpha = 0.5; p.lambda_h = 0.45; out.push_back(p);
  p = FrameParameters{};
  p.pi_sigma_b = p.pi_sigma_c = p.pi_e_b = p.pi_e_c = 0.0; out.push_back(p);
  return out;
}

double central(auto f, double x, double h) { return (f(x + h) - f(x - h)) / (2 * h); }

class EomConsistency : public ::testing::TestWithParam<FrameParameters> {};

TEST_P(EomConsistency, KinematicDerivativesMatchFiniteDifferences) {
  const EquationOfMotion eom(make_frame(GetParam()));
  for (double th : {-0.001, -0.02, -0.1, -0.3}) {
    Configuration c;
    ASSERT_TRUE(eom.linkage().solve(th, c));
    auto t2 = [&](double x) { Configuration k; eom.linkage().solve(x, k); return k.theta2; };
    auto t3 = [&](double x) { Configuration k; eom.linkage().solve(x, k); return k.theta3; };
    auto d2 = [&](double x) { Configuration k; eom.linkage().solve(x, k); return k.d_theta2; };
    auto d3 = [&](double x) { Configuration k; eom.linkage().solve(x, k); return k.d_theta3; };
    EXPECT_NEAR(c.d_theta2, central(t2, th, 1e-6), 1e-7);
    EXPECT_NEAR(c.d_theta3, central(t3, th, 1e-6), 1e-7);
    EXPECT_NEAR(c.dd_theta2, central(d2, th, 1e-6), 1e-6);
    EXPECT_NEAR(c.dd_theta3, central(d3, th, 1e-6), 1e-6);
  }
}

TEST_P(EomConsistency, TermsAreDerivativesOfTheEnergies) {
  const EquationOfMotion eom(make_frame(GetParam()));
  for (double th : {-0.005, -0.05, -0.2}) {
    EomTerms t;
    ASSERT_TRUE(eom.terms(th, -1, t));
    // V(θ) = E(θ, 0); Gg + K = dV/dθ.
    auto V = [&](double x) { return eom.energy(x, 0.0, -1); };
    const double dV = central(V, th, 1e-6);
    EXPECT_NEAR(t.G * kGravity_m_s2 + t.K, dV, 1e-5 * (std::abs(dV) + 1e3));
    // T = ½ I θ̇²: I = 2 (E(θ,1) − E(θ,0)); J = ½ dI/dθ.
    auto I = [&](double x) { return 2.0 * (eom.energy(x, 1.0, -1) - eom.energy(x, 0.0, -1)); };
    EXPECT_NEAR(t.I, I(th), 1e-8 * t.I);
    EXPECT_NEAR(t.J, 0.5 * central(I, th, 1e-5), 1e-5 * t.I);
  }
}

TEST_P(EomConsistency, BranchesAreOddMirrors) {
  const EquationOfMotion eom(make_frame(GetParam()));
  for (double th : {0.0, 0.01, 0.1}) {
    for (double w : {-0.3, 0.0, 0.4}) {
      for (double a : {-3.0, 0.0, 5.0}) {
        double plus = 0, minus = 0;
        ASSERT_TRUE(eom.acceleration(th, w, a, +1, plus));
        ASSERT_TRUE(eom.acceleration(-th, -w, -a, -1, minus));
        EXPECT_NEAR(plus, -minus, 1e-12 * (1 + std::abs(plus)));
      }
    }
    EXPECT_NEAR(eom.energy(th, 0.2, +1), eom.energy(-th, -0.2, -1), 1e-9);
  }
}

TEST_P(EomConsistency, RestAccelerationOpensOnlyAboveTheThreshold) {
  const EquationOfMotion eom(make_frame(GetParam()));
  const double a_up = eom.uplift_threshold_m_s2();
  EXPECT_GE(a_up, eom.lambda_g() * kGravity_m_s2 - 1e-12);
  EXPECT_LT(eom.rest_acceleration(1.001 * a_up, -1), 0.0);   // opens into θ₁ < 0
  EXPECT_GT(eom.rest_acceleration(0.999 * a_up, -1), 0.0);   // held closed
  EXPECT_GT(eom.rest_acceleration(-1.001 * a_up, +1), 0.0);  // opens into θ₁ > 0
  EXPECT_LT(eom.rest_acceleration(-0.999 * a_up, +1), 0.0);
}

TEST_P(EomConsistency, PeakStrainsAreTheMaximaOverTheVisitedRange) {
  // Elongations grow with |θ₁| over the physical range, but not always up to the closing
  // limit (slender, light-beam frames): the peak is a maximum over [0, |θ|max].
  const EquationOfMotion eom(make_frame(GetParam()));
  const double limit = eom.closing_limit_rad();
  for (double frac : {0.01, 0.3, 0.9}) {
    const double up_to = frac * limit;
    double brute_c = 0, brute_b = 0;
    for (int i = 0; i <= 4000; ++i) {
      const TendonState s = eom.tendons(-up_to * i / 4000.0, -1);
      brute_c = std::max(brute_c, s.strain_column_max());
      brute_b = std::max(brute_b, s.strain_beam);
    }
    const TendonState peak = eom.peak_tendon_strains(up_to);
    // A dense scan can only underestimate a maximum; near the closing limit the strain
    // varies fast, so allow the scan's sampling error above it.
    EXPECT_GE(peak.strain_column_max(), brute_c * (1 - 1e-12));
    EXPECT_LE(peak.strain_column_max(), brute_c * (1 + 1e-4));
    EXPECT_GE(peak.strain_beam, brute_b * (1 - 1e-12));
    EXPECT_LE(peak.strain_beam, brute_b * (1 + 1e-4));
  }
  // Small rotations: monotone, so the peak is at the end of the range.
  const TendonState at_end = eom.tendons(-0.01, -1);
  EXPECT_DOUBLE_EQ(eom.peak_tendon_strains(0.01).strain_beam, at_end.strain_beam);
}

/// Test names for the frames() above (readable ctest names instead of parameter bytes).
std::string frame_name(const ::testing::TestParamInfo<FrameParameters>& param_info) {
  static const char* const kNames[] = {"basic", "slender_light_low_beam", "stocky_heavy_deep_beam", "no_tendons"};
  return kNames[param_info.index];
}

INSTANTIATE_TEST_SUITE_P(Frames, EomConsistency, ::testing::ValuesIn(frames()), frame_name);

TEST(FrameValidation, ImpossibleGeometryNamesTheParameter) {
  FrameParameters p;
  p.lambda_h = 1.2;
  EXPECT_THROW(
      {
        try {
          make_frame(p);
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("lambda_h"), std::string::npos) << e.what();
          throw;
        }
      },
      std::invalid_argument);
  p = FrameParameters{};
  p.lambda = 0.1;  // columns overlap
  EXPECT_THROW(make_frame(p), std::invalid_argument);
  p = FrameParameters{};
  p.kappa = -1;
  EXPECT_THROW(make_frame(p), std::invalid_argument);
  p = FrameParameters{};
  p.pi_sigma_c = std::nan("");
  EXPECT_THROW(make_frame(p), std::invalid_argument);
}

}  // namespace
}  // namespace pcrf
