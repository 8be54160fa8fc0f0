// `pcrf cube risk`: the hazard file's refusals (file, line, problem; exit 2; nothing on
// stdout), the annual collapse rates of an IDA cube against the fragility and the hazard
// curve directly, the tail choice reported, and the warnings of few collapses.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>

#include "pcrf/analysis/risk.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/analysis/p695.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/post/cube_fragility.hpp"
#include "pcrf/post/cube_p695.hpp"
#include "pcrf/post/cube_reports.hpp"
#include "pcrf/post/cube_risk.hpp"
#include "pcrf/hazard/hazard_file.hpp"
#include "study/study_test_support.hpp"

namespace pcrf {
namespace {

using study_test::pcrf;
using study_test::quoted;
namespace fs = std::filesystem;

/// λ(x) = 1e-4 x^−2.5 /yr at five PGAs (the synthetic curve of studies/risk_hazard_pga.csv).
constexpr const char* kHazard =
    "# synthetic power law lambda = 1e-4 x^-2.5\npga_g,annual_rate_per_yr\n0.05,0.178885\n0.1,0.0316228\n"
    "0.3,0.00202837\n1,0.0001\n3,6.415e-06\n";

/// The studies' folder: an IDA of 12 stochastic records (one frame, i), a 6-record stripe
/// cube (f), hazard-consistent stripes (t) and four LHS-sampled frames (m); each cube is run
/// when a test first asks for it (cube()), once per process.
const fs::path& folder() {
  static const fs::path dir = [] {
    const auto d = test::scratch_dir(std::string("cube_risk_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    auto records = [](int n) {
      std::string text = "[[records]]\nsynthetic = [";
      for (int seed = 1; seed <= n; ++seed)
        text += std::string(seed > 1 ? ", " : "") + "\"stochastic:seed=" + std::to_string(seed) + ",pga_g=1,duration_s=6\"";
      return text + "]\n[intensity]\nmeasure = \"pga_g\"\n";
    };
    test::write_file(d, "i.toml", records(12) + "[ida]\nstart = 0.5\nmax_intensity = 8\n");
    test::write_file(d, "f.toml", records(6) + "[axes]\nintensity = [1, 1.5, 2, 3, 4.5, 6]\n");
    test::write_file(d, "h.csv", kHazard);
    // Hazard-consistent stripes: the intensities of six return periods on the same power law
    // sampled up to 10 g (0.57 to 8.3 g).
    test::write_file(d, "wide.csv", "pga_g,annual_rate_per_yr\n0.05,0.178885\n0.3,0.00202837\n1,0.0001\n3,6.415e-06\n10,3.16228e-07\n");
    test::write_file(d, "t.toml", records(6) + "hazard = \"wide.csv\"\nreturn_periods_yr = [2475, 10000, 50000, 200000, 600000, 2000000]\n");
    // Modelling uncertainty: four frames drawn by LHS (tan_alpha, kappa), an IDA of each.
    test::write_file(d, "m.toml", records(6) + "[plan]\nkind = \"lhs\"\nsamples = 4\nseed = 3\n[axes]\n"
                     "tan_alpha = {from = 0.17, to = 0.25}\nkappa = {from = 1.5, to = 2.1}\n[ida]\nstart = 0.5\nmax_intensity = 8\n");
    // One record at one Sa(0.5 s) stripe: a cube whose measure has a period.
    test::write_file(d, "s.toml", "[[records]]\nsynthetic = \"stochastic:seed=1,pga_g=1,duration_s=6\"\n[intensity]\n"
                     "measure = \"sa_g\"\nperiod_s = 0.5\n[axes]\nintensity = [1]\n");
    return d;
  }();
  return dir;
}

/// The cube of study `name` (i, f, t, m or s), run on first use.
fs::path cube(const std::string& name) {
  static std::map<std::string, fs::path> made;
  if (const auto it = made.find(name); it != made.end()) return it->second;
  const auto r = test::run_command("cd " + quoted(folder()) + " && " + pcrf() + " study " + name + ".toml -o " + name +
                                   ".h5 --progress-interval 0");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return made[name] = folder() / (name + ".h5");
}

/// `pcrf cube risk ARGS`, ARGS starting with the cube (X.h5), run first when needed.
test::CommandResult risk_command(const std::string& args) {
  (void)cube(args.substr(0, args.find(".h5")));
  return test::run_command("cd " + quoted(folder()) + " && " + pcrf() + " cube risk " + args);
}

/// The CSV on stdout as header → value of its only row.
std::map<std::string, std::string> only_row(const std::string& csv) {
  std::istringstream in(csv);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  std::map<std::string, std::string> values;
  std::stringstream h(header), r(row);
  for (std::string name, value; std::getline(h, name, ',');) {
    std::getline(r, value, ',');
    values[name.substr(0, name.find(" ["))] = value;
  }
  return values;
}

TEST(CubeRisk, HazardFileRefusalsNameFileLineAndProblem) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"pga_g,annual_rate_per_yr\n0.1,1e-2\n0.2,1e-2\n", "flat.csv:3: the curve is not decreasing"},
      {"pga_g,annual_rate_per_yr\n0.1,1e-2\n0.2,2e-2\n", "flat.csv:3: the curve is not decreasing"},
      {"pga_g,annual_rate_per_yr\n0.1,1e-2\n0.2,0\n", "flat.csv:3: the annual rate must be positive"},
      {"pga_g,annual_rate_per_yr\n0.1,1e-2\n0.2,-1e-3\n", "flat.csv:3: the annual rate must be positive"},
      {"\n# c\npgv_m_s,annual_rate_per_yr\n0.1,1e-2\n0.2,1e-3\n", "flat.csv:3: the curve's measure is pgv_m_s, the cube's"},
      {"# period_s = 1\nsa_g,annual_rate_per_yr\n0.1,1e-2\n0.2,1e-3\n", "flat.csv:2: the curve's measure is sa_g"},
      {"sa_g,annual_rate_per_yr\n0.1,1e-2\n", "flat.csv:1: an sa measure needs a '# period_s"},
      {"pga,annual_rate_per_yr\n0.1,1e-2\n", "flat.csv:1: the header's first column must name the intensity measure"},
      {"pga_g,annual_rate_per_yr\n0.1,abc\n", "flat.csv:2: the rate is not a number"},
      {"pga_g,annual_rate_per_yr\n0.1,1e-2,3\n", "flat.csv:2: expected two fields"},
      {"pga_g,annual_rate_per_yr\n0.1,1e-2\n", "flat.csv: a hazard curve needs at least two points"},
      {"0.1,1e-2\n", "flat.csv:1: the header's first column"},
  };
  for (const auto& [text, message] : cases) {
    test::write_file(folder(), "flat.csv", text);
    const auto r = risk_command("i.h5 --hazard flat.csv");
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_NE(r.err.find(message), std::string::npos) << text << "\n" << r.err;
    EXPECT_EQ(r.out, "") << text;
  }
  // An Sa curve at another period than the cube's Sa.
  test::write_file(folder(), "sa1.csv", "# period_s = 1.0\nsa_g,annual_rate_per_yr\n0.1,1e-2\n1,1e-4\n");
  const auto period = risk_command("s.h5 --hazard sa1.csv");
  EXPECT_EQ(period.exit_code, 2);
  EXPECT_NE(period.err.find("sa1.csv:2: the curve is at period_s = 1 s, the cube's Sa at 0.5 s"), std::string::npos) << period.err;
  EXPECT_EQ(period.out, "");
  const auto missing = risk_command("i.h5 --hazard none.csv");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("none.csv: no such file"), std::string::npos) << missing.err;
}

TEST(CubeRisk, RatesAreTheFragilitysIntegratedAgainstTheCurve) {
  const auto r = risk_command("i.h5 --hazard h.csv --years 10 --tail cut-off --csv -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto row = only_row(r.out);
  const cube::CubeReader reader(cube("i"));
  const auto frames = post::cube_fragility(reader, {});
  ASSERT_EQ(frames.size(), 1u);
  const auto& f = frames.front();
  ASSERT_TRUE(f.fit);
  const auto hazard = pcrf::hazard::read_hazard_file(folder() / "h.csv", risk::Tail::kCutOff);
  // The lognormal's rate: the library's integral to its 1e-7 (the command adds bin edges).
  const double lognormal = risk::collapse_rate(hazard.curve, *f.fit).lambda_per_yr;
  EXPECT_NEAR(std::stod(row["lambda_collapse_per_yr"]) / lognormal, 1.0, 1e-6);
  EXPECT_NEAR(std::stod(row["p_collapse_in_years"]), 1.0 - std::exp(-10.0 * std::stod(row["lambda_collapse_per_yr"])), 1e-15);
  // The empirical rate: each curve that collapsed at c adds λ(c) / curves (exact).
  double empirical = 0.0;
  for (double c : f.collapse_intensities) empirical += hazard.curve.rate_per_yr(c) / static_cast<double>(f.cases);
  EXPECT_NEAR(std::stod(row["lambda_collapse_empirical_per_yr"]), empirical, 1e-12 * empirical);
  EXPECT_NEAR(std::stod(row["empirical_vs_lognormal"]), empirical / lognormal - 1.0, 1e-5);
  EXPECT_EQ(row["bracketing"], std::to_string(f.collapse_intensities.size()));
  // With P-695's ratings B, B, B (0.2 each) added to β in quadrature.
  const double widened = std::sqrt(f.fit->beta * f.fit->beta + 3 * 0.2 * 0.2);
  EXPECT_NEAR(std::stod(row["beta_with_ratings"]), widened, 1e-12);
  EXPECT_NEAR(std::stod(row["lambda_collapse_with_ratings_per_yr"]) /
                  risk::collapse_rate(hazard.curve, {f.fit->median, widened}).lambda_per_yr, 1.0, 1e-6);
  // The bootstrap interval holds the estimate.
  EXPECT_LT(std::stod(row["lambda_collapse_5%"]), std::stod(row["lambda_collapse_per_yr"]));
  EXPECT_GT(std::stod(row["lambda_collapse_95%"]), std::stod(row["lambda_collapse_per_yr"]));
  EXPECT_EQ(risk_command("i.h5 --hazard h.csv --ratings B,B,X").exit_code, 2);

  // The text says which tail was used; the JSON carries it as a field.
  const auto text = risk_command("i.h5 --hazard h.csv --tail cut-off");
  EXPECT_NE(text.out.find("beyond its last point: cut-off"), std::string::npos) << text.out;
  const auto json = risk_command("i.h5 --hazard h.csv --json");
  EXPECT_NE(json.out.find("\"tail\": \"power-law\""), std::string::npos) << json.out.substr(0, 400);
  // The power law beyond 3 g adds what the cut-off leaves at 3 g: never less.
  auto power = only_row(risk_command("i.h5 --hazard h.csv --csv -").out);
  EXPECT_GE(std::stod(power["lambda_collapse_per_yr"]), std::stod(row["lambda_collapse_per_yr"]));
}

TEST(CubeRisk, FewCollapsesAreWarnedOf) {
  // Six records: at most six collapses bracket the fragility.
  const auto r = risk_command("f.h5 --hazard h.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("curves bracket a collapse (fewer than 10)"), std::string::npos) << r.err;
  // Twelve curves that all collapsed: no such warning.
  const auto ida = risk_command("i.h5 --hazard h.csv");
  ASSERT_EQ(ida.exit_code, 0) << ida.err;
  EXPECT_EQ(ida.err.find("fewer than 10"), std::string::npos) << ida.err;
}

TEST(CubeRisk, ALowerTailThatDecidesTheRateIsWarnedOf) {
  // A steep hazard (lambda ~ x^-20) puts the collapses' weight far below the fragility's
  // median: most of lambda_c then comes from below the lowest collapse seen.
  std::string steep = "pga_g,annual_rate_per_yr\n";
  for (double x : {0.25, 0.5, 1.0, 2.0, 4.0, 8.0}) steep += number_text(x) + "," + number_text(1e-4 * std::pow(x, -20.0)) + "\n";
  test::write_file(folder(), "steep.csv", steep);
  post::RiskInputs in;
  in.hazard = folder() / "steep.csv";
  const cube::CubeReader reader(cube("i"));
  const auto report = post::cube_risk(reader, {}, in);
  ASSERT_EQ(report.frames.size(), 1u);
  const auto& f = report.frames.front();
  ASSERT_TRUE(f.lognormal);
  const auto hazard = pcrf::hazard::read_hazard_file(in.hazard, in.tail).curve;
  const auto split = risk::collapse_rate(hazard, *f.fit, {f.lowest_collapse});
  EXPECT_GT(f.lower_tail_share, 0.5);
  EXPECT_NEAR(f.lower_tail_share, split.rate_below(f.lowest_collapse) / split.lambda_per_yr, 1e-6);
  const auto r = risk_command("i.h5 --hazard steep.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("of the lognormal lambda_c comes from intensities below the lowest collapse seen"), std::string::npos)
      << r.err;
  // Under the gentle curve (x^-2.5) the tail does not decide it: no such warning.
  EXPECT_EQ(risk_command("i.h5 --hazard h.csv").err.find("below the lowest collapse"), std::string::npos);
}

TEST(CubeRisk, ReadsACubeOfHazardConsistentStripes) {
  const cube::CubeReader reader(cube("t"));
  const auto& layout = reader.layout();
  const auto* periods = layout.find_coordinate("return_period_yr");
  ASSERT_NE(periods, nullptr);
  EXPECT_EQ(periods->dimension, "intensity");
  EXPECT_EQ(periods->units, "yr");
  EXPECT_EQ(layout.text_attribute("intensity_hazard"), "wide.csv");
  const auto& levels = layout.find_coordinate("intensity")->numbers;
  const auto hazard = pcrf::hazard::read_hazard_file(folder() / "wide.csv", risk::Tail::kPowerLaw);
  ASSERT_EQ(levels.size(), 6u);
  for (std::size_t j = 0; j < levels.size(); ++j) {
    EXPECT_NEAR(levels[j], hazard.curve.intensity_at_rate(1.0 / periods->numbers[j]), 1e-12 * levels[j]) << j;
    EXPECT_NEAR(hazard.curve.rate_per_yr(levels[j]) * periods->numbers[j], 1.0, 1e-9) << j;
  }
  // The stripes' binomial fit feeds cube risk; the empirical rate of stripes at return periods
  // T_j is exactly sum_j (P_j - P_j-1) / T_j, the curve's rate at each stripe being 1/T_j.
  const auto r = risk_command("t.h5 --hazard wide.csv --csv -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto row = only_row(r.out);
  const auto frames = post::cube_fragility(reader, {});
  ASSERT_EQ(frames.size(), 1u);
  double expected = 0.0, before = 0.0;
  for (std::size_t j = 0; j < levels.size(); ++j) {
    const auto& s = frames.front().stripes[j];
    ASSERT_DOUBLE_EQ(s.intensity, levels[j]);
    const double p = s.trials > 0.0 ? s.collapses / s.trials : before;
    expected += (p - before) / periods->numbers[j];
    before = p;
  }
  EXPECT_GT(frames.front().collapses, 0.0);  // the stripes reach collapses: the rate is not 0 = 0
  EXPECT_NEAR(std::stod(row["lambda_collapse_empirical_per_yr"]), expected, 1e-9 * expected);
  ASSERT_TRUE(frames.front().fit);
  EXPECT_NEAR(std::stod(row["lambda_collapse_per_yr"]) / risk::collapse_rate(hazard.curve, *frames.front().fit).lambda_per_yr,
              1.0, 1e-6);
}

TEST(CubeRisk, SampledFramesMeasureTheModellingDispersion) {
  const cube::CubeReader reader(cube("m"));
  const auto frames = post::cube_fragility(reader, {});
  ASSERT_EQ(frames.size(), 4u);
  post::RiskInputs in;
  in.hazard = folder() / "h.csv";
  const auto report = post::cube_risk(reader, {}, in);
  ASSERT_TRUE(report.model);
  const auto& d = report.model->dispersion;
  // The pooled fit: every frame's curves fitted as one; beta_rtr: the frames' own betas' root
  // mean square; beta_model the rest of the pooled variance.
  std::vector<double> observed, censored;
  double sum_beta2 = 0.0;
  for (const auto& f : frames) {
    ASSERT_TRUE(f.fit);
    observed.insert(observed.end(), f.collapse_intensities.begin(), f.collapse_intensities.end());
    censored.insert(censored.end(), f.censored_intensities.begin(), f.censored_intensities.end());
    censored.insert(censored.end(), f.unresolved_intensities.begin(), f.unresolved_intensities.end());
    sum_beta2 += f.fit->beta * f.fit->beta;
  }
  const auto pooled = analysis::fit_censored(observed, censored);
  ASSERT_TRUE(pooled);
  EXPECT_EQ(d.frames, 4u);
  EXPECT_DOUBLE_EQ(d.pooled.median, pooled->median);
  EXPECT_DOUBLE_EQ(d.pooled.beta, pooled->beta);
  EXPECT_NEAR(d.beta_rtr, std::sqrt(sum_beta2 / 4.0), 1e-15);
  EXPECT_GT(d.beta_model, 0.0);
  EXPECT_NEAR(d.beta_rtr * d.beta_rtr + d.beta_model * d.beta_model, pooled->beta * pooled->beta, 1e-12);
  // Every curve collapsed (no censoring): the pooled variance is the frames' own plus their
  // medians' scatter exactly (total variance), so beta_model is the medians' scatter.
  ASSERT_TRUE(censored.empty());
  EXPECT_NEAR(d.beta_model, d.beta_medians, 1e-6);
  // The totals with ratings B, B, B (0.2 each), and the rates they imply at the pooled median.
  EXPECT_NEAR(report.model->beta_total_measured, std::sqrt(pooled->beta * pooled->beta + 0.08), 1e-12);
  EXPECT_NEAR(report.model->beta_total_rated, std::sqrt(sum_beta2 / 4.0 + 0.12), 1e-12);
  const auto hazard = pcrf::hazard::read_hazard_file(in.hazard, in.tail).curve;
  auto rate = [&](double beta) { return risk::collapse_rate(hazard, {pooled->median, beta}).lambda_per_yr; };
  EXPECT_NEAR(report.model_pooled->lambda_per_yr / rate(pooled->beta), 1.0, 1e-12);
  EXPECT_NEAR(report.model_measured->lambda_per_yr / rate(report.model->beta_total_measured), 1.0, 1e-12);
  EXPECT_NEAR(report.model_rated->lambda_per_yr / rate(report.model->beta_total_rated), 1.0, 1e-12);
  // Wider dispersion, more collapses from the weaker ground motions under this hazard.
  EXPECT_GT(report.model_rated->lambda_per_yr, report.model_measured->lambda_per_yr);

  // The group of frames: their mean lambda_c (which the pooled fragility's estimates too) and the largest.
  const auto fields = post::risk_report(report, in, "m.h5");
  double sum = 0.0, most = 0.0;
  for (const auto& f : report.frames) sum += f.lognormal->lambda_per_yr, most = std::max(most, f.lognormal->lambda_per_yr);
  EXPECT_DOUBLE_EQ(std::get<double>(fields.field("group_lambda_collapse_per_yr")), sum / 4.0);
  EXPECT_DOUBLE_EQ(std::get<double>(fields.field("group_lambda_collapse_max_per_yr")), most);
  EXPECT_NEAR(report.model_pooled->lambda_per_yr / (sum / 4.0), 1.0, 0.05);

  // The command shows the same numbers; a cube whose frames are not sampled has none.
  const auto json = risk_command("m.h5 --hazard h.csv --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"model_beta_model\": " + number_text(d.beta_model) + ","), std::string::npos) << json.out;
  std::ostringstream text;
  post::print_risk(post::risk_report(report, in, "m.h5"), text);
  EXPECT_NE(text.str().find("modelling uncertainty measured over 4 sampled frames"), std::string::npos) << text.str();
  const cube::CubeReader grid(cube("i"));
  const auto grid_risk = post::cube_risk(grid, {}, in);
  EXPECT_FALSE(grid_risk.model);
  const auto grid_report = post::risk_report(grid_risk, in, "i.h5");
  EXPECT_TRUE(std::holds_alternative<std::monostate>(grid_report.field("model_beta_model")));

  // cube p695: the same dispersion, and P(collapse | MCE) at the pooled median with each total.
  const auto p695_in = post::p695_inputs("Dmax", 0.5, 0.0, "B,B,C");
  const auto p695 = post::cube_p695(reader, {}, p695_in);
  ASSERT_TRUE(p695.model);
  EXPECT_DOUBLE_EQ(p695.model->dispersion.beta_model, d.beta_model);
  EXPECT_NEAR(p695.model->beta_total_rated, std::sqrt(sum_beta2 / 4.0 + 0.08 + 0.35 * 0.35), 1e-12);
  const double s_mt = p695::mce_spectrum(p695::Sdc::kDmax).at(0.5);
  EXPECT_NEAR(p695.model_p_collapse_mce_measured,
              analysis::normal_cdf(std::log(s_mt / pooled->median) / p695.model->beta_total_measured), 1e-15);
  EXPECT_NEAR(p695.model_p_collapse_mce_rated,
              analysis::normal_cdf(std::log(s_mt / pooled->median) / p695.model->beta_total_rated), 1e-15);
  const auto p695_text = test::run_command("cd " + quoted(folder()) + " && " + pcrf() + " cube p695 m.h5 --period-s 0.5 --json");
  ASSERT_EQ(p695_text.exit_code, 0) << p695_text.err;
  EXPECT_NE(p695_text.out.find("\"model_p_collapse_mce_rated\": "), std::string::npos) << p695_text.out;
}

}  // namespace
}  // namespace pcrf
