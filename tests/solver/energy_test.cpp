// Energy: with no ground motion, T + V is constant between impacts; across an impact the
// kinetic energy is multiplied by r².
#include <gtest/gtest.h>

#include <cmath>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

/// Free rocking of the basic frame released from rest at θ₁ = −0.02 with no ground motion.
class FreeRocking : public ::testing::TestWithParam<Integrator> {
 protected:
  CaseResult release(double duration_s) {
    PhysicsOptions physics = test::record_only();
    physics.theta0_rad = -0.02;
    return solve_case(frame, test::quiet_record(duration_s, 0.001), physics, test::tight(GetParam()), {},
                      trace.sink());
  }
  const Frame frame = basic_frame();
  const EquationOfMotion eom{frame};
  test::Trace trace;
};

TEST_P(FreeRocking, EnergyIsConservedUntilTheFirstImpact) {
  const CaseResult r = release(3.0);
  ASSERT_GT(r.impacts, 0);
  const double e_rest = eom.energy(0.0, 0.0, -1);
  const double e0 = eom.energy(-0.02, 0.0, -1) - e_rest;  // energy above rest
  ASSERT_GT(e0, 0.0);
  int checked = 0;
  for (const auto& s : trace.samples) {
    if (s.theta1_rad == 0.0) break;  // first impact
    const double e = eom.energy(s.theta1_rad, s.omega1_rad_s, -1) - e_rest;
    EXPECT_LT(std::abs(e - e0) / e0, 1e-8) << "t = " << s.t_s;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST_P(FreeRocking, KineticEnergyRatioAcrossImpactIsRSquared) {
  const CaseResult r = release(1.5);
  ASSERT_GT(r.impacts, 1);
  // An impact is one history row: the velocity arriving and the one leaving.
  int impacts_checked = 0;
  for (const auto& row : trace.samples) {
    const auto events = static_cast<std::uint32_t>(row.event);
    if ((events & kEventImpact) && !(events & kEventRest)) {
      EXPECT_EQ(row.theta1_rad, 0.0);
      const double ke_before = eom.energy(0.0, row.omega1_rad_s, -1) - eom.energy(0.0, 0.0, -1);
      const double ke_after = eom.energy(0.0, row.omega1_after_rad_s, +1) - eom.energy(0.0, 0.0, +1);
      EXPECT_NEAR(ke_after / ke_before, r.restitution * r.restitution, 1e-12);
      ++impacts_checked;
    }
  }
  EXPECT_GE(impacts_checked, 2);
}

// Every integrator that locates its events (the fixed-step contender crosses θ₁ = 0 by up to a
// step before it sees an impact, and never puts a frame back at rest: no energy balance holds
// at its impacts). On this frame taylor takes its without_series (dopri5); its own series
// steps are checked on the block below.
INSTANTIATE_TEST_SUITE_P(Integrators, FreeRocking, ::testing::ValuesIn(test::event_locating_integrators()),
                         test::integrator_test_name);

}  // namespace
}  // namespace pcrf
