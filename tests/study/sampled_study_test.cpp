// Sampled plans end to end: the cube's frames are the plan's points mapped onto the ranges,
// the saltelli cube's indices are the estimator's on its outputs, and bad sampled studies
// are refused with their file, line and key.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "pcrf/analysis/sobol_indices.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/study/sampling.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

test::CommandResult run_in(const std::filesystem::path& dir, const std::string& text, const std::string& args) {
  const auto file = test::write_file(dir, "s.toml", text);
  return test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study " + quoted(file) + " " + args);
}

const std::string kRecords = std::string("[[records]]\nsynthetic = [\"") + kPulse + "\", \"" + kPulse2 + "\"]\n";

TEST(SampledStudy, LatinHypercubeFramesFillTheRanges) {
  const auto dir = test::scratch_dir("sampled_lhs");
  const std::string text = kRecords + "[plan]\nkind = \"lhs\"\nsamples = 20\nseed = 4\n[axes]\n"
                                      "kappa = {from = 1.2, to = 2.4}\npi_e_c = {from = 1000, to = 8000, spacing = \"log\"}\n";
  ASSERT_EQ(run_in(dir, text, "-o lhs.h5 --progress-interval 0").exit_code, 0);
  cube::CubeReader cube(dir / "lhs.h5");
  const auto& layout = cube.layout();
  EXPECT_EQ(layout.dimensions.back().name, "case");
  EXPECT_EQ(layout.dimensions.back().size, 20u);
  const auto unit = study::latin_hypercube(20, 2, 4);
  const auto* kappa = layout.find_coordinate("kappa");
  const auto* pi_e_c = layout.find_coordinate("pi_e_c");
  for (std::size_t j = 0; j < 20; ++j) {
    EXPECT_DOUBLE_EQ(kappa->numbers[j], 1.2 + unit[j * 2] * 1.2);
    EXPECT_DOUBLE_EQ(pi_e_c->numbers[j], 1000.0 * std::pow(8.0, unit[j * 2 + 1]));
  }
  EXPECT_DOUBLE_EQ(layout.find_coordinate("lambda")->numbers[7], 2.0);  // not varied: the base
}

// A sampled frame's label ("s<case>") is its case number: the cube stores no text per case
// (issue 38), yet a history still names its case by that label, and the fragility table names
// a frame by its case number.
TEST(SampledStudy, LabelsAreNotStoredButStillNameAHistory) {
  const auto dir = test::scratch_dir("sampled_labels");
  const std::string text = kRecords + "[plan]\nkind = \"lhs\"\nsamples = 6\nseed = 2\n[axes]\n"
                                      "kappa = {from = 1.2, to = 2.4}\n"
                                      "[[outputs.histories]]\nlabel = \"four\"\nrecord = \"" + std::string(kPulse) + "\"\ncase = \"s4\"\n";
  const auto run = run_in(dir, text, "-o lhs.h5 --progress-interval 0");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  cube::CubeReader cube(dir / "lhs.h5");
  EXPECT_EQ(cube.layout().find_coordinate("case_label"), nullptr);
  ASSERT_NE(cube.layout().find_coordinate("case"), nullptr);
  const auto names = cube.history_names();
  ASSERT_EQ(names.size(), 1u);
  const auto history = cube.read_history(names[0]);
  bool case_four = false;
  for (const auto& a : history.attributes)
    if (a.name == "case_index")
      if (const auto* i = std::get_if<std::int64_t>(&a.value)) case_four = case_four || *i % 6 == 4;  // linear index: record × scale × case
  EXPECT_TRUE(case_four) << names[0];
}

// Without stored labels, the fragility table names a sampled frame by its case number.
TEST(SampledStudy, FragilityNamesASampledFrameByItsCaseNumber) {
  const auto dir = test::scratch_dir("sampled_fragility");
  const std::string text = kRecords + "[plan]\nkind = \"lhs\"\nsamples = 3\nseed = 3\n[intensity]\nmeasure = \"pga_g\"\n"
                                      "[axes]\nkappa = {from = 1.2, to = 2.4}\nintensity = [0.5, 2.0]\n";
  ASSERT_EQ(run_in(dir, text, "-o lhs.h5 --progress-interval 0").exit_code, 0);
  const auto table = test::run_command(pcrf() + " cube fragility " + quoted(dir / "lhs.h5"));
  ASSERT_EQ(table.exit_code, 0) << table.err;
  for (const char* frame : {"\ncase=0 ", "\ncase=1 ", "\ncase=2 "})
    EXPECT_NE(table.out.find(frame), std::string::npos) << frame << " in\n" << table.out;
}

TEST(SampledStudy, SensitivityOfASaltelliCubeIsTheEstimatorOnItsOutputs) {
  const auto dir = test::scratch_dir("sampled_saltelli");
  const std::string text = kRecords + "[plan]\nkind = \"saltelli\"\nsamples = 32\nscramble = true\n[axes]\n"
                                      "kappa = {from = 1.2, to = 2.4}\ntan_alpha = {from = 0.15, to = 0.25}\n"
                                      "lambda_h = {from = 0.15, to = 0.25}\n";
  ASSERT_EQ(run_in(dir, text, "-o sal.h5 --progress-interval 0").exit_code, 0);
  const auto r = test::run_command(pcrf() + " cube sensitivity " + quoted(dir / "sal.h5") + " -m impacts --csv " +
                                   quoted(dir / "sal.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "sal.h5");
  const auto impacts = cube.read_metric("impacts");
  const auto status = cube.read_status();
  const std::size_t frames = 32 * 5;
  analysis::SaltelliOutputs o{{}, {}, std::vector<std::vector<double>>(3)};
  for (std::size_t j = 0; j < 32; ++j) {
    std::vector<double> y(5);
    bool ok = true;
    for (std::size_t b = 0; b < 5; ++b) {
      const std::size_t c = j * 5 + b;  // record-major: case c of record 0 and record 1
      ok = ok && status[c] <= 3 && status[frames + c] <= 3;
      y[b] = 0.5 * (impacts[c] + impacts[frames + c]);
    }
    if (!ok) continue;
    o.f_a.push_back(y[0]);
    o.f_b.push_back(y[1]);
    for (std::size_t i = 0; i < 3; ++i) o.f_ab[i].push_back(y[2 + i]);
  }
  const auto expected = analysis::sobol_indices(o);
  std::ifstream csv(dir / "sal.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "record,parameter,S1,S1_5%,S1_95%,ST,ST_5%,ST_95%,samples");
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(std::getline(csv, line));
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 9u) << line;
    EXPECT_EQ(cells[1], (std::vector<std::string>{"kappa", "tan_alpha", "lambda_h"})[i]);
    EXPECT_NEAR(std::stod(cells[2]), expected[i].s1, 5e-4) << line;
    EXPECT_NEAR(std::stod(cells[5]), expected[i].st, 5e-4) << line;
  }
  const auto by_record = test::run_command(pcrf() + " cube sensitivity " + quoted(dir / "sal.h5") + " -m collapse --by record");
  ASSERT_EQ(by_record.exit_code, 0) << by_record.err;
  EXPECT_EQ(std::count(by_record.out.begin(), by_record.out.end(), '\n'), 7) << by_record.out;  // header + 2 × 3
}

// Issue 29: a partial Saltelli cube gave an empty sensitivity table, because cases went out
// record by record and no base sample was whole before the last record. They go out base
// sample by base sample: the first half of a run (here shard 1/2) holds whole base samples
// across both records, and gives interim indices saying how many it used.
TEST(SampledStudy, APartialSaltelliCubeGivesInterimIndices) {
  const auto dir = test::scratch_dir("sampled_saltelli_partial");
  const std::string text = kRecords + "[plan]\nkind = \"saltelli\"\nsamples = 16\nscramble = true\n[axes]\n"
                                      "kappa = {from = 1.2, to = 2.4}\ntan_alpha = {from = 0.15, to = 0.25}\n";
  ASSERT_EQ(run_in(dir, text, "-o half.h5 --shard 1/2 --progress-interval 0").exit_code, 0);
  cube::CubeReader cube(dir / "half.h5");
  const auto* sample = cube.layout().find_coordinate("saltelli_sample");
  ASSERT_NE(sample, nullptr);
  EXPECT_TRUE(sample->is_index) << "saltelli_sample is stored as integers";
  const auto status = cube.read_status();
  const std::size_t frames = 16 * 4;
  for (std::size_t c = 0; c < frames; ++c) {  // the first 8 base samples, for both records
    const bool first_half = sample->numbers[c] < 8.0;
    EXPECT_EQ(status[c] != cube::kStatusNotRun, first_half) << c;
    EXPECT_EQ(status[frames + c] != cube::kStatusNotRun, first_half) << c;
  }
  const auto r = test::run_command(pcrf() + " cube sensitivity " + quoted(dir / "half.h5") + " -m impacts --csv -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("interim indices from 8 of 16 base samples"), std::string::npos) << r.err;
  std::stringstream csv(r.out);
  std::string line;
  std::getline(csv, line);
  for (int i = 0; i < 2; ++i) {
    ASSERT_TRUE(std::getline(csv, line)) << r.out;
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 9u) << line;
    EXPECT_TRUE(std::isfinite(std::stod(cells[5]))) << "ST of " << cells[1] << ": " << line;
    EXPECT_EQ(cells[8], "8") << line;
  }
}

TEST(SampledStudy, BadSampledStudiesAreRejected) {
  const auto dir = test::scratch_dir("sampled_bad");
  const std::vector<std::pair<std::string, std::string>> corpus = {
      {kRecords + "[plan]\nkind = \"lhs\"\nsamples = 1\n[axes]\nkappa = {from = 1, to = 2}\n", "s.toml:5: [plan] samples: must be at least 2"},
      {kRecords + "[plan]\nkind = \"sobol\"\nsamples = 8\n[axes]\nkappa = [1, 2]\n", "s.toml:7: [axes] kappa: a sampled plan draws from a range"},
      {kRecords + "[plan]\nkind = \"sobol\"\nsamples = 8\n[axes]\nkappa = {from = 0, to = 2, spacing = \"log\"}\n",
       "[axes] kappa.from: a log range must start above 0"},
      {kRecords + "[plan]\nkind = \"saltelli\"\nsamples = 8\n[axes]\nkappa = {from = 1, to = 2}\n",
       "plan \"saltelli\" needs at least two varied parameters"},
      {kRecords + "[plan]\nkind = \"lhs\"\n[axes]\nkappa = {from = 1, to = 2}\n", "[plan] samples: required"},
      {kRecords + "[plan]\nkind = \"lhs\"\nsamples = 4\n[axes]\nkappa = {from = 1, to = 2, count = 3}\n", "no count"},
  };
  for (const auto& [text, message] : corpus) {
    const auto r = run_in(dir, text, "-o bad.h5");
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_NE(r.err.find(message), std::string::npos) << "got: " << r.err << "\nfor:\n" << text;
  }
  ASSERT_EQ(run_in(dir, kRecords, "-o grid.h5 --progress-interval 0").exit_code, 0);
  const auto not_saltelli = test::run_command(pcrf() + " cube sensitivity " + quoted(dir / "grid.h5") + " -m impacts");
  EXPECT_EQ(not_saltelli.exit_code, 2);
  EXPECT_NE(not_saltelli.err.find("is not a saltelli design"), std::string::npos) << not_saltelli.err;
}

}  // namespace
}  // namespace pcrf::study_test
