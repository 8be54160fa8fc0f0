// A hazard curve whose numbers cannot be what its header says (issue 41, item 8): intensities
// in cm/s² or % g under pga_g, 50-year probabilities in the rate column, scale factors no
// record is meant for; each a warning naming the file, the line and the likely cause. And a
// byte-order mark read as what it is, a curve's points bounded.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pcrf/hazard/hazard_file.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/study/study_parser.hpp"
#include "pcrf/units.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study {
namespace {

namespace fs = std::filesystem;
using study_test::pcrf;
using study_test::quoted;

/// A folder of this test's own (ctest runs the tests of a suite side by side).
const fs::path& folder() {
  static const fs::path dir =
      test::scratch_dir(std::string("hazard_plausibility_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  return dir;
}

/// λ(x) = 2.625e-4 x^-3 /yr from 0.05 to 3 g, the intensities multiplied by `scale`.
std::string power_law(double scale = 1.0) {
  std::string text = "pga_g,annual_rate_per_yr\n";
  for (double x : {0.05, 0.1, 0.5, 1.0, 3.0}) text += number_text(x * scale) + "," + number_text(2.625e-4 / (x * x * x)) + "\n";
  return text;
}

hazard::HazardFile read(const std::string& name, const std::string& text) {
  return hazard::read_hazard_file(test::write_file(folder(), name, text), risk::Tail::kPowerLaw);
}

std::string warnings_of(const hazard::HazardFile& h) {
  std::string all;
  for (const auto& w : h.warnings) all += w.message(Dialect::kFlag) + "\n";
  return all;
}

TEST(HazardPlausibility, APlausibleCurveGivesNoWarning) {
  EXPECT_EQ(warnings_of(read("plain.csv", power_law())), "");
  // Rates above 1 at the start are annual rates, not probabilities.
  EXPECT_EQ(warnings_of(read("start.csv", "pga_g,annual_rate_per_yr\n0.01,3\n0.1,0.2\n1,1e-4\n")), "");
}

TEST(HazardPlausibility, IntensitiesInOtherUnitsNameTheFileLineAndTheLikelyUnit) {
  // The curve: in cm/s² under pga_g (g = kGravity_m_s2), read as up to 2943 g.
  const auto cm = read("cm.csv", power_law(100.0 * kGravity_m_s2));
  ASSERT_EQ(cm.warnings.size(), 1u) << warnings_of(cm);
  const std::string w = warnings_of(cm);
  EXPECT_NE(w.find("cm.csv:6: the largest intensity, 2943 g, is beyond any pga_g (at most 10 g on a hazard curve)"),
            std::string::npos) << w;
  EXPECT_NE(w.find("is it in cm/s2 (3 g)?"), std::string::npos) << w;
  // In % g: 300 g, which cm/s² would make 0.31 g and % g 3 g.
  const std::string percent = warnings_of(read("percent.csv", power_law(100.0)));
  EXPECT_NE(percent.find("the largest intensity, 300 g"), std::string::npos) << percent;
  EXPECT_NE(percent.find("% g (3 g)"), std::string::npos) << percent;
  // PGV in cm/s.
  const std::string pgv = warnings_of(read("pgv.csv", "pgv_m_s,annual_rate_per_yr\n1,1e-2\n50,1e-3\n300,1e-5\n"));
  EXPECT_NE(pgv.find("pgv.csv:4: the largest intensity, 300 m/s, is beyond any pgv_m_s"), std::string::npos) << pgv;
  EXPECT_NE(pgv.find("cm/s (3 m/s)"), std::string::npos) << pgv;
}

TEST(HazardPlausibility, ProbabilitiesOverAPeriodAreWarnedOf) {
  // 50-year probabilities of exceedance of the same power law: 1 − exp(−50 λ).
  std::string text = "# 50-year\npga_g,annual_rate_per_yr\n";
  for (double x : {0.05, 0.1, 0.5, 1.0, 3.0}) text += number_text(x) + "," + number_text(-std::expm1(-50 * 2.625e-4 / (x * x * x))) + "\n";
  const std::string w = warnings_of(read("poe.csv", text));
  EXPECT_NE(w.find("poe.csv:3: the rates start at 1 /yr and never exceed 1"), std::string::npos) << w;
  EXPECT_NE(w.find("-ln(1 - p)/T"), std::string::npos) << w;
}

TEST(HazardPlausibility, AByteOrderMarkIsSkippedAndUtf16Refused) {
  const auto plain = read("plain.csv", power_law());
  const auto marked = read("bom.csv", "\xEF\xBB\xBF" + power_law());
  EXPECT_EQ(marked.measure, "pga_g");
  EXPECT_EQ(marked.curve.intensities(), plain.curve.intensities());
  EXPECT_EQ(marked.header_line, 1u);
  try {
    read("utf16.csv", "\xFF\xFEp\0g\0");
    FAIL() << "read UTF-16";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("utf16.csv:1: UTF-16 text"), std::string::npos) << e.what();
  }
}

TEST(HazardPlausibility, TooManyPointsAreRefusedAtTheFirstOneBeyond) {
  std::string text = "pga_g,annual_rate_per_yr\n";
  for (std::size_t i = 0; i <= hazard::kMaxHazardPoints; ++i) {
    const double x = 0.01 * std::pow(1000.0, static_cast<double>(i) / hazard::kMaxHazardPoints);
    text += number_text(x) + "," + number_text(1.0 / (1.0 + static_cast<double>(i))) + "\n";
  }
  try {
    read("many.csv", text);
    FAIL() << "read more than kMaxHazardPoints";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("many.csv:" + std::to_string(hazard::kMaxHazardPoints + 2) + ": more than " +
                                         std::to_string(hazard::kMaxHazardPoints) + " points"),
              std::string::npos)
        << e.what();
  }
}

// Hazard-consistent stripes from a curve in cm/s²: the study warns of the curve (file, line)
// and of the scale factors it asks (above hazard::kMaxHazardScaleFactor); warnings as errors refuse.
TEST(HazardPlausibility, StripesFromACurveInOtherUnitsAreWarnedOf) {
  test::write_file(folder(), "cm.csv", power_law(100.0 * kGravity_m_s2));
  const std::string study = "[[records]]\nsynthetic = \"stochastic:seed=1,pga_g=0.5,duration_s=3\"\n[intensity]\n"
                            "measure = \"pga_g\"\nhazard = \"cm.csv\"\nreturn_periods_yr = [475, 2475]\n";
  test::write_file(folder(), "cm.toml", study);
  const auto r = test::run_command("cd " + quoted(folder()) + " && " + pcrf() + " study cm.toml --check");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("cm.csv:6: the largest intensity, 2943 g"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cm.toml:6: [intensity] return_periods_yr: the hazard curve cm.csv asks record"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("above 100: are the curve's intensities in the units its header names?"), std::string::npos) << r.err;
  test::write_file(folder(), "strict.toml", study + "[run]\nwarnings_as_errors = true\n");
  const auto strict = test::run_command("cd " + quoted(folder()) + " && " + pcrf() + " study strict.toml --check");
  EXPECT_EQ(strict.exit_code, 2) << strict.err;
  // The same curve in g: no warning of either kind.
  test::write_file(folder(), "g.csv", power_law());
  test::write_file(folder(), "g.toml", study.substr(0, study.find("cm.csv")) + "g.csv\"\nreturn_periods_yr = [475, 2475]\n");
  const auto g = test::run_command("cd " + quoted(folder()) + " && " + pcrf() + " study g.toml --check");
  EXPECT_EQ(g.exit_code, 0) << g.err;
  EXPECT_EQ(g.err.find("warning"), std::string::npos) << g.err;
}

}  // namespace
}  // namespace pcrf::study
