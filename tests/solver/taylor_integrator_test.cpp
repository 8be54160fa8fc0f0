// The Taylor-step integrator (src/solver/taylor/taylor_integrator.hpp) on a problem with a closed
// form: y'' = −ω² y (y = cos ωt) has the series a_{k+2} = −ω² a_k / ((k+1)(k+2)). Its order
// against the tolerance, its dense output, breakpoints, the closed-form roots (y, y', y'' and
// |y| − c) located to the time tolerance, directions, and the refusals of its constructor.
// The rigid rockers under it: taylor_test.cpp and rocking_canon_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <vector>

#include "solver/taylor/taylor_integrator.hpp"  // private to the solver: the test makes one directly

namespace pcrf {
namespace {

using detail::OdeIntegrator;
using detail::RootForm;
using detail::SampleGrid;
using detail::TaylorIntegrator;

/// y'' = −ω² y with roots y (0), y' (1), y'' (2) and |y| − level (3); its series.
class SeriesOscillator final : public detail::OdeProblem {
 public:
  double omega = 2.0;
  double level = 0.5;
  bool closed_forms = true;
  bool constant_curvature_root = false;  ///< root 2 the constant 1 instead of y''
  int root_3_derivative = 0;             ///< the derivative root 3 reads (0: |y| − level)
  int series_calls = 0;
  int rhs(double, const double* y, double* ydot) override {
    ydot[0] = y[1];
    ydot[1] = -omega * omega * y[0];
    return 0;
  }
  int roots(double, const double* y, double* g) override {
    const double d[3] = {y[0], y[1], -omega * omega * y[0]};
    for (int i = 0; i < 4; ++i) g[i] = detail::root_value(root_form(i), d);
    return 0;
  }
  int root_count() const override { return 4; }
  RootForm root_form(int i) const override {
    if (!closed_forms) return {};
    if (i == 3) return {root_3_derivative, true, level};
    if (i == 2 && constant_curvature_root) return {RootForm::kConstant, false, 1.0};
    return {i, false, 0.0};
  }
  int taylor_order_max() const override { return 24; }
  bool taylor(double, const double* y0, double, int order, double* a, bool& for_any_h) override {
    ++series_calls;
    a[0] = y0[0], a[1] = y0[1];
    for (int k = 0; k + 2 <= order; ++k) a[k + 2] = -omega * omega * a[k] / ((k + 1.0) * (k + 2.0));
    for_any_h = true;
    return true;
  }
};

SolverSettings taylor_settings(double rtol) {
  SolverSettings s;
  s.integrator = Integrator::kTaylor;
  s.rtol = rtol;
  s.atol_theta_rad = 1e-3 * rtol;
  s.atol_omega_rad_s = 1e-3 * rtol;
  return s;
}

struct Found {
  double t;
  int which;
};

/// From y = 1 at rest to t_end, past every root; each root's time and function.
std::vector<Found> run(TaylorIntegrator& integ, double t_end, const int* dirs, double& y_end) {
  const double y0[2] = {1.0, 0.0};
  integ.restart(0.0, y0, dirs, t_end, 0.0);
  std::vector<Found> found;
  double t = 0.0, y[2];
  while (integ.advance(t_end, t, y, false) == OdeIntegrator::Outcome::kRoot) {
    int f[4] = {0, 0, 0, 0};
    integ.root_info(f);
    for (int i = 0; i < 4; ++i)
      if (f[i]) found.push_back({t, i});
  }
  EXPECT_DOUBLE_EQ(t, t_end);
  y_end = y[0];
  return found;
}

TEST(TaylorIntegrator, OrderGrowsWithTheTolerance) {
  EXPECT_EQ(TaylorIntegrator::order_for(1e-4, 24), 6);
  EXPECT_EQ(TaylorIntegrator::order_for(1e-7, 24), 7);
  EXPECT_EQ(TaylorIntegrator::order_for(1e-10, 24), 8);
  EXPECT_EQ(TaylorIntegrator::order_for(1e-10, 5), 5);
}

TEST(TaylorIntegrator, ErrorFallsAsTheToleranceTightens) {
  double last = 1.0;
  for (double rtol : {1e-4, 1e-7, 1e-10}) {
    SeriesOscillator p;
    TaylorIntegrator integ(taylor_settings(rtol), p, {});
    const int dirs[4] = {0, 0, 0, 0};
    double y = 0.0;
    run(integ, 10.0, dirs, y);
    const double err = std::abs(y - std::cos(20.0));
    EXPECT_LT(err, 100.0 * rtol) << rtol;
    EXPECT_LT(err, last) << rtol;
    last = err;
  }
}

TEST(TaylorIntegrator, PassesOverPeaksThatCannotReachTheirFloor) {
  // cos 2t: |y| peaks at 1 (root 1, y' = 0), |y'| at 2 (root 2, y'' = 0). With floors above
  // what the series can reach over a step (e^{2h} < 3 for the steps here) those roots are
  // never reported; floors on y itself (root 0) and on |y| − c (root 3) are ignored; floors
  // below the peaks change nothing.
  const int dirs[4] = {0, 0, 0, 0};
  auto counts = [&](double floor_1, double floor_2, double floor_0, double floor_3) {
    SeriesOscillator p;
    TaylorIntegrator integ(taylor_settings(1e-7), p, {});
    integ.set_peak_floor(1, floor_1);
    integ.set_peak_floor(2, floor_2);
    integ.set_peak_floor(0, floor_0);
    integ.set_peak_floor(3, floor_3);
    double y = 0.0;
    std::vector<int> n(4, 0);
    for (const Found& f : run(integ, 6.0, dirs, y)) ++n[static_cast<std::size_t>(f.which)];
    EXPECT_NEAR(y, std::cos(12.0), 1e-5);
    return n;
  };
  const double none = -std::numeric_limits<double>::infinity();
  const std::vector<int> all = counts(none, none, none, none);
  ASSERT_GT(all[1], 2);
  ASSERT_GT(all[2], 2);
  EXPECT_EQ(counts(0.5, 1.0, none, none), all);  // below the peaks: every one
  const std::vector<int> above = counts(3.0, 6.0, 10.0, 10.0);
  EXPECT_EQ(above[0], all[0]);
  EXPECT_EQ(above[1], 0);
  EXPECT_EQ(above[2], 0);
  EXPECT_EQ(above[3], all[3]);
}

TEST(TaylorIntegrator, LocatesEveryClosedFormRoot) {
  // cos 2t: y = 0 at (2k+1)π/4; y' = 0 at kπ/2; y'' = −4 cos 2t = 0 with y; |y| = 1/2 where
  // 2t = ±π/3 + kπ. Each within the time tolerance (100 ulp), far below the state tolerance.
  SeriesOscillator p;
  TaylorIntegrator integ(taylor_settings(1e-7), p, {});
  const int dirs[4] = {0, 0, 0, 0};
  double y = 0.0;
  const std::vector<Found> found = run(integ, 3.0, dirs, y);
  std::vector<double> expected[4];
  for (int k = 0; k < 4; ++k) {
    const double zero = (2.0 * k + 1.0) * std::numbers::pi / 4.0;
    if (zero < 3.0) expected[0].push_back(zero), expected[2].push_back(zero);
    if (k > 0 && k * std::numbers::pi / 2.0 < 3.0) expected[1].push_back(k * std::numbers::pi / 2.0);
  }
  for (int k = 0; k < 3; ++k)
    for (double s : {-1.0, 1.0}) {
      const double t = 0.5 * (s * std::numbers::pi / 3.0 + k * std::numbers::pi);
      if (t > 0.0 && t < 3.0) expected[3].push_back(t);
    }
  for (int i = 0; i < 4; ++i) {
    std::vector<double> times;
    for (const Found& f : found)
      if (f.which == i) times.push_back(f.t);
    std::sort(expected[i].begin(), expected[i].end());
    ASSERT_EQ(times.size(), expected[i].size()) << "root " << i;
    for (std::size_t k = 0; k < times.size(); ++k) EXPECT_NEAR(times[k], expected[i][k], 1e-7) << "root " << i;
  }
}

TEST(TaylorIntegrator, HonoursDirectionsAndConstants) {
  // Only falling zeros of y (at π/4 and 5π/4 before 4.5); a constant root never crosses.
  SeriesOscillator p;
  p.constant_curvature_root = true;
  TaylorIntegrator integ(taylor_settings(1e-7), p, {});
  const int dirs[4] = {-1, 0, 0, 0};
  double y = 0.0;
  const std::vector<Found> found = run(integ, 4.5, dirs, y);
  std::vector<double> falling;
  for (const Found& f : found) {
    if (f.which == 0) falling.push_back(f.t);
    EXPECT_NE(f.which, 2) << "the constant root at t = " << f.t;
  }
  ASSERT_EQ(falling.size(), 2u);
  EXPECT_NEAR(falling[0], std::numbers::pi / 4.0, 1e-9);
  EXPECT_NEAR(falling[1], 5.0 * std::numbers::pi / 4.0, 1e-9);
}

TEST(TaylorIntegrator, NoStepCrossesABreakpointAndTheDenseOutputIsTheSeries) {
  SeriesOscillator p;
  const double dt = 0.01;
  TaylorIntegrator integ(taylor_settings(1e-7), p, SampleGrid{dt, 301});
  const int dirs[4] = {0, 0, 0, 0};
  const double y0[2] = {1.0, 0.0};
  integ.restart(0.0, y0, dirs, 3.0, 0.0);
  double t = 0.0, y[2];
  int steps = 0;
  while (t < 3.0) {
    const double before = t;
    integ.advance(3.0, t, y, true);
    ++steps;
    // One step at most to the next sample (or a root within it).
    EXPECT_LE(t, std::floor(before / dt + 1e-9) * dt + dt + 1e-12);
    double mid[2];
    integ.interpolate(0.5 * (before + t), mid);
    EXPECT_NEAR(mid[0], std::cos(2.0 * 0.5 * (before + t)), 1e-7);
    EXPECT_NEAR(mid[1], -2.0 * std::sin(2.0 * 0.5 * (before + t)), 1e-6);
  }
  EXPECT_GE(steps, 300);
  EXPECT_GE(integ.counts().steps, 300);
}

TEST(TaylorIntegrator, RefusesAProblemWithoutSeriesOrClosedFormRoots) {
  SeriesOscillator p;
  p.closed_forms = false;
  EXPECT_THROW(TaylorIntegrator(taylor_settings(1e-7), p, {}), detail::IntegratorError);
  p.closed_forms = true;
  for (int derivative : {3, -5}) {  // beyond the series' θ̈, and no form at all
    p.root_3_derivative = derivative;
    EXPECT_THROW(TaylorIntegrator(taylor_settings(1e-7), p, {}), detail::IntegratorError) << derivative;
  }
  struct NoSeries final : detail::OdeProblem {
    int rhs(double, const double*, double*) override { return 0; }
    int roots(double, const double*, double*) override { return 0; }
    int root_count() const override { return 0; }
  } none;
  EXPECT_THROW(TaylorIntegrator(taylor_settings(1e-7), none, {}), detail::IntegratorError);
}

}  // namespace
}  // namespace pcrf
