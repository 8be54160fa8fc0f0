// The root search shared by the event-locating integrators (src/solver/integrator/root_search.hpp) and
// the breakpoint cursor of integrators.hpp: the local model's step, the bracketed search with
// and without the curvature (probes counted, the reported root past the crossing and within
// the tolerance of it), and NextSample against SampleGrid::next_after.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "solver/integrator/integrator.hpp"  // private to the solver: the test calls them directly
#include "solver/integrator/root_search.hpp"

namespace pcrf {
namespace {

using detail::model_step;
using detail::newton_in_bracket;

TEST(ModelStep, WithoutCurvatureIsNewtonsStepBitForBit) {
  for (const double v : {1e-3, -2.5, 7e-12})
    for (const double slope : {-3.0, 0.125, 9e5}) EXPECT_EQ(model_step(v, slope, 0.0), -v / slope);
}

TEST(ModelStep, IsTheRootOfAQuadraticNearestZero) {
  // v + s·δ + ½c·δ² with roots δ = 0.01 and δ = −3: the step is the near one.
  const double r1 = 0.01, r2 = -3.0, half_c = 2.0;
  const double v = half_c * r1 * r2, s = -half_c * (r1 + r2), c = 2.0 * half_c;
  EXPECT_NEAR(model_step(v, s, c), r1, 1e-15);
  // At a double root's shoulder (slope 0) Newton's step is infinite, the model's exact (the
  // two roots ±10⁻³ are equally near).
  EXPECT_NEAR(std::abs(model_step(1e-6, 0.0, -2.0)), 1e-3, 1e-15);
  // No real root of the model: Newton's step.
  EXPECT_EQ(model_step(1.0, 0.5, 4.0), -1.0 / 0.5);
}

/// The search on f(t) = a − b·t² (a flight leaving where its acceleration is nearly zero:
/// θ̇ = ω₀ − b t², slope 0 at t = 0) over [0, 1]; its root √(a/b).
struct Shoulder {
  double a = 2e-4, b = 1.0;
  double f(double t) const { return a - b * t * t; }
  double root() const { return std::sqrt(a / b); }
};

int probes_to_locate(const Shoulder& s, bool curvature, double& lo, double& hi, double ttol) {
  int probes = 0;
  double glo = s.f(lo), ghi = s.f(hi);
  newton_in_bracket(
      [&](double t, double& v, double& slope, double& c) {
        ++probes;
        v = s.f(t);
        slope = -2.0 * s.b * t;
        c = curvature ? -2.0 * s.b : 0.0;
      },
      lo, glo, hi, ghi, ttol);
  return probes;
}

TEST(NewtonInBracket, TheCurvatureLocatesAShoulderRootInFewProbes) {
  const Shoulder s;
  const double ttol = 1e-13;
  double lo_n = 0.0, hi_n = 1.0, lo_c = 0.0, hi_c = 1.0;
  const int newton = probes_to_locate(s, false, lo_n, hi_n, ttol);
  const int model = probes_to_locate(s, true, lo_c, hi_c, ttol);
  EXPECT_LE(model, 4);
  EXPECT_LT(model, newton);
  // Both report a time past the root (the function has changed sign there) within ttol of it.
  for (const double hi : {hi_n, hi_c}) {
    EXPECT_LT(s.f(hi), 0.0);
    EXPECT_GE(hi, s.root());
    EXPECT_LE(hi - s.root(), ttol);
  }
  EXPECT_LE(hi_n - lo_n, ttol);  // without the curvature the bracket is closed from both sides
}

TEST(NewtonInBracket, WithTheCurvatureEndsOnAProbePastTheRoot) {
  // A smooth crossing, started at the secant: the model steps aim past the root, and the
  // search ends on the first probe that crossed with a step back below half the tolerance.
  const double ttol = 1e-13, root = 0.3;
  auto f = [&](double t) { return std::sin(t - root) * (2.0 + t); };
  auto df = [&](double t) { return std::cos(t - root) * (2.0 + t) + std::sin(t - root); };
  auto d2f = [&](double t) { return -std::sin(t - root) * (2.0 + t) + 2.0 * std::cos(t - root); };
  double lo = 0.0, hi = 1.0, glo = f(lo), ghi = f(hi);
  int probes = 0;
  newton_in_bracket(
      [&](double t, double& v, double& slope, double& c) {
        ++probes;
        v = f(t), slope = df(t), c = d2f(t);
      },
      lo, glo, hi, ghi, ttol);
  EXPECT_GT(f(hi), 0.0);  // crossed (f rises through the root)
  EXPECT_GE(hi, root);
  EXPECT_LE(hi - root, ttol);
  EXPECT_LE(probes, 4);
}

TEST(NextSample, AgreesWithNextAfterAlongAnIntegratorsTimes) {
  // Times as an integrator meets them: sample to sample, roots inside intervals, roots a hair
  // short of a sample, restarts there, the end of the grid, and a jump back.
  const detail::SampleGrid grid{0.01, 500};
  detail::NextSample next(grid);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> times;
  double t = 0.0;
  while (t < 5.2) {
    times.push_back(t);
    const double tb = grid.next_after(t);
    const double r = u(rng);
    if (!std::isfinite(tb)) {
      t += 0.013;
    } else if (r < 0.6) {
      t = tb;  // a whole step
    } else if (r < 0.8) {
      t = t + (tb - t) * u(rng);  // a root inside the step
    } else if (r < 0.9) {
      t = tb - 1e-12 * grid.dt_s;  // a root a hair short of the sample
    } else {
      t = std::nextafter(tb, 0.0);
    }
  }
  times.push_back(1.234);  // back in time (a new case on the same integrator)
  times.push_back(1.234);
  times.push_back(0.0);
  for (const double time : times) EXPECT_EQ(next.after(time), grid.next_after(time)) << "t = " << time;
}

TEST(NextSample, NoGridMeansNoSample) {
  detail::NextSample none(detail::SampleGrid{});
  EXPECT_EQ(none.after(0.5), std::numeric_limits<double>::infinity());
  EXPECT_EQ(none.after(0.7), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace pcrf
