// The machine-readable answers of `pcrf cube stats|fragility|sensitivity|p695`: --json is the
// library's report (post::*_report) at full precision, --csv FILE and --csv - write full
// precision and `--csv -` nothing else; stats groups by several coordinates; export leaves
// the record texts out on request; an unknown flag is one line with the flag meant.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/row_major.hpp"
#include "pcrf/post/cube_reports.hpp"
#include "study/study_test_support.hpp"

namespace pcrf {
namespace {

using study_test::pcrf;
using study_test::quoted;
namespace fs = std::filesystem;

/// The small grid (3 records × scale 0.9, 1.2 × κ 1.2, 2.4 × tan α 0.18, 0.22) and an
/// intensity-stripe cube of stochastic records, made once per test process (ctest runs the
/// tests in parallel processes: each in its own folder).
const fs::path& cubes() {
  static const fs::path dir = [] {
    const auto d = test::scratch_dir(std::string("cube_outputs_") +
                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    test::write_file(d, "g.toml", study_test::small_grid_study());
    std::string records = "[[records]]\nsynthetic = [";
    for (int seed = 1; seed <= 6; ++seed)
      records += std::string(seed > 1 ? ", " : "") + "\"stochastic:seed=" + std::to_string(seed) + ",pga_g=1,duration_s=6\"";
    test::write_file(d, "f.toml", records + "]\n[intensity]\nmeasure = \"pga_g\"\n[axes]\nintensity = [1, 1.5, 2, 3, 4.5, 6]\n");
    for (const char* name : {"g", "f"}) {
      const auto r = test::run_command("cd " + quoted(d) + " && " + pcrf() + " study " + name + ".toml -o " + name +
                                       ".h5 --progress-interval 0");
      EXPECT_EQ(r.exit_code, 0) << r.err;
    }
    return d;
  }();
  return dir;
}

test::CommandResult cube_command(const std::string& args) {
  return test::run_command("cd " + quoted(cubes()) + " && " + pcrf() + " cube " + args);
}

std::string json_of(const post::Report& report) {
  std::ostringstream out;
  post::write_json(report, out);
  return out.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

TEST(CubeOutputs, StatsJsonIsTheLibrarysReportGroupedBySeveralCoordinates) {
  const auto r = cube_command("stats g.h5 --by kappa --by scale -m theta_max_rad -w tan_alpha=0.18 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cube::CubeReader reader(cubes() / "g.h5");
  const auto report = post::stats_report(reader, {{"kappa", "scale"}, "theta_max_rad", {{"tan_alpha", "0.18"}}, {}});
  const auto expected = json_of(report);
  EXPECT_EQ(r.out, expected.substr(0, expected.find("\"file\": ")) + "\"file\": \"g.h5\"" +
                       expected.substr(expected.find(", \"metric\"")));
  // Four groups (2 κ × 2 scales), each with its full-precision median.
  const auto& groups = report.table("groups");
  ASSERT_EQ(groups.rows.size(), 4u);
  for (const auto& row : groups.rows) {
    const double median = std::get<double>(row[groups.column("median")]);
    EXPECT_NE(r.out.find("\"median\": " + number_text(median)), std::string::npos) << number_text(median);
  }
  EXPECT_NE(r.out.find("{\"kappa\": 1.2, \"scale\": 0.9, \"cases\": 3,"), std::string::npos) << r.out;  // numbers
  EXPECT_NE(r.out.find("\"columns\": {\"groups\": [{\"name\": \"kappa\""), std::string::npos) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << "one object on one line";
}

TEST(CubeOutputs, StatsCsvIsItsDefaultOutputAndAFileCopy) {
  const auto plain = cube_command("stats g.h5 --by kappa -m theta_max_rad");
  const auto dash = cube_command("stats g.h5 --by kappa -m theta_max_rad --csv -");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(dash.out, plain.out);
  EXPECT_EQ(lines_of(plain.out).front(), "kappa,cases,collapses,values,median,p16,p84,unresolved");
  const auto file = cube_command("stats g.h5 --by kappa -m theta_max_rad --csv s.csv --overwrite");
  ASSERT_EQ(file.exit_code, 0) << file.err;
  std::ifstream in(cubes() / "s.csv");
  std::stringstream copy;
  copy << in.rdbuf();
  EXPECT_EQ(copy.str(), plain.out);
}

TEST(CubeOutputs, P695OfStripesCountsTheLowestStripeWhereHalfTheRecordsCollapse) {
  // P-695 6.3/6.4 on a stripe cube: S_CT is the lowest intensity at which at least half the
  // records with a verdict collapsed, counted here from the statuses; --s-ct lognormal takes
  // the fragility's median instead.
  const cube::CubeReader reader(cubes() / "f.h5");
  const auto& layout = reader.layout();
  const auto level = *layout.find_dimension("intensity");
  const auto& levels = layout.find_coordinate("intensity")->numbers;
  std::vector<int> trials(levels.size(), 0), collapses(levels.size(), 0);
  const auto status = reader.read_status();
  for (std::size_t i = 0; i < status.size(); ++i) {
    const auto s = static_cast<CaseStatus>(status[i]);
    if (!has_verdict(s)) continue;
    const auto l = unravel(static_cast<std::int64_t>(i), layout.shape())[level];
    ++trials[l];
    collapses[l] += is_collapse(s) ? 1 : 0;
  }
  double counted_g = NAN;
  for (std::size_t l = 0; l < levels.size() && std::isnan(counted_g); ++l)
    if (trials[l] > 0 && 2 * collapses[l] >= trials[l]) counted_g = levels[l];
  ASSERT_TRUE(std::isfinite(counted_g)) << "no stripe where half collapse: raise the intensities";
  const auto inputs = post::p695_inputs("Dmax", 0.5, 3.0, "B,B,B");
  const auto report = post::p695_report(reader, {}, inputs);
  const auto& frames = report.table("frames");
  ASSERT_EQ(frames.rows.size(), 1u);
  EXPECT_EQ(std::get<double>(frames.rows[0][frames.column("s_ct_g")]), counted_g);
  EXPECT_EQ(std::get<double>(frames.rows[0][frames.column("s_ct_counted_g")]), counted_g);
  const double lognormal_g = std::get<double>(frames.rows[0][frames.column("s_ct_lognormal_g")]);
  const auto fragility = post::fragility_report(reader, {{}, std::nullopt});
  EXPECT_EQ(lognormal_g, std::get<double>(fragility.table("frames").rows[0][fragility.table("frames").column("median")]));
  const auto by_fit = post::p695_report(reader, {}, post::p695_inputs("Dmax", 0.5, 3.0, "B,B,B", "lognormal"));
  EXPECT_EQ(std::get<double>(by_fit.table("frames").rows[0][by_fit.table("frames").column("s_ct_g")]), lognormal_g);
  EXPECT_THROW(post::p695_inputs("Dmax", 0.5, 3.0, "B,B,B", "mean"), std::invalid_argument);
}

TEST(CubeOutputs, FragilityCsvAndJsonCarryFullPrecision) {
  const cube::CubeReader reader(cubes() / "f.h5");
  const auto report = post::fragility_report(reader, {{}, 1.5});
  const auto& frames = report.table("frames");
  ASSERT_EQ(frames.rows.size(), 1u);
  const double median = std::get<double>(frames.rows[0][frames.column("median")]);
  const double beta = std::get<double>(frames.rows[0][frames.column("beta")]);

  // --csv -: the CSV alone, full precision (the text table would round to 4 digits).
  const auto dash = cube_command("fragility f.h5 --mce 1.5 --csv -");
  ASSERT_EQ(dash.exit_code, 0) << dash.err;
  const auto lines = lines_of(dash.out);
  ASSERT_EQ(lines.size(), 2u) << dash.out;
  EXPECT_EQ(lines[0], "frame,records,cases,collapses,failed,median [g],median_5% [g],median_95% [g],beta,beta_5%,beta_95%,CMR");
  const auto cells = cells_of(lines[1]);
  ASSERT_EQ(cells.size(), 12u) << lines[1];
  EXPECT_EQ(std::stod(cells[5]), median) << lines[1];
  EXPECT_EQ(std::stod(cells[8]), beta) << lines[1];
  EXPECT_EQ(std::stod(cells[11]), median / 1.5) << lines[1];

  // --csv FILE: the text on stdout, the same CSV in the file.
  const auto file = cube_command("fragility f.h5 --mce 1.5 --csv fr.csv --overwrite");
  ASSERT_EQ(file.exit_code, 0) << file.err;
  EXPECT_NE(file.out.find("median [g]"), std::string::npos);
  EXPECT_EQ(file.out.find(number_text(median)), std::string::npos) << "the text table rounds";
  std::ifstream in(cubes() / "fr.csv");
  std::stringstream copy;
  copy << in.rdbuf();
  EXPECT_EQ(copy.str(), dash.out);

  // --json: frames and points, the frame's selection, the library's numbers.
  const auto json = cube_command("fragility f.h5 --mce 1.5 --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"median\": " + number_text(median) + ","), std::string::npos) << json.out;
  EXPECT_NE(json.out.find("\"intensity_units\": \"g\", \"mce\": 1.5"), std::string::npos) << json.out;
  EXPECT_NE(json.out.find("\"points\": [{\"frame\": \"all\", \"kind\": \"stripe\", \"intensity\": 1,"), std::string::npos)
      << json.out;
  EXPECT_NE(json.out.find("\"selection\": \"\""), std::string::npos) << json.out;
  EXPECT_EQ(lines_of(json.out).size(), 1u);
}

TEST(CubeOutputs, JsonAndCsvOnStdoutTogetherAreRefused) {
  for (const std::string command : {"fragility f.h5", "stats g.h5 --by kappa -m impacts"}) {
    const auto r = cube_command(command + " --json --csv -");
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_NE(r.err.find("--json and --csv - both write to stdout"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST(CubeOutputs, ExportLeavesTheRecordTextsOutOnRequest) {
  const auto with = cube_command("export g.h5 -m impacts");
  const auto without = cube_command("export g.h5 -m impacts --no-record-text");
  ASSERT_EQ(with.exit_code, 0) << with.err;
  ASSERT_EQ(without.exit_code, 0) << without.err;
  const auto header_with = lines_of(with.out).front(), header_without = lines_of(without.out).front();
  EXPECT_NE(header_with.find("record_source"), std::string::npos) << header_with;
  EXPECT_EQ(header_without.find("record_source"), std::string::npos) << header_without;
  EXPECT_EQ(header_without.find("record_title"), std::string::npos) << header_without;
  EXPECT_EQ(header_without.rfind("record,", 0), 0u) << header_without;
  EXPECT_EQ(lines_of(with.out).size(), lines_of(without.out).size());
  EXPECT_LT(without.out.size(), with.out.size());
}

struct UnknownFlag {
  std::string command;
  std::string message;
};

TEST(CubeOutputs, AnUnknownFlagIsOneLineWithTheFlagMeant) {
  const std::vector<UnknownFlag> cases = {
      {"cube stats g.h5 --by kappa --metirc impacts", "pcrf: error: cube stats: unknown flag --metirc (did you mean --metric?)"},
      {"cube fragility f.h5 --jsn", "pcrf: error: cube fragility: unknown flag --jsn (did you mean --json?)"},
      {"cube export g.h5 --no-record-texts", "unknown flag --no-record-texts (did you mean --no-record-text?)"},
      // Study spellings (underscores) name the flag with dashes, in every command.
      {"run --tan_alpha 0.2", "pcrf: error: run: unknown flag --tan_alpha (did you mean --tan-alpha?)"},
      {"frame --pi_sigma_b=0.5", "pcrf: error: frame: unknown flag --pi_sigma_b=0.5 (did you mean --pi-sigma-b?)"},
      {"cube p695 f.h5 --period_s 0.5", "unknown flag --period_s (did you mean --period-s?)"},
      {"run --tail_s 2", "unknown flag --tail_s (did you mean --tail-s?)"},
      {"cube stats g.h5 --zzzzzz", "pcrf: error: cube stats: unknown flag --zzzzzz (see pcrf cube stats --help)"},
  };
  for (const auto& c : cases) {
    const auto r = test::run_command("cd " + quoted(cubes()) + " && " + pcrf() + " " + c.command);
    EXPECT_EQ(r.exit_code, 2) << c.command << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.command << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.command << "\n" << r.err;
  }
}

}  // namespace
}  // namespace pcrf
