// A station's components for a frame at an incidence: h1 alone at φ = az₁ bit for bit, a
// half turn mirrors the response exactly, the components' order does not matter.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "pcrf/excitation/station_record.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "support/test_support.hpp"

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
  const ScaledExcitation along = frame_excitation(station, 260.0, 1.3),
                         alone = frame_excitation(StationRecord{station.h1, {}, {}, {}, {}}, {}, 1.3);
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
    const CaseResult a = solve_case(basic_frame(), frame_excitation(station, phi, 1.2).view(), {}, {});
    const CaseResult b = solve_case(basic_frame(), frame_excitation(station, phi + 180.0, 1.2).view(), {}, {});
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
    const ScaledExcitation a = frame_excitation(station, phi, 1.3), b = frame_excitation(swapped, phi, 1.3);
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
    frame_excitation(single, 30.0, 1.0);
    FAIL() << "an incidence without a pair accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("has no second component"), std::string::npos) << e.what();
  }
}

/// A two-column file of `rows` samples at `dt_s`, its time column written to 2 decimals.
std::filesystem::path time_column_file(const std::filesystem::path& dir, const std::string& name, std::size_t rows,
                                       double dt_s) {
  std::string text;
  char line[64];
  for (std::size_t i = 0; i < rows; ++i) {
    std::snprintf(line, sizeof line, "%.2f %.6f\n", static_cast<double>(i) * dt_s, 0.1 * std::sin(0.3 * static_cast<double>(i)));
    text += line;
  }
  return test::write_file(dir, name, text);
}

// Issue 29: two text components of one station with different lengths were refused as
// "sampled at different intervals (0.010000 s and 0.010000 s)": their intervals come from
// the time columns (19.9 s / 1990 against 9.99 s / 999) and differ in the last digit. They
// are the same interval: the shorter component is padded with zeros to the longer.
TEST(StationRecord, TextComponentsOfDifferentLengthsArePadded) {
  const auto dir = test::scratch_dir("station_text_components");
  const auto spec = [](const std::filesystem::path& file) { return RecordFileSpec{file, RecordFormat::kTwoColumn, AccelUnit::kG}; };
  GroundMotion h1 = read_record(spec(time_column_file(dir, "long.txt", 1991, 0.01)));
  GroundMotion h2 = read_record(spec(time_column_file(dir, "short.txt", 1000, 0.01)));
  ASSERT_NE(h1.dt_s(), h2.dt_s()) << "the fixture no longer shows the rounding it is about";
  const double short_last = h2.samples_m_s2().back();
  std::vector<std::string> notes;
  const StationRecord station = make_station({h1, "", "long.txt"}, 0.0, StationComponent{h2, "", "short.txt"}, 90.0,
                                             std::nullopt, notes);
  ASSERT_EQ(station.h2->size(), 1991u);
  EXPECT_EQ(station.h2->dt_s(), station.h1.dt_s());
  EXPECT_EQ(station.h2->samples_m_s2()[999], short_last);
  EXPECT_EQ(station.h2->samples_m_s2()[1000], 0.0);
  EXPECT_EQ(station.h2->samples_m_s2().back(), 0.0);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("padded with zeros to 1991"), std::string::npos) << notes[0];
  // A frame at an incidence and a vertical see one time axis.
  const ScaledExcitation excitation = frame_excitation(station, 30.0, 1.0);
  EXPECT_EQ(excitation.horizontal().size(), 1991u);
}

// Intervals that do differ are refused, and the message tells them apart.
TEST(StationRecord, DifferentIntervalsAreNamedInFull) {
  StationRecord station{GroundMotion("a", 0.01, {0.0, 1.0, 0.0}), 0.0, GroundMotion("b", 0.0100001, {0.0, 1.0}), 90.0,
                        std::nullopt};
  try {
    station.align();
    FAIL() << "different intervals accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("0.01 s and 0.0100001 s"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(same_sample_interval(19.9 / 1990, 0.01));
  EXPECT_FALSE(same_sample_interval(0.01, 0.01 * (1 + 1e-8)));
}

}  // namespace
}  // namespace pcrf
