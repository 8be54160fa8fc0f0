// The excitation view: components evaluated together, refused when they do not share a time axis.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "pcrf/excitation/excitation.hpp"

namespace {

using pcrf::Excitation;
using pcrf::ExcitationCursor;
using pcrf::GroundMotion;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

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

TEST(ExcitationCursor, IsExcitationAtBitForBitBeforeWithinAndPastTheRecord) {
  // Times in order (an integrator's), back and forth (a root search), on the samples, at the
  // last sample and in the still tail after it, where the cursor keeps an interval of zeros.
  const GroundMotion h("h", 0.01, {0.0, 1.5, -2.25, 0.5, -0.0, 3.0});
  const GroundMotion v("v", 0.01, {0.25, -1.0, 2.0, 0.0, 1.0, -0.5});
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-0.01, 0.2);
  std::vector<double> times = {0.0, 0.01, 0.02, 0.05, 0.05000000000000001, 0.06, 0.2, 0.05, 1e300, -0.0};
  for (int i = 0; i < 2000; ++i) times.push_back(i % 2 == 0 ? 1e-4 * i : u(rng));
  for (const Excitation& e : {Excitation(h), Excitation(h, &v)}) {
    ExcitationCursor cursor(e);
    int tail = 0;
    for (const double t : times) {
      const auto c = cursor.at(t), a = e.at(t);
      EXPECT_TRUE(same_bits(c.horizontal_m_s2, a.horizontal_m_s2)) << t;
      EXPECT_TRUE(same_bits(c.vertical_m_s2, a.vertical_m_s2)) << t;
      tail += t > e.duration_s() && t >= cursor.interval().lo_s && t < cursor.interval().hi_s;
    }
    EXPECT_GT(tail, 100);  // the tail is an interval of the cursor, not a call of at() each time
  }
}

TEST(ExcitationCursor, NextIntervalIsTheOneItsEndEntersUpToTheRecordsEnd) {
  const GroundMotion h("h", 0.01, {0.0, 1.5, -2.25, 0.5, 3.0});
  const GroundMotion v("v", 0.01, {0.25, -1.0, 2.0, 0.0, 1.0});
  const Excitation e(h, &v);
  ExcitationCursor stepped(e), entered(e);
  EXPECT_FALSE(stepped.next_interval());  // no interval yet
  stepped.at(0.003);
  int steps = 0;
  while (stepped.next_interval()) {
    ++steps;
    const auto& i = stepped.interval();
    entered.at(i.lo_s);
    const auto& j = entered.interval();
    EXPECT_TRUE(same_bits(i.lo_s, j.lo_s) && same_bits(i.hi_s, j.hi_s) && same_bits(i.h0, j.h0) &&
                same_bits(i.dh, j.dh) && same_bits(i.v0, j.v0) && same_bits(i.dv, j.dv))
        << i.lo_s;
  }
  EXPECT_EQ(steps, 3);  // [0.01, 0.02) … [0.03, 0.04): the last sample interval ends the record
  stepped.at(1.0);      // the tail: no interval after it
  EXPECT_FALSE(stepped.next_interval());
}

}  // namespace
