// The tabulated coefficients reproduce the exact right-hand side on both branches, up to
// and beyond the range the cells can represent (where they fall back to exact terms).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pcrf/model/eom_table.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"

namespace pcrf {
namespace {

void expect_matches_exact(const FrameParameters& p) {
  const EquationOfMotion eom(make_frame(p));
  const EomTable table(eom);
  const double limit = eom.closing_limit_rad();
  int compared = 0;
  for (int i = 0; i <= 2000; ++i) {
    const double u = -0.01 + (limit + 0.01) * i / 2000.0 * 0.9999;  // includes a small overshoot
    for (int side : {-1, +1}) {
      const double theta = side < 0 ? -u : u;
      for (double w : {0.0, 0.7}) {
        for (double a : {-12.0, 3.0}) {
          double exact = 0, tab = 0;
          const bool ok_exact = eom.acceleration(theta, w, a, side, exact);
          const bool ok_tab = table.acceleration(theta, w, a, side, tab);
          ASSERT_EQ(ok_exact, ok_tab) << theta;
          if (!ok_exact) continue;
          // Relative to the size of the terms in the sum (θ̈ itself can pass through zero).
          EomTerms t;
          ASSERT_TRUE(eom.terms(theta, side, t));
          const double scale = (std::abs(t.S * a) + std::abs(t.J) * w * w + std::abs(t.G * 9.81) + std::abs(t.K)) / t.I;
          EXPECT_NEAR(tab, exact, 2e-11 * scale) << "theta=" << theta << " side=" << side;
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 15000);
  EXPECT_GT(table.cells_built(), 10);
}

TEST(EomTable, MatchesExactTermsForTheBasicFrame) { expect_matches_exact(FrameParameters{}); }

TEST(EomTable, MatchesExactTermsForSlenderLightFrame) {
  FrameParameters p;
  p.kappa = 0.1;
  p.lambda = 1.0;
  p.tan_alpha = 0.05;
  p.lambda_h = 0.05;
  expect_matches_exact(p);
}

TEST(EomTable, MatchesExactTermsForStockyHeavyFrameWithoutTendons) {
  FrameParameters p;
  p.kappa = 10.0;
  p.lambda = 5.0;
  p.tan_alpha = 0.5;
  p.lambda_h = 0.45;
  p.pi_sigma_b = p.pi_sigma_c = p.pi_e_b = p.pi_e_c = 0.0;
  expect_matches_exact(p);
}

TEST(EomTable, BuildsOnlyTheCellsItIsAskedFor) {
  const EquationOfMotion eom(basic_frame());
  const EomTable table(eom);
  double acc = 0;
  for (double th = 0.0; th > -0.03; th -= 1e-4) ASSERT_TRUE(table.acceleration(th, 0.1, 1.0, -1, acc));
  EXPECT_LE(table.cells_built(), 3);
}

TEST(EomTable, JacobianMatchesDifferencesOfTheExactTerms) {
  for (double stiffness : {1.0, 1e4}) {  // the basic tendons, and 10⁴ times stiffer
    FrameParameters p;
    p.pi_e_b *= stiffness;
    p.pi_e_c *= stiffness;
    const EquationOfMotion eom(make_frame(p));
    const EomTable table(eom);
    for (double u : {1e-9, 4e-6, 0.003, 0.05, 0.4}) {
      for (int side : {-1, +1}) {
        const double theta = side < 0 ? -u : u, w = 0.3, a = 2.0;
        double acc = 0, d_theta = 0, d_omega = 0, plus = 0, minus = 0;
        ASSERT_TRUE(table.acceleration_jacobian(theta, w, a, side, acc, d_theta, d_omega));
        const double h = 1e-7 * std::max(u, 1e-3);
        ASSERT_TRUE(eom.acceleration(theta + h, w, a, side, plus));
        ASSERT_TRUE(eom.acceleration(theta - h, w, a, side, minus));
        const double fd = (plus - minus) / (2 * h);
        // The derivative of the degree-9 interpolant is least accurate at the cell ends
        // (Markov's inequality): a few parts in 10⁶ there, far more than Newton needs.
        EXPECT_NEAR(d_theta, fd, 1e-5 * std::abs(fd)) << "u=" << u << " side=" << side << " k×" << stiffness;
        // θ̈ is quadratic in θ̇, so a central difference with a large step is exact.
        ASSERT_TRUE(eom.acceleration(theta, w + 0.1, a, side, plus));
        ASSERT_TRUE(eom.acceleration(theta, w - 0.1, a, side, minus));
        EXPECT_NEAR(d_omega, (plus - minus) / 0.2, 1e-9 * (std::abs(plus) + std::abs(minus)) + 1e-12);
      }
    }
  }
}

}  // namespace
}  // namespace pcrf
