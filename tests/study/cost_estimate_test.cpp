// `pcrf study --check`'s cost estimate (issue 41 item 7): which work it samples and what it
// calls its figure. Its timings are measured by bench/check_estimate.py, not here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/run/cost_estimate.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

using run::CostEstimate;

TEST(CostEstimate, SamplePositionsAreTheMiddlesOfEqualPartsAndEveryPrefixIsSpread) {
  const auto positions = run::sample_positions(100, 16);
  ASSERT_EQ(positions.size(), 16u);
  std::vector<std::int64_t> sorted = positions;
  std::sort(sorted.begin(), sorted.end());
  for (std::int64_t k = 0; k < 16; ++k) EXPECT_EQ(sorted[static_cast<std::size_t>(k)], k * 100 / 16 + 3);
  // The first two in different halves, the first four one in each quarter.
  EXPECT_NE(positions[0] / 50, positions[1] / 50);
  std::set<std::int64_t> quarters;
  for (std::size_t k = 0; k < 4; ++k) quarters.insert(positions[k] / 25);
  EXPECT_EQ(quarters.size(), 4u);
  // Fewer units than the sample: each once; none: nothing.
  const auto all = run::sample_positions(5, 16);
  EXPECT_EQ(std::set<std::int64_t>(all.begin(), all.end()), (std::set<std::int64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(all.size(), 5u);
  EXPECT_TRUE(run::sample_positions(0, 16).empty());
  // A sample that is not a power of two keeps every slot once.
  const auto eleven = run::sample_positions(1000, 11);
  EXPECT_EQ(std::set<std::int64_t>(eleven.begin(), eleven.end()).size(), 11u);
}

/// The study in `text`, parsed as `pcrf study` would, with its case space and records.
struct Parsed {
  explicit Parsed(const std::filesystem::path& dir, const std::string& text)
      : study(study::parse_study(text, (dir / "s.toml").string(), dir)), space(study), records(study.records) {}
  study::Study study;
  study::CaseSpace space;
  study::RecordCache records;
};

std::string ida_study() {
  std::string text = "[[records]]\nsynthetic = [";
  for (int seed = 1; seed <= 3; ++seed)
    text += std::string(seed > 1 ? ", " : "") + "\"stochastic:seed=" + std::to_string(seed) + ",pga_g=1,duration_s=6\"";
  return text + "]\n[axes]\nkappa = [1.4, 2.2]\n[intensity]\nmeasure = \"pga_g\"\n[ida]\nstart = 0.25\nmax_intensity = 8\n"
                "max_runs = 10\n[outputs]\nmetrics = [\"theta_max_rad\"]\n";
}

TEST(CostEstimate, AnIdaIsSampledAtTheIntensitiesItsCurvesReach) {
  // The runs the estimate times for a curve are the runs the study makes for it: compared
  // with the cube of the same study, curve by curve, intensity by intensity.
  const auto dir = test::scratch_dir("cost_estimate_ida");
  const auto file = test::write_file(dir, "s.toml", ida_study());
  const auto r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study s.toml -o ida.h5 --progress-interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "ida.h5");
  const auto intensity = cube.read_metric("ida_intensity");
  const auto runs = cube.read_side("ida_runs");

  Parsed p(dir, ida_study());
  const CostEstimate estimate = run::estimate_cost(p.study, p.space, p.records, 4, 1e9);
  EXPECT_TRUE(estimate.ida);
  EXPECT_EQ(estimate.population, 6);
  ASSERT_EQ(estimate.sampled(), 4);
  std::map<std::int64_t, std::vector<double>> by_curve;
  for (const auto& item : estimate.runs) by_curve[item.case_index / 10].push_back(item.argument);
  ASSERT_EQ(by_curve.size(), 4u);
  bool beyond_start = false;
  for (const auto& [curve, timed] : by_curve) {
    const auto c = static_cast<std::size_t>(curve);
    ASSERT_EQ(static_cast<double>(timed.size()), runs[c]) << "curve " << curve;
    for (std::size_t k = 0; k < timed.size(); ++k) {
      EXPECT_EQ(timed[k], intensity[c * 10 + k]) << "curve " << curve << " run " << k;
      beyond_start = beyond_start || timed[k] > 0.25;
    }
  }
  EXPECT_TRUE(beyond_start);
  // Each case index belongs to its run's point of the curve, in order.
  for (std::size_t i = 1; i < estimate.runs.size(); ++i) {
    if (estimate.runs[i].case_index / 10 == estimate.runs[i - 1].case_index / 10) {
      EXPECT_EQ(estimate.runs[i].case_index, estimate.runs[i - 1].case_index + 1);
    }
  }

  const std::string text = estimate.text();
  EXPECT_NE(text.find("CPU"), std::string::npos) << text;
  EXPECT_NE(text.find("4 sampled IDA curves of 6"), std::string::npos) << text;
  EXPECT_NE(text.find("two standard errors"), std::string::npos) << text;
  EXPECT_EQ(text.find("upper bound"), std::string::npos) << text;
  EXPECT_GE(estimate.two_standard_errors_cpu_s(), 0.0);
}

TEST(CostEstimate, AGridIsSampledOverItsHandOutOrder) {
  const auto dir = test::scratch_dir("cost_estimate_grid");
  Parsed p(dir, small_grid_study("[run]\nlanes = 1\n"));
  const CostEstimate estimate = run::estimate_cost(p.study, p.space, p.records, 8, 1e9);
  EXPECT_FALSE(estimate.ida);
  EXPECT_EQ(estimate.population, 24);
  const auto positions = run::sample_positions(24, 8);
  ASSERT_EQ(estimate.runs.size(), positions.size());
  for (std::size_t k = 0; k < positions.size(); ++k) {
    EXPECT_EQ(estimate.runs[k].case_index, p.space.handout_index(positions[k]));
    EXPECT_EQ(estimate.runs[k].argument, 0.0);
  }
  const std::string text = estimate.text();
  EXPECT_NE(text.find("8 sampled cases of 24"), std::string::npos) << text;
  EXPECT_EQ(text.find("upper bound"), std::string::npos) << text;
  // The figure is the sample mean scaled to the study.
  double sum = 0.0;
  for (const double s : estimate.unit_cpu_s) sum += s;
  EXPECT_DOUBLE_EQ(estimate.total_cpu_s(), 24.0 * sum / 8.0);
}

TEST(CostEstimate, InLanesASampledCaseIsSolvedWithItsLaneMates) {
  // 4 frames under each of the 6 excitations (3 records × 2 scales): a case's lane batch is 4
  // cases of its excitation, the sampled one first; each unit costs its share of the batch.
  const auto dir = test::scratch_dir("cost_estimate_lanes");
  Parsed p(dir, small_grid_study("[run]\nlanes = 4\n"));
  const CostEstimate estimate = run::estimate_cost(p.study, p.space, p.records, 5, 1e9);
  const auto positions = run::sample_positions(24, 5);
  ASSERT_EQ(estimate.unit_runs.size(), positions.size());
  std::size_t cursor = 0;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    ASSERT_EQ(estimate.unit_runs[k], 4u) << "unit " << k;
    const std::int64_t sampled = p.space.handout_index(positions[k]);
    EXPECT_EQ(estimate.runs[cursor].case_index, sampled);
    std::set<std::int64_t> distinct;
    for (std::size_t r = cursor; r < cursor + 4; ++r) {
      EXPECT_EQ(p.space.excitation_of(estimate.runs[r].case_index), p.space.excitation_of(sampled));
      distinct.insert(estimate.runs[r].case_index);
    }
    EXPECT_EQ(distinct.size(), 4u);
    cursor += 4;
  }
  EXPECT_EQ(estimate.runs.size(), cursor);
}

TEST(CostEstimate, EveryUnitTimedHasNoSamplingErrorAndOneUnitNoSpread) {
  CostEstimate all;
  all.population = 3;
  all.unit_cpu_s = {0.1, 0.2, 0.6};
  EXPECT_DOUBLE_EQ(all.total_cpu_s(), 0.9);
  EXPECT_EQ(all.two_standard_errors_cpu_s(), 0.0);
  EXPECT_NE(all.text().find("every one of the study's cases timed"), std::string::npos) << all.text();
  CostEstimate one;
  one.population = 50;
  one.unit_cpu_s = {0.1};
  EXPECT_TRUE(std::isnan(one.two_standard_errors_cpu_s()));
  EXPECT_NE(one.text().find("spread unknown"), std::string::npos) << one.text();
  // Two of four: mean 0.2, sample variance 0.02, error of the mean sqrt(0.02/2 · (1 − 2/4)).
  CostEstimate two;
  two.population = 4;
  two.unit_cpu_s = {0.1, 0.3};
  EXPECT_NEAR(two.two_standard_errors_cpu_s(), 2.0 * 4.0 * std::sqrt(0.02 / 2.0 * 0.5), 1e-15);
  EXPECT_EQ(CostEstimate{}.text(), "no case could be timed: no cost estimate");
}

}  // namespace
}  // namespace pcrf::study_test
