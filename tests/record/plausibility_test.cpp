/// \file plausibility_test.cpp
/// \brief record_plausibility: a file read in the wrong units is flagged with the unit that
/// fits, and every real record of ../shared/records read in its own units is not.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_readers.hpp"
#include "support/test_support.hpp"

namespace pcrf {
namespace {

/// A record with PGA `pga` in `unit`, read as if it were in `read_as`.
GroundMotion read_as(double pga, AccelUnit unit, AccelUnit read_as_unit) {
  std::vector<double> a;
  for (int i = 0; i < 2000; ++i) a.push_back(pga * std::sin(0.05 * i) * std::exp(-0.002 * i));
  for (double& x : a) x *= to_m_s2(read_as_unit);  // the numbers as written, taken in read_as_unit
  (void)unit;
  return GroundMotion("r", 0.01, a);
}

TEST(RecordPlausibility, AFileInOtherUnitsIsFlaggedWithTheUnitThatFits) {
  // A cm/s² file (PGA 490 cm/s², 0.5 g) read as g: 490 g.
  const auto as_g = record_plausibility(read_as(490.0, AccelUnit::kCentimeterPerSecond2, AccelUnit::kG), AccelUnit::kG);
  EXPECT_NE(as_g.problem.find("above 3 g"), std::string::npos) << as_g.problem;
  ASSERT_TRUE(as_g.likely_unit.has_value());
  EXPECT_EQ(*as_g.likely_unit, AccelUnit::kCentimeterPerSecond2);
  // A g file (PGA 0.5) read as cm/s²: 0.0005 g.
  const auto as_cm = record_plausibility(read_as(0.5, AccelUnit::kG, AccelUnit::kCentimeterPerSecond2),
                                         AccelUnit::kCentimeterPerSecond2);
  EXPECT_NE(as_cm.problem.find("below"), std::string::npos) << as_cm.problem;
  ASSERT_TRUE(as_cm.likely_unit.has_value());
  EXPECT_EQ(*as_cm.likely_unit, AccelUnit::kG);
  // An m/s² file (PGA 4.9 m/s²) read as cm/s²: 0.005 g; m/s² is the unit that gives 0.5 g.
  const auto m_as_cm = record_plausibility(read_as(4.9, AccelUnit::kMeterPerSecond2, AccelUnit::kCentimeterPerSecond2),
                                           AccelUnit::kCentimeterPerSecond2);
  ASSERT_TRUE(m_as_cm.likely_unit.has_value());
  EXPECT_EQ(*m_as_cm.likely_unit, AccelUnit::kMeterPerSecond2);
  // The same files read in their own units pass.
  EXPECT_TRUE(record_plausibility(read_as(0.5, AccelUnit::kG, AccelUnit::kG), AccelUnit::kG).problem.empty());
}

TEST(RecordPlausibility, AWrongTimeStepIsFlaggedByPgvOverPga) {
  std::vector<double> a;
  for (int i = 0; i < 2000; ++i) a.push_back(3.0 * std::sin(0.05 * i) * std::exp(-0.002 * i));
  EXPECT_TRUE(record_plausibility(GroundMotion("r", 0.01, a), AccelUnit::kG).problem.empty());
  const auto slow = record_plausibility(GroundMotion("r", 1.0, a), AccelUnit::kG);  // dt 100 times too long
  EXPECT_NE(slow.problem.find("PGV/PGA"), std::string::npos) << slow.problem;
}

TEST(RecordPlausibility, EverySharedRecordReadInItsUnitsPasses) {
  PCRF_REQUIRE_RECORDS(dir);
  int checked = 0, other_layout = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    const auto path = entry.path();
    const auto ext = path.extension().string();
    if (ext != ".AT2" && ext != ".txt") continue;
    if (path.filename() == "MetaData.txt") continue;
    RecordFileSpec spec;
    spec.path = path;
    spec.format = guess_record_format(path);
    spec.unit = AccelUnit::kG;  // every series there is in g (README)
    GroundMotion motion("none", 1.0, {0.0});
    try {
      motion = read_record(spec);
    } catch (const UserError&) {  // a text layout of its own (MANIFEST.csv's format column): not a two-column file
      ++other_layout;
      continue;
    }
    const auto p = record_plausibility(motion, AccelUnit::kG);
    EXPECT_TRUE(p.problem.empty()) << path << ": " << p.problem;
    ++checked;
  }
  EXPECT_GE(checked, 190) << other_layout << " files of another layout";
}

}  // namespace
}  // namespace pcrf
