// Study files: values, ranges, plans, defaults, and the errors of the parser (in process).
#include <gtest/gtest.h>

#include <cmath>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study {
namespace {

/// A parameter of the prestressed frame's point by name.
double at(const ScenePoint& point, std::string_view key) { return point.at(scene_model("pcrf").index(key)); }

Study parse(const std::string& text) { return parse_study(text, "t.toml", test::source_dir()); }

const std::string kRecords = "[[records]]\nsynthetic = \"sine:amplitude_g=1.5\"\n";

/// The plan's coordinate variable `name` (fails the test when there is none), its values held
/// (a plan computes those along `case` from the case number: every one is asked for here).
cube::Coordinate coordinate(const Study& s, const std::string& name) {
  for (auto& c : s.plan->coordinates())
    if (c.name == name) {
      for (std::size_t i = 0; c.computed() && i < c.computed_size; ++i)
        c.is_text ? c.strings.push_back(c.text(i)) : c.numbers.push_back(c.number(i));
      c.number_at = nullptr;
      c.text_at = nullptr;
      return c;
    }
  ADD_FAILURE() << "no coordinate " << name;
  return {};
}

/// The message of the UserError a text raises ("" if none).
std::string error_of(const std::string& text) { return study_test::error_of(parse, text); }

TEST(StudyParser, DefaultsAreTheBasicModelAndEveryMetric) {
  const Study s = parse(kRecords);
  EXPECT_EQ(s.plan->name(), "grid");
  EXPECT_EQ(s.name, "t");
  EXPECT_EQ(s.levels, std::vector<double>{1.0});
  EXPECT_DOUBLE_EQ(at(s.base, "kappa"), FrameParameters{}.kappa);
  EXPECT_DOUBLE_EQ(at(s.base, "pi_e_c"), FrameParameters{}.pi_e_c);
  // every metric but the verdict check's three (they need [solver] verdict_check = true)
  EXPECT_EQ(s.metrics.size(), all_metrics().size() - 3);
  const Study checked = parse(kRecords + "[solver]\nverdict_check = true\n");
  EXPECT_EQ(checked.metrics.size(), all_metrics().size());
  EXPECT_EQ(s.solver.rtol, preset_settings("balanced").rtol);
  EXPECT_EQ(CaseSpace(s).size(), 1);
}

TEST(StudyParser, ListsNumbersAndLinearAndLogRanges) {
  const Study s = parse(kRecords +
                        "[axes]\nscale = [0.5, 1]\nkappa = 2\nlambda = {from = 1.5, to = 2.5, count = 3}\n"
                        "pi_e_c = {from = 1000, to = 100000, count = 3, spacing = \"log\"}\n");
  EXPECT_EQ(s.levels, (std::vector<double>{0.5, 1.0}));
  EXPECT_EQ(coordinate(s, "kappa").numbers, std::vector<double>{2.0});
  EXPECT_EQ(coordinate(s, "lambda").numbers, (std::vector<double>{1.5, 2.0, 2.5}));
  EXPECT_EQ(coordinate(s, "tan_alpha").numbers, std::vector<double>{at(s.base, "tan_alpha")});  // not given: the base value
  const auto pi_e_c = coordinate(s, "pi_e_c").numbers;
  ASSERT_EQ(pi_e_c.size(), 3u);
  EXPECT_DOUBLE_EQ(pi_e_c[1], 10000.0);
  EXPECT_EQ(pi_e_c[2], 100000.0);  // exact end
  const CaseSpace space(s);
  EXPECT_EQ(space.size(), 2 * 1 * 3 * 3);
  EXPECT_EQ(space.dimension_names().size(), 10u);
}

TEST(StudyParser, RangeValuesAreTheDecimalsTheStudyMeant) {
  // from + t (to - from) gives 1.7999999999999998 for the fifth value of 1.2 … 2.4 in 7 steps,
  // and 0.30000000000000004 in 0.1 … 0.9: the axis holds the decimals, read as a reader types them.
  const Study s = parse(kRecords + "[axes]\nkappa = {from = 1.2, to = 2.4, count = 7}\n"
                                   "lambda_h = {from = 0.1, to = 0.9, count = 9}\n"
                                   "lambda = {from = 1, to = 2, count = 4}\n"
                                   "pi_e_c = {from = 1000, to = 100000, count = 4, spacing = \"log\"}\n");
  EXPECT_EQ(coordinate(s, "kappa").numbers, (std::vector<double>{1.2, 1.4, 1.6, 1.8, 2.0, 2.2, 2.4}));
  EXPECT_EQ(coordinate(s, "lambda_h").numbers, (std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9}));
  // Values that are no short decimal stay as computed: thirds, and log-spaced values.
  const auto lambda = coordinate(s, "lambda").numbers;
  EXPECT_EQ(lambda[1], 1.0 + (1.0 / 3.0) * 1.0);
  EXPECT_EQ(lambda[2], 1.0 + (2.0 / 3.0) * 1.0);
  const auto pi_e_c = coordinate(s, "pi_e_c").numbers;
  EXPECT_EQ(pi_e_c[1], 1000.0 * std::pow(100.0, 1.0 / 3.0));
  EXPECT_EQ(pi_e_c[2], 1000.0 * std::pow(100.0, 2.0 / 3.0));
}

TEST(StudyParser, SyntheticRecordsAreNamedByTheirText) {
  const Study s = parse("[[records]]\nsynthetic = [\"sine:cycles=1\", \"stochastic:seed=2\"]\n"
                        "[[records]]\nsynthetic = \"sine:cycles=3\"\nname = \"three\"\n");
  ASSERT_EQ(s.records.size(), 3u);
  EXPECT_EQ(s.records[0].name, "sine:cycles=1");
  EXPECT_EQ(s.records[2].name, "three");
}

TEST(StudyParser, RecordFilesResolveAgainstTheStudyFolderAndGlob) {
  const auto dir = test::scratch_dir("parser_globs");
  std::filesystem::create_directories(dir / "rec");
  test::write_file(dir / "rec", "a.txt", "0 0\n0.01 0.1\n");
  test::write_file(dir / "rec", "b.txt", "0 0\n0.01 0.2\n");
  const Study s = parse_study("[[records]]\nfiles = [\"rec/*.txt\"]\nunits = \"g\"\n", "t.toml", dir);
  ASSERT_EQ(s.records.size(), 2u);
  EXPECT_EQ(s.records[0].name, "a");
  EXPECT_EQ(s.records[1].file->path, dir / "rec" / "b.txt");
  EXPECT_EQ(s.records[1].file->format, RecordFormat::kTwoColumn);
}

TEST(StudyParser, OneAtATimeSweepsEachParameterAroundTheBase) {
  const Study s = parse(kRecords + "[plan]\nkind = \"one-at-a-time\"\n[base]\nkappa = 2.0\n"
                                   "[axes]\nkappa = [1, 3]\ntan_alpha = [0.15, 0.25]\n");
  const CaseSpace space(s);
  const auto labels = coordinate(s, "case_label").strings;
  const auto varied = coordinate(s, "varied_parameter").strings;
  ASSERT_EQ(labels.size(), 5u);  // base + 2 + 2
  ASSERT_EQ(varied.size(), 5u);
  EXPECT_EQ(labels[0], "base");
  EXPECT_EQ(varied[0], "none");
  EXPECT_EQ(labels[1], "kappa=1");
  EXPECT_EQ(varied[3], "tan_alpha");
  EXPECT_DOUBLE_EQ(at(space.case_at(3).frame.values, "kappa"), 2.0);  // the base, not the default
  EXPECT_DOUBLE_EQ(at(space.case_at(3).frame.values, "tan_alpha"), 0.15);
  EXPECT_EQ(space.dimension_names(), (std::vector<std::string>{"record", "scale", "case"}));
}

TEST(StudyParser, ListPlanTakesExplicitCases) {
  const Study s = parse(kRecords + "[plan]\nkind = \"list\"\n[[cases]]\nlabel = \"stocky\"\ntan_alpha = 0.3\n"
                                   "[[cases]]\nkappa = 3\n");
  const CaseSpace space(s);
  EXPECT_EQ(coordinate(s, "case_label").strings, (std::vector<std::string>{"stocky", "case1"}));
  EXPECT_DOUBLE_EQ(at(space.case_at(1).frame.values, "kappa"), 3.0);
}

TEST(StudyParser, PhysicsSolverOutputsAndRun) {
  const Study s = parse(kRecords +
                        "[physics]\nuplift = \"paper\"\ntail_s = 2\n[solver]\npreset = \"fast\"\nrtol = 1e-6\n"
                        "[outputs]\nmetrics = [\"theta_max_rad\", \"impacts\"]\n[run]\nflush_interval_s = 5\nbatch_size = 4\n");
  EXPECT_EQ(s.physics.uplift, UpliftCriterion::kPaper);
  EXPECT_EQ(s.physics.tail_s, 2.0);
  EXPECT_EQ(s.solver.rtol, 1e-6);
  EXPECT_EQ(s.solver.atol_theta_rad, preset_settings("fast").atol_theta_rad);
  EXPECT_EQ(s.metrics, (std::vector<std::string>{"theta_max_rad", "impacts"}));
  EXPECT_EQ(s.run.flush_interval_s, 5.0);
  EXPECT_EQ(s.run.batch_size, 4u);
}

struct BadStudy {
  std::string text;
  std::string message;  ///< expected in the error
};

/// Each study of `corpus` fails to parse with its message.
/// `names` as the parser lists the choices of a key, "a, b or c", each within `quote`: a new
/// scene or plan kind changes the list, not these tests.
std::string choices(const std::vector<std::string_view>& names, const std::string& quote) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i)
    text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + quote + std::string(names[i]) + quote;
  return text;
}

/// "(expected pcrf, block or rocking-frame)": the catalogue's models.
std::string expected_models() {
  std::vector<std::string_view> names;
  for (const auto& m : scene_models()) names.push_back(m.name);
  return "(expected " + choices(names, "") + ")";
}

void expect_each_refused(const std::vector<BadStudy>& corpus) {
  for (const auto& bad : corpus) {
    const std::string message = error_of(bad.text);
    EXPECT_NE(message.find(bad.message), std::string::npos) << "got: " << message << "\nfor:\n" << bad.text;
  }
}

TEST(StudyParser, RejectsBadStudiesNamingFileLineKeyAndProblem) {
  const std::vector<BadStudy> corpus = {
      {kRecords + "[axes]\nkapa = 2\n", "t.toml:4: [axes] kapa: unknown key (did you mean 'kappa'?)"},
      {kRecords + "[axes]\nkappa = \"big\"\n", "t.toml:4: [axes] kappa: expected a number, a list of numbers"},
      {kRecords + "[axes]\nkappa = []\n", "t.toml:4: [axes] kappa: empty list"},
      {kRecords + "[axes]\nkappa = {from = 3, to = 1, count = 3}\n", "[axes] kappa.to: the range runs backwards"},
      {kRecords + "[axes]\nkappa = {from = 1, to = 3, count = 0}\n", "[axes] kappa.count: must be at least 1"},
      {kRecords + "[axes]\nscale = [-1, 1]\n", "[axes] scale: value -1 must be positive"},
      {kRecords + "[axes]\nlambda_h = [0.5, 1.2]\n", "[axes] lambda_h: value 1.2 must be between 0 and 1"},
      {kRecords + "[axes]\nkappa = [1, 1]\n", "[axes] kappa: value 1 appears twice"},
      {kRecords + "[physics]\nfracture_strain = \"x\"\n", "[physics] fracture_strain: expected a number, got a string"},
      {kRecords + "[solver]\nintegrator = \"euler\"\n", "t.toml:4: [solver] integrator:"},
      {kRecords + "[outputs]\nmetrics = [\"theta_max\"]\n", "unknown metric \"theta_max\" (did you mean \"theta_max_rad\"?)"},
      {kRecords + "[outputs]\nmetrics = [\"wall_time_s\"]\n", "t.toml:4: [outputs] metrics: metric \"wall_time_s\" is now \"cpu_time_s\": CPU time"},
      {kRecords + "[physics]\nrest_rise_rad = -1e-10\n", "t.toml:4: [physics] rest_rise_rad:"},
      {"[axes]\nkappa = 2\n", "t.toml: records: a study needs at least one [[records]]"},
      {"[[records]]\nfile = \"no/such/file.AT2\"\n", "t.toml:2: [[records]] #1 file: file not found"},
      {kRecords + "[plan]\nkind = \"random\"\n", "[plan] kind: expected " + choices(plan_kinds(), "\"")},
      {kRecords + "[plan]\nkind = \"one-at-a-time\"\n", "needs at least one parameter to sweep"},
      {kRecords + "kappa = [1\n", "t.toml:3: not valid TOML"},
      {kRecords + "[outputs]\nmetrics = [\"status_stable\"]\n", "metric \"status_stable\" needs [solver] verdict_check = true"},
  };
  expect_each_refused(corpus);
}

TEST(StudyParser, AScenesParametersAreItsAxesAndBasePoint) {
  const Study s = parse(kRecords + "[frame]\nmodel = \"block\"\nslenderness_rad = 0.2\ngiven_restitution = 0.9\n"
                                   "[axes]\nfrequency_parameter_rad_s = {from = 1, to = 4, count = 3, spacing = \"log\"}\n");
  ASSERT_EQ(s.model->name, "block");
  EXPECT_EQ(coordinate(s, "frequency_parameter_rad_s").numbers, (std::vector<double>{1.0, 2.0, 4.0}));
  EXPECT_EQ(coordinate(s, "slenderness_rad").numbers, std::vector<double>{0.2});
  EXPECT_EQ(coordinate(s, "frequency_parameter_rad_s").units, "rad/s");
  const CaseSpace space(s);
  ASSERT_EQ(space.size(), 3);
  const auto& block = scene_model("block");
  EXPECT_EQ(space.case_at(2).frame.values[block.index("frequency_parameter_rad_s")], 4.0);
  EXPECT_EQ(space.case_at(2).frame.values[block.index("given_restitution")], 0.9);
  EXPECT_EQ(space.case_at(2).frame.values[block.index("slenderness_rad")], 0.2);
  // The rocking frame's γ on a one-at-a-time sweep; the list plan's cases take a scene's keys too.
  const Study frames = parse(kRecords + "[frame]\nmodel = \"rocking-frame\"\n[plan]\nkind = \"one-at-a-time\"\n"
                                        "[axes]\nbeam_mass_ratio = [0.5, 1]\n");
  EXPECT_EQ(CaseSpace(frames).size(), 3);
  const Study listed = parse(kRecords + "[frame]\nmodel = \"block\"\n[plan]\nkind = \"list\"\n"
                                        "[[cases]]\nlabel = \"slender\"\nslenderness_rad = 0.1\n");
  EXPECT_EQ(CaseSpace(listed).case_at(0).frame.values[block.index("slenderness_rad")], 0.1);
}

TEST(StudyParser, RefusesAnotherScenesKeysAndImpossibleScenes) {
  const std::string block = kRecords + "[frame]\nmodel = \"block\"\n";
  const std::vector<BadStudy> corpus = {
      {block + "[axes]\nkappa = [1, 2]\n",
       "t.toml:6: [axes] kappa: does not apply to model \"block\" (it is a parameter of model \"pcrf\""},
      {block + "pi_sigma_c = 3\n", "t.toml:5: [frame] pi_sigma_c: does not apply to model \"block\""},
      {kRecords + "[axes]\nslenderness_rad = [0.1, 0.2]\n", "[axes] slenderness_rad: does not apply to model \"pcrf\""},
      {block + "slenderness_rad = 1.6\n", "t.toml:5: [frame] slenderness_rad: value 1.6 must lie between 0 and pi/2"},
      {block + "[axes]\nslenderness_rad = [0.1, 1.5708]\n", "[axes] slenderness_rad: value 1.5708 must lie between 0 and pi/2"},
      {block + "beam_mass_ratio = 0.5\n", "[frame] beam_mass_ratio: does not apply to model \"block\" (it is a parameter of model \"rocking-frame\""},
      {kRecords + "[frame]\nmodel = \"rocking-frame\"\nbeam_mass_ratio = -0.5\n", "t.toml:5: [frame] beam_mass_ratio: value -0.5 must not be negative"},
      {block + "size_m = 2\nfrequency_parameter_rad_s = 3\n", "give either size_m or frequency_parameter_rad_s, not both"},
      {block + "given_restitution = 1.2\n", "[frame] given_restitution: value 1.2 must lie in [0, 1]"},
      {kRecords + "[frame]\nmodel = \"cylinder\"\n", "t.toml:4: [frame] model: unknown scene 'cylinder' " + expected_models()},
      {kRecords + "[frame]\nkappa = 2\n[base]\nkappa = 3\n", "[base] kappa: is also given in [frame]"},
  };
  expect_each_refused(corpus);
}

TEST(StudyParser, AListedCaseMayNameAnotherSceneStartingFromItsDefaults) {
  // A prestressed-frame study (its base kappa = 2) with a block and a rocking frame listed
  // beside its own frame: each case keeps its model, the others start from their defaults.
  const Study s = parse(kRecords + "[frame]\nkappa = 2\n[plan]\nkind = \"list\"\n"
                                   "[[cases]]\nlabel = \"frame\"\n"
                                   "[[cases]]\nlabel = \"block\"\nmodel = \"block\"\nslenderness_rad = 0.2\n"
                                   "[[cases]]\nlabel = \"portal\"\nmodel = \"rocking-frame\"\nbeam_mass_ratio = 0.5\n");
  const CaseSpace space(s);
  ASSERT_EQ(space.size(), 3);
  EXPECT_EQ(space.case_at(0).frame.model->name, "pcrf");
  EXPECT_EQ(space.case_at(0).frame.value("kappa"), 2.0);
  EXPECT_EQ(space.case_at(1).frame.model->name, "block");
  EXPECT_EQ(space.case_at(1).frame.value("slenderness_rad"), 0.2);
  EXPECT_EQ(space.case_at(1).frame.value("size_m"), scene_model("block").defaults()[scene_model("block").index("size_m")]);
  EXPECT_EQ(space.case_at(2).frame.model->name, "rocking-frame");
  EXPECT_EQ(space.case_at(2).frame.value("beam_mass_ratio"), 0.5);
  // One coordinate per parameter of any model present, NaN where a case's model has none.
  EXPECT_EQ(coordinate(s, "scene_model").strings, (std::vector<std::string>{"pcrf", "block", "rocking-frame"}));
  const auto kappa = coordinate(s, "kappa").numbers;
  EXPECT_EQ(kappa[0], 2.0);
  EXPECT_TRUE(std::isnan(kappa[1]) && std::isnan(kappa[2]));
  const auto alpha = coordinate(s, "slenderness_rad").numbers;
  EXPECT_TRUE(std::isnan(alpha[0]));
  EXPECT_EQ(alpha[1], 0.2);
  EXPECT_TRUE(std::isnan(coordinate(s, "beam_mass_ratio").numbers[1]));
  // A list of one model has no scene_model coordinate (its cubes as they were).
  for (const auto& c : parse(kRecords + "[plan]\nkind = \"list\"\n[[cases]]\nkappa = 2\n").plan->coordinates())
    EXPECT_NE(c.name, "scene_model");
}

TEST(StudyParser, RefusesAListedCasesKeysOfAnotherSceneThanItsOwn) {
  const std::string list = kRecords + "[plan]\nkind = \"list\"\n[[cases]]\n";
  const std::vector<BadStudy> corpus = {
      {list + "model = \"block\"\nkappa = 2\n", "t.toml:7: [[cases]] #1 kappa: does not apply to model \"block\""},
      {list + "slenderness_rad = 0.2\n", "t.toml:6: [[cases]] #1 slenderness_rad: does not apply to model \"pcrf\""},
      {list + "model = \"sphere\"\n", "t.toml:6: [[cases]] #1 model: unknown scene 'sphere' " + expected_models()},
      {list + "model = \"block\"\nslenderness_rad = 1.6\n", "[[cases]] #1 slenderness_rad: value 1.6 must lie between 0 and pi/2"},
      {list + "h_m = 5\n", "t.toml:6: [[cases]] #1 h_m: is set once for every case, in [frame] or [base]"},
  };
  expect_each_refused(corpus);
  // A case of another model than the study's sets all of its parameters: it has no base point.
  // Its cube keeps them as coordinates, since no base point (attribute) holds them.
  const Study s = parse(kRecords + "[frame]\nmodel = \"block\"\n[plan]\nkind = \"list\"\n[[cases]]\nmodel = \"pcrf\"\nh_m = 5\n"
                                   "[[cases]]\nlabel = \"block\"\n");
  EXPECT_EQ(CaseSpace(s).case_at(0).frame.value("h_m"), 5.0);
  const auto h = coordinate(s, "h_m").numbers;
  EXPECT_EQ(h[0], 5.0);
  EXPECT_TRUE(std::isnan(h[1]));
}

TEST(StudyParser, PulseParametersAreAxesOfPulseRecords) {
  const Study s = parse("[[records]]\npulse = [\"pulse-sine\", \"pulse-cycles\"]\ndt_s = 0.002\n"
                        "[axes]\npulse_period_s = {from = 0.1, to = 1, count = 3, spacing = \"log\"}\n"
                        "pulse_amplitude_g = [0.5, 2]\npulse_cycles = [1, 3]\n");
  // pulse-sine: 3 periods x 2 amplitudes; pulse-cycles also x 2 cycle counts.
  ASSERT_EQ(s.records.size(), 6u + 12u);
  EXPECT_EQ(s.records[0].name, "pulse-sine:period_s=0.1,amplitude_g=0.5,dt_s=0.002");
  EXPECT_EQ(s.records[1].name, "pulse-sine:period_s=0.1,amplitude_g=2,dt_s=0.002");
  EXPECT_EQ(s.records[6].name, "pulse-cycles:period_s=0.1,amplitude_g=0.5,cycles=1,dt_s=0.002");
  EXPECT_EQ(s.records[6].pulse_shape, "pulse-cycles");
  ASSERT_EQ(s.records[2].pulse_values.size(), 2u);
  EXPECT_EQ(s.records[2].pulse_values[0].first, "pulse_period_s");
  EXPECT_NEAR(s.records[2].pulse_values[0].second, std::sqrt(0.1), 1e-15);
  // Every record is a pulse that the synthetic reader makes.
  for (const auto& r : s.records) EXPECT_NO_THROW(load_record(r)) << r.name;
}

TEST(StudyParser, RefusesImpossiblePulses) {
  const std::string pulse = "[[records]]\npulse = \"ricker\"\n";
  const std::vector<BadStudy> corpus = {
      {pulse + "[axes]\npulse_period_s = [0.5, 0]\n", "t.toml:4: [axes] pulse_period_s: value 0 must be positive"},
      {pulse + "[axes]\npulse_period_s = [-1, 0.5]\n", "t.toml:4: [axes] pulse_period_s: value -1 must be positive"},
      {pulse + "[axes]\npulse_period_s = [0.01, 0.5]\n", "t.toml:4: [axes] pulse_period_s: value 0.01 is below 4 dt = 0.02 s"},
      {"[[records]]\npulse = \"ricker\"\ndt_s = 0.01\n[axes]\npulse_period_s = 0.03\n", "[axes] pulse_period_s: value 0.03 is below 4 dt = 0.04 s"},
      {"[[records]]\npulse = \"wavelet\"\n", "t.toml:2: [[records]] #1 pulse: unknown pulse \"wavelet\" (expected pulse-sine"},
      {kRecords + "[axes]\npulse_period_s = [0.5, 1]\n", "t.toml:4: [axes] pulse_period_s: needs a [[records]] pulse entry"},
      {pulse + "name = \"r\"\n", "[[records]] #1 name: does not apply to pulse records"},
  };
  expect_each_refused(corpus);
}

TEST(CaseSpace, LinearIndexAndCoordinatesRoundTrip) {
  const Study s = parse(kRecords + "[axes]\nscale = [1, 2, 3]\nkappa = [1, 2]\npi_e_c = [1000, 2000, 3000, 4000]\n");
  const CaseSpace space(s);
  ASSERT_EQ(space.size(), 24);
  for (std::int64_t i = 0; i < space.size(); ++i) EXPECT_EQ(space.index(space.coordinates(i)), i);
  const CaseSpec last = space.case_at(23);  // last of every axis
  EXPECT_EQ(last.level, 3.0);
  EXPECT_EQ(at(last.frame.values, "kappa"), 2.0);
  EXPECT_EQ(at(last.frame.values, "pi_e_c"), 4000.0);
  const CaseSpec second = space.case_at(1);  // the fastest axis moves first
  EXPECT_EQ(at(second.frame.values, "pi_e_c"), 2000.0);
  EXPECT_EQ(second.level, 1.0);
}

TEST(CaseSpace, HistoryRequestsNameExactlyOneCase) {
  const Study s = parse(kRecords + "[axes]\nkappa = [1, 2]\n[[outputs.histories]]\nlabel = \"a\"\nkappa = 2\n"
                                   "[[outputs.histories]]\nlabel = \"b\"\n");
  const CaseSpace space(s);
  EXPECT_EQ(space.resolve(s.histories[0]), 1);
  try {
    space.resolve(s.histories[1]);
    FAIL() << "ambiguous request accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("the kappa axis has 2 values: give `kappa`"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pcrf::study
