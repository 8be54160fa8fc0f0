// A station's components for a frame at an incidence: h1 alone at φ = az₁ bit for bit, a
// half turn mirrors the response exactly, the components' order does not matter.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "pcrf/excitation/station_record.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace pcrf {
namespace {

GroundMotion stochastic(std::uint64_t seed, double pga_g, double duration_s = 10.0) {
  StochasticSpec s;
  s.seed = seed;
  s.pga_g = pga_g;
  s.duration_s = duration_s;
  return make_stochastic(s);
}

StationRecord pair(double az1, double az2) {
  return StationRecord{stochastic(3, 1.6), az1, stochastic(4, 1.4), az2, std::nullopt};
}

TEST(StationRecord, AtTheFirstAzimuthTheFrameFeelsTheFirstComponentBitForBit) {
  const StationRecord station = pair(260.0, 345.0);
  const FrameExcitation along(station, 260.0, 1.3), alone(StationRecord{station.h1, {}, {}, {}, {}}, {}, 1.3);
  EXPECT_EQ(along.horizontal().samples_m_s2(), alone.horizontal().samples_m_s2());
  const CaseResult a = solve_case(basic_frame(), along.view(), {}, {});
  const CaseResult b = solve_case(basic_frame(), station.h1.scaled(1.3), {}, {});
  ASSERT_GT(b.impacts, 0);
  EXPECT_EQ(a.theta_max_rad, b.theta_max_rad);
  EXPECT_EQ(a.t_theta_max_s, b.t_theta_max_s);
  EXPECT_EQ(a.impacts, b.impacts);
}

TEST(StationRecord, AHalfTurnMirrorsTheResponse) {
  const StationRecord station = pair(140.0, 230.0);
  for (const double phi : {140.0, 171.0, 300.0}) {
    const CaseResult a = solve_case(basic_frame(), FrameExcitation(station, phi, 1.2).view(), {}, {});
    const CaseResult b = solve_case(basic_frame(), FrameExcitation(station, phi + 180.0, 1.2).view(), {}, {});
    EXPECT_EQ(a.theta_max_rad, b.theta_max_rad) << phi;
    EXPECT_EQ(a.impacts, b.impacts) << phi;
  }
}

TEST(StationRecord, TheOrderOfTheComponentsDoesNotMatter) {
  const StationRecord station = pair(260.0, 345.0);
  const StationRecord swapped{*station.h2, station.az2_deg, station.h1, station.az1_deg, std::nullopt};
  for (const double phi : {0.0, 47.0, 300.5}) {
    // Bit for bit: rocking is sensitive enough that a last-digit difference in the record
    // moved θ_max by 2.6 % here before the weights were made order-independent.
    const FrameExcitation a(station, phi, 1.3), b(swapped, phi, 1.3);
    EXPECT_EQ(a.horizontal().samples_m_s2(), b.horizontal().samples_m_s2()) << phi;
    const CaseResult ra = solve_case(basic_frame(), a.view(), {}, {}), rb = solve_case(basic_frame(), b.view(), {}, {});
    EXPECT_EQ(ra.theta_max_rad, rb.theta_max_rad) << phi;
  }
}

TEST(StationRecord, ComponentsAreAlignedOrRefused) {
  StationRecord station{stochastic(3, 1.0, 10.0), 0.0, stochastic(4, 1.0, 8.0), 90.0, stochastic(5, 0.3, 9.0)};
  const auto notes = station.align();
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("padded with zeros to 1001"), std::string::npos) << notes[0];
  EXPECT_EQ(station.h2->size(), station.h1.size());
  EXPECT_EQ(station.up->size(), station.h1.size());
  EXPECT_EQ(station.h2->samples_m_s2().back(), 0.0);
  StationRecord coarse{stochastic(3, 1.0), 0.0, GroundMotion("RSN1_H2", 0.02, {0.0, 1.0}), 90.0, std::nullopt};
  EXPECT_THROW(coarse.align(), std::invalid_argument);
  const StationRecord single{stochastic(3, 1.0), 0.0, std::nullopt, std::nullopt, std::nullopt};
  try {
    FrameExcitation(single, 30.0, 1.0);
    FAIL() << "an incidence without a pair accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("has no second component"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pcrf
