// The excitation view: components evaluated together, refused when they do not share a time axis.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "pcrf/excitation/excitation.hpp"

namespace {

using pcrf::Excitation;
using pcrf::GroundMotion;

TEST(Excitation, AHorizontalAloneHasNoVerticalAndIsTheRecordBitForBit) {
  const GroundMotion h("h", 0.01, {0.0, 1.5, -2.25, 0.5});
  const Excitation e = h;  // the implicit conversion every single-record caller relies on
  EXPECT_FALSE(e.has_vertical());
  for (const double t : {0.0, 0.005, 0.01, 0.017, 0.03, 0.031, -1.0}) {
    EXPECT_EQ(e.at(t).horizontal_m_s2, h.accel_m_s2(t)) << t;
    EXPECT_EQ(e.at(t).vertical_m_s2, 0.0) << t;
  }
  EXPECT_EQ(e.duration_s(), h.duration_s());
  EXPECT_EQ(e.dt_s(), 0.01);
}

TEST(Excitation, BothComponentsAreEvaluatedAtTheSameInstant) {
  const GroundMotion h("h", 0.01, {0.0, 1.0, 2.0});
  const GroundMotion v("v", 0.01, {0.0, -3.0, 3.0});
  const Excitation e(h, &v);
  ASSERT_TRUE(e.has_vertical());
  EXPECT_EQ(e.at(0.015).horizontal_m_s2, h.accel_m_s2(0.015));
  EXPECT_EQ(e.at(0.015).vertical_m_s2, v.accel_m_s2(0.015));
  EXPECT_EQ(e.at(0.5).vertical_m_s2, 0.0) << "zero after the record: the free-vibration tail";
}

TEST(Excitation, ComponentsOnDifferentTimeAxesAreRefusedByName) {
  const GroundMotion h("RSN1_H1", 0.01, {0.0, 1.0, 2.0});
  const GroundMotion coarse("RSN1_UP", 0.02, {0.0, 1.0, 2.0});
  const GroundMotion shorter("RSN1_UP", 0.01, {0.0, 1.0});
  try {
    Excitation(h, &coarse);
    FAIL() << "different dt accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'RSN1_UP' is sampled every 0.02"), std::string::npos) << e.what();
  }
  try {
    Excitation(h, &shorter);
    FAIL() << "different lengths accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pad the shorter with zeros"), std::string::npos) << e.what();
  }
}

TEST(Excitation, AScaledExcitationScalesEveryComponent) {
  const GroundMotion h("h", 0.01, {0.0, 1.0, 2.0});
  const GroundMotion v("v", 0.01, {0.5, -3.0, 3.0});
  const pcrf::ScaledExcitation twice(Excitation(h, &v), 2.0);
  const Excitation e = twice.view();
  ASSERT_TRUE(e.has_vertical());
  EXPECT_EQ(e.at(0.01).horizontal_m_s2, 2.0);
  EXPECT_EQ(e.at(0.01).vertical_m_s2, -6.0);
  const pcrf::ScaledExcitation alone(Excitation(h), -1.0);
  EXPECT_FALSE(alone.view().has_vertical());
  EXPECT_EQ(alone.view().at(0.02).horizontal_m_s2, -2.0);
}

}  // namespace
