// `pcrf cube fragility --reduce-over incidence_deg`: the fit of each record's collapse
// intensity reduced over the orientations (min: the worst, median, max: the best) equals a fit
// of the reduction done here by hand from the cube's own values; a bad --reduce is one line,
// exit code 2, nothing written. cube::reduce_censored: when a censored curve changes the value.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/row_major.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "study/study_test_support.hpp"

namespace pcrf {
namespace {

using study_test::pcrf;
using study_test::quoted;
namespace fs = std::filesystem;

/// Three stations (one pair of motions at three geometries) × 4 incidences, an adaptive IDA
/// of the basic frame scaled by RotD50 of PGA; made once per test process.
const fs::path& ida_cube() {
  static const fs::path dir = [] {
    const auto d = test::scratch_dir(std::string("cube_reduce_") +
                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    const std::string records =
        study_test::station_pair(d, "a") +
        "[[records]]\nh1 = \"h2.txt\"\nh2 = \"h1.txt\"\nunits = \"m/s2\"\naz1_deg = 30\naz2_deg = 120\nname = \"b\"\n"
        "[[records]]\nh1 = \"h1.txt\"\nh2 = \"h2.txt\"\nunits = \"m/s2\"\naz1_deg = 0\naz2_deg = 60\nname = \"c\"\n";
    test::write_file(d, "ida.toml", records +
                                        "[intensity]\nmeasure = \"pga_rotd50_g\"\n"
                                        "[ida]\nstart = 1.0\nstep = 1.0\nmax_intensity = 16\nmax_runs = 10\n"
                                        "[axes]\nincidence_deg = [0, 45, 90, 135]\n");
    const auto r = test::run_command("cd " + quoted(d) + " && " + pcrf() + " study ida.toml -o ida.h5 --progress-interval 0");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return d;
  }();
  return dir;
}

/// The study of ida_cube() with `from` replaced by `to`, run into NAME.h5 beside it.
test::CommandResult run_variant(const std::string& name, const std::string& from, const std::string& to) {
  const auto& dir = ida_cube();
  std::ifstream in(dir / "ida.toml");
  std::stringstream text;
  text << in.rdbuf();
  test::write_file(dir, name + ".toml", std::regex_replace(text.str(), std::regex(from), to));
  return test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study " + name + ".toml -o " + name +
                           ".h5 --overwrite --progress-interval 0");
}

/// The number after `"key": ` in the first frame of a fragility JSON.
double json_number(const std::string& json, const std::string& key) {
  const auto frames = json.find("\"frames\"");
  const auto at = json.find("\"" + key + "\": ", frames);
  EXPECT_NE(at, std::string::npos) << key << " in " << json;
  return at == std::string::npos ? std::nan("") : std::strtod(json.c_str() + at + key.size() + 4, nullptr);
}

TEST(CubeReduce, TheReducedFragilityFitsEachRecordsReductionOverTheIncidence) {
  const auto file = ida_cube() / "ida.h5";
  cube::CubeReader cube(file);
  const auto ci = cube.read_side("collapse_intensity");
  ASSERT_EQ(ci.size(), 12u);  // record × incidence (the frame axes have one value each)
  for (double c : ci) ASSERT_TRUE(std::isfinite(c)) << "every curve must collapse below max_intensity";
  for (double s : cube.read_side("curve_state")) ASSERT_EQ(s, 0.0) << "every curve bracketed";
  for (const std::string how : {"min", "median", "max"}) {
    // By hand: per record its four orientations' collapse intensities reduced; with nothing
    // censored the lognormal's maximum-likelihood median is their geometric mean.
    double log_sum = 0.0;
    for (std::size_t rec = 0; rec < 3; ++rec) {
      std::vector<double> v(ci.begin() + static_cast<long>(rec * 4), ci.begin() + static_cast<long>(rec * 4 + 4));
      std::sort(v.begin(), v.end());
      const double reduced = how == "min" ? v.front() : how == "max" ? v.back() : 0.5 * (v[1] + v[2]);
      log_sum += std::log(reduced);
    }
    const auto out = test::run_command(pcrf() + " cube fragility " + quoted(file) +
                                       " --reduce-over incidence_deg --reduce " + how + " --json");
    ASSERT_EQ(out.exit_code, 0) << out.err;
    EXPECT_NEAR(json_number(out.out, "median"), std::exp(log_sum / 3.0), 1e-9 * std::exp(log_sum / 3.0)) << how;
    EXPECT_EQ(json_number(out.out, "cases"), 3.0) << how;  // one reduced value per record
    EXPECT_NE(out.out.find("\"reduced_over\": \"incidence_deg\""), std::string::npos) << out.out;
    EXPECT_NE(out.out.find("\"frame\": \"all\""), std::string::npos) << "incidence is no frame axis once reduced";
  }
  // Without --reduce the fragility takes each record's worst orientation, the smallest.
  const auto worst = test::run_command(pcrf() + " cube fragility " + quoted(file) + " --reduce-over incidence_deg --json");
  const auto min = test::run_command(pcrf() + " cube fragility " + quoted(file) + " --reduce-over incidence_deg --reduce min --json");
  EXPECT_EQ(worst.out, min.out);
  // Not reduced: one frame per incidence.
  const auto plain = test::run_command(pcrf() + " cube fragility " + quoted(file) + " --json");
  EXPECT_NE(plain.out.find("\"frame\": \"incidence_deg=45\""), std::string::npos) << plain.out;
}

TEST(CubeReduce, ABadReductionIsOneLineAndWritesNothing) {
  const auto dir = ida_cube();
  const auto csv = dir / "bad.csv";
  for (const std::string args : {"fragility ida.h5 --reduce-over incidence_deg --reduce mean --csv bad.csv",
                                 "stats ida.h5 --by kappa -m theta_max_rad --reduce-over incidence_deg --reduce mean --csv bad.csv",
                                 "fragility ida.h5 --reduce min --csv bad.csv",
                                 "fragility ida.h5 --reduce-over record --csv bad.csv",
                                 "fragility ida.h5 --reduce-over kappa_typo --csv bad.csv"}) {
    const auto r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " cube " + args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(csv)) << args;
  }
  const auto r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " cube fragility ida.h5 --reduce-over incidence_deg --reduce mean");
  EXPECT_NE(r.err.find("--reduce: reduce with max, min or median, not 'mean'"), std::string::npos) << r.err;
}

TEST(CubeReduce, CurvesThatNeverCollapsedStayCensoredInTheWorstOrientation) {
  // The same stations searched only up to 3 g: some orientations never collapse.
  const auto dir = ida_cube();
  auto r = run_variant("capped", "max_intensity = 16", "max_intensity = 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "capped.h5");
  const auto ci = cube.read_side("collapse_intensity"), safe = cube.read_side("last_safe_intensity");
  // By hand, per record: the worst orientation (min) is a collapse when one was found at or
  // below every censored curve's last safe intensity, else it is only known to exceed the lowest
  // bound; the best (max) is a collapse when no curve is censored, else it exceeds every value.
  std::size_t censored_curves = 0;
  for (const std::string how : {"min", "max"}) {
    std::multiset<std::pair<std::string, double>> expected;
    censored_curves = 0;
    for (std::size_t rec = 0; rec < 3; ++rec) {
      const double inf = std::numeric_limits<double>::infinity();
      double lowest_collapse = inf, lowest_bound = inf, highest = -inf;
      for (std::size_t k = rec * 4; k < rec * 4 + 4; ++k) {
        if (std::isfinite(ci[k])) lowest_collapse = std::min(lowest_collapse, ci[k]), highest = std::max(highest, ci[k]);
        else lowest_bound = std::min(lowest_bound, safe[k]), highest = std::max(highest, safe[k]), ++censored_curves;
      }
      const bool some_censored = lowest_bound < inf;
      if (how == "min")
        expected.insert(lowest_collapse <= lowest_bound ? std::pair{std::string("collapse"), lowest_collapse}
                                                         : std::pair{std::string("censored"), lowest_bound});
      else
        expected.insert({some_censored ? "censored" : "collapse", highest});
    }
    ASSERT_GT(censored_curves, 0u) << "the cap must leave some curves censored";
    r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " cube fragility capped.h5 --reduce-over incidence_deg --reduce " +
                          how + " --points points.csv --overwrite");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream points(dir / "points.csv");
    std::multiset<std::pair<std::string, double>> found;
    std::string line;
    std::getline(points, line);  // frame,kind,intensity,trials,collapses
    while (std::getline(points, line)) {
      std::stringstream fields(line);
      std::string frame, kind, intensity;
      std::getline(fields, frame, ',');
      std::getline(fields, kind, ',');
      std::getline(fields, intensity, ',');
      found.insert({kind, std::stod(intensity)});
    }
    EXPECT_EQ(found, expected) << how;
  }
  // cube stats reduces what collapsed only, and says so.
  r = test::run_command("cd " + quoted(dir) + " && " + pcrf() +
                        " cube stats capped.h5 --by kappa -m collapse_intensity --reduce-over incidence_deg --reduce min");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(std::to_string(censored_curves) + " curves without a collapse (censored, or unbracketed before "
                       "one) are left out of the reduction"), std::string::npos) << r.err;
}

TEST(CubeReduce, StatsNameTheUnbracketedCollapsesTheyReduce) {
  // Too few runs to refine: curves that found a collapse end unbracketed, their collapse an
  // upper bound; cube stats reduces them as the cube holds them, and says how many there are.
  const auto dir = ida_cube();
  auto r = run_variant("short", "max_runs = 10", "max_runs = 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "short.h5");
  const auto ci = cube.read_side("collapse_intensity"), state = cube.read_side("curve_state");
  std::size_t unrefined = 0;
  for (std::size_t c = 0; c < ci.size(); ++c) unrefined += std::isfinite(ci[c]) && state[c] == 2.0;  // ida::CurveState::kUnbracketed
  ASSERT_GT(unrefined, 0u) << "no curve found a collapse it could not refine: the test sees too little";
  r = test::run_command("cd " + quoted(dir) + " && " + pcrf() +
                        " cube stats short.h5 --by kappa -m collapse_intensity --reduce-over incidence_deg --reduce min");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(std::to_string(unrefined) + " unbracketed curves enter the reduction at a collapse not refined to the resolution"),
            std::string::npos) << r.err;
}

/// The row of `key` in a CSV of `cube stats`: column name → text.
std::map<std::string, std::string> csv_row(const fs::path& file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  std::vector<std::string> names;
  for (std::getline(in, line); std::stringstream header{line};) {
    for (std::string name; std::getline(header, name, ',');) names.push_back(name);
    break;
  }
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::map<std::string, std::string> row;
    for (const auto& name : names) std::getline(fields, row[name], ',');
    if (row[names.front()] == key) return row;
  }
  ADD_FAILURE() << "no row " << key << " in " << file;
  return {};
}

TEST(CubeReduce, AReducedStatisticCountsApartWhatAMovingCaseCouldChange) {
  // Scaled records at four orientations, two frames, the free vibration cut short
  // (max_tail_s) so that some cases end still rocking: a reduction over the orientations is a
  // collapse when the collapses decide it (any for max, all for min, most for median), else
  // unresolved when any member is still moving, else the reduction of the members' values.
  const auto dir = test::scratch_dir("cube_reduce_unresolved");
  test::write_file(dir, "moving.toml", study_test::station_pair(dir, "a") +
                                           "[[records]]\nh1 = \"h2.txt\"\nh2 = \"h1.txt\"\nunits = \"m/s2\"\naz1_deg = 30\naz2_deg = 120\nname = \"b\"\n"
                                           "[physics]\nmax_tail_s = 0.05\n"
                                           "[axes]\nscale = [1.5, 2.5, 4]\nincidence_deg = [0, 45, 90, 135]\nkappa = [1.4, 1.8]\n"
                                           "[outputs]\nmetrics = [\"theta_max_rad\"]\n");
  auto r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study moving.toml -o moving.h5 --progress-interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "moving.h5");
  const auto& layout = cube.layout();
  const auto status = cube.read_status();
  const auto collapses = schema::collapse_statuses(), moving = schema::unresolved_statuses();
  auto is = [](const std::vector<std::int8_t>& set, std::int8_t s) { return std::find(set.begin(), set.end(), s) != set.end(); };
  const auto shape = layout.shape();
  const std::size_t incidence = *layout.find_dimension("incidence_deg"), kappa = *layout.find_dimension("kappa");
  // Per κ and combination of the other coordinates (record, scale): its members' statuses.
  std::map<std::size_t, std::map<std::int64_t, std::vector<std::int8_t>>> members;
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    auto c = unravel(i, shape);
    const std::size_t k = c[kappa];
    c[incidence] = 0;
    members[k][ravel(c, shape)].push_back(status[static_cast<std::size_t>(i)]);
  }
  std::size_t decided_by_collapses = 0, left_unresolved = 0;
  for (const std::string how : {"max", "min", "median"}) {
    r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " cube stats moving.h5 --by kappa -m theta_max_rad --reduce-over incidence_deg --reduce " +
                          how + " --csv " + how + ".csv");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const auto& [k, combinations] : members) {
      std::size_t apart = 0, unresolved = 0, reduced = 0;
      for (const auto& [key, statuses] : combinations) {
        const auto collapsed = static_cast<std::size_t>(std::count_if(statuses.begin(), statuses.end(), [&](auto s) { return is(collapses, s); }));
        const bool any_moving = std::any_of(statuses.begin(), statuses.end(), [&](auto s) { return is(moving, s); });
        const bool decided = how == "max" ? collapsed > 0 : how == "min" ? collapsed == statuses.size() : 2 * collapsed > statuses.size();
        if (decided) ++apart;
        else if (any_moving) ++unresolved;
        else ++reduced;
        if (how == "max" && any_moving) (decided ? decided_by_collapses : left_unresolved) += 1;
      }
      const auto row = csv_row(dir / (how + ".csv"), layout.find_coordinate("kappa")->label(k));
      EXPECT_EQ(row.at("cases"), std::to_string(combinations.size())) << how;
      EXPECT_EQ(row.at("collapses"), std::to_string(apart)) << how << " kappa " << k;
      EXPECT_EQ(row.at("unresolved"), std::to_string(unresolved)) << how << " kappa " << k;
      EXPECT_EQ(row.at("values"), std::to_string(reduced)) << how << " kappa " << k;
    }
  }
  EXPECT_GT(left_unresolved, 0u) << "no reduction is left unknown by a moving case: the test sees too little";
  EXPECT_GT(decided_by_collapses, 0u) << "no collapse decides a reduction with a moving member: the test sees too little";
}

TEST(CubeReduce, ACensoredValueCensorsTheReductionOnlyWhereItCouldChangeIt) {
  using cube::reduce_censored;
  // min: a curve safe up to 1 may collapse anywhere above 1: the worst is only known to exceed 1.
  auto r = reduce_censored({2.0, 3.0}, {1.0}, "min");
  EXPECT_EQ(r.value, 1.0);
  EXPECT_TRUE(r.censored);
  r = reduce_censored({2.0, 3.0}, {5.0}, "min");  // safe up to 5: the worst is the collapse at 2
  EXPECT_EQ(r.value, 2.0);
  EXPECT_FALSE(r.censored);
  r = reduce_censored({2.0, 3.0}, {5.0}, "max");  // the best exceeds 5
  EXPECT_EQ(r.value, 5.0);
  EXPECT_TRUE(r.censored);
  r = reduce_censored({1.0, 2.0, 3.0}, {10.0}, "median");  // above the middle: (2 + 3) / 2 whatever it is
  EXPECT_EQ(r.value, 2.5);
  EXPECT_FALSE(r.censored);
  r = reduce_censored({1.0, 2.0}, {1.5, 10.0}, "median");  // 1.5 is a middle value: known from below only
  EXPECT_EQ(r.value, 1.75);
  EXPECT_TRUE(r.censored);
  r = reduce_censored({}, {}, "min");
  EXPECT_TRUE(std::isnan(r.value));
  EXPECT_THROW(reduce_censored({1.0}, {}, "mean"), cube::CubeError);
}

}  // namespace
}  // namespace pcrf
