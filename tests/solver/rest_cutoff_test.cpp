// The return-to-rest cut-off is physics ([physics] rest_rise_rad), not a solver tolerance
// (docs/physics.md, "Return to rest"): the same case at two presets' absolute tolerances ends
// in the same state after the same impacts, and only the physical setting moves them.
#include <gtest/gtest.h>

#include <cstdlib>

#include "pcrf/model/frame.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

/// The basic frame rocked by a sine pulse train, then free until it rests: every impact
/// sequence ends in a Zeno cascade, which the cut-off closes.
struct PulseCase {
  Frame frame = basic_frame();
  GroundMotion record = [] {
    SinePulseSpec pulse;
    pulse.amplitude_g = 1.5;
    pulse.duration_s = 1.0;
    return make_sine_pulse_train(pulse);
  }();

  CaseResult solve(const PhysicsOptions& physics, const SolverSettings& solver) const {
    return solve_case(frame, record, physics, solver, {});
  }
};

/// The balanced preset's integrator and rtol with the `fast` preset's absolute tolerances.
SolverSettings balanced_with_fast_atol() {
  SolverSettings s = preset_settings("balanced");
  const SolverSettings fast = preset_settings("fast");
  s.atol_theta_rad = fast.atol_theta_rad;
  s.atol_omega_rad_s = fast.atol_omega_rad_s;
  return s;
}

TEST(RestCutoff, SolverToleranceDoesNotDecideTheRest) {
  const PulseCase c;
  const PhysicsOptions physics;  // one cut-off for all
  const CaseResult balanced = c.solve(physics, preset_settings("balanced"));
  ASSERT_EQ(balanced.status, CaseStatus::kAtRest);
  ASSERT_GT(balanced.impacts, 20);
  // Before the cut-off was physics, fast's atol (1e-6 rad) ended the motion at a rise of 1e-5
  // rad, balanced's at 1e-10: 2.2 times fewer impacts. Now only the numerics differ: a late
  // flight near the cut-off may end one impact earlier or later.
  for (const SolverSettings& other : {balanced_with_fast_atol(), preset_settings("fast"), preset_settings("reference")}) {
    SCOPED_TRACE(other.preset + ", atol_theta_rad " + std::to_string(other.atol_theta_rad));
    const CaseResult r = c.solve(physics, other);
    EXPECT_EQ(r.status, balanced.status);
    EXPECT_LE(std::abs(r.impacts - balanced.impacts), 2) << r.impacts << " against " << balanced.impacts;
    EXPECT_NEAR(r.theta_max_rad, balanced.theta_max_rad, 1e-4 * balanced.theta_max_rad);
    // The free rocking's end: within the last few flights, each shorter than the previous.
    EXPECT_NEAR(r.t_end_s, balanced.t_end_s, 0.02);
  }
}

TEST(RestCutoff, ThePhysicalSettingDecidesTheRest) {
  const PulseCase c;
  const SolverSettings solver = preset_settings("balanced");
  PhysicsOptions fine, coarse;
  coarse.rest_rise_rad = 1e-5;
  ASSERT_LT(fine.rest_rise_rad, coarse.rest_rise_rad);
  const CaseResult a = c.solve(fine, solver), b = c.solve(coarse, solver);
  ASSERT_EQ(a.status, CaseStatus::kAtRest);
  ASSERT_EQ(b.status, CaseStatus::kAtRest);
  // A larger cut-off stops the cascade earlier: fewer impacts, an earlier rest, the same peak
  // (it came during the pulse, far above either cut-off).
  EXPECT_LT(b.impacts, a.impacts);
  EXPECT_LT(b.t_end_s, a.t_end_s);
  EXPECT_EQ(b.theta_max_rad, a.theta_max_rad);
  // The same cut-off gives the same answer whatever the tolerance that runs it.
  const CaseResult b_fast = c.solve(coarse, balanced_with_fast_atol());
  EXPECT_LE(std::abs(b_fast.impacts - b.impacts), 2);
  // A cut-off is a rotation: negative values are refused; zero leaves only the Zeno time.
  PhysicsOptions negative;
  negative.rest_rise_rad = -1e-10;
  EXPECT_THROW(c.solve(negative, solver), std::exception);
  PhysicsOptions zero;
  zero.rest_rise_rad = 0.0;
  const CaseResult z = c.solve(zero, solver);
  EXPECT_EQ(z.status, CaseStatus::kAtRest);
  EXPECT_GE(z.impacts, a.impacts);
}

}  // namespace
}  // namespace pcrf
