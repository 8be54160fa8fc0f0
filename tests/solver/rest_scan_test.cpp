// The scans of a record at rest (uplift, the paper's trigger, the ground's free fall) skip a
// record whose extremes cannot reach their level (issue 27). The shortcut must never change an
// answer: at the edges (a peak exactly at the level, a hair above or below) each scan gives what
// the sample-by-sample rule says.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pcrf/excitation/excitation.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"
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
