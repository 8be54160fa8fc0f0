// The rocking solver: odd symmetry, rest below the threshold, return to rest, status,
// convergence as tolerances tighten, agreement between integrators.
#include <gtest/gtest.h>

#include <cmath>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/model/rigid_rocker.hpp"
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

/// Every integrator that locates its events (the registry's; the fixed-step contender
/// takes a step's worth of θ₁ past an impact, so neither a mirrored motion bit for bit nor a
/// located peak that converges is its to give).
class EveryIntegrator : public ::testing::TestWithParam<Integrator> {};

TEST_P(EveryIntegrator, MirroredRecordGivesTheMirroredResponse) {
  // The prestressed frame, and the block (whose series the Taylor steps take).
  RockerParameters block;
  block.slenderness_rad = 0.2;
  block.size_m = 1.0;
  SolverSettings settings;
  settings.integrator = GetParam();
  const std::shared_ptr<PreparedFrame> scenes[] = {prepare_frame(basic_frame(), {}),
                                                   prepare_scene(std::make_unique<RigidRocker>(block), {})};
  for (const auto& frame : scenes) {
    const bool tendons = frame == scenes[0];
    SCOPED_TRACE(tendons ? "frame" : "block");
    const GroundMotion rec = tendons ? test::strong_record(3) : test::strong_record(3).scaled(0.25);
    test::Trace a, b;
    const CaseResult ra = solve_case(*frame, rec, settings, {}, a.sink());
    const CaseResult rb = solve_case(*frame, rec.scaled(-1.0), settings, {}, b.sink());
    ASSERT_GT(ra.impacts, 3);
    EXPECT_EQ(ra.status, rb.status);
    EXPECT_EQ(ra.impacts, rb.impacts);
    EXPECT_DOUBLE_EQ(ra.theta_max_rad, rb.theta_max_rad);
    EXPECT_DOUBLE_EQ(ra.t_theta_max_s, rb.t_theta_max_s);
    EXPECT_DOUBLE_EQ(ra.omega_max_rad_s, rb.omega_max_rad_s);
    EXPECT_DOUBLE_EQ(ra.t_uplift_s, rb.t_uplift_s);
    test::expect_mirrored(a, b, tendons);
  }
}

TEST(RockingSolver, SubThresholdMotionNeverLifts) {
  const Frame frame = basic_frame();
  const EquationOfMotion eom(frame);
  const GroundMotion raw = test::strong_record(5);
  const double scale = 0.98 * eom.uplift_threshold_m_s2() / raw.pga_m_s2();
  const CaseResult r = solve_case(frame, raw.scaled(scale), {}, {});
  EXPECT_EQ(r.status, CaseStatus::kAtRest);
  EXPECT_EQ(r.impacts, 0);
  EXPECT_EQ(r.theta_max_rad, 0.0);
  EXPECT_TRUE(std::isnan(r.t_uplift_s));
  EXPECT_EQ(r.counts.steps, 0);  // nothing to integrate while at rest
  EXPECT_FALSE(std::isnan(r.t_trigger_paper_s));  // the paper's criterion was met
  // Just above the threshold it lifts, at the first exceedance.
  const double scale_up = 1.02 * eom.uplift_threshold_m_s2() / raw.pga_m_s2();
  const CaseResult up = solve_case(frame, raw.scaled(scale_up), {}, {});
  EXPECT_GT(up.theta_max_rad, 0.0);
  EXPECT_FALSE(std::isnan(up.t_uplift_s));
  EXPECT_NEAR(std::abs(raw.scaled(scale_up).accel_m_s2(up.t_uplift_s)), eom.uplift_threshold_m_s2(), 1e-9);
}

TEST(RockingSolver, FreeRockingReturnsToRestInFiniteTimeWithFiniteImpacts) {
  const Frame frame = basic_frame();
  PhysicsOptions physics;
  physics.theta0_rad = -0.02;
  test::Trace trace;
  const CaseResult r = solve_case(frame, test::quiet_record(20.0), physics, {}, {}, trace.sink());
  EXPECT_EQ(r.status, CaseStatus::kAtRest);
  EXPECT_GT(r.impacts, 10);
  EXPECT_LT(r.impacts, 1000);
  // Once at rest the frame stays there: the last sample is exactly at rest and the last
  // non-zero rotation is well before the end of the record.
  ASSERT_FALSE(trace.samples.empty());
  EXPECT_EQ(trace.samples.back().theta1_rad, 0.0);
  double last_motion = 0.0;
  for (const auto& s : trace.samples) {
    if (s.theta1_rad != 0.0) last_motion = s.t_s;
  }
  EXPECT_LT(last_motion, 15.0);
  // Amplitude decays: peak at the start.
  EXPECT_DOUBLE_EQ(r.theta_max_rad, 0.02);
}

TEST(RockingSolver, RestingFrameUnderLongSubThresholdMotionStaysClosed) {
  // A frame at rest under a long harmonic motion just below the threshold: no step, no
  // impact, no spurious chatter.
  const Frame frame = basic_frame();
  const EquationOfMotion eom(frame);
  SinePulseSpec weak;
  weak.amplitude_g = 0.999 * eom.uplift_threshold_m_s2() / kGravity_m_s2;
  weak.period_s = 0.3;
  weak.cycles = 60;
  weak.duration_s = 20.0;
  weak.dt_s = 0.005;
  const CaseResult r = solve_case(frame, make_sine_pulse_train(weak), {}, {});
  EXPECT_EQ(r.status, CaseStatus::kAtRest);
  EXPECT_EQ(r.impacts, 0);
  EXPECT_EQ(r.counts.steps, 0);
}

TEST(RockingSolver, PaperAndPhysicalCriteriaGiveTheSameMotion) {
  // docs/physics.md "Uplift criteria": after the paper's trigger the prestress still holds the
  // frame closed and the contact cannot pull, so the motion is the same.
  const Frame frame = basic_frame();
  const GroundMotion rec = test::strong_record(11);
  PhysicsOptions paper;
  paper.uplift = UpliftCriterion::kPaper;
  const CaseResult a = solve_case(frame, rec, {}, {});
  const CaseResult b = solve_case(frame, rec, paper, {});
  EXPECT_EQ(a.theta_max_rad, b.theta_max_rad);
  EXPECT_EQ(a.t_uplift_s, b.t_uplift_s);
  EXPECT_EQ(a.impacts, b.impacts);
  EXPECT_EQ(a.t_trigger_paper_s, b.t_trigger_paper_s);
  EXPECT_LT(a.t_trigger_paper_s, a.t_uplift_s);
}

TEST_P(EveryIntegrator, ThetaMaxConvergesAsToleranceTightens) {
  // A two-cycle pulse: θ_max comes in the first excursions, before the response has had
  // time to amplify perturbations (long random records are ill-conditioned: a 1e-8
  // relative change of the record moves θ_max by ~1e-4; see docs/results.md, "Speed and accuracy").
  const Frame frame = basic_frame();
  SinePulseSpec pulse;
  pulse.amplitude_g = 1.5;
  const GroundMotion rec = make_sine_pulse_train(pulse);
  {
    const Integrator integrator = GetParam();
    std::vector<double> theta;
    for (double rtol : {1e-5, 1e-7, 1e-9, 1e-12}) {
      SolverSettings s;
      s.integrator = integrator;
      s.rtol = rtol;
      s.atol_theta_rad = rtol * 1e-3;
      s.atol_omega_rad_s = rtol * 1e-2;
      theta.push_back(solve_case(frame, rec, {}, s).theta_max_rad);
    }
    const double ref = theta.back();
    const double e5 = std::abs(theta[0] - ref) / ref, e7 = std::abs(theta[1] - ref) / ref,
                 e9 = std::abs(theta[2] - ref) / ref;
    EXPECT_LT(e5, 1e-2) << to_string(integrator);
    EXPECT_LT(e7, 1e-4) << to_string(integrator);
    EXPECT_LT(e9, 1e-6) << to_string(integrator);
    EXPECT_LT(e9, e5) << to_string(integrator);
  }
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryIntegrator, ::testing::ValuesIn(test::event_locating_integrators()),
                         test::integrator_test_name);

TEST(RockingSolver, IntegratorsAgreeAtTightTolerance) {
  const Frame frame = basic_frame();
  const GroundMotion rec = test::strong_record(4);
  const CaseResult ref = solve_case(frame, rec, {}, test::tight(Integrator::kCvodeAdams));
  ASSERT_GT(ref.theta_max_rad, 0.0);
  for (Integrator i : {Integrator::kCvodeBdf, Integrator::kArkodeErk5, Integrator::kArkodeErk8}) {
    const CaseResult r = solve_case(frame, rec, {}, test::tight(i));
    EXPECT_NEAR(r.theta_max_rad, ref.theta_max_rad, 1e-7 * ref.theta_max_rad) << to_string(i);
    EXPECT_NEAR(r.t_theta_max_s, ref.t_theta_max_s, 1e-6) << to_string(i);
    EXPECT_NEAR(r.omega_max_rad_s, ref.omega_max_rad_s, 1e-6 * ref.omega_max_rad_s) << to_string(i);
    EXPECT_EQ(r.status, ref.status) << to_string(i);
  }
}

TEST(RockingSolver, TendonFractureIsAStatus) {
  const Frame frame = basic_frame();
  PhysicsOptions physics;
  physics.fracture_strain = 0.003;  // low, so the strong record breaks a tendon
  const CaseResult r = solve_case(frame, test::strong_record(3), physics, {});
  EXPECT_EQ(r.status, CaseStatus::kTendonFracture);
  EXPECT_NEAR(std::max(r.strain_column_max, r.strain_beam_max), 0.003, 1e-9);
  EXPECT_LT(r.t_end_s, 12.0);
}

TEST(RockingSolver, FreeVibrationTailExtendsTheCaseUntilRest) {
  const Frame frame = basic_frame();
  SinePulseSpec pulse;
  pulse.amplitude_g = 1.5;
  pulse.duration_s = 1.0;  // the record ends while the frame still rocks
  const GroundMotion rec = make_sine_pulse_train(pulse);
  const CaseResult no_tail = solve_case(frame, rec, test::record_only(), {});
  EXPECT_EQ(no_tail.status, CaseStatus::kRockingAtEnd);
  EXPECT_DOUBLE_EQ(no_tail.t_end_s, 1.0);
  PhysicsOptions physics;
  physics.tail_s = 20.0;
  const CaseResult tail = solve_case(frame, rec, physics, {});
  EXPECT_EQ(tail.status, CaseStatus::kAtRest);
  EXPECT_DOUBLE_EQ(tail.t_end_s, 21.0);
  EXPECT_GT(tail.impacts, no_tail.impacts);
  EXPECT_EQ(tail.theta_max_rad, no_tail.theta_max_rad);  // the peak came during the pulse
  // The default tail goes on until the frame rests, and ends there: the same motion as the
  // fixed tail (the frame rests well before 21 s), ending at the return to rest.
  const CaseResult until_rest = solve_case(frame, rec, {}, {});
  EXPECT_EQ(until_rest.status, CaseStatus::kAtRest);
  EXPECT_GT(until_rest.t_end_s, 1.0);
  EXPECT_LT(until_rest.t_end_s, 21.0);
  EXPECT_EQ(until_rest.impacts, tail.impacts);
  EXPECT_EQ(until_rest.theta_max_rad, tail.theta_max_rad);
  // A cap shorter than the rocking leaves it unresolved: still rocking, not at rest.
  PhysicsOptions capped;
  capped.max_tail_s = 0.05;
  const CaseResult short_cap = solve_case(frame, rec, capped, {});
  EXPECT_EQ(short_cap.status, CaseStatus::kRockingAtEnd);
  EXPECT_TRUE(is_unresolved(short_cap.status));
  EXPECT_FALSE(has_verdict(short_cap.status));
  EXPECT_DOUBLE_EQ(short_cap.t_end_s, 1.05);
}

TEST(RockingSolver, SkippingTheOmegaPeakLeavesItUnset) {
  OutputRequest request;
  request.omega_peak = false;
  const CaseResult r = solve_case(basic_frame(), test::strong_record(3), {}, {}, request);
  EXPECT_TRUE(std::isnan(r.omega_max_rad_s));
  EXPECT_TRUE(std::isnan(r.t_omega_max_s));
  EXPECT_GT(r.theta_max_rad, 0.0);
  const CaseResult full = solve_case(basic_frame(), test::strong_record(3), {}, {});
  EXPECT_LT(r.counts.root_evals, full.counts.root_evals + 1);  // never more work
  EXPECT_NEAR(r.theta_max_rad, full.theta_max_rad, 1e-6 * full.theta_max_rad);
}

TEST(RockingSolver, InvalidSettingsThrow) {
  SolverSettings s;
  s.rtol = -1;
  EXPECT_THROW(solve_case(basic_frame(), test::quiet_record(1.0), {}, s), std::invalid_argument);
}

}  // namespace
}  // namespace pcrf
