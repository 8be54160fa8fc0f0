// Taylor steps for the rigid rockers (integrator `taylor`, the presets' default for them):
// the series itself, then the solver's checks — mirror symmetry, energy between impacts,
// convergence as the tolerance tightens, the batch's treatment. Housner's period, the
// amplitude decay and the published overturning amplitudes run with Taylor steps too
// (rocking_canon_test.cpp is instantiated for both integrators).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "pcrf/model/rigid_rocker.hpp"
#include "pcrf/solver/batch_solver.hpp"
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

RigidRocker block_of(double alpha = 0.2, double R = 1.5) {
  RockerParameters p;
  p.slenderness_rad = alpha;
  p.size_m = R;
  return RigidRocker(p);
}

std::shared_ptr<PreparedFrame> prepared(double alpha = 0.2, double R = 1.5, double gamma = 0.0) {
  RockerParameters p;
  p.slenderness_rad = alpha;
  p.size_m = R;
  p.beam_mass_ratio = gamma;
  return prepare_scene(std::make_unique<RigidRocker>(p), {});
}

SolverSettings taylor(double rtol) {
  SolverSettings s = test::tight(Integrator::kTaylor);
  s.rtol = rtol;
  s.atol_theta_rad = 1e-4 * rtol;
  s.atol_omega_rad_s = 1e-3 * rtol;
  return s;
}

TEST(RigidRockerSeries, SecondCoefficientIsHalfTheAcceleration) {
  const RigidRocker r = block_of();
  const GroundLine ground{3.0, -40.0, 1.5, 25.0};
  for (int side : {-1, 1}) {
    double a[9];
    ASSERT_TRUE(r.taylor_series(0.05 * side, -0.3 * side, ground, side, 8, a));
    double acc = 0.0;
    ASSERT_TRUE(r.acceleration(0.05 * side, -0.3 * side, {ground.h0_m_s2, ground.v0_m_s2}, side, acc));
    EXPECT_EQ(a[0], 0.05 * side);
    EXPECT_EQ(a[1], -0.3 * side);
    EXPECT_NEAR(2.0 * a[2], acc, 1e-14 * std::abs(acc)) << "side " << side;
  }
}

TEST(RigidRockerSeries, TheSeriesSolvesTheEquationUnderALinearGround) {
  // θ̈ from the series equals the equation of motion at the series' own (θ, θ̇) and the
  // ground of that instant, along a record interval: the recurrences of sin, cos and the
  // ground's line are right to every order kept.
  const RigidRocker r = block_of();
  const GroundLine ground{3.0, -400.0, 1.5, 250.0};
  constexpr int n = 18;
  for (int side : {-1, 1}) {
    double a[n + 1];
    ASSERT_TRUE(r.taylor_series(-0.04 * side, 0.5 * side, ground, side, n, a));
    for (double tau : {0.001, 0.004, 0.01}) {
      double th = 0.0, om = 0.0, ac = 0.0;
      for (int k = n; k >= 0; --k) th = th * tau + a[k];
      for (int k = n; k >= 1; --k) om = om * tau + k * a[k];
      for (int k = n; k >= 2; --k) ac = ac * tau + k * (k - 1.0) * a[k];
      double expected = 0.0;
      ASSERT_TRUE(r.acceleration(th, om, {ground.h0_m_s2 + ground.h1_m_s3 * tau, ground.v0_m_s2 + ground.v1_m_s3 * tau},
                                 side, expected));
      EXPECT_NEAR(ac, expected, 1e-11 * std::abs(expected)) << "side " << side << ", tau " << tau;
    }
  }
}

TEST(RigidRockerSeries, OrdersBeyondTheTableAreRefused) {
  const RigidRocker r = block_of();
  double a[RigidRocker::kTaylorOrderMax + 2];
  EXPECT_FALSE(r.taylor_series(0.0, 0.1, {}, -1, RigidRocker::kTaylorOrderMax + 1, a));
  EXPECT_FALSE(r.taylor_series(0.0, 0.1, {}, -1, 0, a));
  EXPECT_FALSE(r.taylor_series(std::nan(""), 0.1, {}, -1, 6, a));
}

TEST(TaylorSteps, AMirroredRecordGivesTheMirroredMotion) {
  const GroundMotion g = test::strong_record(11, 8.0).scaled(0.5);
  const GroundMotion mirrored = g.scaled(-1.0);
  for (double gamma : {0.0, 0.5}) {
    auto frame = prepared(0.2, 1.5, gamma);
    test::Trace a, b;
    const CaseResult ra = solve_case(*frame, g, preset_settings("balanced"), {}, a.sink());
    const CaseResult rb = solve_case(*frame, mirrored, preset_settings("balanced"), {}, b.sink());
    ASSERT_GT(ra.impacts, 2) << "the case must rock";
    EXPECT_EQ(ra.impacts, rb.impacts);
    EXPECT_EQ(ra.status, rb.status);
    EXPECT_EQ(ra.theta_max_rad, rb.theta_max_rad);
    test::expect_mirrored(a, b);
  }
}

TEST(TaylorSteps, EnergyIsConservedBetweenImpacts) {
  PhysicsOptions physics;
  physics.theta0_rad = -0.1;
  const RigidRocker scene = block_of();
  auto released = prepare_scene(std::make_unique<RigidRocker>(block_of()), physics);
  test::Trace trace;
  const CaseResult r = solve_case(*released, test::quiet_record(4.0, 0.001), preset_settings("balanced"), {}, trace.sink());
  ASSERT_GT(r.impacts, 2);
  double e0 = NAN;
  int checked = 0;
  for (const auto& s : trace.samples) {
    if (static_cast<std::uint32_t>(s.event) & kEventImpact) {
      e0 = NAN;  // a new flight: its energy is the one after the impact
      continue;
    }
    const int side = s.theta1_rad < 0.0 ? -1 : 1;
    const double e = scene.energy(s.theta1_rad, s.omega1_rad_s, side) - scene.energy(0.0, 0.0, side);
    if (std::isnan(e0)) {
      e0 = e;
      continue;
    }
    // balanced: rtol 1e-7; plus the rounding of the difference of two totals (late flights
    // hold 1e-9 of the energy at rest)
    const double rounding = 16.0 * 2.2e-16 * std::abs(scene.energy(0.0, 0.0, side));
    EXPECT_NEAR(e, e0, 1e-7 * std::abs(e0) + rounding) << "t = " << s.t_s;
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(TaylorSteps, ConvergeToTheEighthOrderReferenceAsTheToleranceTightens) {
  const GroundMotion g = test::strong_record(5, 10.0).scaled(0.45);
  for (double gamma : {0.0, 0.5}) {
    auto frame = prepared(0.2, 1.5, gamma);
    const CaseResult ref = solve_case(*frame, g, test::tight(Integrator::kArkodeErk8));
    ASSERT_GT(ref.impacts, 2);
    double last = INFINITY;
    for (double rtol : {1e-5, 1e-8, 1e-11}) {
      const CaseResult r = solve_case(*frame, g, taylor(rtol));
      EXPECT_EQ(r.status, ref.status);
      const double err = std::abs(r.theta_max_rad - ref.theta_max_rad) / ref.theta_max_rad;
      EXPECT_LE(err, std::max(100.0 * rtol, 1e-10)) << "gamma " << gamma << ", rtol " << rtol;
      EXPECT_LE(err, last + 1e-12);
      last = err;
    }
  }
}

TEST(TaylorSteps, OneSeriesPerStepAndFarFewerThanDopri5sStages) {
  // The point of the series: one expansion per step (no rejected attempt inside a record
  // interval: the estimate gives the step before it is taken), where dopri5 makes six stages.
  const GroundMotion g = test::strong_record(5, 10.0).scaled(0.45);
  auto frame = prepared();
  SolverSettings dp = preset_settings("balanced");
  dp.integrator = Integrator::kDormandPrince5;
  const CaseResult d = solve_case(*frame, g, dp);
  const CaseResult t = solve_case(*frame, g, preset_settings("balanced"));
  ASSERT_GT(d.impacts, 2);
  EXPECT_EQ(t.impacts, d.impacts);
  EXPECT_LE(t.counts.rhs_evals, t.counts.steps + t.counts.reinits + 1);  // + one f at each restart
  EXPECT_LT(t.counts.rhs_evals, d.counts.rhs_evals / 3);
}

TEST(TaylorSteps, WithoutAHistoryOnlyThePeaksThatRaiseTheMaximaAreLocated) {
  // A rocking block (many flights, most of them small): without a history the steps pass
  // over the θ and θ̇ peaks that cannot raise θ_max or ω_max, so fewer root-function
  // evaluations; the maxima, their times, the impacts and the end are those of a run that
  // records every peak. At 0.45 the block overturns: ω_max is then the speed at the stop.
  for (const double scale : {0.3, 0.45})
  for (double gamma : {0.0, 0.5}) {
    const GroundMotion g = test::strong_record(5, 10.0).scaled(scale);
    auto frame = prepared(0.2, 1.5, gamma);
    test::Trace trace;
    const CaseResult with = solve_case(*frame, g, preset_settings("balanced"), {}, trace.sink());
    const CaseResult plain = solve_case(*frame, g, preset_settings("balanced"));
    ASSERT_GT(with.impacts, 5) << "the case must rock";
    int peaks = 0;
    for (const auto& row : trace.samples) peaks += (static_cast<std::uint32_t>(row.event) & kEventThetaPeak) != 0;
    EXPECT_GE(peaks, with.impacts / 2) << "a history records the peaks of the flights";
    EXPECT_EQ(plain.status, with.status);
    EXPECT_EQ(plain.impacts, with.impacts);
    EXPECT_EQ(plain.counts.steps, with.counts.steps);
    EXPECT_NEAR(plain.theta_max_rad, with.theta_max_rad, 1e-12 * with.theta_max_rad);
    EXPECT_NEAR(plain.t_theta_max_s, with.t_theta_max_s, 1e-12);
    EXPECT_NEAR(plain.omega_max_rad_s, with.omega_max_rad_s, 1e-12 * with.omega_max_rad_s);
    EXPECT_NEAR(plain.t_omega_max_s, with.t_omega_max_s, 1e-12);
    EXPECT_EQ(plain.t_end_s, with.t_end_s);
    EXPECT_LT(plain.counts.root_evals, with.counts.root_evals);
  }
}

TEST(TaylorSteps, TheBatchSolvesThemOneAtATimeWithTheSameAnswers) {
  const GroundMotion g = test::strong_record(5, 6.0).scaled(0.45);
  std::vector<std::shared_ptr<PreparedFrame>> frames;
  std::vector<PreparedFrame*> views;
  for (double alpha : {0.15, 0.2, 0.25}) frames.push_back(prepared(alpha)), views.push_back(frames.back().get());
  BatchOptions options;
  options.lanes = 4;
  BatchStats stats;
  const auto batch = solve_batch(views, g, preset_settings("balanced"), {}, options, &stats);
  ASSERT_EQ(batch.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const CaseResult one = solve_case(*frames[i], g, preset_settings("balanced"));
    EXPECT_EQ(batch[i].theta_max_rad, one.theta_max_rad);
    EXPECT_EQ(batch[i].impacts, one.impacts);
  }
  EXPECT_EQ(stats.scalar_cases + stats.rest_cases, static_cast<long>(frames.size()));
}

}  // namespace
}  // namespace pcrf
