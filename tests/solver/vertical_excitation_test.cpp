// Vertical shaking (docs/vertical_excitation.md): ü_v adds to gravity in Eq. (31), so
//  - a constant ü_v = c·g is the same frame standing in gravity (1 + c)·g;
//  - the uplift threshold moves with ü_v at each instant;
//  - mirroring the horizontal mirrors the response, the vertical staying as it is;
//  - between impacts T + V changes by the work of the ground in the moving frame,
//    dE/dt = θ̇₁ (S ü_h − G ü_v).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pcrf/excitation/excitation.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

/// A record of `n` samples every `dt_s` with a(t) = f(t).
template <class F>
GroundMotion record_of(const char* name, std::size_t n, double dt_s, F f) {
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = f(static_cast<double>(i) * dt_s);
  return GroundMotion(name, dt_s, std::move(a));
}

/// A one-sine pulse that rocks the basic frame through a few impacts and back to rest.
GroundMotion pulse(std::size_t n, double dt_s) {
  return record_of("pulse", n, dt_s, [](double t) {
    return t < 0.5 ? 1.6 * kGravity_m_s2 * std::sin(2.0 * M_PI * t / 0.5) : 0.0;
  });
}

void expect_same_response(const CaseResult& a, const CaseResult& b, double rtol) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.impacts, b.impacts);
  EXPECT_NEAR(a.t_uplift_s, b.t_uplift_s, rtol * b.t_uplift_s);
  EXPECT_NEAR(a.theta_max_rad, b.theta_max_rad, rtol * b.theta_max_rad);
  EXPECT_NEAR(a.t_theta_max_s, b.t_theta_max_s, rtol * b.t_theta_max_s);
  EXPECT_NEAR(a.omega_max_rad_s, b.omega_max_rad_s, rtol * b.omega_max_rad_s);
  EXPECT_NEAR(a.t_end_s, b.t_end_s, rtol * b.t_end_s);
}

class ConstantVertical : public ::testing::TestWithParam<double> {};

TEST_P(ConstantVertical, IsTheSameFrameInAChangedGravity) {
  const double c = GetParam();
  const double dt = 0.001;
  const std::size_t n = 3001;
  const GroundMotion h = pulse(n, dt);
  const GroundMotion v = record_of("up", n, dt, [c](double) { return c * kGravity_m_s2; });
  const Frame frame = basic_frame();
  Frame heavier = frame;
  heavier.gravity_m_s2 = (1.0 + c) * kGravity_m_s2;
  for (const Integrator integrator : {Integrator::kCvodeAdams, Integrator::kArkodeErk8, Integrator::kCvodeBdf}) {
    SCOPED_TRACE(to_string(integrator));
    const CaseResult shaken = solve_case(frame, Excitation(h, &v), test::record_only(), test::tight(integrator));
    const CaseResult in_gravity = solve_case(heavier, h, test::record_only(), test::tight(integrator));
    ASSERT_GT(in_gravity.impacts, 0) << "the pulse must rock the frame";
    // The two differ only in how g + c·g and (1 + c)·g round: far below the tolerances.
    expect_same_response(shaken, in_gravity, 1e-9);
    // The reported threshold is the frame's own, without vertical shaking (MODEL.md).
    EXPECT_NEAR(shaken.uplift_threshold_g, 1.021372, 1e-6);
    EXPECT_EQ(in_gravity.uplift_threshold_g > shaken.uplift_threshold_g, c > 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(UpAndDown, ConstantVertical, ::testing::Values(0.25, -0.2));

TEST(VerticalExcitation, UpliftWaitsForTheThresholdOfThatInstant) {
  // ü_h = k t and ü_v = m t, both exact in a linear record: the frame opens where
  // k t = threshold(ü_v(t)) = threshold₀ + λ_g m t, i.e. at t* = threshold₀ / (k − λ_g m).
  const Frame frame = basic_frame();
  const EquationOfMotion eom(frame);
  const double k = 1.0 * kGravity_m_s2;  // [m/s³]
  const double dt = 0.01;
  const std::size_t n = 301;
  const GroundMotion h = record_of("ramp", n, dt, [k](double t) { return k * t; });
  const double t_alone = eom.uplift_threshold_m_s2() / k;
  for (const double m : {0.5 * kGravity_m_s2, -0.5 * kGravity_m_s2}) {
    const GroundMotion v = record_of("up", n, dt, [m](double t) { return m * t; });
    const double predicted = eom.uplift_threshold_m_s2() / (k - eom.lambda_g() * m);
    for (const Integrator integrator : {Integrator::kCvodeAdams, Integrator::kFixedRk4SignChange}) {
      SCOPED_TRACE(to_string(integrator) + " m = " + std::to_string(m));
      SolverSettings solver;
      solver.integrator = integrator;
      solver.fixed_step_s = 1e-3;
      const CaseResult r = solve_case(frame, Excitation(h, &v), {}, solver);
      EXPECT_NEAR(r.t_uplift_s, predicted, 1e-12 * predicted);
      EXPECT_GT(std::abs(r.t_uplift_s - t_alone), 0.01) << "the vertical moved the uplift";
      EXPECT_EQ(m > 0.0, r.t_uplift_s > t_alone) << "upward acceleration holds the frame longer";
    }
  }
}

TEST(VerticalExcitation, MirroringTheHorizontalMirrorsTheResponse) {
  const Frame frame = basic_frame();
  const GroundMotion h = test::strong_record(3);
  StochasticSpec spec;
  spec.seed = 11;
  spec.pga_g = 0.5;
  spec.duration_s = h.duration_s();
  spec.dt_s = h.dt_s();
  const GroundMotion v = make_stochastic(spec);
  ASSERT_EQ(v.size(), h.size());
  const GroundMotion mirrored = h.scaled(-1.0);
  test::Trace a, b;
  const CaseResult ra = solve_case(frame, Excitation(h, &v), {}, {}, {}, a.sink());
  const CaseResult rb = solve_case(frame, Excitation(mirrored, &v), {}, {}, {}, b.sink());
  const CaseResult alone = solve_case(frame, h, {}, {});
  ASSERT_GT(ra.impacts, 3);
  EXPECT_NE(ra.theta_max_rad, alone.theta_max_rad) << "the vertical changed the response";
  EXPECT_EQ(ra.impacts, rb.impacts);
  EXPECT_EQ(ra.theta_max_rad, rb.theta_max_rad);
  EXPECT_EQ(ra.t_theta_max_s, rb.t_theta_max_s);
  EXPECT_EQ(ra.t_uplift_s, rb.t_uplift_s);
  test::expect_mirrored(a, b);
}

TEST(VerticalExcitation, EnergyChangesByTheVerticalWorkBetweenImpacts) {
  // Released from θ₁ = −0.02 with no horizontal motion under a vertical sine of 0.3 g:
  // until the first impact, E(t) − E(0) = −∫ θ̇₁ G(θ₁) ü_v dt (trapezoid over 0.1 ms rows).
  const Frame frame = basic_frame();
  const EquationOfMotion eom(frame);
  const double dt = 1e-4;
  const std::size_t n = 20001;
  const GroundMotion h = record_of("still", n, dt, [](double) { return 0.0; });
  const GroundMotion v = record_of("up", n, dt, [](double t) { return 0.3 * kGravity_m_s2 * std::sin(2 * M_PI * 3.0 * t); });
  PhysicsOptions physics = test::record_only();
  physics.theta0_rad = -0.02;
  test::Trace trace;
  const CaseResult r = solve_case(frame, Excitation(h, &v), physics, test::tight(), {}, trace.sink());
  ASSERT_GT(r.impacts, 0);
  const double e0 = eom.energy(-0.02, 0.0, -1);
  double work = 0.0, largest_work = 0.0;
  int checked = 0;
  auto power = [&](const HistorySample& s) {
    EomTerms t;
    eom.terms(s.theta1_rad, -1, t);
    return -s.omega1_rad_s * t.G * v.accel_m_s2(s.t_s);
  };
  for (std::size_t i = 1; i < trace.samples.size(); ++i) {
    const HistorySample& s = trace.samples[i];
    if (s.theta1_rad == 0.0) break;  // the first impact
    work += 0.5 * (power(trace.samples[i - 1]) + power(s)) * (s.t_s - trace.samples[i - 1].t_s);
    largest_work = std::max(largest_work, std::abs(work));
    const double change = eom.energy(s.theta1_rad, s.omega1_rad_s, -1) - e0;
    EXPECT_NEAR(change, work, 1e-6 * (e0 - eom.energy(0.0, 0.0, -1))) << "t = " << s.t_s;
    ++checked;
  }
  EXPECT_GT(checked, 100);
  // The vertical work (2 % of the energy here) is 10⁴ times the tolerance: an error in it would show.
  EXPECT_GT(largest_work, 0.01 * (e0 - eom.energy(0.0, 0.0, -1)));
}

}  // namespace
}  // namespace pcrf

namespace pcrf {
namespace {

TEST(VerticalExcitation, AGroundFallingFasterThanGravityEndsTheCaseThere) {
  // ü_v = −1.5 g · t/(1 s) reaches −g at t = 2/3 s: the case ends there, whether the frame
  // rests (no horizontal) or rocks (a strong pulse), for every integrator; never a NaN.
  const double dt = 0.001;
  const std::size_t n = 1501;
  const GroundMotion v = record_of("falling", n, dt, [](double t) { return -1.5 * kGravity_m_s2 * t; });
  const GroundMotion still = record_of("still", n, dt, [](double) { return 0.0; });
  const GroundMotion shaken = record_of("pulse", n, dt, [](double t) { return 1.3 * kGravity_m_s2 * std::sin(2 * M_PI * t / 0.4); });
  const double t_fall = 2.0 / 3.0;
  for (const GroundMotion* h : {&still, &shaken}) {
    for (const Integrator integrator : {Integrator::kCvodeAdams, Integrator::kArkodeErk5, Integrator::kFixedRk4SignChange}) {
      SCOPED_TRACE(h->name() + " " + to_string(integrator));
      SolverSettings solver;
      solver.integrator = integrator;
      solver.fixed_step_s = 1e-4;
      const CaseResult r = solve_case(basic_frame(), Excitation(*h, &v), {}, solver);
      EXPECT_EQ(r.status, CaseStatus::kGroundFreeFall);
      EXPECT_NEAR(r.t_end_s, t_fall, 1e-12);
      EXPECT_NE(r.message.find("fell faster than gravity"), std::string::npos) << r.message;
      EXPECT_FALSE(std::isnan(r.theta_max_rad));
      EXPECT_EQ(h == &shaken, r.theta_max_rad > 0.0);
      EXPECT_FALSE(has_verdict(r.status));
    }
  }
  // A vertical that stays above −g never ends a case early.
  const GroundMotion shallow = record_of("shallow", n, dt, [](double t) { return -0.9 * kGravity_m_s2 * t / 1.5; });
  EXPECT_EQ(solve_case(basic_frame(), Excitation(still, &shallow), {}, {}).status, CaseStatus::kAtRest);
}

}  // namespace
}  // namespace pcrf
