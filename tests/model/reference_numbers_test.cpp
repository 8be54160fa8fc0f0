// MODEL.md's reference numbers for the basic model (Table 1, corrected), to 1e-6 relative.
#include <gtest/gtest.h>

#include <cmath>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/four_bar.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/model/impact.hpp"

namespace pcrf {
namespace {

// |actual − expected| ≤ 1e-6·|expected|, where `expected` is printed to the digits
// MODEL.md gives; the tolerance also admits the rounding of the printed value.
void expect_rel(double actual, double expected, int printed_digits_after_point) {
  const double rounding = 0.5 * std::pow(10.0, -printed_digits_after_point);
  EXPECT_NEAR(actual, expected, std::max(1e-6 * std::abs(expected), rounding))
      << "expected " << expected;
}

class BasicModel : public ::testing::Test {
 protected:
  Frame frame = basic_frame();
  EquationOfMotion eom{frame};
};

TEST_F(BasicModel, DimensionlessParametersMatchSection7) {
  const FrameParameters p = frame.parameters();
  EXPECT_DOUBLE_EQ(p.kappa, 1.8);
  EXPECT_DOUBLE_EQ(p.lambda, 2.0);
  EXPECT_DOUBLE_EQ(p.tan_alpha, 0.2);
  EXPECT_DOUBLE_EQ(p.lambda_h, 0.2);
  EXPECT_NEAR(p.pi_sigma_b, 4.13, 0.005);
  EXPECT_NEAR(p.pi_sigma_c, 6.61, 0.005);
  EXPECT_NEAR(p.pi_e_b, 2684.1, 0.05);
  EXPECT_NEAR(p.pi_e_c, 4294.6, 0.05);
}

TEST_F(BasicModel, FromParametersEqualsFromDimensions) {
  const Frame g = make_frame(FrameParameters{});
  EXPECT_NEAR(g.b, frame.b, 1e-12);
  EXPECT_NEAR(g.m_b, frame.m_b, 1e-9);
  EXPECT_NEAR(g.P_c0, frame.P_c0, 1e-6);
  EXPECT_NEAR(g.EA_b, frame.EA_b, 1e-2);
}

TEST_F(BasicModel, KinematicDerivativesAtRest) {
  Configuration c;
  ASSERT_TRUE(eom.linkage().solve(0.0, c));
  EXPECT_NEAR(c.theta2, 0.0, 1e-14);
  EXPECT_NEAR(c.theta3, 0.0, 1e-14);
  EXPECT_NEAR(c.d_theta3, 7.0 / 9.0, 1e-12);
  EXPECT_NEAR(c.d_theta2, -1.0 / 9.0, 1e-12);
  expect_rel(c.dd_theta3, -0.244170, 6);
  expect_rel(c.dd_theta2, -0.109739, 6);
}

TEST_F(BasicModel, TermsAtRest) {
  EomTerms t;
  ASSERT_TRUE(eom.terms(0.0, -1, t));
  expect_rel(t.I, 39673.34, 2);
  expect_rel(2.0 * t.J, -11605.81, 2);
  expect_rel(t.G, -2782.08, 2);
  expect_rel(t.K, -152600.0, 1);
  expect_rel(t.S, -17953.92, 2);
}

TEST_F(BasicModel, TermsAtMinusOneHundredth) {
  EomTerms t;
  ASSERT_TRUE(eom.terms(-0.01, -1, t));
  expect_rel(t.I, 39788.51, 2);
  expect_rel(t.G, -2622.806, 3);
  expect_rel(t.K, -242631.2, 1);
  expect_rel(t.S, -18006.03, 2);
}

TEST_F(BasicModel, UpliftCoefficients) {
  expect_rel(eom.lambda_g(), 0.154957, 6);
  expect_rel(eom.uplift_threshold_m_s2() / 9.81, 1.021372, 6);
}

TEST_F(BasicModel, Restitution) {
  expect_rel(restitution_momentum(eom), 0.950472, 6);
}

TEST_F(BasicModel, MechanismStopsClosingWhereBeamAndRightColumnAlign) {
  // MODEL.md quotes "≈ −1.65 rad". The exact limit is where |BD| = 2R_b + 2h (beam and
  // right column collinear, the circles of the loop closure touch), computed here
  // independently of FourBar from the law of cosines in triangle ABD (paper Eq. 2).
  const double limit = eom.linkage().closing_limit_rad();
  const double Rc1 = std::hypot(frame.b, frame.h_prime);
  const double beta = std::atan2(frame.h_prime, frame.b);
  const double BD = std::sqrt(4 * frame.L * frame.L + 4 * Rc1 * Rc1 - 8 * Rc1 * frame.L * std::cos(beta - limit));
  EXPECT_NEAR(BD, 2 * std::hypot(frame.L_b, frame.h_b) + 2 * frame.h, 1e-7);
  EXPECT_NEAR(limit, -1.600225, 1e-6);
  Configuration c;
  EXPECT_TRUE(eom.linkage().solve(limit + 1e-6, c));
  EXPECT_FALSE(eom.linkage().solve(limit - 1e-3, c));
}

}  // namespace
}  // namespace pcrf
