// The result row's columns: the stored metrics in the study's order, then an IDA run's
// intensity and scale factor; the cube declares its variables in that order, and a failed
// case clears the metrics only.
#include <gtest/gtest.h>

#include <cmath>

#include "pcrf/study/case_space.hpp"
#include "pcrf/run/result_row.hpp"
#include "pcrf/run/study_cube.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study {
namespace {

const std::string kIda =
    "[[records]]\nsynthetic = \"sine:amplitude_g=1.5\"\n[intensity]\nmeasure = \"pga_g\"\n"
    "[ida]\nstart = 0.5\nmax_intensity = 4\nmax_runs = 4\n[outputs]\nmetrics = [\"impacts\", \"theta_max_rad\"]\n";

TEST(ResultColumns, AnIdaRowEndsWithTheRunsIntensityAndFactor) {
  const Study study = parse_study(kIda, "t.toml", test::source_dir());
  const run::ResultColumns columns(study);
  ASSERT_EQ(columns.width(), 4u);
  EXPECT_EQ(columns.metric_column("theta_max_rad"), 1u);
  EXPECT_EQ(columns.metric_column("omega_max_rad_s"), run::ResultColumns::npos);  // not stored
  EXPECT_EQ(columns.ida_intensity_column(), 2u);
  EXPECT_EQ(columns.scale_factor_column(), 3u);
  EXPECT_EQ(columns.variables()[columns.ida_intensity_column()].name, "ida_intensity");
  EXPECT_EQ(columns.variables()[columns.ida_intensity_column()].units, "g");
  EXPECT_EQ(columns.variables()[columns.scale_factor_column()].name, "scale_factor");

  auto row = columns.empty_row();
  ASSERT_EQ(row.size(), 4u);
  for (double v : row) EXPECT_TRUE(std::isnan(v));
  row = {1.0, 0.01, 0.7, 2.0};
  columns.clear_metrics(row);
  EXPECT_TRUE(std::isnan(row[0]) && std::isnan(row[1]));
  EXPECT_EQ(row[2], 0.7);  // known before the run: kept
  EXPECT_EQ(row[3], 2.0);
}

TEST(ResultColumns, WithoutAnIdaTheRowIsTheMetrics) {
  const Study study = parse_study("[[records]]\nsynthetic = \"sine:amplitude_g=1.5\"\n[outputs]\nmetrics = [\"impacts\"]\n",
                                  "t.toml", test::source_dir());
  const run::ResultColumns columns(study);
  EXPECT_EQ(columns.width(), 1u);
  EXPECT_EQ(columns.ida_intensity_column(), run::ResultColumns::npos);
  EXPECT_EQ(columns.scale_factor_column(), run::ResultColumns::npos);
}

TEST(ResultColumns, TheCubeDeclaresItsMetricVariablesInColumnOrder) {
  const Study study = parse_study(kIda, "t.toml", test::source_dir());
  const CaseSpace space(study);
  RecordCache records(study.records);
  const auto layout = run::make_cube_layout(study, space, records, "0123456789abcdef");
  const run::ResultColumns columns(study);
  ASSERT_EQ(layout.metrics.size(), columns.width());
  for (std::size_t c = 0; c < columns.width(); ++c) EXPECT_EQ(layout.metrics[c].name, columns.variables()[c].name) << c;
}

}  // namespace
}  // namespace pcrf::study
