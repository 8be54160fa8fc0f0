// Housner's block and the Makris–Vassiliou frame as scenes: restitution, uplift threshold,
// frequency parameter, and the frame as a larger block.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "pcrf/model/frame_properties.hpp"
#include "pcrf/model/rigid_rocker.hpp"

namespace pcrf {
namespace {

RigidRocker block(double alpha, double R, double gamma = 0.0) {
  RockerParameters p;
  p.slenderness_rad = alpha;
  p.size_m = R;
  p.beam_mass_ratio = gamma;
  return RigidRocker(p);
}

TEST(RigidRocker, TheBlockHasHousnersRestitutionThresholdAndFrequency) {
  for (const double alpha : {0.05, 0.2, 0.35}) {
    const RigidRocker b = block(alpha, 1.3);
    const double s = std::sin(alpha);
    EXPECT_DOUBLE_EQ(b.restitution(), 1.0 - 1.5 * s * s) << alpha;          // Housner (1963)
    EXPECT_NEAR(b.uplift_threshold_m_s2(), kGravity_m_s2 * std::tan(alpha), 1e-14 * kGravity_m_s2);
    EXPECT_NEAR(b.lambda_g(), std::tan(alpha), 1e-15);
    const FrameProperties p = frame_properties(b, 0.01, 11);
    EXPECT_NEAR(p.frequency_parameter_rad_s, std::sqrt(3.0 * kGravity_m_s2 / (4.0 * 1.3)), 1e-12);
    EXPECT_NEAR(p.equivalent_block_size_m, 1.3, 1e-12);
    EXPECT_NEAR(p.equivalent_block_slenderness_rad, alpha, 1e-14);
    // The static pushover of a block is g tan(α − θ): it falls from the threshold.
    for (const auto& point : p.pushover)
      EXPECT_NEAR(point.accel_g, std::tan(alpha - point.theta_rad), 1e-12) << point.theta_rad;
    EXPECT_TRUE(std::isnan(b.tendons(-0.01, -1).strain_beam)) << "a block has no tendons";
  }
}

TEST(RigidRocker, TheRockingFrameIsTheBlockOfSizeRHat) {
  // Makris & Vassiliou (2013): θ̈ of the frame equals θ̈ of the block R̂ = R(1 + 3γ)/(1 + 2γ),
  // at any state and ground acceleration; its restitution is its own.
  const double alpha = 0.2, R = 1.5;
  for (const double gamma : {0.0, 0.5, 2.0}) {
    const RigidRocker frame = block(alpha, R, gamma);
    const RigidRocker equivalent = block(alpha, R * (1.0 + 3.0 * gamma) / (1.0 + 2.0 * gamma));
    for (const int side : {-1, 1})
      for (const double theta : {0.0, -0.1, 0.15})
        for (const double a_h : {0.0, 3.0, -7.0}) {
          double x = 0, y = 0;
          ASSERT_TRUE(frame.acceleration(theta, 0.3, {a_h, 1.5}, side, x));
          ASSERT_TRUE(equivalent.acceleration(theta, 0.3, {a_h, 1.5}, side, y));
          EXPECT_NEAR(x, y, 1e-13 * (std::abs(y) + 1.0)) << gamma << " " << side << " " << theta;
        }
    EXPECT_NEAR(frame.restitution(),
                (1.0 - 1.5 * std::pow(std::sin(alpha), 2) + 3.0 * gamma * std::cos(2.0 * alpha)) / (1.0 + 3.0 * gamma),
                1e-15);
  }
  EXPECT_DOUBLE_EQ(block(alpha, R, 0.0).restitution(), RigidRocker::restitution_from_momentum(alpha, 0.0));
}

TEST(RigidRocker, ImpossibleRockersAreRefusedNamingTheParameter) {
  const std::vector<std::pair<RockerParameters, std::string>> bad = {
      {{1.6, 1.0, 0.0, {}, kGravity_m_s2}, "slenderness_rad"},
      {{0.0, 1.0, 0.0, {}, kGravity_m_s2}, "slenderness_rad"},
      {{0.2, -1.0, 0.0, {}, kGravity_m_s2}, "size_m"},
      {{0.2, 1.0, -0.5, {}, kGravity_m_s2}, "beam_mass_ratio"},
      {{0.2, 1.0, 0.0, 1.2, kGravity_m_s2}, "restitution"}};
  for (const auto& [parameters, key] : bad) {
    try {
      RigidRocker r(parameters);
      ADD_FAILURE() << key << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(key + ":", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace pcrf
