// The adaptive IDA end to end: the cube holds every curve's runs over ida_point and its
// summaries; a curve's collapse and last safe intensities rerun with `pcrf run` collapse and
// do not; ranks do not change the result; a killed IDA resumes to the uninterrupted cube.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/analysis/fragility.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/ida/ida_search.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

std::string ida_study(int records, int max_runs) {
  std::string text = "[[records]]\nsynthetic = [";
  for (int seed = 1; seed <= records; ++seed)
    text += std::string(seed > 1 ? ", " : "") + "\"stochastic:seed=" + std::to_string(seed) + ",pga_g=1,duration_s=8\"";
  return text + "]\n[axes]\nkappa = [1.4, 2.2]\n[intensity]\nmeasure = \"pga_g\"\n[ida]\nstart = 0.5\nmax_intensity = 8\n"
                "max_runs = " + std::to_string(max_runs) + "\n[outputs]\nmetrics = [\"theta_max_rad\", \"impacts\"]\n";
}

test::CommandResult run_ida(const std::filesystem::path& dir, const std::string& text, const std::string& output,
                            const std::string& launcher = "") {
  const auto file = test::write_file(dir, "ida.toml", text);
  return test::run_command("cd " + quoted(dir) + " && " + launcher + pcrf() + " study " + quoted(file) + " -o " + output +
                           " --progress-interval 0");
}

bool collapsed(std::int8_t status) { return status == 2 || status == 3 || status == 4 || status == 5; }

TEST(IdaStudy, CurvesAreBracketedAndTheirEndsRerunAsTheySay) {
  const auto dir = test::scratch_dir("ida_study");
  ASSERT_EQ(run_ida(dir, ida_study(3, 14), "ida.h5").exit_code, 0);
  cube::CubeReader cube(dir / "ida.h5");
  const auto& layout = cube.layout();
  ASSERT_EQ(layout.dimensions.back().name, "ida_point");
  ASSERT_EQ(layout.dimensions.back().size, 14u);
  const auto status = cube.read_status();
  const auto intensity = cube.read_metric("ida_intensity");
  const auto c = cube.read_side("collapse_intensity");
  const auto s = cube.read_side("last_safe_intensity");
  const auto runs = cube.read_side("ida_runs");
  ASSERT_EQ(c.size(), 6u);  // 3 records × 2 frames
  const auto* kappa = layout.find_coordinate("kappa");
  for (std::size_t curve = 0; curve < 6; ++curve) {
    // The summaries are those of the stored points.
    double lowest_collapse = NAN, highest_safe = NAN;
    int stored = 0;
    for (std::size_t k = 0; k < 14; ++k) {
      const auto i = curve * 14 + k;
      if (status[i] == cube::kStatusNotRun) continue;
      ++stored;
      if (collapsed(status[i]) && !(intensity[i] >= lowest_collapse)) lowest_collapse = intensity[i];
    }
    for (std::size_t k = 0; k < 14; ++k) {
      const auto i = curve * 14 + k;
      if (status[i] != cube::kStatusNotRun && !collapsed(status[i]) && intensity[i] < lowest_collapse &&
          !(intensity[i] <= highest_safe))
        highest_safe = intensity[i];
    }
    EXPECT_EQ(runs[curve], stored);
    ASSERT_EQ(c[curve], lowest_collapse) << "curve " << curve;
    EXPECT_EQ(s[curve], highest_safe);
    EXPECT_LE(c[curve] / s[curve] - 1.0, 0.02) << "curve " << curve;
    // Rerun both ends alone.
    const std::size_t record = curve / 2;
    const std::string base = pcrf() + " run --synthetic 'stochastic:seed=" + std::to_string(record + 1) +
                             ",pga_g=1,duration_s=8' --kappa " + kappa->label(curve % 2) + " --measure pga_g --intensity ";
    auto status_at = [&](double x) {
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", x);
      const auto r = test::run_command(base + text);
      const auto at = r.out.find("\"status\": \"");
      return r.out.substr(at + 11, r.out.find('"', at + 11) - at - 11);
    };
    const auto at_collapse = status_at(c[curve]);
    EXPECT_TRUE(at_collapse == "tendon_fracture" || at_collapse == "overturned") << at_collapse;
    const auto at_safe = status_at(s[curve]);
    EXPECT_TRUE(at_safe == "at_rest" || at_safe == "rocking_at_end") << at_safe;
  }
}

TEST(IdaStudy, FragilityFitsTheCollapseIntensitiesWithCensoring) {
  const auto dir = test::scratch_dir("ida_fragility");
  // max_intensity 3 g censors the records that survive it.
  std::string text = ida_study(8, 12);
  text.replace(text.find("max_intensity = 8"), 17, "max_intensity = 3");
  ASSERT_EQ(run_ida(dir, text, "ida.h5").exit_code, 0);
  cube::CubeReader cube(dir / "ida.h5");
  const auto c = cube.read_side("collapse_intensity");
  const auto s = cube.read_side("last_safe_intensity");
  const auto r = test::run_command(pcrf() + " cube fragility " + quoted(dir / "ida.h5") + " --csv " + quoted(dir / "f.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream csv(dir / "f.csv");
  std::string line;
  std::getline(csv, line);
  int censored_total = 0;
  for (std::size_t frame = 0; frame < 2; ++frame) {
    std::vector<double> observed, censored;
    for (std::size_t record = 0; record < 8; ++record) {
      const auto curve = record * 2 + frame;  // record-major, then κ
      if (std::isfinite(c[curve])) observed.push_back(c[curve]);
      else censored.push_back(s[curve]);
    }
    censored_total += static_cast<int>(censored.size());
    const auto fit = analysis::fit_censored(observed, censored);
    ASSERT_TRUE(std::getline(csv, line));
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    ASSERT_TRUE(fit) << line;
    EXPECT_EQ(std::stod(cells[3]), static_cast<double>(observed.size())) << line;
    EXPECT_NEAR(std::stod(cells[5]), fit->median, 1e-3 * fit->median) << line;
    EXPECT_NEAR(std::stod(cells[8]), fit->beta, 1e-3 * fit->beta) << line;
  }
  EXPECT_GT(censored_total, 0) << "no record survived 3 g: lower max_intensity";

  // --points lists what was fitted: each curve's collapse intensity, or its censoring value.
  const auto points = test::run_command(pcrf() + " cube fragility " + quoted(dir / "ida.h5") + " --points " +
                                        quoted(dir / "p.csv"));
  ASSERT_EQ(points.exit_code, 0) << points.err;
  std::ifstream p(dir / "p.csv");
  std::getline(p, line);
  EXPECT_EQ(line, "frame,kind,intensity,trials,collapses");
  std::vector<double> listed_collapse, listed_censored, stored_collapse, stored_censored;
  while (std::getline(p, line)) {
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 5u) << line;
    (cells[1] == "collapse" ? listed_collapse : listed_censored).push_back(std::stod(cells[2]));
  }
  for (std::size_t curve = 0; curve < c.size(); ++curve)
    (std::isfinite(c[curve]) ? stored_collapse : stored_censored).push_back(std::isfinite(c[curve]) ? c[curve] : s[curve]);
  for (auto* v : {&listed_collapse, &listed_censored, &stored_collapse, &stored_censored}) std::sort(v->begin(), v->end());
  ASSERT_EQ(listed_collapse.size(), stored_collapse.size());
  ASSERT_EQ(listed_censored.size(), stored_censored.size());
  for (std::size_t i = 0; i < listed_collapse.size(); ++i)
    EXPECT_NEAR(listed_collapse[i], stored_collapse[i], 1e-9 * stored_collapse[i]);
  for (std::size_t i = 0; i < listed_censored.size(); ++i)
    EXPECT_NEAR(listed_censored[i], stored_censored[i], 1e-9 * stored_censored[i]);

  // The export repeats each curve's collapse intensity on its runs, beside the run's intensity.
  const auto exported = test::run_command(pcrf() + " cube export " + quoted(dir / "ida.h5") +
                                          " -m ida_intensity -m collapse_intensity");
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const auto runs = cube.read_metric("ida_intensity");  // over every dimension: read as a metric
  std::istringstream rows(exported.out);
  std::getline(rows, line);
  std::size_t k = 0;
  for (; std::getline(rows, line); ++k) {
    const auto last = line.rfind(','), before = line.rfind(',', last - 1);
    const std::string run = line.substr(before + 1, last - before - 1), curve = line.substr(last + 1);
    if (std::isfinite(runs[k])) {
      EXPECT_NEAR(std::stod(run), runs[k], 1e-12 * runs[k]) << line;
    }
    const std::size_t curve_index = k / (runs.size() / c.size());
    if (std::isfinite(c[curve_index])) {
      EXPECT_NEAR(std::stod(curve), c[curve_index], 1e-12 * c[curve_index]) << line;
    } else {
      EXPECT_TRUE(curve.empty()) << line;
    }
  }
  EXPECT_EQ(k, runs.size());
}

TEST(IdaStudy, EveryCurveEndsInAStateTheCubeRecordsAndTheFragilityCensorsUnbracketedOnesAtTheirLastSafeRun) {
  const auto dir = test::scratch_dir("ida_states");
  // 6 runs up to 3 g at 2 %: a curve safe at 0.5, 1, 2, 3 is censored; one collapsing at 1 or
  // 2 has 4 or 2 runs left to bisect a 100 % bracket down to 2 %: too few, unbracketed.
  std::string text = ida_study(8, 6);
  text.replace(text.find("max_intensity = 8"), 17, "max_intensity = 3");
  ASSERT_EQ(run_ida(dir, text, "ida.h5").exit_code, 0);
  cube::CubeReader cube(dir / "ida.h5");
  const auto c = cube.read_side("collapse_intensity");
  const auto s = cube.read_side("last_safe_intensity");
  const auto state = cube.read_side("curve_state");
  int counts[3] = {0, 0, 0};
  std::vector<std::vector<double>> censored_of(2);  // per frame: what the fit must censor
  for (std::size_t curve = 0; curve < c.size(); ++curve) {
    const double expected = std::isnan(c[curve]) ? (s[curve] >= 3.0 ? 1.0 : 2.0) : (c[curve] / s[curve] - 1.0 <= 0.02 ? 0.0 : 2.0);
    ASSERT_EQ(state[curve], expected) << "curve " << curve;
    ++counts[static_cast<int>(expected)];
    if (expected != 0.0 && std::isfinite(s[curve])) censored_of[curve % 2].push_back(s[curve]);
  }
  ASSERT_GT(counts[2], 0) << "no curve ran out of runs: lower max_runs";
  ASSERT_GT(counts[1] + counts[0], 0);
  const auto info = test::run_command(pcrf() + " cube info " + quoted(dir / "ida.h5"));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("16 IDA curves: " + std::to_string(counts[0]) + " bracketed to the resolution, " +
                          std::to_string(counts[1]) + " right-censored at max_intensity, " + std::to_string(counts[2]) +
                          " unbracketed (max_runs ran out)"),
            std::string::npos)
      << info.out;
  const auto fragility = test::run_command(pcrf() + " cube fragility " + quoted(dir / "ida.h5") + " --csv " +
                                           quoted(dir / "f.csv") + " --points " + quoted(dir / "p.csv"));
  ASSERT_EQ(fragility.exit_code, 0) << fragility.err;
  EXPECT_NE(fragility.err.find("unbracketed curves (max_runs ran out"), std::string::npos) << fragility.err;
  std::ifstream csv(dir / "f.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.substr(line.rfind(',') + 1), "unbracketed") << line;
  int unbracketed_listed = 0;
  while (std::getline(csv, line)) unbracketed_listed += std::stoi(line.substr(line.rfind(',') + 1));
  EXPECT_EQ(unbracketed_listed, counts[2]);
  // The censored points are the censored curves' caps and the unbracketed curves' last safe runs.
  std::ifstream points(dir / "p.csv");
  std::getline(points, line);
  std::vector<double> listed;
  while (std::getline(points, line))
    if (line.find(",censored,") != std::string::npos) listed.push_back(std::stod(line.substr(line.find(",censored,") + 10)));
  std::vector<double> expected = censored_of[0];
  expected.insert(expected.end(), censored_of[1].begin(), censored_of[1].end());
  std::sort(listed.begin(), listed.end());
  std::sort(expected.begin(), expected.end());
  ASSERT_EQ(listed.size(), expected.size());
  for (std::size_t i = 0; i < listed.size(); ++i) EXPECT_NEAR(listed[i], expected[i], 1e-9 * expected[i]);
}

TEST(IdaStudy, RanksDoNotChangeTheCurves) {
  PCRF_REQUIRE_MPIRUN();
  const auto dir = test::scratch_dir("ida_ranks");
  ASSERT_EQ(run_ida(dir, ida_study(4, 12), "one.h5").exit_code, 0);
  ASSERT_EQ(run_ida(dir, ida_study(4, 12), "three.h5", mpirun(3)).exit_code, 0);
  expect_same_cube(dir / "one.h5", dir / "three.h5");
  cube::CubeReader one(dir / "one.h5"), three(dir / "three.h5");
  EXPECT_EQ(one.read_side("collapse_intensity"), three.read_side("collapse_intensity"));
  EXPECT_EQ(one.read_side("ida_runs"), three.read_side("ida_runs"));
}

TEST(IdaStudy, AKilledIdaResumesToTheUninterruptedCube) {
  const auto dir = test::scratch_dir("ida_kill");
  const std::string text = ida_study(14, 14);
  ASSERT_EQ(run_ida(dir, text, "whole.h5").exit_code, 0);
  const auto err = dir / "killed.err";
  const std::string command = "cd " + quoted(dir) + " && exec " + pcrf() + " study ida.toml -o killed.h5" +
                              " --flush-interval-s 0.02 --progress-interval 0.02 2>" + quoted(err);
  const pid_t pid = spawn_shell(command);
  ASSERT_GT(pid, 0);
  // Kill once a part of the runs is on disk: waiting on progress, not on a time measured
  // beforehand, keeps the kill inside the run however loaded the machine is.
  wait_for_a_tenth(err);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // past one more flush
  ::kill(pid, SIGKILL);
  int wstatus = 0;
  ::waitpid(pid, &wstatus, 0);
  {
    cube::CubeReader killed(dir / "killed.h5");
    const auto runs = killed.read_side("ida_runs");
    const auto whole_runs = cube::CubeReader(dir / "whole.h5").read_side("ida_runs");
    EXPECT_NE(runs, whole_runs) << "the IDA finished before it was killed: make it longer";
  }
  const auto resumed = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study ida.toml -o killed.h5 --resume --progress-interval 0");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_cube(dir / "whole.h5", dir / "killed.h5");
  cube::CubeReader whole(dir / "whole.h5"), killed(dir / "killed.h5");
  EXPECT_EQ(whole.read_side("collapse_intensity"), killed.read_side("collapse_intensity"));
  EXPECT_EQ(whole.read_side("last_safe_intensity"), killed.read_side("last_safe_intensity"));
  EXPECT_EQ(whole.read_side("ida_runs"), killed.read_side("ida_runs"));
}

TEST(IdaStudy, BadIdaStudiesAreRejected) {
  const auto dir = test::scratch_dir("ida_bad");
  const std::string records = "[[records]]\nsynthetic = \"stochastic:seed=1,pga_g=1,duration_s=4\"\n";
  const std::string im = "[intensity]\nmeasure = \"pga_g\"\n";
  const std::vector<std::pair<std::string, std::string>> corpus = {
      {records + "[ida]\nstart = 0.5\nmax_intensity = 8\n", "an IDA needs an intensity measure"},
      {records + im + "[ida]\nstart = 0.5\nmax_intensity = 8\nresolution = 0\n", "[ida] resolution: must be above 0 and below 1"},
      {records + im + "[ida]\nstart = 0.5\nmax_intensity = 8\nresolution = 1\n", "[ida] resolution: must be above 0 and below 1"},
      {records + im + "[ida]\nstart = 0.5\nmax_intensity = 8\nmax_runs = 1\n", "[ida] max_runs: must be at least 2"},
      {records + im + "[ida]\nmax_intensity = 8\n", "[ida] start: required"},
      {records + im + "[ida]\nstart = 0.5\n", "[ida] max_intensity: required"},
      {records + im + "[ida]\nstart = 0.5\nmax_intensity = 8\ncollapse = [\"at_rest\"]\n", "[ida] collapse: unknown value \"at_rest\""},
      {records + im + "[ida]\nstart = 0.5\nmax_intensity = 8\n[axes]\nintensity = [1]\n", "the search chooses the intensities"},
      {records + im + "[ida]\nstart = 0.5\nmax_intensity = 8\ntheta_limit_rad = 0.1\n[outputs]\nmetrics = [\"impacts\"]\n",
       "[ida] theta_limit_rad: needs theta_max_rad"},
  };
  for (const auto& [text, message] : corpus) {
    const auto r = run_ida(dir, text, "bad.h5");
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_NE(r.err.find(message), std::string::npos) << "got: " << r.err << "\nfor:\n" << text;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.h5"));
  }
}

}  // namespace
}  // namespace pcrf::study_test

namespace pcrf::study_test {
namespace {

TEST(IdaStudy, P695CarriesTheCollapseIntensityToItsVerdict) {
  // An IDA at Sa(0.5 s): cube p695 at that period gives the methodology's numbers, derived
  // here independently from the fragility's median; at another period it says why not.
  const auto dir = test::scratch_dir("ida_p695");
  std::string text = ida_study(6, 12);
  text.replace(text.find("measure = \"pga_g\""), std::string("measure = \"pga_g\"").size(),
               "measure = \"sa_g\"\nperiod_s = 0.5");
  ASSERT_EQ(run_ida(dir, text, "sa.h5").exit_code, 0);
  const auto cube = quoted(dir / "sa.h5");
  const auto json = test::run_command(pcrf() + " cube p695 " + cube + " --period-s 0.5 --sdc Dmax --mu-t 3 --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  // Its synthetic records have no pairs to normalise as Appendix A does: the one warning says so.
  EXPECT_NE(json.err.find("not normalised"), std::string::npos) << json.err;
  EXPECT_EQ(json.err.find("not Sa(T)"), std::string::npos) << json.err;
  for (const char* key : {"\"s_ct_g\": ", "\"s_mt_g\": 1.5", "\"ssf\": ", "\"beta_total\": 0.525", "\"acmr10\": ",
                          "\"p_collapse_mce\": ", "\"group\": "})
    EXPECT_NE(json.out.find(key), std::string::npos) << key << " in " << json.out;
  // Ŝ_CT is counted (P-695 6.3/6.4): of the frame's 6 curves, the 3rd smallest collapse
  // intensity, computed here from the cube; the lognormal median (the fragility's, 4 digits in
  // its CSV) is shown beside it, and feeds CMR only with --s-ct lognormal.
  cube::CubeReader reader(dir / "sa.h5");
  const auto c = reader.read_side("collapse_intensity"), state = reader.read_side("curve_state");
  std::vector<double> collapses;
  for (std::size_t curve = 0; curve < c.size(); curve += 2) {  // kappa = 1.4: the even curves
    ASSERT_TRUE(state[curve] == 0.0 || state[curve] == 1.0) << "curve " << curve << ": a bound would move the count";
    if (state[curve] == 0.0) collapses.push_back(c[curve]);
  }
  std::sort(collapses.begin(), collapses.end());
  ASSERT_GE(collapses.size(), 3u);
  const double counted_g = collapses[2];
  const auto fragility = test::run_command(pcrf() + " cube fragility " + cube + " --csv -");
  ASSERT_EQ(fragility.exit_code, 0) << fragility.err;
  const std::regex row(R"(kappa=1\.4,\d+,\d+,\d+,\d+,([0-9.]+),)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(fragility.out, m, row)) << fragility.out;
  const double median_g = std::stod(m[1].str());
  // 6 curves per frame: a caution, and no bootstrap interval (its cells are empty).
  EXPECT_NE(fragility.err.find("frame kappa=1.4: a fit from 6 curves, fewer than 10"), std::string::npos) << fragility.err;
  EXPECT_NE(fragility.out.find(m[1].str() + ",,,"), std::string::npos) << fragility.out;
  const std::regex s_ct(
      R"(\{"frame": "kappa=1\.4", "mu_t": 3, "ssf_beta1": [0-9.e+-]+, "s_ct_g": ([0-9.e+-]+), "s_ct_counted_g": ([0-9.e+-]+), )"
      R"("s_ct_lognormal_g": ([0-9.e+-]+), "s_ct_bounded": 0, "s_mt_g": 1\.5, "cmr": ([0-9.e+-]+))");
  ASSERT_TRUE(std::regex_search(json.out, m, s_ct)) << json.out;
  EXPECT_EQ(std::stod(m[1].str()), counted_g);
  EXPECT_EQ(std::stod(m[2].str()), counted_g);
  EXPECT_NEAR(std::stod(m[3].str()), median_g, 5e-4 * median_g);
  EXPECT_NEAR(std::stod(m[4].str()), counted_g / 1.5, 1e-12);
  EXPECT_NE(json.out.find("\"s_ct\": \"counted\""), std::string::npos) << json.out;
  const auto lognormal = test::run_command(pcrf() + " cube p695 " + cube + " --period-s 0.5 --sdc Dmax --mu-t 3 --json --s-ct lognormal");
  ASSERT_EQ(lognormal.exit_code, 0) << lognormal.err;
  ASSERT_TRUE(std::regex_search(lognormal.out, m, s_ct)) << lognormal.out;
  EXPECT_NEAR(std::stod(m[1].str()), median_g, 5e-4 * median_g);
  EXPECT_NEAR(std::stod(m[4].str()), std::stod(m[1].str()) / 1.5, 1e-12);
  // Default ratings and a group of one frame are said; given ratings are not.
  EXPECT_NE(json.err.find("quality ratings not given"), std::string::npos) << json.err;
  const auto one = test::run_command(pcrf() + " cube p695 " + cube + " --period-s 0.5 --mu-t 3 --ratings B,B,C -w kappa=1.4");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.err.find("a performance group of one archetype"), std::string::npos) << one.err;
  EXPECT_EQ(one.err.find("quality ratings not given"), std::string::npos) << one.err;
  const auto other = test::run_command(pcrf() + " cube p695 " + cube + " --period-s 1.0");
  EXPECT_EQ(other.exit_code, 0) << other.err;
  EXPECT_NE(other.err.find("not at the --period-s 1 s"), std::string::npos) << other.err;
  const auto bad = test::run_command(pcrf() + " cube p695 " + cube + " --period-s 0.5 --ratings B,E,B");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("unknown quality rating 'E'"), std::string::npos) << bad.err;
}

TEST(IdaStudy, P695OfAStudyOfSeveralScenesTakesTheFramesDuctilityOnlyFromAPrestressedFrame) {
  // The engine's mu_T is the prestressed frame's (docs/p695_rocking_frame.md): a block listed
  // beside it has none, so the verdict needs --mu-t rather than the frame's applied to the block.
  const auto dir = test::scratch_dir("ida_p695_scenes");
  std::string text = ida_study(4, 10);
  text.replace(text.find("[axes]\nkappa = [1.4, 2.2]\n"), std::string("[axes]\nkappa = [1.4, 2.2]\n").size(),
               "[plan]\nkind = \"list\"\n[[cases]]\nlabel = \"frame\"\n"
               "[[cases]]\nlabel = \"block\"\nmodel = \"block\"\nslenderness_rad = 0.2\n");
  ASSERT_EQ(run_ida(dir, text, "scenes.h5").exit_code, 0);
  const auto cube = quoted(dir / "scenes.h5");
  const auto refused = test::run_command(pcrf() + " cube p695 " + cube + " --period-s 0.5");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("frame block: a block scene has no engine convention for mu_T"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.out, "");
  const auto given = test::run_command(pcrf() + " cube p695 " + cube + " --period-s 0.5 --mu-t 3");
  EXPECT_EQ(given.exit_code, 0) << given.err;
  EXPECT_NE(given.out.find("block "), std::string::npos) << given.out;
}

}  // namespace
}  // namespace pcrf::study_test

namespace pcrf::study_test {
namespace {

TEST(IdaStudy, ACollapseStatusLeftOutOfTheCollapseSetIsNamedAtTheEndAndByFragility) {
  // collapse = ["overturned"] while these frames fracture their tendons first: the search
  // calls every fracture safe, and both the run and cube fragility say how many there were.
  const auto dir = test::scratch_dir("ida_collapse_set");
  std::string text = ida_study(2, 6);
  text.replace(text.find("max_runs"), 0, "collapse = [\"overturned\"]\n");
  const auto run = run_ida(dir, text, "ida.h5");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  cube::CubeReader cube(dir / "ida.h5");
  const auto status = cube.read_status();
  const auto fractures = std::count(status.begin(), status.end(), static_cast<std::int8_t>(pcrf::CaseStatus::kTendonFracture));
  ASSERT_GT(fractures, 0) << "the frames must fracture for this test to mean anything";
  const std::string line = std::to_string(fractures) + " runs ended in tendon_fracture, which this study does not count "
                           "as collapse";
  EXPECT_NE(run.err.find(line), std::string::npos) << run.err;
  const auto fragility = test::run_command(pcrf() + " cube fragility " + quoted(dir / "ida.h5"));
  ASSERT_EQ(fragility.exit_code, 0) << fragility.err;
  EXPECT_NE(fragility.err.find(line), std::string::npos) << fragility.err;
  // With the default set nothing is left out, and nothing is said.
  const auto dir2 = test::scratch_dir("ida_collapse_set_default");
  const auto plain = run_ida(dir2, ida_study(2, 6), "ida.h5");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(plain.err.find("does not count as collapse"), std::string::npos) << plain.err;
}

// Issue 29: `cube info` of a finished IDA read "93.1 % complete", its unused slots counted as
// not_run, and listed one message line per tendon fracture. It counts curves, names the
// unused slots apart, and counts messages by kind.
TEST(IdaStudy, CubeInfoOfAFinishedIdaCountsCurvesAndMessagesByKind) {
  const auto dir = test::scratch_dir("ida_info");
  std::string text = ida_study(2, 6);
  text.replace(text.find("max_runs"), 0, "collapse = [\"overturned\"]\n");  // fractures go on: many messages
  ASSERT_EQ(run_ida(dir, text, "ida.h5").exit_code, 0);
  cube::CubeReader cube(dir / "ida.h5");
  const auto status = cube.read_status();
  const auto unused = std::count(status.begin(), status.end(), cube::kStatusNotRun);
  const auto notes = cube.read_notes();
  const auto info = test::run_command(pcrf() + " cube info " + quoted(dir / "ida.h5"));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("completion: 4/4 curves (100.0 %)"), std::string::npos) << info.out;
  EXPECT_EQ(info.out.find("not_run"), std::string::npos) << info.out;
  if (unused > 0) {
    EXPECT_NE(info.out.find("no_run_slot: " + std::to_string(unused)), std::string::npos) << info.out;
  }
  ASSERT_GT(notes.size(), 1u) << "the runs must leave several messages for this test to mean anything";
  std::map<std::string, long> same;
  for (const auto& [index, note] : notes) ++same[note];
  const auto& [most, count] = *std::max_element(same.begin(), same.end(),
                                               [](const auto& a, const auto& b) { return a.second < b.second; });
  ASSERT_GT(count, 1) << "no message repeats";
  // The repeated message is one line with its count, not `count` lines.
  std::size_t lines = 0;
  for (std::size_t at = info.out.find(most); at != std::string::npos; at = info.out.find(most, at + 1)) ++lines;
  EXPECT_EQ(lines, 1u) << info.out;
  EXPECT_NE(info.out.find(most + " (" + std::to_string(count) + " cases"), std::string::npos) << info.out;
  const auto json = test::run_command(pcrf() + " cube info --json " + quoted(dir / "ida.h5"));
  EXPECT_NE(json.out.find("\"completion\": {\"done\": 4, \"total\": 4, \"unit\": \"curves\"}"), std::string::npos) << json.out;
}

TEST(IdaStudy, UnresolvedRunsAreCountedPerCurveInTheCubeAndOnStderr) {
  // A 0.05 s cap on the free vibration leaves frames that rocked still moving when their tail
  // ends: those runs are rocking_at_end, unresolved. The cube counts them per curve in
  // unresolved_runs, which must equal the count of that status among the curve's own runs.
  const auto dir = test::scratch_dir("ida_unresolved");
  std::string text = ida_study(2, 6);
  text.replace(text.find("[intensity]"), 0, "[physics]\nmax_tail_s = 0.05\n");
  const auto run = run_ida(dir, text, "ida.h5");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  cube::CubeReader cube(dir / "ida.h5");
  const auto status = cube.read_status();
  const auto per_curve = cube.read_side("unresolved_runs");
  const std::size_t points = 6;
  ASSERT_EQ(per_curve.size() * points, status.size());
  std::size_t total = 0;
  for (std::size_t c = 0; c < per_curve.size(); ++c) {
    const auto first = status.begin() + static_cast<std::ptrdiff_t>(c * points);
    const auto n = std::count(first, first + static_cast<std::ptrdiff_t>(points),
                              static_cast<std::int8_t>(pcrf::CaseStatus::kRockingAtEnd));
    EXPECT_EQ(per_curve[c], static_cast<double>(n)) << "curve " << c;
    total += static_cast<std::size_t>(n);
  }
  ASSERT_GT(total, 0u) << "some runs must end unresolved for this test to mean anything";
  EXPECT_NE(run.err.find(std::to_string(total) + " runs"), std::string::npos) << run.err;
  const auto info = test::run_command(pcrf() + " cube info " + quoted(dir / "ida.h5"));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.err.find(std::to_string(total) + " runs ended with the frame still rocking"), std::string::npos) << info.err;
}

}  // namespace
}  // namespace pcrf::study_test

namespace pcrf::study_test {
namespace {

/// A station whose vertical is twice its horizontal (a sine of period 0.5 s, in g): scaled by
/// the horizontal's PGA, the ground falls faster than gravity (g + ü_v ≤ 0) from PGA 0.5 g up.
std::string free_fall_station(const std::filesystem::path& dir) {
  std::string h1, up;
  for (int i = 0; i <= 800; ++i) {
    const double t = 0.005 * i, a = std::sin(2.0 * M_PI * t / 0.5);
    h1 += number_text(t) + " " + number_text(a) + "\n";
    up += number_text(t) + " " + number_text(2.0 * a) + "\n";
  }
  test::write_file(dir, "h1.txt", h1);
  test::write_file(dir, "up.txt", up);
  return "[[records]]\nh1 = \"h1.txt\"\nup = \"up.txt\"\nunits = \"g\"\nname = \"falling\"\n"
         "[intensity]\nmeasure = \"pga_g\"\n[ida]\nstart = 0.2\nmax_intensity = 10\nmax_runs = 10\n"
         "[outputs]\nmetrics = [\"theta_max_rad\"]\n";
}

TEST(IdaStudy, ACurveEndingInFreeFallIsUnresolvedNotSafeAtTheCap) {
  // Issue 29: free-fall runs were safe to the search, so these curves read "right-censored,
  // safe at 10 g" and a fragility fitted them there. Now the first free-fall run stops the
  // hunt, the curve is unresolved with no collapse intensity, its last safe run below 0.5 g.
  const auto dir = test::scratch_dir("ida_free_fall");
  const auto run = run_ida(dir, free_fall_station(dir), "ida.h5");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  cube::CubeReader cube(dir / "ida.h5");
  const auto status = cube.read_status();
  const auto falls = std::count(status.begin(), status.end(), static_cast<std::int8_t>(CaseStatus::kGroundFreeFall));
  ASSERT_GT(falls, 0) << "no run fell: the test sees nothing";
  const auto state = cube.read_side("curve_state"), safe = cube.read_side("last_safe_intensity");
  const auto collapse = cube.read_side("collapse_intensity");
  ASSERT_EQ(state.size(), 1u);
  EXPECT_EQ(state[0], static_cast<double>(ida::CurveState::kUnresolved));
  EXPECT_TRUE(std::isnan(collapse[0]));
  EXPECT_LT(safe[0], 0.5);
  EXPECT_NE(run.err.find(std::to_string(falls) + " ground_free_fall"), std::string::npos) << run.err;
  const auto info = test::run_command(pcrf() + " cube info " + quoted(dir / "ida.h5"));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("1 IDA curves: 0 bracketed to the resolution, 0 right-censored at max_intensity, 0 unbracketed"
                          " (max_runs ran out), 1 unresolved"),
            std::string::npos)
      << info.out;
  // The fragility bounds it at its last safe run, never at the cap, and says so with the count.
  const auto fragility = test::run_command(pcrf() + " cube fragility " + quoted(dir / "ida.h5") + " --points -");
  ASSERT_EQ(fragility.exit_code, 0) << fragility.err;
  EXPECT_NE(fragility.err.find("1 unresolved curves"), std::string::npos) << fragility.err;
  EXPECT_EQ(fragility.out.find(",censored,"), std::string::npos) << fragility.out;
  const auto at = fragility.out.find(",unresolved,");
  ASSERT_NE(at, std::string::npos) << fragility.out;
  EXPECT_NEAR(std::stod(fragility.out.substr(at + 12)), safe[0], 1e-9 * safe[0]) << fragility.out;
}

}  // namespace
}  // namespace pcrf::study_test

namespace pcrf::study_test {
namespace {

TEST(IdaStudy, CasesInFreeFallAreCountedApartByStatsNotInItsPercentiles) {
  // The same station on a grid: from scale 0.5 up the ground falls (ground_free_fall). Their
  // θ_max (up to the fall) is no result of the frame: stats count them as unresolved.
  const auto dir = test::scratch_dir("grid_free_fall");
  free_fall_station(dir);
  test::write_file(dir, "grid.toml",
                                     "[[records]]\nh1 = \"h1.txt\"\nup = \"up.txt\"\nunits = \"g\"\n"
                                     "[axes]\nscale = [0.2, 0.4, 0.8, 1.0]\n[outputs]\nmetrics = [\"theta_max_rad\"]\n");
  const auto run = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study grid.toml -o grid.h5 --progress-interval 0");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("2 cases ended where the model no longer applies (2 ground_free_fall)"), std::string::npos) << run.err;
  const auto stats = test::run_command(pcrf() + " cube stats " + quoted(dir / "grid.h5") + " --by scale -m theta_max_rad");
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_NE(stats.out.find("\n0.8,1,0,0,,,,1\n"), std::string::npos) << stats.out;
  EXPECT_NE(stats.out.find("\n1,1,0,0,,,,1"), std::string::npos) << stats.out;
  EXPECT_NE(stats.out.find("\n0.4,1,0,1,"), std::string::npos) << stats.out;
}

}  // namespace
}  // namespace pcrf::study_test
