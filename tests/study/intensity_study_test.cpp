// Studies that scale every record to a common intensity: the cube's intensity axis, its
// scale factors, the records' unscaled intensities, and the cube equals `pcrf run
// --measure … --intensity …` case by case.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include <fstream>
#include <sstream>

#include "pcrf/analysis/fragility.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

const std::string kTwoPulses = std::string("[[records]]\nsynthetic = [\"") + kPulse + "\", \"" + kPulse2 + "\"]\n";

test::CommandResult run_in(const std::filesystem::path& dir, const std::string& text, const std::string& args) {
  const auto file = test::write_file(dir, "im.toml", text);
  return test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study " + quoted(file) + " " + args);
}

TEST(IntensityStudy, EachRecordIsScaledToTheIntensity) {
  const auto dir = test::scratch_dir("intensity_study");
  const std::string text = kTwoPulses + "[intensity]\nmeasure = \"sa_g\"\nperiod_s = 0.5\n[axes]\nintensity = [1.2, 2.0]\n";
  const auto r = run_in(dir, text, "-o im.h5 --progress-interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "im.h5");
  const auto& layout = cube.layout();
  ASSERT_EQ(layout.dimensions[1].name, "intensity");
  EXPECT_EQ(layout.find_coordinate("intensity")->units, "g");
  EXPECT_NE(layout.find_coordinate("intensity")->long_name.find("Sa(T = 0.5 s, 5 % damping)"), std::string::npos);
  const auto* unscaled = layout.find_coordinate("record_sa_g");
  ASSERT_NE(unscaled, nullptr);
  const auto factors = cube.read_side("scale_factor");
  ASSERT_EQ(factors.size(), 4u);
  const auto theta = cube.read_metric("theta_max_rad");
  for (std::size_t rec = 0; rec < 2; ++rec) {
    const double sa = spectral_acceleration_g(make_synthetic(rec == 0 ? kPulse : kPulse2), 0.5);
    EXPECT_DOUBLE_EQ(unscaled->numbers[rec], sa);
    for (std::size_t l = 0; l < 2; ++l) {
      const double level = layout.find_coordinate("intensity")->numbers[l];
      EXPECT_DOUBLE_EQ(factors[rec * 2 + l], level / sa);
      // The scaled record has the intensity asked for.
      EXPECT_NEAR(spectral_acceleration_g(make_synthetic(rec == 0 ? kPulse : kPulse2).scaled(level / sa), 0.5), level, 1e-12 * level);
      const auto run = test::run_command(pcrf() + " run --synthetic '" + (rec == 0 ? kPulse : kPulse2) +
                                         "' --measure sa_g --period-s 0.5 --intensity " + layout.find_coordinate("intensity")->label(l));
      ASSERT_EQ(run.exit_code, 0) << run.err;
      const auto at = run.out.find("\"theta_max_rad\": ");
      EXPECT_EQ(std::strtod(run.out.c_str() + at + 17, nullptr), theta[rec * 2 + l]) << rec << ", " << l;
    }
  }
}

TEST(IntensityStudy, BadIntensityStudiesAreRejected) {
  const auto dir = test::scratch_dir("intensity_bad");
  test::write_file(dir, "zero.txt", "0 0\n0.01 0\n0.02 0\n");
  test::write_file(dir, "huge.txt", "0 1e300\n0.01 -1e300\n0.02 1e300\n");
  const std::map<std::string, std::string> corpus = {
      {kTwoPulses + "[intensity]\nmeasure = \"pga_g\"\n[axes]\nscale = [1]\nintensity = [1]\n", "not both"},
      {kTwoPulses + "[axes]\nintensity = [1]\n", "an intensity axis needs an [intensity] table"},
      {kTwoPulses + "[intensity]\nmeasure = \"sa_g\"\n[axes]\nintensity = [1]\n",
       "im.toml:3: [intensity] period_s: sa_g needs an oscillator period above 0 s"},
      {kTwoPulses + "[intensity]\nmeasure = \"sa_g\"\nperiod_s = -1\n[axes]\nintensity = [1]\n",
       "im.toml:5: [intensity] period_s: must not be negative"},
      {kTwoPulses + "[intensity]\nmeasure = \"pga\"\n[axes]\nintensity = [1]\n", "[intensity] measure: unknown value \"pga\""},
      {kTwoPulses + "[intensity]\nmeasure = \"pga_g\"\n", "an [intensity] table needs [axes] intensity"},
      {"[[records]]\nfile = \"zero.txt\"\n[intensity]\nmeasure = \"pga_g\"\n[axes]\nintensity = [1]\n",
       "im.toml:2: [[records]] #1 file: record \"zero\" has pga_g = 0: it cannot be scaled to an intensity"},
      {kTwoPulses + "[intensity]\nmeasure = \"pga_g\"\nperiod_s = 1.0\n[axes]\nintensity = [1]\n",
       "im.toml:5: [intensity] period_s: pga_g has no oscillator: period_s belongs to sa_g"},
      {kTwoPulses + "[intensity]\nmeasure = \"sa_g\"\nperiod_s = 1e-9\n[axes]\nintensity = [1]\n",
       "im.toml:5: [intensity] period_s: an oscillator period of 1e-09 s is below 2·dt"},
      {kTwoPulses + "[intensity]\nmeasure = \"sa_g\"\nperiod_s = 1e300\n[axes]\nintensity = [1]\n",
       "im.toml:5: [intensity] period_s: the oscillator period must be above 0 s and at most 100 s, got 1e+300 s"},
      {kTwoPulses + "[intensity]\nmeasure = \"sa_g\"\nperiod_s = inf\n[axes]\nintensity = [1]\n", "[intensity] period_s"},
      {"[[records]]\nfile = \"huge.txt\"\n[axes]\nscale = [1]\n",
       "im.toml:2: [[records]] #1 file: record \"huge\": its accelerations (PGA 1e+300 g) overflow the intensity measures"},
  };
  for (const auto& [text, message] : corpus) {
    const auto r = run_in(dir, text, "-o bad.h5");
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_NE(r.err.find(message), std::string::npos) << "got: " << r.err << "\nfor:\n" << text;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.h5"));
    const auto check = run_in(dir, text, "--check");  // --check refuses what the run refuses
    EXPECT_EQ(check.exit_code, 2) << text;
    EXPECT_EQ(check.err, r.err) << text;
  }
  const auto both = test::run_command(pcrf() + " run --synthetic '" + kPulse + "' --scale 2 --intensity 1");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("either --scale or --intensity"), std::string::npos) << both.err;
}

TEST(IntensityStudy, FragilityFitsTheStripesOfTheCube) {
  const auto dir = test::scratch_dir("fragility_cli");
  std::string records = "[[records]]\nsynthetic = [";
  for (int seed = 1; seed <= 8; ++seed)
    records += std::string(seed > 1 ? ", " : "") + "\"stochastic:seed=" + std::to_string(seed) + ",pga_g=1,duration_s=8\"";
  records += "]\n";
  const std::string text = records + "[intensity]\nmeasure = \"pga_g\"\n[axes]\nintensity = [1.5, 2.5, 4, 6, 9]\n";
  ASSERT_EQ(run_in(dir, text, "-o f.h5 --progress-interval 0").exit_code, 0);
  const auto r = test::run_command(pcrf() + " cube fragility " + quoted(dir / "f.h5") + " --mce 1.5 --csv " + quoted(dir / "f.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("median [g]"), std::string::npos) << r.out;
  // The same fit from the cube's statuses.
  cube::CubeReader cube(dir / "f.h5");
  const auto status = cube.read_status();
  const auto& levels = cube.layout().find_coordinate("intensity")->numbers;
  std::vector<analysis::Stripe> stripes;
  for (std::size_t l = 0; l < levels.size(); ++l) {
    analysis::Stripe s{levels[l], 0, 0};
    for (std::size_t rec = 0; rec < 8; ++rec) {
      s.trials += 1;
      s.collapses += status[rec * levels.size() + l] == 2 || status[rec * levels.size() + l] == 3;
    }
    stripes.push_back(s);
  }
  const auto fit = analysis::fit_stripes(stripes);
  ASSERT_TRUE(fit) << r.out;
  std::ifstream csv(dir / "f.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header.rfind("frame,records,cases,collapses,failed,median [g],", 0), 0u) << header;
  std::vector<std::string> cells;
  for (std::stringstream in(row); std::getline(in, header, ',');) cells.push_back(header);
  ASSERT_EQ(cells.size(), 12u) << row;
  EXPECT_NEAR(std::stod(cells[5]), fit->median, 1e-3 * fit->median);
  EXPECT_NEAR(std::stod(cells[8]), fit->beta, 1e-3 * fit->beta);
  EXPECT_NEAR(std::stod(cells[11]), fit->median / 1.5, 1e-3 * fit->median);
  // A cube without an intensity axis has nothing to fit against.
  ASSERT_EQ(run_in(dir, kTwoPulses, "-o s.h5 --progress-interval 0").exit_code, 0);
  const auto scale_only = test::run_command(pcrf() + " cube fragility " + quoted(dir / "s.h5"));
  EXPECT_EQ(scale_only.exit_code, 2);
  EXPECT_NE(scale_only.err.find("has no 'intensity' axis"), std::string::npos) << scale_only.err;
}

TEST(IntensityStudy, GlobsSortNaturallyAndTextRecordsSkipRows) {
  const auto dir = test::scratch_dir("natural_sort");
  for (const char* name : {"ER10.txt", "ER2.txt", "ER1.txt"})
    test::write_file(dir, name, "# header\n0 0.1\n0.01 0.2\n0.02 0.1\n");
  const auto s = study::parse_study("[[records]]\nfiles = \"ER*.txt\"\nskip_rows = 1\n", "t.toml", dir);
  ASSERT_EQ(s.records.size(), 3u);
  EXPECT_EQ(s.records[0].name, "ER1");
  EXPECT_EQ(s.records[1].name, "ER2");
  EXPECT_EQ(s.records[2].name, "ER10");
  EXPECT_EQ(s.records[0].file->skip_rows, 1u);
}

}  // namespace
}  // namespace pcrf::study_test
