// Where the rigid-body rocking model holds: a frame must stand at rest (uplift threshold > 0)
// and its impacts must be dissipative rocking impacts (0 ≤ r ≤ 1). Both edges are found by
// bisection on λ_h at λ = 2, tan α = 0.8 (where an audit found them inside the documented
// ranges), and frames just inside and just outside get the verdicts they should.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/impact.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace pcrf {
namespace {

FrameParameters deep_beam(double lambda_h) {
  FrameParameters p;
  p.lambda = 2.0;
  p.tan_alpha = 0.8;
  p.lambda_h = lambda_h;
  return p;
}

/// The λ_h in (lo, hi) where `sign` changes from positive to not positive.
double crossing(double lo, double hi, const std::function<double(double)>& f) {
  EXPECT_GT(f(lo), 0.0);
  EXPECT_LE(f(hi), 0.0);
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  return lo;
}

std::string verdict(double lambda_h) {
  try {
    (void)prepare_frame(make_frame(deep_beam(lambda_h)), PhysicsOptions{});
  } catch (const UserError& e) {
    return e.what();
  }
  return "valid";
}

TEST(ModelDomain, RestitutionEdge) {
  const double edge = crossing(0.3, 0.6, [](double lh) { return restitution_momentum(EquationOfMotion(make_frame(deep_beam(lh)))); });
  EXPECT_GT(edge, 0.5);
  EXPECT_LT(edge, 0.6);  // the audit: r < 0 from λ_h = 0.6 on
  EXPECT_EQ(verdict(edge * (1.0 - 1e-3)), "valid");
  EXPECT_NE(verdict(edge * (1.0 + 1e-3)).find("coefficient of restitution"), std::string::npos) << verdict(edge * 1.001);
}

TEST(ModelDomain, InertiaTermEdge) {
  // S(0) changes sign with a deep beam: λ_g = G/S and the threshold (G g + K)/S run through
  // a pole and turn negative (the audit's "thresholds below 0").
  const double edge = crossing(0.6, 0.95, [](double lh) { return EquationOfMotion(make_frame(deep_beam(lh))).lambda_g(); });
  EXPECT_GT(edge, 0.8);
  EXPECT_LT(edge, 0.9);
  EXPECT_LT(EquationOfMotion(make_frame(deep_beam(edge * 1.001))).uplift_threshold_m_s2(), 0.0);
  EXPECT_NE(verdict(edge * (1.0 + 1e-3)).find("the ground cannot rock this frame"), std::string::npos) << verdict(edge * 1.001);
  // Just below it the frame stands and the ground drives it, but its r is already negative.
  EXPECT_NE(verdict(edge * (1.0 - 1e-3)).find("coefficient of restitution"), std::string::npos);
}

TEST(ModelDomain, TheBasicModelAndThePaperRangesAreValid) {
  EXPECT_EQ(verdict(0.2), "valid");
  for (double tan_alpha : {0.1, 0.2, 0.3})
    for (double lambda_h : {0.1, 0.2, 0.3}) {
      FrameParameters p;
      p.tan_alpha = tan_alpha;
      p.lambda_h = lambda_h;
      EXPECT_NO_THROW(prepare_frame(make_frame(p), PhysicsOptions{})) << tan_alpha << ", " << lambda_h;
    }
}

TEST(ModelDomain, ASingleRunRefusesAnInvalidFrame) {
  const GroundMotion quiet("quiet", 0.01, std::vector<double>(100, 0.0));
  EXPECT_THROW(solve_case(make_frame(deep_beam(0.7)), quiet, PhysicsOptions{}, preset_settings("balanced")), UserError);
}

}  // namespace
}  // namespace pcrf
