// The engine's event machinery (uplift, impacts, rest, overturning) against the closed forms
// of the rocking canon: Housner's block (1963) and the Makris–Vassiliou frame (2013).
#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "pcrf/model/rigid_rocker.hpp"
#include "pcrf/record/pulses.hpp"
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

/// The integrator the canon is checked with: each test runs with dopri5 and with Taylor steps.
Integrator g_integrator = Integrator::kDormandPrince5;

class RockingCanon : public ::testing::TestWithParam<Integrator> {
 protected:
  void SetUp() override { g_integrator = GetParam(); }
};

std::shared_ptr<PreparedFrame> rocker(double alpha, double R, double gamma = 0.0, std::optional<double> r = {},
                                      const PhysicsOptions& physics = {}) {
  RockerParameters p;
  p.slenderness_rad = alpha;
  p.size_m = R;
  p.beam_mass_ratio = gamma;
  p.restitution = r;
  return prepare_scene(std::make_unique<RigidRocker>(p), physics);
}

double p_of(double R) { return std::sqrt(3.0 * kGravity_m_s2 / (4.0 * R)); }

/// Time a block released at rest from θ₀ < 0 takes to reach θ = 0, from the nonlinear
/// equation θ̈ = p² sin(α + θ): ∫ dθ / √(2p² (cos(α + θ₀) − cos(α + θ))). With θ = θ₀ + s² the
/// integrand is smooth (cos A − cos B = 2 sin((A + B)/2) sin((B − A)/2), no cancellation).
double first_impact_exact_s(double alpha, double p, double theta0) {
  const auto integrand = [&](double s) {
    const double theta = theta0 + s * s;
    const double drop = 2.0 * std::sin(alpha + 0.5 * (theta0 + theta)) * std::sin(0.5 * s * s);
    return s == 0.0 ? 2.0 / std::sqrt(2.0 * p * p * std::sin(alpha + theta0)) : 2.0 * s / std::sqrt(2.0 * p * p * drop);
  };
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(integrand, 0.0, std::sqrt(-theta0), 15, 1e-14);
}

/// Free rocking from θ₀ = −θ0_over_alpha · α: its history.
test::Trace release(double alpha, double R, double theta0_over_alpha, double seconds, CaseResult& result) {
  PhysicsOptions physics;
  physics.theta0_rad = -theta0_over_alpha * alpha;
  test::Trace trace;
  result = solve_case(*rocker(alpha, R, 0.0, {}, physics), test::quiet_record(seconds, 0.001), test::tight(g_integrator), {},
                      trace.sink());
  return trace;
}

double first_impact_s(const test::Trace& trace) {
  for (const auto& row : trace.samples)
    if (static_cast<std::uint32_t>(row.event) & kEventImpact) return row.t_s;
  return NAN;
}

TEST_P(RockingCanon, FreeRockingReachesItsFirstImpactAtTheExactTime) {
  for (const double alpha : {0.05, 0.25}) {
    CaseResult r;
    const auto trace = release(alpha, 2.0, 0.5, 4.0, r);
    ASSERT_GT(r.impacts, 0);
    const double exact = first_impact_exact_s(alpha, p_of(2.0), -0.5 * alpha);
    EXPECT_NEAR(first_impact_s(trace), exact, 1e-9 * exact) << alpha;
  }
}

TEST_P(RockingCanon, SlenderBlocksApproachHousnersLinearisedPeriod) {
  // T/4 = (1/p) cosh⁻¹(1/(1 − θ₀/α)) holds in the slender limit: the error falls like α².
  double previous = 0.0;
  for (const double alpha : {0.2, 0.1, 0.05}) {
    CaseResult r;
    const auto trace = release(alpha, 2.0, 0.5, 4.0, r);
    const double linear = std::acosh(1.0 / (1.0 - 0.5)) / p_of(2.0);
    const double error = std::abs(first_impact_s(trace) - linear) / linear;
    EXPECT_LT(error, 0.5 * alpha * alpha) << alpha;
    if (previous > 0.0) {
      EXPECT_NEAR(previous / error, 4.0, 0.3) << "second order in alpha at " << alpha;
    }
    previous = error;
  }
}

TEST_P(RockingCanon, AmplitudesDecayAsHousnersRestitutionSays) {
  // Energy before and after each impact: cos(α − θₙ₊₁) = cos α + r² (cos(α − θₙ) − cos α).
  const double alpha = 0.2;
  CaseResult r;
  const auto trace = release(alpha, 1.0, 0.8, 6.0, r);
  std::vector<double> peaks = {0.8 * alpha};
  for (const auto& row : trace.samples)
    if ((static_cast<std::uint32_t>(row.event) & kEventThetaPeak) && row.t_s > 0.0) peaks.push_back(std::abs(row.theta1_rad));
  ASSERT_GE(peaks.size(), 6u);
  const double r2 = r.restitution * r.restitution;
  for (std::size_t n = 0; n + 1 < 6; ++n) {
    const double next = alpha - std::acos(std::cos(alpha) + r2 * (std::cos(alpha - peaks[n]) - std::cos(alpha)));
    EXPECT_NEAR(peaks[n + 1], next, 1e-9) << "peak " << n + 1;
  }
  EXPECT_NEAR(r.restitution, 1.0 - 1.5 * std::sin(alpha) * std::sin(alpha), 1e-15);
}

TEST_P(RockingCanon, TheBlockLiftsExactlyWhenTheGroundExceedsGTanAlpha) {
  const double alpha = 0.15, k = 0.5 * kGravity_m_s2;  // a ramp of 0.5 g/s
  std::vector<double> a;
  for (int i = 0; i <= 100; ++i) a.push_back(k * 0.01 * i);
  const CaseResult r = solve_case(*rocker(alpha, 1.0), GroundMotion("ramp", 0.01, a), {}, {});
  EXPECT_NEAR(r.t_uplift_s, kGravity_m_s2 * std::tan(alpha) / k, 1e-12);
}

TEST_P(RockingCanon, TheRockingFrameRespondsAsTheBlockOfSizeRHat) {
  // Makris & Vassiliou (2013): the same response as the block R̂ = R(1 + 3γ)/(1 + 2γ) when both
  // have the same restitution (the frame's own is given to the block).
  const double alpha = 0.2, R = 1.0;
  // A 0.4 s one-sine pulse of 0.6 g rocks the frame through many impacts; a 0.8 s one
  // overturns it after one.
  for (const double period_s : {0.4, 0.8}) {
    PulseSpec pulse;
    pulse.shape = PulseShape::kSine;
    pulse.period_s = period_s;
    pulse.amplitude_g = 0.6;
    pulse.duration_s = 8.0;
    const GroundMotion g = make_pulse(pulse);
    for (const double gamma : {0.5, 2.0}) {
      SCOPED_TRACE("Tp " + std::to_string(period_s) + " gamma " + std::to_string(gamma));
      const double r = RigidRocker::restitution_from_momentum(alpha, gamma);
      const CaseResult frame = solve_case(*rocker(alpha, R, gamma), g, test::tight(g_integrator), {});
      const CaseResult block =
          solve_case(*rocker(alpha, R * (1 + 3 * gamma) / (1 + 2 * gamma), 0.0, r), g, test::tight(g_integrator), {});
      ASSERT_GT(frame.impacts, 0);
      EXPECT_EQ(frame.impacts, block.impacts);
      EXPECT_EQ(frame.status, block.status);
      EXPECT_NEAR(frame.theta_max_rad, block.theta_max_rad, 1e-9 * block.theta_max_rad);
      EXPECT_NEAR(frame.t_theta_max_s, block.t_theta_max_s, 1e-9 * block.t_theta_max_s);
      EXPECT_NEAR(frame.omega_max_rad_s, block.omega_max_rad_s, 1e-9 * block.omega_max_rad_s);
      EXPECT_NEAR(frame.t_end_s, block.t_end_s, 1e-9 * block.t_end_s);
    }
  }
}

TEST_P(RockingCanon, ABlockOverturnsOnlyWhenItFalls) {
  // Past θ = α the ground can still bring a block back; a case ends as overturned at π/2.
  const double alpha = 0.25;
  PhysicsOptions physics;
  physics.theta0_rad = -1.05 * alpha;  // released just past its static limit: it falls
  const CaseResult fallen = solve_case(*rocker(alpha, 1.0, 0.0, {}, physics), test::quiet_record(5.0), {}, {});
  EXPECT_EQ(fallen.status, CaseStatus::kOverturned);
  EXPECT_NEAR(fallen.theta_max_rad, 0.5 * M_PI, 1e-6);
  physics.theta0_rad = -0.95 * alpha;  // just inside: it rocks back
  const CaseResult back = solve_case(*rocker(alpha, 1.0, 0.0, {}, physics), test::quiet_record(5.0), {}, {});
  EXPECT_NE(back.status, CaseStatus::kOverturned);
  EXPECT_GT(back.impacts, 0);
}

}  // namespace
}  // namespace pcrf

namespace pcrf {
namespace {

/// The least one-sine (type A) amplitude, over g α, that overturns a slender block without an
/// impact (after Zhang & Makris 2001), from the linearised equation ü − p²u = p²(a/g − α)
/// with u = |θ|: the block lifts at sin(ω t_u) = 1/β and, after the pulse, u − α grows
/// without bound exactly when u(T) − α + u̇(T)/p ≥ 0, which works out to
///     (√(β² − 1) − Ω) exp((2π − asin(1/β))/Ω) = β,   Ω = ω_p/p.
double no_impact_overturning_beta(double omega_ratio) {
  const auto residual = [omega_ratio](double beta) {
    return (std::sqrt(beta * beta - 1.0) - omega_ratio) * std::exp((2.0 * M_PI - std::asin(1.0 / beta)) / omega_ratio) -
           beta;
  };
  double lo = std::sqrt(1.0 + omega_ratio * omega_ratio), hi = lo;  // the bracket starts where the root's factor turns positive
  while (residual(hi) < 0.0) hi *= 1.5;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// The engine's least amplitude (over g α) at which a one-sine pulse overturns the block
/// before its first impact, to 1e-6 by bisection.
double engine_no_impact_overturning_beta(double alpha, double R, double omega_ratio) {
  PhysicsOptions physics;
  physics.tail_s = 20.0;
  const auto block = rocker(alpha, R, 0.0, {}, physics);
  const double p = p_of(R), period_s = 2.0 * M_PI / (omega_ratio * p);
  auto overturns_without_impact = [&](double beta) {
    PulseSpec pulse;
    pulse.shape = PulseShape::kSine;
    pulse.period_s = period_s;
    pulse.amplitude_g = beta * std::tan(alpha);
    pulse.dt_s = period_s / 2000.0;
    const CaseResult r = solve_case(*block, make_pulse(pulse), test::tight(g_integrator), {});
    return r.status == CaseStatus::kOverturned && r.impacts == 0;
  };
  double lo = 1.0, hi = 2.0;
  while (!overturns_without_impact(hi)) lo = hi, hi *= 1.5;
  while (hi - lo > 1e-6 * hi) {
    const double mid = 0.5 * (lo + hi);
    (overturns_without_impact(mid) ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST_P(RockingCanon, OneSineOverturningWithoutImpactMatchesTheClosedFormForSlenderBlocks) {
  // The closed form is the slender (linearised) limit: the engine, which keeps sin and cos,
  // approaches it as α² (measured: 2.3499 against 2.34990 at ω_p/p = 2, 5.2391 against 5.23896 at
  // 4, 14.8725 against 14.8714 at 8, for α = 0.01).
  for (const double omega_ratio : {2.0, 4.0, 8.0}) {
    const double closed = no_impact_overturning_beta(omega_ratio);
    double previous = 0.0;
    for (const double alpha : {0.04, 0.02, 0.01}) {
      const double engine = engine_no_impact_overturning_beta(alpha, 1.0, omega_ratio);
      const double error = std::abs(engine - closed) / closed;
      EXPECT_LT(error, alpha * alpha) << "omega_p/p " << omega_ratio << " alpha " << alpha << ": engine " << engine
                                    << ", closed form " << closed;
      if (previous > 0.0) {
        EXPECT_LT(error, 0.35 * previous) << "second order in alpha: omega_p/p " << omega_ratio << " alpha " << alpha;
      }
      previous = error;
    }
  }
}

/// The block's verdict under one pulse: overturned or not, and its impacts.
struct PulseVerdict {
  bool overturned;
  long impacts;
};
PulseVerdict under_pulse(double alpha, double p_rad_s, std::optional<double> restitution, PulseShape shape,
                         double period_s, double amplitude_g) {
  PhysicsOptions physics;
  physics.tail_s = 30.0;
  const double R = 3.0 * kGravity_m_s2 / (4.0 * p_rad_s * p_rad_s);
  PulseSpec pulse;
  pulse.shape = shape;
  pulse.period_s = period_s;
  pulse.amplitude_g = amplitude_g;
  pulse.dt_s = period_s / 2000.0;
  const CaseResult r = solve_case(*rocker(alpha, R, 0.0, restitution, physics), make_pulse(pulse), test::tight(g_integrator), {});
  return {r.status == CaseStatus::kOverturned, r.impacts};
}

TEST_P(RockingCanon, PublishedOverturningAmplitudesOfTheNonlinearBlock) {
  // Makris & Konstantinidis (2003), EESD 32(2), Fig. 4 and its text: p = 2 rad/s, alpha = 15 deg,
  // Housner's restitution, a 2-s one-cosine (type B) pulse: 0.315 g is on the verge, 0.316 g overturns.
  const double alpha15 = 15.0 * M_PI / 180.0;
  EXPECT_FALSE(under_pulse(alpha15, 2.0, {}, PulseShape::kCosine, 2.0, 0.315).overturned);
  EXPECT_TRUE(under_pulse(alpha15, 2.0, {}, PulseShape::kCosine, 2.0, 0.316).overturned);
  // Zhang & Makris (2001), J. Eng. Mech. 127(5), p. 480, nonlinear formulation: alpha = 0.25 rad,
  // p = 2.14 rad/s, restitution 0.9, one-sine (type A) pulse of 15.7 rad/s: least overturning
  // amplitude 2.22 g, after one impact (mode 1). 2.215 g is safe, 2.225 g overturns after one.
  const double period_s = 2.0 * M_PI / 15.7;
  EXPECT_FALSE(under_pulse(0.25, 2.14, 0.9, PulseShape::kSine, period_s, 2.215).overturned);
  const auto mode1 = under_pulse(0.25, 2.14, 0.9, PulseShape::kSine, period_s, 2.225);
  EXPECT_TRUE(mode1.overturned);
  EXPECT_EQ(mode1.impacts, 1);
}

TEST_P(RockingCanon, TheOneSineSafeCapeBetweenTheTwoOverturningModes) {
  // Zhang & Makris (2001), Figs. 7 and 8 (linearised formulation, restitution 0.9, omega_p/p = 5):
  // the block overturns after one impact from a_p = 3.01 alpha g to 6.32 alpha g, survives from
  // 6.33 to 7.17 alpha g and overturns without an impact from 7.18 alpha g. A slender block
  // (alpha = 0.01: the linear limit) shows the same three regions; the points are taken 0.3-1 %
  // inside them (the engine's boundaries: 3.0187, 6.3209, 7.1707; docs/rocking_canon.md).
  const double alpha = 0.01, p = 2.14, period_s = 2.0 * M_PI / (5.0 * p);
  auto at = [&](double beta) { return under_pulse(alpha, p, 0.9, PulseShape::kSine, period_s, beta * alpha); };
  EXPECT_FALSE(at(2.99).overturned);
  for (const double beta : {3.03, 4.5, 6.30}) {
    const auto v = at(beta);
    EXPECT_TRUE(v.overturned) << beta;
    EXPECT_EQ(v.impacts, 1) << beta;
  }
  for (const double beta : {6.35, 6.8, 7.15}) EXPECT_FALSE(at(beta).overturned) << beta;
  const auto mode2 = at(7.20);
  EXPECT_TRUE(mode2.overturned);
  EXPECT_EQ(mode2.impacts, 0);
}

INSTANTIATE_TEST_SUITE_P(Integrators, RockingCanon, ::testing::Values(Integrator::kDormandPrince5, Integrator::kTaylor),
                         test::integrator_test_name);

}  // namespace
}  // namespace pcrf
