// The three second axes: scale factors, intensity stripes and an IDA each give their
// dimensions (before or after the frames), coordinates, row columns and canonical line.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "pcrf/study/case_space.hpp"
#include "pcrf/study/level_axis.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study {
namespace {

const std::string kRecords = "[[records]]\nsynthetic = [\"sine:amplitude_g=1.5\", \"sine:amplitude_g=0.5\"]\n[axes]\nkappa = [1.5, 2]\n";

Study parse(const std::string& text) { return parse_study(kRecords + text, "t.toml", test::source_dir()); }

std::string line_of(const LevelAxis& axis) {
  std::ostringstream out;
  axis.describe(out);
  return out.str();
}

bool has_coordinate(const cube::CubeLayout& layout, const std::string& name, const std::string& dimension, std::size_t size) {
  return std::any_of(layout.coordinates.begin(), layout.coordinates.end(),
                     [&](const auto& c) { return c.name == name && c.dimension == dimension && c.size() == size; });
}

TEST(LevelAxis, ScaleFactorsAreTheDimensionBeforeTheFrames) {
  const Study study = parse("scale = [0.5, 1, 2]\n");
  const CaseSpace space(study);
  EXPECT_EQ(space.dimension_names(), (std::vector<std::string>{"record", "scale", "kappa", "lambda", "tan_alpha", "lambda_h",
                                                               "pi_sigma_b", "pi_sigma_c", "pi_e_b", "pi_e_c"}));
  const LevelAxis& axis = space.level_axis();
  EXPECT_EQ(axis.levels(), (std::vector<double>{0.5, 1, 2}));
  EXPECT_TRUE(axis.row_variables().empty());
  EXPECT_EQ(line_of(axis), "scale 0.5 1 2");
  RecordCache records(study.records);
  cube::CubeLayout layout;
  axis.add_leading(layout, records);
  EXPECT_TRUE(has_coordinate(layout, "scale", "scale", 3));
}

TEST(LevelAxis, IntensityStripesScaleEveryRecordToEveryIntensity) {
  const Study study = parse("intensity = [0.5, 1]\n[intensity]\nmeasure = \"pga_g\"\n");
  const CaseSpace space(study);
  EXPECT_EQ(space.dimension_names()[1], "intensity");
  const LevelAxis& axis = space.level_axis();
  EXPECT_EQ(line_of(axis), "intensity 0.5 1");
  RecordCache records(study.records);
  cube::CubeLayout layout;
  axis.add_leading(layout, records);
  EXPECT_TRUE(has_coordinate(layout, "intensity", "intensity", 2));
  EXPECT_TRUE(has_coordinate(layout, "record_pga_g", "record", 2));
  ASSERT_EQ(layout.side_variables.size(), 1u);
  const auto& factor = layout.side_variables.front();
  EXPECT_EQ(factor.name, "scale_factor");
  ASSERT_EQ(factor.values.size(), 4u);  // record × intensity
  EXPECT_DOUBLE_EQ(factor.values[3] * records.intensity(1, *study.intensity), 1.0);
}

TEST(LevelAxis, AnIdaPutsTheRunsOfACurveAfterTheFrames) {
  const std::string ida = "[intensity]\nmeasure = \"pga_g\"\n[ida]\nstart = 0.5\nmax_intensity = 4\nmax_runs = 5\n";
  const Study study = parse(ida + "[solver]\nverdict_check = true\n");
  const CaseSpace space(study);
  EXPECT_EQ(space.dimension_names()[1], "kappa");
  EXPECT_EQ(space.dimension_names().back(), "ida_point");
  EXPECT_EQ(space.ida_runs(), 5u);
  EXPECT_EQ(space.curves(), 2 * 2);
  const LevelAxis& axis = space.level_axis();
  EXPECT_TRUE(axis.levels().empty());
  ASSERT_EQ(axis.row_variables().size(), 2u);
  EXPECT_EQ(axis.row_variables()[0].name, "ida_intensity");
  RecordCache records(study.records);
  cube::CubeLayout layout;
  axis.add_leading(layout, records);
  axis.add_trailing(layout, {"record", "kappa"});
  EXPECT_TRUE(has_coordinate(layout, "record_pga_g", "record", 2));
  EXPECT_TRUE(has_coordinate(layout, "ida_point", "ida_point", 5));
  std::vector<std::string> side;
  for (const auto& s : layout.side_variables) {
    side.push_back(s.name);
    EXPECT_EQ(s.dimensions, (std::vector<std::string>{"record", "kappa"})) << s.name;
  }
  EXPECT_EQ(side, (std::vector<std::string>{"collapse_intensity", "last_safe_intensity", "ida_runs", "curve_state",
                                            "unresolved_runs", "unstable_from_intensity", "unstable_to_intensity"}));
  cube::CubeLayout plain;
  make_level_axis(parse(ida))->add_trailing(plain, {"record", "kappa"});
  EXPECT_EQ(plain.side_variables.size(), 5u);  // no verdict check, no unstable band
}

}  // namespace
}  // namespace pcrf::study
