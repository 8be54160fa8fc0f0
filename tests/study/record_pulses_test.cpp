// Issue 42 item 4: studies use T_p. With [outputs] record_pulses every record's pulse is
// identified (Baker 2007 on one component, Shahi & Baker 2014 on a pair) and the cube gets
// pulse_like, pulse_method, pulse_period_s and pulse_azimuth_deg along `record`, and ω_p/p =
// 2π/(T_p p) over record and frame, as [[records]] pulse entries have.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pcrf/excitation/station_pulse.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/run/study_cube.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/fingerprint.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study {
namespace {

struct Made {
  Study study;
  cube::CubeLayout layout;
};

Made layout_of(const std::string& text, const std::filesystem::path& dir = test::source_dir()) {
  Study study = parse_study(text, "t.toml", dir);
  const CaseSpace space(study);
  RecordCache records(study.records);
  auto layout = run::make_cube_layout(study, space, records, "0123456789abcdef");
  return {std::move(study), std::move(layout)};
}

const cube::Coordinate& coordinate(const cube::CubeLayout& layout, const std::string& name) {
  const auto* c = layout.find_coordinate(name);
  if (c == nullptr) throw std::runtime_error("no coordinate " + name);
  return *c;
}

// A ricker pulse given as a motion (identified: Baker 2007), a stochastic motion (no pulse),
// and a [[records]] pulse entry (its period given): one pulse_period_s over all three, and
// ω_p/p = 2π/(T_p p) for every record and frame, NaN for the record without a pulse.
TEST(RecordPulses, EveryRecordGetsItsPulseAndOmegaOverP) {
  const std::string ricker = "ricker:period_s=1.2,amplitude_g=0.5,duration_s=20,dt_s=0.01";
  const std::string text = "[[records]]\nsynthetic = [\"" + ricker +
                           "\", \"stochastic:seed=3,pga_g=0.3,duration_s=20,dt_s=0.01\"]\n"
                           "[[records]]\npulse = \"ricker\"\ndt_s = 0.01\n"
                           "[axes]\npulse_period_s = [0.8]\npulse_amplitude_g = [0.5]\nlambda = [2, 3]\n"
                           "[outputs]\nrecord_pulses = true\n";
  const auto [study, layout] = layout_of(text);
  ASSERT_EQ(study.records.size(), 3u);
  const cube::Coordinate like = coordinate(layout, "record_pulse_like");
  const cube::Coordinate method = coordinate(layout, "record_pulse_method");
  const cube::Coordinate period = coordinate(layout, "pulse_period_s");
  EXPECT_TRUE(like.is_index);
  EXPECT_EQ(like.numbers, (std::vector<double>{1.0, 0.0, 1.0}));
  EXPECT_EQ(method.strings, (std::vector<std::string>{"baker-2007", "baker-2007", "synthetic-pulse"}));
  // The identified T_p is the one `pcrf record pulse` gives for the same motion.
  const PulseClassification direct = classify_pulse(make_synthetic(ricker));
  ASSERT_TRUE(direct.pulse_like);
  EXPECT_EQ(period.numbers[0], direct.period_s);
  EXPECT_TRUE(std::isnan(period.numbers[1]));  // not pulse-like: NaN, never 0
  EXPECT_EQ(period.numbers[2], 0.8);
  EXPECT_TRUE(std::isnan(coordinate(layout, "record_pulse_azimuth_deg").numbers[0]));  // one component: none
  // One pulse_period_s coordinate, not the axis' and the identified one.
  int periods = 0;
  for (const auto& c : layout.coordinates) periods += c.name == "pulse_period_s";
  EXPECT_EQ(periods, 1);

  const auto* p = layout.find_side_variable("frame_frequency_parameter_rad_s");
  const auto* ratio = layout.find_side_variable("omega_p_over_p");
  ASSERT_TRUE(p != nullptr && ratio != nullptr);
  ASSERT_EQ(p->values.size(), 2u);
  EXPECT_NE(p->values[0], p->values[1]);  // two frames
  EXPECT_EQ(ratio->dimensions.front(), "record");
  ASSERT_EQ(ratio->values.size(), 6u);
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t f = 0; f < 2; ++f) {
      const double v = ratio->values[r * 2 + f];
      if (r == 1) {
        EXPECT_TRUE(std::isnan(v));
      } else {
        EXPECT_DOUBLE_EQ(v, 2.0 * std::numbers::pi / (period.numbers[r] * p->values[f]));
      }
    }
}

// The study key changes the cube, so it changes the fingerprint (a cube made without the pulse
// coordinates is not resumed as one with them); studies without it keep theirs.
TEST(RecordPulses, TheKeyIsPartOfTheFingerprintAndOffByDefault) {
  const std::string base = "[[records]]\nsynthetic = \"ricker:period_s=1.2,amplitude_g=0.5,duration_s=20,dt_s=0.01\"\n";
  auto fingerprint = [](const std::string& text) {
    const Study study = parse_study(text, "t.toml", test::source_dir());
    const CaseSpace space(study);
    RecordCache records(study.records);
    return std::make_pair(study_fingerprint(study, space, records), canonical_description(study, space, records));
  };
  const auto [plain, plain_text] = fingerprint(base);
  const auto [off, off_text] = fingerprint(base + "[outputs]\nrecord_pulses = false\n");
  const auto [on, on_text] = fingerprint(base + "[outputs]\nrecord_pulses = true\n");
  EXPECT_EQ(plain, off);
  EXPECT_NE(plain, on);
  EXPECT_EQ(plain_text.find("record_pulses"), std::string::npos);
  const auto [study, layout] = layout_of(base);
  EXPECT_EQ(layout.find_coordinate("record_pulse_like"), nullptr);
  EXPECT_EQ(layout.find_coordinate("pulse_period_s"), nullptr);
  EXPECT_EQ(layout.find_side_variable("omega_p_over_p"), nullptr);
}

// A pair whose files state no azimuths cannot be classified by orientation: refused at its
// [[records]] entry before anything is written; a flag that is not a boolean is refused too.
TEST(RecordPulses, APairWithoutAzimuthsIsRefusedAtItsEntry) {
  const auto dir = test::scratch_dir("record_pulses_pair");
  const GroundMotion a = make_synthetic("ricker:period_s=1,amplitude_g=0.5,duration_s=10,dt_s=0.01");
  for (const char* name : {"h1.txt", "h2.txt"}) {
    std::string rows;
    for (std::size_t i = 0; i < a.size(); ++i)
      rows += std::to_string(static_cast<double>(i) * a.dt_s()) + " " + std::to_string(a.samples_m_s2()[i]) + "\n";
    test::write_file(dir, name, rows);
  }
  const std::string entry = "[[records]]\nh1 = \"h1.txt\"\nh2 = \"h2.txt\"\nunits = \"m/s2\"\n";
  try {
    layout_of(entry + "[outputs]\nrecord_pulses = true\n", dir);
    ADD_FAILURE() << "no error";
  } catch (const UserError& e) {
    const std::string m = e.message(Dialect::kStudy);
    EXPECT_NE(m.find("t.toml:2: [[records]] #1 h1: [outputs] record_pulses: record \"h1\""), std::string::npos) << m;
    EXPECT_NE(m.find("give az1_deg and az2_deg"), std::string::npos) << m;
  }
  const auto [study, layout] = layout_of(entry + "az1_deg = 0\naz2_deg = 90\n[outputs]\nrecord_pulses = true\n", dir);
  EXPECT_EQ(coordinate(layout, "record_pulse_method").strings.front(), "shahi-baker-2014");
  try {
    layout_of(entry + "[outputs]\nrecord_pulses = 1\n", dir);
    ADD_FAILURE() << "no error";
  } catch (const UserError& e) {
    EXPECT_NE(e.message(Dialect::kStudy).find("[outputs] record_pulses"), std::string::npos) << e.message(Dialect::kStudy);
  }
}

// Real records: Rinaldi (Northridge 1994, a pulse) and Chihuahua (Imperial Valley 1979, no
// pulse, labelled so in ../shared/records' MANIFEST) as pairs: the cube's T_p and azimuth are
// Shahi & Baker's on the same components, bit for bit, and Chihuahua's T_p is NaN.
TEST(RecordPulses, RealPairsGetShahiAndBakersPulse) {
  PCRF_REQUIRE_RECORDS(records);
  const auto rinaldi = records / "nearfault_vacalderon" / "RSN1063_NORTHR_RRS228.AT2";
  const auto chihuahua = records / "nearfault_hsiifu3" / "RSN165_IMPVALL.H_H-CHI012.AT2";
  if (!std::filesystem::exists(rinaldi) || !std::filesystem::exists(chihuahua)) GTEST_SKIP() << "records not present";
  const std::string text = "[[records]]\nh1 = \"" + rinaldi.string() + "\"\nh2 = \"" +
                           (records / "nearfault_vacalderon" / "RSN1063_NORTHR_RRS318.AT2").string() +
                           "\"\n[[records]]\nh1 = \"" + chihuahua.string() + "\"\nh2 = \"" +
                           (records / "nearfault_hsiifu3" / "RSN165_IMPVALL.H_H-CHI282.AT2").string() +
                           "\"\n[outputs]\nrecord_pulses = true\n";
  const auto [study, layout] = layout_of(text);
  RecordCache cache(study.records);
  const PulseClassification direct = classify_station_pulse(cache.station(0));
  ASSERT_TRUE(direct.pulse_like);
  EXPECT_EQ(coordinate(layout, "record_pulse_like").numbers, (std::vector<double>{1.0, 0.0}));
  EXPECT_EQ(coordinate(layout, "record_pulse_method").strings, (std::vector<std::string>{"shahi-baker-2014", "shahi-baker-2014"}));
  EXPECT_EQ(coordinate(layout, "pulse_period_s").numbers[0], direct.period_s);
  EXPECT_EQ(coordinate(layout, "record_pulse_azimuth_deg").numbers[0], direct.candidates[direct.decided_by].azimuth_deg);
  EXPECT_NEAR(direct.period_s, 1.25, 0.01);  // docs/commands/record.md's table (Baker 2007: 1.2 s)
  EXPECT_TRUE(std::isnan(coordinate(layout, "pulse_period_s").numbers[1]));
  EXPECT_TRUE(std::isnan(coordinate(layout, "record_pulse_azimuth_deg").numbers[1]));
}

}  // namespace
}  // namespace pcrf::study
