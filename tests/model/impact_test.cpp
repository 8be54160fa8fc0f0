// Coefficient of restitution: the five momentum equations against the closed form
// Eq. (42) with erratum 3, over a spread of frames; kinetic energy ratio r².
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/impact.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {
namespace {

TEST(Restitution, MomentumBalanceEqualsClosedFormOverParameterSpread) {
  int n = 0;
  for (double kappa : {0.1, 0.5, 1.8, 4.0, 10.0}) {
    for (double lambda : {1.0, 2.0, 3.5, 5.0}) {
      for (double tan_alpha : {0.05, 0.1, 0.2, 0.35, 0.5}) {
        for (double lambda_h : {0.05, 0.2, 0.45}) {
          if (lambda <= tan_alpha) continue;
          FrameParameters p;
          p.kappa = kappa;
          p.lambda = lambda;
          p.tan_alpha = tan_alpha;
          p.lambda_h = lambda_h;
          const EquationOfMotion eom(make_frame(p));
          const double r_m = restitution_momentum(eom);
          const double r_c = restitution_closed_form(eom);
          EXPECT_NEAR(r_m, r_c, 1e-12 * std::abs(r_c))
              << "kappa=" << kappa << " lambda=" << lambda << " tan_alpha=" << tan_alpha << " lambda_h=" << lambda_h;
          EXPECT_GT(r_m, 0.0);
          EXPECT_LT(r_m, 1.0);
          ++n;
        }
      }
    }
  }
  EXPECT_GT(n, 250);
}

TEST(Restitution, ExtremeMassRatiosAreSolvedOrRefusedNeverAnInternalError) {
  // A beam 10^12 times the columns' mass makes the momentum system's rows differ by more than
  // double precision resolves: the QR calls it rank-deficient, and the closed form (the same
  // balance, exact there) answers. The answers approach the heavy-beam limit smoothly, and a
  // frame nothing can compute is refused as the user's input (UserError), not a bug.
  double previous = 0.0;
  for (double kappa : {1e6, 1e8, 1e9, 1e10, 1e11, 1e12, 1e15, 1e20}) {
    FrameParameters p;
    p.kappa = kappa;
    const EquationOfMotion eom(make_frame(p));
    const double r_m = restitution_momentum(eom);
    EXPECT_NEAR(r_m, restitution_closed_form(eom), 1e-9 * r_m) << "kappa=" << kappa;
    EXPECT_GT(r_m, 0.0);
    EXPECT_LT(r_m, 1.0);
    if (kappa > 1e6) {
      EXPECT_NEAR(r_m, previous, 1e-5) << "kappa=" << kappa;  // the limit, O(1/kappa)
    }
    previous = r_m;
  }
  for (double kappa : {1e-12, 1e300}) {
    FrameParameters p;
    p.kappa = kappa;
    try {
      const EquationOfMotion eom(make_frame(p));
      EXPECT_GT(restitution_momentum(eom), 0.0) << "kappa=" << kappa;
      EXPECT_LT(restitution_momentum(eom), 1.0) << "kappa=" << kappa;
    } catch (const UserError&) {
    }
  }
}

TEST(Restitution, PrintedSignOfLambdaLMissesTheMomentumBalance) {
  // Erratum 3: with λ_L = +∂θ₂/∂θ₁ the closed form is off (MODEL.md: by up to 0.2 %).
  double worst = 0.0;
  for (double kappa : {0.5, 1.8, 10.0}) {
    for (double tan_alpha : {0.1, 0.2, 0.5}) {
      FrameParameters p;
      p.kappa = kappa;
      p.tan_alpha = tan_alpha;
      const EquationOfMotion eom(make_frame(p));
      const double r_m = restitution_momentum(eom);
      worst = std::max(worst, std::abs(restitution_closed_form(eom, LambdaLSign::kAsPrinted) - r_m) / r_m);
    }
  }
  EXPECT_GT(worst, 1e-4);
}

TEST(Restitution, KineticEnergyRatioIsRSquared) {
  const EquationOfMotion eom(basic_frame());
  const double r = restitution_momentum(eom);
  const double w = 0.3;
  const double before = eom.energy(0.0, w, -1) - eom.energy(0.0, 0.0, -1);
  const double after = eom.energy(0.0, r * w, +1) - eom.energy(0.0, 0.0, +1);
  EXPECT_NEAR(after / before, r * r, 1e-12);
}

}  // namespace
}  // namespace pcrf
