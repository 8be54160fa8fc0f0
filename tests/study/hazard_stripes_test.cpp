// Hazard-consistent stripes: [intensity] hazard = "FILE" with return_periods_yr = [...] sets
// the stripes' intensities to the hazard curve's inverse at 1/T (log-log), the file relative
// to the study; every refusal names the study file, line and key (and the hazard file's line).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "pcrf/hazard/hazard_file.hpp"
#include "pcrf/study/level_axis.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study {
namespace {

namespace fs = std::filesystem;

/// λ(x) = 2.625e-4 x^-3 at five PGAs and a steeper last segment (not one power law, so the
/// inverse must be taken segment by segment).
constexpr const char* kHazard =
    "# test curve\npga_g,annual_rate_per_yr\n0.05,2.1\n0.1,0.2625\n0.5,0.0021\n1,0.0002625\n3,4e-6\n";

const fs::path& folder() {
  static const fs::path dir = [] {
    const auto d = test::scratch_dir("hazard_stripes");
    fs::create_directories(d / "site");
    test::write_file(d / "site", "pga.csv", kHazard);
    test::write_file(d / "site", "sa.csv", "# period_s = 1.0\nsa_g,annual_rate_per_yr\n0.1,1e-2\n1,1e-4\n");
    return d;
  }();
  return dir;
}

const std::string kRecords = "[[records]]\nsynthetic = \"sine:amplitude_g=1.5\"\n";

Study parse(const std::string& text) { return parse_study(text, "t.toml", folder()); }

std::string error_of(const std::string& text) { return study_test::error_of(parse, text); }

TEST(HazardStripes, StripesAreTheCurvesIntensitiesAtTheReturnPeriods) {
  const Study s = parse(kRecords + "[intensity]\nmeasure = \"pga_g\"\nhazard = \"site/pga.csv\"\n"
                                   "return_periods_yr = [2475, 43, 475, 10000]\n");
  ASSERT_TRUE(s.hazard_stripes);
  EXPECT_EQ(s.hazard_stripes->hazard, "site/pga.csv");
  EXPECT_EQ(s.hazard_stripes->return_periods_yr, (std::vector<double>{2475, 43, 475, 10000}));
  ASSERT_EQ(s.levels.size(), 4u);
  // The curve's inverse, written out: in the segment [x_i, x_i+1] holding the rate 1/T,
  // x = x_i (r / λ_i)^(-1/k_i), k_i = ln(λ_i/λ_i+1) / ln(x_i+1/x_i).
  const std::vector<double> x{0.05, 0.1, 0.5, 1, 3}, rate{2.1, 0.2625, 0.0021, 0.0002625, 4e-6};
  for (std::size_t j = 0; j < s.levels.size(); ++j) {
    const double r = 1.0 / s.hazard_stripes->return_periods_yr[j];
    std::size_t i = 0;
    while (rate[i + 1] > r) ++i;
    const double k = std::log(rate[i] / rate[i + 1]) / std::log(x[i + 1] / x[i]);
    EXPECT_NEAR(s.levels[j], x[i] * std::pow(r / rate[i], -1.0 / k), 1e-12) << j;
  }
  // On the power-law part, the closed form: x = (k0 T)^(1/3).
  EXPECT_NEAR(s.levels[2], std::cbrt(2.625e-4 * 475.0), 1e-12);
  // And back: the curve's rate at each stripe is 1/T.
  const auto curve = pcrf::hazard::read_hazard_file(folder() / "site/pga.csv", risk::Tail::kCutOff).curve;
  for (std::size_t j = 0; j < s.levels.size(); ++j)
    EXPECT_NEAR(curve.rate_per_yr(s.levels[j]) * s.hazard_stripes->return_periods_yr[j], 1.0, 1e-12) << j;
  // The return periods are part of the study's canonical text (its fingerprint).
  std::ostringstream described;
  make_level_axis(s)->describe(described);
  EXPECT_NE(described.str().find("return_periods_yr 2475 43 475 10000"), std::string::npos) << described.str();

  const Study sa = parse(kRecords + "[intensity]\nmeasure = \"sa_g\"\nperiod_s = 1\nhazard = \"site/sa.csv\"\n"
                                    "return_periods_yr = 1000\n");
  EXPECT_NEAR(sa.levels.at(0), std::sqrt(0.1 * 1.0), 1e-12);  // 1e-3 /yr halfway in log between 1e-2 and 1e-4
}

TEST(HazardStripes, RefusalsNameTheStudyFileLineAndKey) {
  const std::string head = kRecords + "[intensity]\nmeasure = \"pga_g\"\n";
  const std::map<std::string, std::string> corpus = {
      {head + "hazard = \"site/pga.csv\"\nreturn_periods_yr = [475, 1e6]\n",
       "t.toml:6: [intensity] return_periods_yr: return period 1e+06 yr is outside the hazard curve site/pga.csv, whose "
       "rates span return periods from 0.4762 to 2.5e+05 yr"},
      {head + "hazard = \"site/pga.csv\"\nreturn_periods_yr = [0.1]\n", "t.toml:6: [intensity] return_periods_yr: return period 0.1 yr is outside"},
      {head + "hazard = \"site/pga.csv\"\nreturn_periods_yr = [475, 475]\n", "t.toml:6: [intensity] return_periods_yr: value 475 appears twice"},
      {head + "hazard = \"site/pga.csv\"\nreturn_periods_yr = [-5]\n", "t.toml:6: [intensity] return_periods_yr: value -5 must be positive"},
      {head + "hazard = \"site/pga.csv\"\n", "t.toml:5: [intensity] hazard: a hazard curve sets the stripes' intensities: give return_periods_yr"},
      {head + "return_periods_yr = [475]\n", "t.toml:5: [intensity] return_periods_yr: needs hazard = \"FILE\""},
      {head + "hazard = \"site/none.csv\"\nreturn_periods_yr = [475]\n", "t.toml:5: [intensity] hazard: "},
      {head + "hazard = \"site/sa.csv\"\nreturn_periods_yr = [475]\n",
       "t.toml:5: [intensity] hazard: " + (folder() / "site/sa.csv").string() +
           ":2: the curve's measure is sa_g, the study's [intensity] measure is pga_g"},
      {kRecords + "[intensity]\nmeasure = \"sa_g\"\nperiod_s = 0.5\nhazard = \"site/sa.csv\"\nreturn_periods_yr = [475]\n",
       "t.toml:6: [intensity] hazard: " + (folder() / "site/sa.csv").string() +
           ":2: the curve is at period_s = 1 s, the study's Sa at 0.5 s"},
      {head + "hazard = \"site/pga.csv\"\nreturn_periods_yr = [475]\n[axes]\nintensity = [0.5, 1]\n",
       "t.toml:8: [axes] intensity: [intensity] return_periods_yr (t.toml:6) sets the stripes' intensities: give either it or "
       "this axis, not both"},
      {head + "hazard = \"site/pga.csv\"\nreturn_periods_yr = [475]\n[axes]\nscale = [1]\n", "t.toml:8: [axes] scale: [intensity] return_periods_yr"},
      {head + "hazard = \"site/pga.csv\"\nreturn_periods_yr = [475]\n[ida]\nstart = 0.1\nmax_intensity = 2\n",
       "t.toml:6: [intensity] return_periods_yr: with [ida] the search chooses the intensities"},
      {head + "hazard = 3\nreturn_periods_yr = [475]\n", "t.toml:5: [intensity] hazard: expected a string"},
  };
  for (const auto& [text, message] : corpus) {
    const std::string error = error_of(text);
    EXPECT_NE(error.find(message), std::string::npos) << text << "\ngot: " << error;
  }
  // A file the hazard reader refuses: its own file and line inside the study's message.
  test::write_file(folder() / "site", "rising.csv", "pga_g,annual_rate_per_yr\n0.1,1e-3\n0.2,2e-3\n");
  const std::string rising = error_of(head + "hazard = \"site/rising.csv\"\nreturn_periods_yr = [475]\n");
  EXPECT_NE(rising.find("t.toml:5: [intensity] hazard: " + (folder() / "site/rising.csv").string() + ":3: the curve is not decreasing"),
            std::string::npos)
      << rising;
}

}  // namespace
}  // namespace pcrf::study
