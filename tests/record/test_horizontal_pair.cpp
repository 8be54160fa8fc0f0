// Projections of a horizontal pair on any azimuth, and the azimuths component names state.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/synthetic.hpp"

namespace {

using pcrf::GroundMotion;
using pcrf::HorizontalPair;

double radians(double deg) { return deg * std::numbers::pi / 180.0; }

GroundMotion stochastic(std::uint64_t seed, double duration_s = 6.0) {
  pcrf::StochasticSpec s;
  s.seed = seed;
  s.duration_s = duration_s;
  return pcrf::make_stochastic(s);
}

/// The components a vector motion (east, north) leaves along az₁ and az₂.
struct VectorMotion {
  GroundMotion east = stochastic(1), north = stochastic(2);
  GroundMotion along(double az_deg) const {
    std::vector<double> a(east.size());
    for (std::size_t i = 0; i < a.size(); ++i)
      a[i] = east.samples_m_s2()[i] * std::sin(radians(az_deg)) + north.samples_m_s2()[i] * std::cos(radians(az_deg));
    return GroundMotion("along", east.dt_s(), std::move(a));
  }
};

TEST(HorizontalPair, ProjectionRecoversTheVectorFromAnyTwoAzimuths) {
  const VectorMotion v;
  // Orthogonal, Lucerne's 85° (LCN260/LCN345), and a skew 40° pair.
  for (const auto& [az1, az2] : std::vector<std::pair<double, double>>{{140, 230}, {260, 345}, {10, 50}}) {
    const GroundMotion h1 = v.along(az1), h2 = v.along(az2);
    for (const double phi : {0.0, 33.0, 140.0, 200.5, 359.0, -75.0}) {
      SCOPED_TRACE(std::to_string(az1) + "/" + std::to_string(az2) + " at " + std::to_string(phi));
      const GroundMotion projected = pcrf::project(HorizontalPair{h1, az1, h2, az2}, phi);
      const GroundMotion direct = v.along(phi);
      ASSERT_EQ(projected.size(), direct.size());
      for (std::size_t i = 0; i < direct.size(); i += 37)
        EXPECT_NEAR(projected.samples_m_s2()[i], direct.samples_m_s2()[i], 1e-12 * v.east.pga_m_s2());
    }
  }
}

TEST(HorizontalPair, AtTheFirstAzimuthItIsTheFirstComponentAndAHalfTurnMirrorsExactly) {
  const GroundMotion h1 = stochastic(3), h2 = stochastic(4);
  for (const double az1 : {0.0, 140.0, 260.0}) {
    const HorizontalPair pair{h1, az1, h2, az1 + 85.0};
    EXPECT_EQ(pcrf::project(pair, az1).samples_m_s2(), h1.samples_m_s2());
    EXPECT_EQ(pcrf::project(pair, az1 + 360.0).samples_m_s2(), h1.samples_m_s2());
    for (const double phi : {az1, az1 + 17.0, az1 + 101.0}) {
      const auto a = pcrf::project(pair, phi).samples_m_s2();
      auto mirrored = pcrf::project(pair, phi + 180.0).samples_m_s2();
      for (double& x : mirrored) x = -x;
      EXPECT_EQ(a, mirrored) << phi;
    }
  }
  const auto w = pcrf::projection_weights(140.0, 230.0, 170.0);
  EXPECT_NEAR(w.w1, std::cos(radians(30.0)), 1e-15);  // the orthogonal formula
  EXPECT_NEAR(w.w2, std::sin(radians(30.0)), 1e-15);
}

TEST(HorizontalPair, TheShorterComponentIsZeroAfterItsEndAndBadPairsAreRefused) {
  const GroundMotion h1("h1", 0.01, {1.0, 2.0, 3.0, 4.0});
  const GroundMotion h2("h2", 0.01, {10.0, 20.0});
  const GroundMotion p = pcrf::project(HorizontalPair{h1, 0.0, h2, 90.0}, 90.0);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_NEAR(p.samples_m_s2()[1], 20.0, 1e-14);
  EXPECT_NEAR(p.samples_m_s2()[3], 0.0, 1e-14);
  EXPECT_THROW(pcrf::project(HorizontalPair{h1, 0.0, h2, 180.5}, 10.0), std::invalid_argument);
  const GroundMotion coarse("RSN1_H2", 0.02, {1.0, 2.0});
  try {
    pcrf::project(HorizontalPair{h1, 0.0, coarse, 90.0}, 10.0);
    FAIL() << "different dt accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'RSN1_H2'"), std::string::npos) << e.what();
  }
}

TEST(HorizontalPair, ComponentNamesStateTheirAzimuth) {
  EXPECT_EQ(pcrf::azimuth_of_component("230"), 230.0);
  EXPECT_EQ(pcrf::azimuth_of_component("0"), 0.0);
  EXPECT_EQ(pcrf::azimuth_of_component("H-E07140"), 140.0);
  EXPECT_EQ(pcrf::azimuth_of_component("LCN345"), 345.0);
  EXPECT_EQ(pcrf::azimuth_of_component("MUL009"), 9.0);
  EXPECT_EQ(pcrf::azimuth_of_component("SYL360"), 360.0);  // north, as PEER names it (RIO360, NWH360)
  EXPECT_EQ(pcrf::azimuth_of_component("CHY101-N"), 0.0);
  EXPECT_EQ(pcrf::azimuth_of_component("TCU045-E"), 90.0);
  EXPECT_EQ(pcrf::azimuth_of_component("CLW-LN"), std::nullopt);
  EXPECT_EQ(pcrf::azimuth_of_component("ABBAR--T"), std::nullopt);
  for (const char* vertical : {"UP", "H-E07-UP", "CHY101-V", "ABBAR--V", "H-CHIDWN", "HECVER"}) {
    EXPECT_TRUE(pcrf::is_vertical_component(vertical)) << vertical;
    EXPECT_EQ(pcrf::azimuth_of_component(vertical), std::nullopt) << vertical;
  }
  EXPECT_FALSE(pcrf::is_vertical_component("LCN260"));
}

}  // namespace
