// Solver counters are deterministic, even for a case whose integrator fails in its set-up.
#include <gtest/gtest.h>

#include "pcrf/solver/rocking_solver.hpp"

namespace pcrf {
namespace {

TEST(SolverCounters, ASegmentThatNeverStartedCountsNothing) {
  // One sample above the threshold: the frame lifts at t = 0 with no time left to fly.
  const GroundMotion one("one", 0.01, {15.0});
  const CaseResult a = solve_case(basic_frame(), one, {}, preset_settings("balanced"));
  const CaseResult b = solve_case(basic_frame(), one, {}, preset_settings("balanced"));
  EXPECT_EQ(a.counts.root_evals, b.counts.root_evals);
  EXPECT_EQ(a.counts.steps, b.counts.steps);
  if (a.counts.rhs_evals == 0) {
    EXPECT_EQ(a.counts.root_evals, 0);
  }
  EXPECT_LT(a.counts.root_evals, 1000);
}

TEST(SolverCounters, ADisplacedStartBeyondTheOverturningAngleIsRejected) {
  PhysicsOptions physics;
  physics.theta0_rad = 100.0;
  const GroundMotion quiet("quiet", 0.01, std::vector<double>(100, 0.0));
  EXPECT_THROW(solve_case(basic_frame(), quiet, physics, preset_settings("balanced")), std::invalid_argument);
  physics.theta0_rad = -0.1;
  EXPECT_NO_THROW(solve_case(basic_frame(), quiet, physics, preset_settings("balanced")));
}

}  // namespace
}  // namespace pcrf
