// Time histories: dense output at any interval from the integrator's interpolant, one row per
// event, time strictly increasing, and a history that never changes the result.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "pcrf/model/frame.hpp"
#include "pcrf/units.hpp"
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

std::uint32_t events_of(const HistorySample& row) { return static_cast<std::uint32_t>(row.event); }

class History : public ::testing::Test {
 protected:
  CaseResult solve(double history_dt_s, test::Trace* trace, SolverSettings solver = {}) {
    OutputRequest request;
    request.history_dt_s = history_dt_s;
    return solve_case(frame, record, PhysicsOptions{}, solver, request, trace ? trace->sink() : HistorySink{});
  }
  const Frame frame = basic_frame();
  const GroundMotion record = test::strong_record(7, 6.0);  // dt 10 ms, rocks with impacts
};

TEST_F(History, TimeStrictlyIncreasesAndImpactsAreOneRow) {
  test::Trace trace;
  const CaseResult r = solve(0.001, &trace);
  ASSERT_GT(r.impacts, 3);
  int impacts = 0;
  for (std::size_t i = 1; i < trace.samples.size(); ++i)
    ASSERT_LT(trace.samples[i - 1].t_s, trace.samples[i].t_s) << "row " << i;
  for (const auto& row : trace.samples) {
    if (events_of(row) & kEventImpact) {
      ++impacts;
      EXPECT_EQ(row.theta1_rad, 0.0);
      const double leaving = (events_of(row) & kEventRest) ? 0.0 : r.restitution * row.omega1_rad_s;
      EXPECT_DOUBLE_EQ(row.omega1_after_rad_s, leaving) << "t = " << row.t_s;
    } else {
      EXPECT_EQ(row.omega1_after_rad_s, row.omega1_rad_s);
    }
    EXPECT_DOUBLE_EQ(row.ground_accel_g * kGravity_m_s2, row.ground_accel_m_s2);
  }
  EXPECT_EQ(impacts, r.impacts);
  EXPECT_TRUE(events_of(trace.samples.back()) & kEventEnd);
  EXPECT_EQ(trace.samples.back().t_s, r.t_end_s);
}

TEST_F(History, ThePeaksAndTheUpliftAreRowsAtTheirExactTimes) {
  test::Trace trace;
  const CaseResult r = solve(0.0, &trace);  // rows at the record's 10 ms, plus events
  const auto peak = std::max_element(trace.samples.begin(), trace.samples.end(), [](const auto& a, const auto& b) {
    return std::abs(a.theta1_rad) < std::abs(b.theta1_rad);
  });
  EXPECT_EQ(std::abs(peak->theta1_rad), r.theta_max_rad);
  EXPECT_EQ(peak->t_s, r.t_theta_max_s);
  EXPECT_TRUE(events_of(*peak) & kEventThetaPeak);
  const auto fastest = std::max_element(trace.samples.begin(), trace.samples.end(), [](const auto& a, const auto& b) {
    return std::abs(a.omega1_rad_s) < std::abs(b.omega1_rad_s);
  });
  EXPECT_EQ(std::abs(fastest->omega1_rad_s), r.omega_max_rad_s);
  const auto uplift = std::find_if(trace.samples.begin(), trace.samples.end(),
                                   [](const auto& row) { return events_of(row) & kEventUplift; });
  ASSERT_NE(uplift, trace.samples.end());
  EXPECT_EQ(uplift->t_s, r.t_uplift_s);
}

// With a history the integrator returns after every step, and SUNDIALS then checks the root
// functions at each return as well: roots are located to round-off from other brackets, so
// the results agree far below the tolerances (rtol 1e-6), not bit for bit. The output
// interval itself changes nothing: rows between steps are interpolated, never stepped to.
TEST_F(History, AskingForAHistoryDoesNotChangeTheResult) {
  const CaseResult plain = solve(0.0, nullptr);
  test::Trace first;
  const CaseResult with = solve(0.0, &first);
  EXPECT_NEAR(with.theta_max_rad, plain.theta_max_rad, 1e-9 * plain.theta_max_rad);
  EXPECT_NEAR(with.omega_max_rad_s, plain.omega_max_rad_s, 1e-9 * plain.omega_max_rad_s);
  EXPECT_EQ(with.impacts, plain.impacts);
  for (double dt : {0.001, 0.0037}) {
    test::Trace trace;
    const CaseResult other = solve(dt, &trace);
    EXPECT_EQ(other.theta_max_rad, with.theta_max_rad) << dt;
    EXPECT_EQ(other.counts.steps, with.counts.steps) << dt;
  }
}

// The rows between steps come from the interpolant: at the balanced preset they agree with a
// reference solution (rtol 1e-12) to the preset's own accuracy, at every 1 ms row of the
// flight, not only at the record's samples.
TEST_F(History, DenseRowsMatchATightSolutionBetweenTheSteps) {
  test::Trace dense, reference;
  const CaseResult r = solve(0.001, &dense);
  solve(0.001, &reference, test::tight(Integrator::kArkodeErk8));
  ASSERT_GT(r.impacts, 0);
  std::size_t j = 0, compared = 0;
  double worst = 0.0;
  for (const auto& row : dense.samples) {
    if (row.t_s > 1.5) break;  // before the motion is sensitive to the last digits
    while (j < reference.samples.size() && reference.samples[j].t_s < row.t_s) ++j;
    if (j == reference.samples.size() || reference.samples[j].t_s != row.t_s || row.event != 0.0) continue;
    worst = std::max(worst, std::abs(row.theta1_rad - reference.samples[j].theta1_rad));
    ++compared;
  }
  EXPECT_GT(compared, 300u);
  EXPECT_LT(worst, 1e-6 * r.theta_max_rad + 1e-9);
}

TEST(FixedStepHistory, ImpactsAreOneRowToo) {
  SolverSettings solver;
  solver.integrator = Integrator::kFixedRk4SignChange;
  solver.fixed_step_s = 0.002;
  test::Trace trace;
  const CaseResult r = solve_case(basic_frame(), test::strong_record(7, 6.0), PhysicsOptions{}, solver, {}, trace.sink());
  ASSERT_GT(r.impacts, 0);
  int impacts = 0;
  for (std::size_t i = 1; i < trace.samples.size(); ++i) ASSERT_LT(trace.samples[i - 1].t_s, trace.samples[i].t_s);
  for (const auto& row : trace.samples)
    if (events_of(row) & kEventImpact) {
      ++impacts;
      EXPECT_DOUBLE_EQ(row.omega1_after_rad_s, r.restitution * row.omega1_rad_s);
    }
  EXPECT_EQ(impacts, r.impacts);
}

}  // namespace
}  // namespace pcrf
