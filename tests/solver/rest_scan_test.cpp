// The scans of a record at rest (uplift, the paper's trigger, the ground's free fall) skip a
// record whose extremes cannot reach their level (issue 27). The shortcut must never change an
// answer: at the edges (a peak exactly at the level, a hair above or below) each scan gives what
// the sample-by-sample rule says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "pcrf/excitation/excitation.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/model/rigid_rocker.hpp"
#include "pcrf/units.hpp"
#include "solver/case/case_common.hpp"

namespace pcrf {
namespace {

constexpr double kDt = 0.01;

/// A decaying oscillation whose largest |sample| is `peak`, reached once, at sample 40.
GroundMotion shaped(double peak) {
  std::vector<double> a(200);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = 0.5 * peak * std::sin(0.3 * static_cast<double>(i));
  a[40] = -peak;
  return GroundMotion("shaped", kDt, std::move(a));
}

/// The first sample where |ü_h| exceeds the uplift threshold at that sample's ü_v, or −1:
/// the scan's crossing lies in the interval that ends there (a margin of exactly zero does
/// not open the frame after t_from).
int first_open_sample(const Excitation& e, const Scene& scene) {
  for (std::size_t i = 0; i < e.horizontal().size(); ++i) {
    const GroundAcceleration a = e.at(static_cast<double>(i) * kDt);
    if (std::abs(a.horizontal_m_s2) > scene.uplift_threshold_m_s2(a.vertical_m_s2)) return static_cast<int>(i);
  }
  return -1;
}

TEST(RestScan, UpliftWithoutVerticalAtTheThreshold) {
  const EquationOfMotion eom(basic_frame());
  const double threshold = eom.uplift_threshold_m_s2();
  for (double factor : {1.0 - 1e-6, 1.0 - 2e-9, 1.0 - 1e-12, 1.0, 1.0 + 1e-12, 1.0 + 1e-6}) {
    const GroundMotion rec = shaped(factor * threshold);
    const Excitation e(rec);
    const double t = detail::first_opening(e, eom, 0.0, 10.0);
    const int sample = first_open_sample(e, eom);
    if (sample < 0) {
      EXPECT_TRUE(std::isnan(t)) << factor;  // a peak exactly at the threshold does not open it
    } else {
      EXPECT_GE(t, (sample - 1) * kDt) << factor;
      EXPECT_LE(t, sample * kDt) << factor;
    }
    EXPECT_EQ(sample >= 0, factor > 1.0) << factor;
  }
}

TEST(RestScan, UpliftUnderVerticalShakingAtTheLowestThreshold) {
  // The vertical lowers the threshold most where it points down hardest (−0.3 g at sample
  // 40, where the horizontal peaks too): scaled around that lowest threshold, the horizontal
  // opens the frame only above it.
  const EquationOfMotion eom(basic_frame());
  std::vector<double> v(200);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = 0.1 * kGravity_m_s2 * std::cos(0.7 * static_cast<double>(i));
  v[40] = -0.3 * kGravity_m_s2;
  const GroundMotion up("up", kDt, v);
  const double lowest = eom.uplift_threshold_m_s2(-0.3 * kGravity_m_s2);
  for (double factor : {0.5, 1.0 - 1e-6, 1.0 - 1e-10, 1.0, 1.0 + 1e-10, 1.0 + 1e-6}) {
    const GroundMotion rec = shaped(factor * lowest);
    const Excitation e(rec, &up);
    const double t = detail::first_opening(e, eom, 0.0, 10.0);
    const int sample = first_open_sample(e, eom);
    if (sample < 0) {
      EXPECT_TRUE(std::isnan(t)) << factor;
    } else {
      EXPECT_GE(t, (sample - 1) * kDt) << factor;
      EXPECT_LE(t, sample * kDt) << factor;
    }
    EXPECT_EQ(sample >= 0, factor > 1.0) << factor;
  }
}

/// The uplift scan under vertical shaking as it was written before it read the samples
/// directly (issue 43): every sample interval in turn, the ground at both ends through
/// Excitation::at, the margins ±ü_h − threshold(ü_v) from the threshold's formula.
double interval_by_interval(const Excitation& e, const Scene& scene, double t_from, double t_end) {
  const double nan = std::nan("");
  if (!scene.holds_closed(e.at(t_from))) return t_from;
  const double dt = e.dt_s();
  for (auto i = static_cast<std::size_t>(std::max(0.0, std::floor(t_from / dt))); i + 1 < e.horizontal().size(); ++i) {
    const double t0 = std::max(static_cast<double>(i) * dt, t_from);
    if (t0 > t_end) break;
    const double t1 = static_cast<double>(i + 1) * dt;
    const GroundAcceleration a0 = e.at(t0), a1 = e.at(t1);
    double best = nan;
    for (const double sign : {1.0, -1.0}) {
      const double m0 = sign * a0.horizontal_m_s2 - scene.uplift_threshold_m_s2(a0.vertical_m_s2);
      const double m1 = sign * a1.horizontal_m_s2 - scene.uplift_threshold_m_s2(a1.vertical_m_s2);
      if (!(m1 > 0.0)) continue;
      const double s = m0 >= 0.0 ? 0.0 : std::clamp(m0 / (m0 - m1), 0.0, 1.0);
      const double tc = t0 + s * (t1 - t0);
      if (std::isnan(best) || tc < best) best = tc;
    }
    if (!std::isnan(best)) return best <= t_end ? best : nan;
  }
  return nan;
}

/// Same bits, or both NaN.
bool same_time(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

TEST(RestScan, SampleScanUnderVerticalShakingGivesTheIntervalRuleBitForBit) {
  // Random pairs around each scene's threshold (some never reach it, some only where the
  // vertical lowers it, some at a sample exactly on it), scanned from random rest times to
  // random ends, including ends on a sample and before t_from's interval ends.
  const EquationOfMotion frame(basic_frame());
  RockerParameters block_parameters;
  block_parameters.slenderness_rad = std::atan(0.2);
  const RigidRocker block(block_parameters);
  RockerParameters rocking_frame_parameters = block_parameters;
  rocking_frame_parameters.beam_mass_ratio = 0.5;
  const RigidRocker rocking_frame(rocking_frame_parameters);
  std::mt19937_64 random(43);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int opened = 0, compared = 0;
  for (const Scene* scene : {static_cast<const Scene*>(&frame), static_cast<const Scene*>(&block),
                             static_cast<const Scene*>(&rocking_frame)}) {
    const double threshold = scene->uplift_threshold_m_s2();
    for (int trial = 0; trial < 300; ++trial) {
      const std::size_t n = 50 + static_cast<std::size_t>(random() % 400);
      const double peak_h = threshold * (0.8 + 0.3 * (unit(random) + 1.0));
      const double peak_v = kGravity_m_s2 * 0.6 * (unit(random) + 1.0) / 2.0;
      std::vector<double> h(n), v(n);
      for (std::size_t i = 0; i < n; ++i) h[i] = peak_h * unit(random), v[i] = trial % 5 == 0 ? 0.0 : peak_v * unit(random);
      if (trial % 7 == 1) {  // a sample exactly at the threshold of its vertical
        const std::size_t k = n / 2;
        h[k] = scene->uplift_threshold_m_s2(v[k]);
      }
      const GroundMotion hr("h", kDt, h), vr("v", kDt, v);
      const Excitation e(hr, &vr);
      for (int scan = 0; scan < 6; ++scan) {
        const double duration = static_cast<double>(n - 1) * kDt;
        const double t_from = scan == 0 ? 0.0 : duration * (unit(random) + 1.0) / 2.0;
        const double t_end = scan == 1 ? duration + 2.0
                             : scan == 2 ? std::ceil(t_from / kDt + 3.0) * kDt
                                         : t_from + (duration + 1.0 - t_from) * (unit(random) + 1.0) / 2.0;
        const double fast = detail::first_opening(e, *scene, t_from, t_end);
        const double before = interval_by_interval(e, *scene, t_from, t_end);
        ASSERT_TRUE(same_time(fast, before)) << "trial " << trial << " scan " << scan << ": " << fast << " vs " << before;
        ++compared;
        opened += std::isnan(fast) ? 0 : 1;
      }
    }
  }
  // Both outcomes were compared many times.
  EXPECT_GT(opened, compared / 10);
  EXPECT_LT(opened, compared - compared / 10);
}

TEST(RestScan, PaperTriggerAndFreeFallAtTheirLevels) {
  const double level = 0.2 * kGravity_m_s2;
  EXPECT_DOUBLE_EQ(detail::paper_trigger_time(shaped(level), 0.2), 40 * kDt);  // |a| ≥ λ_g g counts
  EXPECT_TRUE(std::isnan(detail::paper_trigger_time(shaped(std::nextafter(level, 0.0)), 0.2)));
  const GroundMotion rec = shaped(0.01);
  const GroundMotion falls = shaped(kGravity_m_s2);  // reaches −g exactly at sample 40
  EXPECT_NEAR(detail::free_fall_time(Excitation(rec, &falls), kGravity_m_s2, 10.0), 40 * kDt, 1e-12);
  const GroundMotion almost = shaped(std::nextafter(kGravity_m_s2, 0.0));
  EXPECT_TRUE(std::isnan(detail::free_fall_time(Excitation(rec, &almost), kGravity_m_s2, 10.0)));
}

}  // namespace
}  // namespace pcrf
