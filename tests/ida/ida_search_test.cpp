// The hunt-and-fill search on frames whose collapse intensity is known: the bracket reaches
// the resolution within the run budget, the runs are the ones the algorithm prescribes, and
// censored, immediate and non-monotone curves end as they should.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "pcrf/ida/ida_search.hpp"

namespace pcrf::ida {
namespace {

IdaSearchSettings defaults() {
  IdaSearchSettings s;
  s.start = 0.5;
  s.resolution = 0.02;
  s.max_intensity = 12.0;
  s.max_runs = 16;
  return s;
}

IdaSearch trace(const IdaSearchSettings& settings, const std::function<bool(double)>& collapses) {
  IdaSearch search(settings);
  while (const auto x = search.next()) search.add(*x, collapses(*x));
  return search;
}

std::vector<double> hunt_of(const IdaSearchSettings& settings) {
  IdaSearch search(settings);
  std::vector<double> runs;
  while (const auto x = search.next()) {
    runs.push_back(*x);
    search.add(*x, false);
  }
  return runs;
}

TEST(IdaSearch, HuntStepsGrowGeometricallyAndStopAtTheCap) {
  // step = start, factor 2: the intensity doubles; the cap ends it, censored.
  EXPECT_EQ(hunt_of(defaults()), (std::vector<double>{0.5, 1, 2, 4, 8, 12}));
  auto s = defaults();
  s.step = 1.0;
  s.step_factor = 1.5;  // steps 1, 1.5, 2.25, 3.375, …
  EXPECT_EQ(hunt_of(s), (std::vector<double>{0.5, 1.5, 3.0, 5.25, 8.625, 12}));
  s.step_factor = 1.0;  // equal steps
  EXPECT_EQ(hunt_of(s), (std::vector<double>{0.5, 1.5, 2.5, 3.5, 4.5, 5.5, 6.5, 7.5, 8.5, 9.5, 10.5, 11.5, 12}));
  const auto censored = trace(defaults(), [](double) { return false; });
  EXPECT_TRUE(std::isnan(censored.collapse_intensity()));
  EXPECT_EQ(censored.last_safe_intensity(), 12.0);
  EXPECT_EQ(censored.state(), CurveState::kCensored);
  EXPECT_TRUE(censored.bracketed());
}

TEST(IdaSearch, EveryCurveEndsBracketedCensoredOrUnbracketed) {
  auto s = defaults();
  EXPECT_EQ(trace(s, [](double x) { return x >= 3.3; }).state(), CurveState::kBracketed);
  s.max_runs = 5;  // the hunt alone needs 6 to reach the cap: runs out safe at 8
  const auto short_of_cap = trace(s, [](double) { return false; });
  EXPECT_EQ(short_of_cap.state(), CurveState::kUnbracketed);
  EXPECT_FALSE(short_of_cap.bracketed());
  EXPECT_EQ(short_of_cap.last_safe_intensity(), 8.0);
  s.max_runs = 7;  // collapses at 4 after a safe 2: one bisection is not 2 %
  const auto wide = trace(s, [](double x) { return x >= 3.3; });
  EXPECT_EQ(wide.state(), CurveState::kUnbracketed);
  EXPECT_EQ(wide.runs(), 7);
  EXPECT_GT(wide.collapse_intensity() / wide.last_safe_intensity() - 1.0, 0.02);
  EXPECT_EQ(curve_state_name(CurveState::kUnbracketed), "unbracketed");
}

TEST(IdaSearch, AHundredfoldRangeIsBracketedToOnePercentWithin16Runs) {
  // Rocking spectra: collapse amplitudes anywhere in 1–100 g, found from 1 g at 1 %.
  IdaSearchSettings s;
  s.start = 1.0;
  s.resolution = 0.01;
  s.max_intensity = 100.0;
  s.max_runs = 16;
  int worst = 0;
  for (double x_c = 1.01; x_c < 100.0; x_c *= 1.017) {
    IdaSearch search(s);
    int runs_to_bracket = -1;
    while (const auto x = search.next()) {
      search.add(*x, *x >= x_c);
      if (runs_to_bracket < 0 && search.state() == CurveState::kBracketed) runs_to_bracket = search.runs();
    }
    ASSERT_GT(runs_to_bracket, 0) << "x_c = " << x_c;
    worst = std::max(worst, runs_to_bracket);
    EXPECT_LT(search.last_safe_intensity(), x_c);
    EXPECT_GE(search.collapse_intensity(), x_c);
  }
  EXPECT_LE(worst, 15);
}

TEST(IdaSearch, BracketsEveryCollapseIntensityToTheResolutionWithin16Runs) {
  int worst_runs_to_bracket = 0;
  for (double x_c = 0.55; x_c < 12.0; x_c *= 1.013) {
    IdaSearch search(defaults());
    int runs_to_bracket = -1;
    while (const auto x = search.next()) {
      search.add(*x, *x >= x_c);
      if (runs_to_bracket < 0 && search.bracketed()) runs_to_bracket = search.runs();
    }
    ASSERT_GT(runs_to_bracket, 0) << "x_c = " << x_c;
    worst_runs_to_bracket = std::max(worst_runs_to_bracket, runs_to_bracket);
    const double c = search.collapse_intensity(), s = search.last_safe_intensity();
    EXPECT_GE(c, x_c);
    EXPECT_LT(s, x_c);
    EXPECT_LE(c / s - 1.0, 0.02) << "x_c = " << x_c;
    EXPECT_LE(search.runs(), 16);  // the rest of the budget fills the curve, where a new bracket could still close
  }
  EXPECT_LE(worst_runs_to_bracket, 13);
}

TEST(IdaSearch, AnImmediateCollapseComesDown) {
  const auto s = trace(defaults(), [](double x) { return x >= 0.2; });
  EXPECT_LT(s.last_safe_intensity(), 0.2);
  EXPECT_GE(s.collapse_intensity(), 0.2);
  EXPECT_LE(s.collapse_intensity() / s.last_safe_intensity() - 1.0, 0.02);
}

TEST(IdaSearch, ACollapseBandBelowTheFirstCollapseIsFoundByTheFill) {
  // Collapsing in a band [2.2, 2.6] that the hunt jumps over, safe above it, collapsing
  // again from 5: the fill finds the band, and the lowest collapse wins.
  const auto band = [](double x) { return (x >= 2.2 && x <= 2.6) || x >= 5.0; };
  const auto s16 = trace(defaults(), band);
  EXPECT_LE(s16.collapse_intensity() / s16.last_safe_intensity() - 1.0, 0.02);  // bracketed, whichever it found
  auto more = defaults();
  more.max_runs = 30;
  const auto s30 = trace(more, band);
  EXPECT_GE(s30.collapse_intensity(), 2.2);
  EXPECT_LE(s30.collapse_intensity() / s30.last_safe_intensity() - 1.0, 0.02);
}

TEST(IdaSearch, AFillThatFindsALowerCollapseStillEndsBracketed) {
  // Non-monotone curves: collapse bands at random places below the main collapse.
  for (double band = 0.7; band < 8.0; band *= 1.07) {
    const auto s = trace(defaults(), [band](double x) { return (x >= band && x <= band * 1.1) || x >= 9.0; });
    EXPECT_LE(s.collapse_intensity() / s.last_safe_intensity() - 1.0, 0.02) << "band at " << band;
  }
}

TEST(IdaSearch, TheSameResultsGiveTheSameRuns) {
  IdaSearch a(defaults()), b(defaults());
  while (const auto x = a.next()) a.add(*x, *x >= 3.3);
  while (const auto x = b.next()) b.add(*x, *x >= 3.3);
  EXPECT_EQ(a.collapse_intensity(), b.collapse_intensity());
  EXPECT_EQ(a.last_safe_intensity(), b.last_safe_intensity());
}

TEST(IdaSearch, BadSettingsAreRejected) {
  auto s = defaults();
  s.resolution = 1.0;
  EXPECT_THROW(IdaSearch{s}, std::invalid_argument);
  s = defaults();
  s.max_runs = 1;
  EXPECT_THROW(IdaSearch{s}, std::invalid_argument);
  s = defaults();
  s.max_intensity = 0.1;
  EXPECT_THROW(IdaSearch{s}, std::invalid_argument);
  s = defaults();
  s.step_factor = 0.9;  // shrinking steps could never reach the cap
  EXPECT_THROW(IdaSearch{s}, std::invalid_argument);
}

}  // namespace
}  // namespace pcrf::ida

namespace pcrf::ida {
namespace {

/// A curve's runs on a frame that collapses from `collapse` up and whose runs from `no_verdict`
/// up give no verdict (the ground falls faster than gravity: every higher scale does too).
IdaSearch trace_verdicts(const IdaSearchSettings& settings, double collapse, double no_verdict) {
  IdaSearch search(settings);
  while (const auto x = search.next())
    search.add(*x, *x >= collapse ? RunVerdict::kCollapse : *x >= no_verdict ? RunVerdict::kNoVerdict : RunVerdict::kSafe);
  return search;
}

TEST(IdaSearch, ACurveStoppedByARunWithoutAVerdictIsUnresolvedNeverCensoredAtTheCap) {
  // Free fall from 3.3 on, no collapse below the cap: before, the search called those runs
  // safe and the curve "right-censored, safe at 12"; now it stops there and is unresolved.
  const auto s = defaults();
  const auto curve = trace_verdicts(s, INFINITY, 3.3);
  EXPECT_EQ(curve.state(), CurveState::kUnresolved);
  EXPECT_EQ(curve_state_name(CurveState::kUnresolved), "unresolved");
  EXPECT_TRUE(std::isnan(curve.collapse_intensity()));
  EXPECT_LT(curve.last_safe_intensity(), 3.3);
  EXPECT_GT(curve.last_safe_intensity(), 3.3 / 1.02 / 1.02);  // bisected down to the resolution
  EXPECT_NE(curve.last_safe_intensity(), s.max_intensity);
  // It made the runs a collapse at 3.3 makes: the same hunt and bisection.
  EXPECT_EQ(curve.runs(), trace(s, [](double x) { return x >= 3.3; }).runs());
  // A collapse below the runs without a verdict is found and bracketed as usual.
  const auto below = trace_verdicts(s, 2.2, 3.3);
  EXPECT_EQ(below.state(), CurveState::kBracketed);
  EXPECT_GE(below.collapse_intensity(), 2.2);
  EXPECT_LE(below.collapse_intensity() / below.last_safe_intensity() - 1.0, 0.02);
  // No verdict at the very first run (an invalid frame): no safe run at all.
  const auto invalid = trace_verdicts(s, INFINITY, 0.0);
  EXPECT_EQ(invalid.state(), CurveState::kUnresolved);
  EXPECT_TRUE(std::isnan(invalid.last_safe_intensity()));
  EXPECT_TRUE(std::isnan(invalid.collapse_intensity()));
}

}  // namespace
}  // namespace pcrf::ida
