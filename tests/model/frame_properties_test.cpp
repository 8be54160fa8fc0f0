// A frame's properties: the pushover curve starts at the uplift threshold, p from the
// reference terms of MODEL.md, the fracture angle's tendon, a frame without tendons as a block.
#include <gtest/gtest.h>

#include <cmath>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame_properties.hpp"
#include "pcrf/model/impact.hpp"

namespace pcrf {
namespace {

TEST(FrameProperties, ThePushoverCurveStartsAtTheUpliftThreshold) {
  const EquationOfMotion eom(basic_frame());
  const FrameProperties p = frame_properties(eom, 0.01, 21);
  ASSERT_EQ(p.pushover.size(), 21u);
  EXPECT_EQ(p.pushover.front().theta_rad, 0.0);
  EXPECT_DOUBLE_EQ(p.pushover.front().accel_g, p.uplift_threshold_g);
  EXPECT_NEAR(p.uplift_threshold_g, 1.021372, 1e-6);  // MODEL.md
  // The tendons stiffen the frame up to the fracture of a column tendon, where it ends.
  EXPECT_EQ(p.fracture_tendon, "column");
  EXPECT_DOUBLE_EQ(p.pushover.back().theta_rad, p.fracture_angle_rad);
  for (std::size_t i = 1; i < p.pushover.size(); ++i) EXPECT_GT(p.pushover[i].accel_g, p.pushover[i - 1].accel_g);
  EXPECT_DOUBLE_EQ(p.capacity_g, p.pushover.back().accel_g);
  EXPECT_NEAR(p.restitution, 0.950472, 1e-6);  // MODEL.md
}

TEST(FrameProperties, FrequencyParameterFromTheReferenceTermsAtRest) {
  // p² = g √(G(0)² + S(0)²) / I(0) with MODEL.md's G(0) = −2782.08 kg m, S(0) = −17953.92 kg m,
  // I(0) = 39673.34 kg m²; for a rigid block this is 3g/(4R) (docs/frequency_parameter.md).
  const double expected = std::sqrt(9.81 * std::hypot(2782.08, 17953.92) / 39673.34);
  const FrameProperties p = frame_properties(EquationOfMotion(basic_frame()), 0.01);
  EXPECT_NEAR(p.frequency_parameter_rad_s, expected, 1e-6 * expected);
  EXPECT_NEAR(p.equivalent_block_size_m, 3.0 * 9.81 / (4.0 * expected * expected), 1e-5);
  EXPECT_NEAR(std::tan(p.equivalent_block_slenderness_rad), 0.154957, 1e-6);
}

TEST(FrameProperties, WithoutTendonsTheFrameLosesStrengthFromTheStartAsABlockDoes) {
  FrameParameters loose;
  loose.pi_e_b = loose.pi_e_c = loose.pi_sigma_b = loose.pi_sigma_c = 0.0;
  const FrameProperties p = frame_properties(EquationOfMotion(make_frame(loose)), 0.01, 31);
  EXPECT_TRUE(std::isinf(p.fracture_angle_rad));
  EXPECT_TRUE(p.fracture_tendon.empty());
  EXPECT_NEAR(p.uplift_threshold_g, p.lambda_g, 1e-15) << "no prestress: the paper's criterion is exact";
  EXPECT_EQ(p.capacity_theta_rad, 0.0);
  EXPECT_DOUBLE_EQ(p.capacity_g, p.uplift_threshold_g);
  for (std::size_t i = 1; i < p.pushover.size(); ++i) EXPECT_LT(p.pushover[i].accel_g, p.pushover[i - 1].accel_g);
  EXPECT_DOUBLE_EQ(p.pushover.back().theta_rad, p.overturn_angle_rad);
}

}  // namespace
}  // namespace pcrf
