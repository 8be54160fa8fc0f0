// `pcrf study` end to end: the cube equals `pcrf run` case by case, 1/2/3 ranks give the same
// cube, a killed run resumes to the same cube, bad studies fail cleanly, outputs are protected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <regex>
#include <sstream>
#include <thread>

#include <spawn.h>
#include <sys/wait.h>

#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/record_source.hpp"
#include "pcrf/study/study_check.hpp"
#include "pcrf/user_error.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

/// Runs `pcrf study` on a study text written to dir/name.
test::CommandResult run_study(const std::filesystem::path& dir, const std::string& name, const std::string& text,
                              const std::string& arguments, const std::string& launcher = "") {
  const auto file = test::write_file(dir, name, text);
  return test::run_command("cd " + quoted(dir) + " && " + launcher + pcrf() + " study " + quoted(file) + " " + arguments);
}

/// Flat JSON object of `pcrf run`: key → number text, string or "null".
std::map<std::string, std::string> parse_flat_json(const std::string& json) {
  std::map<std::string, std::string> values;
  static const std::regex pair(R"re("([a-z_0-9]+)":\s*("([^"]*)"|[^,}]+))re");
  for (std::sregex_iterator it(json.begin(), json.end(), pair), end; it != end; ++it)
    values[(*it)[1]] = (*it)[3].matched ? (*it)[3].str() : (*it)[2].str();
  return values;
}

std::string status_meaning(const cube::CubeLayout& layout, std::int8_t value) {
  for (const auto& f : layout.status_flags)
    if (f.value == value) return f.meaning;
  return "not_run";
}

/// Each case of `cube` against `pcrf` + `run_arguments(its coordinates)`: the same status,
/// θ_max (where the run has one) and impacts, bit for bit. Returns the statuses seen.
std::set<std::string> expect_each_case_is_pcrf_run(
    const cube::CubeReader& cube, const std::function<std::string(const std::vector<std::size_t>&)>& run_arguments) {
  const auto& layout = cube.layout();
  const auto status = cube.read_status();
  const auto theta = cube.read_metric("theta_max_rad");
  const auto impacts = cube.read_metric("impacts");
  std::set<std::string> statuses;
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    const std::string args = run_arguments(cube::unravel(i, layout.shape()));
    const auto run = test::run_command(pcrf() + args);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    if (run.exit_code != 0) continue;
    const auto json = parse_flat_json(run.out);
    const auto k = static_cast<std::size_t>(i);
    EXPECT_EQ(json.at("status"), status_meaning(layout, status[k])) << args;
    statuses.insert(json.at("status"));
    if (json.at("theta_max_rad") != "null") {
      EXPECT_EQ(std::strtod(json.at("theta_max_rad").c_str(), nullptr), theta[k]) << args;
    }
    EXPECT_EQ(std::strtod(json.at("impacts").c_str(), nullptr), impacts[k]) << args;
  }
  return statuses;
}

TEST(StudyCommand, EveryCubeValueEqualsPcrfRunForThatCase) {
  const auto dir = test::scratch_dir("study_equals_run");
  const auto r = run_study(dir, "small.toml", small_grid_study(), "-o cube.h5 --progress-interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "cube.h5");
  const auto& layout = cube.layout();
  const auto status = cube.read_status();
  std::map<std::string, std::vector<double>> metrics;
  for (const auto& m : layout.metrics) metrics[m.name] = cube.read_metric(m.name);
  const auto per_case = std::count_if(all_metrics().begin(), all_metrics().end(),
                                      [](const MetricInfo& m) { return !m.needs_verdict_check; });
  ASSERT_EQ(metrics.size(), static_cast<std::size_t>(per_case));  // every per-case metric by default
  const auto shape = layout.shape();
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    const auto c = cube::unravel(i, shape);
    std::string args = " run --synthetic '" + layout.coordinates[0].strings[c[0]] + "'";
    args += " --scale " + layout.find_coordinate("scale")->label(c[1]);
    args += " --kappa " + layout.find_coordinate("kappa")->label(c[2]);
    args += " --tan-alpha " + layout.find_coordinate("tan_alpha")->label(c[4]);
    const auto run = test::run_command(pcrf() + args);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto json = parse_flat_json(run.out);
    const auto k = static_cast<std::size_t>(i);
    EXPECT_EQ(json.at("status"), status_meaning(layout, status[k])) << "case " << i;
    for (const auto& [name, values] : metrics) {
      if (name == "cpu_time_s") continue;
      const std::string& text = json.at(name);
      if (text == "null")
        EXPECT_TRUE(std::isnan(values[k])) << name << " of case " << i;
      else
        EXPECT_EQ(std::strtod(text.c_str(), nullptr), values[k]) << name << " of case " << i << args;
    }
  }
}

TEST(StudyCommand, ABlockStudyGivesWhatPcrfRunGivesForEachCase) {
  const auto dir = test::scratch_dir("study_block");
  const std::string text =
      "[[records]]\nsynthetic = [\"pulse-sine:period_s=0.5,amplitude_g=0.6\", \"ricker:period_s=0.8,amplitude_g=0.9\"]\n"
      "[frame]\nmodel = \"block\"\ngiven_restitution = 0.9\n"
      "[axes]\nslenderness_rad = [0.15, 0.25]\nfrequency_parameter_rad_s = [1.5, 3]\n"
      "[outputs]\nmetrics = [\"theta_max_rad\", \"impacts\", \"t_uplift_s\"]\n";
  const auto r = run_study(dir, "block.toml", text, "-o cube.h5 --progress-interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "cube.h5");
  const auto& layout = cube.layout();
  EXPECT_EQ(layout.text_attribute("scene_model"), "block");
  const auto record = *layout.find_dimension("record");
  const auto alpha = *layout.find_dimension("slenderness_rad");
  const auto p = *layout.find_dimension("frequency_parameter_rad_s");
  const auto statuses = expect_each_case_is_pcrf_run(cube, [&](const std::vector<std::size_t>& c) {
    return " run --model block --restitution 0.9 --synthetic '" + layout.find_coordinate("record")->label(c[record]) +
           "' --slenderness-rad " + layout.find_coordinate("slenderness_rad")->label(c[alpha]) +
           " --frequency-parameter-rad-s " + layout.find_coordinate("frequency_parameter_rad_s")->label(c[p]);
  });
  EXPECT_GE(statuses.size(), 2u) << "every case ended alike: the test sees too little";
}

TEST(StudyCommand, AListOfScenesGivesWhatPcrfRunGivesForEachCase) {
  // The basic frame, a block and a rocking frame in one study (the list plan's `model`): each
  // case equals `pcrf run --model …` bit for bit, and each frame's uplift threshold is its own.
  const auto dir = test::scratch_dir("study_scenes");
  const std::string text =
      "[plan]\nkind = \"list\"\n"
      "[[cases]]\nlabel = \"frame\"\n"
      "[[cases]]\nlabel = \"block\"\nmodel = \"block\"\nslenderness_rad = 0.2\nfrequency_parameter_rad_s = 2.12\n"
      "[[cases]]\nlabel = \"portal\"\nmodel = \"rocking-frame\"\nslenderness_rad = 0.2\nbeam_mass_ratio = 0.5\n"
      "[[records]]\npulse = [\"pulse-sine\", \"ricker\"]\n"
      "[axes]\npulse_period_s = [0.5, 1.5]\npulse_amplitude_g = [0.5, 1.5]\n";  // every metric, as pcrf run
  const auto r = run_study(dir, "scenes.toml", text, "-o cube.h5 --progress-interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "cube.h5");
  const auto& layout = cube.layout();
  EXPECT_EQ(layout.text_attribute("scene_model"), "") << "the cases' models are a coordinate, not one attribute";
  const auto* models = layout.find_coordinate("scene_model");
  ASSERT_NE(models, nullptr);
  EXPECT_EQ(models->strings, (std::vector<std::string>{"pcrf", "block", "rocking-frame"}));
  const std::vector<std::string> flags{"", " --model block --slenderness-rad 0.2 --frequency-parameter-rad-s 2.12",
                                       " --model rocking-frame --slenderness-rad 0.2 --beam-mass-ratio 0.5"};
  const auto threshold = cube.read_side("frame_uplift_threshold_g");
  ASSERT_EQ(threshold.size(), flags.size());
  for (std::size_t f = 0; f < flags.size(); ++f) {
    const auto properties = parse_flat_json(test::run_command(pcrf() + " frame --json" + flags[f]).out);
    EXPECT_EQ(std::strtod(properties.at("uplift_threshold_g").c_str(), nullptr), threshold[f]) << flags[f];
  }
  EXPECT_NEAR(threshold[1], std::tan(0.2), 1e-12) << "the block uplifts at g tan alpha";
  const auto record = *layout.find_dimension("record");
  const auto frame = *layout.find_dimension("case");
  const auto statuses = expect_each_case_is_pcrf_run(cube, [&](const std::vector<std::size_t>& c) {
    return " run --synthetic '" + layout.find_coordinate("record")->label(c[record]) + "'" + flags[c[frame]];
  });
  EXPECT_GE(statuses.size(), 2u) << "every case ended alike: the test sees too little";
}

TEST(StudyCommand, OneTwoAndThreeRanksGiveTheSameCube) {
  PCRF_REQUIRE_MPIRUN();
  const auto dir = test::scratch_dir("study_ranks");
  const std::string text = small_grid_study("[run]\nbatch_size = 2\n");  // many hand-outs
  for (int ranks : {1, 2, 3}) {
    const auto r = run_study(dir, "small.toml", text, "-o cube" + std::to_string(ranks) + ".h5 --progress-interval 0",
                             mpirun(ranks));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  expect_same_cube(dir / "cube1.h5", dir / "cube2.h5");
  expect_same_cube(dir / "cube1.h5", dir / "cube3.h5");
}

TEST(StudyCommand, LockstepLanesGiveTheCubeOfOneCaseAtATime) {
  // [run] lanes (default 8): the cases of one record and scale go to a worker together and
  // are integrated in lockstep lanes (docs/batches.md); the cube stays the same bit for bit.
  const auto dir = test::scratch_dir("study_lanes");
  for (const char* lanes : {"1", "8", "3"}) {
    const auto r = run_study(dir, "small.toml", small_grid_study(std::string("[run]\nlanes = ") + lanes + "\n"),
                             "-o cube" + std::string(lanes) + ".h5 --progress-interval 0");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  expect_same_cube(dir / "cube1.h5", dir / "cube8.h5");
  expect_same_cube(dir / "cube1.h5", dir / "cube3.h5");
}

TEST(StudyCommand, FailingCasesAreRecordedAndTheStudyGoesOn) {
  const auto dir = test::scratch_dir("study_failures");
  // Too few steps for a rocking frame: the cases that lift off fail, the others do not.
  const std::string text = std::string("[[records]]\nsynthetic = \"") + kPulse +
                           "\"\n[axes]\nscale = [0.5, 1.0]\n[solver]\nmax_steps = 20\n";
  const auto r = run_study(dir, "fail.toml", text, "-o cube.h5 --progress-interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("1 failed"), std::string::npos) << r.err;
  cube::CubeReader cube(dir / "cube.h5");
  EXPECT_EQ(cube.read_status(), (std::vector<std::int8_t>{0, 4}));  // at_rest, solver_failure
  ASSERT_EQ(cube.read_notes().size(), 1u);
  EXPECT_EQ(cube.read_notes()[0].first, 1);
  EXPECT_FALSE(cube.read_notes()[0].second.empty());
}

/// A record in cm/s² read as g (PGA 490 g): the run and --check warn naming the file and the
/// likely units; with [run] warnings_as_errors the study stops with exit code 2 and writes no cube.
TEST(StudyCommand, ARecordInTheWrongUnitsWarnsOrStopsTheStudy) {
  const auto dir = test::scratch_dir("study_wrong_units");
  std::ostringstream rows;
  for (int i = 0; i <= 1000; ++i) rows << 0.01 * i << ' ' << 490.0 * std::sin(2.0 * 3.141592653589793 * 0.01 * i) << '\n';
  test::write_file(dir, "cm.txt", rows.str());
  const std::string study = "[[records]]\nfile = \"cm.txt\"\n[axes]\nscale = [0.001]\n";
  const auto warned = run_study(dir, "w.toml", study, "--check");
  EXPECT_EQ(warned.exit_code, 0) << warned.err;
  EXPECT_NE(warned.err.find("cm.txt"), std::string::npos) << warned.err;
  EXPECT_NE(warned.err.find("cm/s2"), std::string::npos) << warned.err;

  const auto stopped = run_study(dir, "e.toml", study + "[run]\nwarnings_as_errors = true\n", "-o e.h5");
  EXPECT_EQ(stopped.exit_code, 2) << stopped.err;
  EXPECT_EQ(std::count(stopped.err.begin(), stopped.err.end(), '\n'), 1) << stopped.err;
  EXPECT_NE(stopped.err.find("cm.txt"), std::string::npos) << stopped.err;
  EXPECT_NE(stopped.err.find("warnings_as_errors"), std::string::npos) << stopped.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "e.h5"));
}

TEST(StudyCommand, MoreRanksThanCasesIsFine) {
  PCRF_REQUIRE_MPIRUN();
  const auto dir = test::scratch_dir("study_few_cases");
  const std::string text = std::string("[[records]]\nsynthetic = \"") + kPulse + "\"\n[axes]\nkappa = [1.5, 2.5]\n";
  const auto r = run_study(dir, "two.toml", text, "-o cube.h5 --progress-interval 0", mpirun(3));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto status = cube::CubeReader(dir / "cube.h5").read_status();
  EXPECT_EQ(std::count(status.begin(), status.end(), cube::kStatusNotRun), 0);
}

TEST(StudyCommand, KilledRunResumesToTheUninterruptedCube) {
  PCRF_REQUIRE_MPIRUN();
  const auto dir = test::scratch_dir("study_kill_resume");
  // 4 records × 3 scales × 9 κ × 9 tan α = 972 cases of a few ms each (~2 s on 2 ranks).
  const std::string text = std::string("[[records]]\nsynthetic = [\"") + kPulse + "\", \"" + kPulse2 + "\", \"" + kNoise +
                           "\", \"stochastic:seed=5,pga_g=1.3,duration_s=8\"]\n"
                           "[axes]\nscale = [0.9, 1.1, 1.3]\nkappa = {from = 1.0, to = 3.0, count = 15}\n"
                           "tan_alpha = {from = 0.16, to = 0.24, count = 15}\n";
  const auto study = test::write_file(dir, "kill.toml", text);
  const auto err = dir / "killed.err";
  const LauncherTmp launcher_tmp;  // the killed launcher's session folder goes with it
  const std::string command = "cd " + quoted(dir) + " && exec " + launcher_tmp.env() + mpirun(2) + pcrf() + " study " +
                              quoted(study) + " -o killed.h5 --flush-interval 0.1 --progress-interval 0.1 --batch-size 1 2>" +
                              quoted(err);
  const pid_t pid = spawn_shell(command);
  ASSERT_GT(pid, 0);
  // Kill mpirun once a good part (but not all) of the study is on disk.
  wait_for_a_tenth(err);
  std::this_thread::sleep_for(std::chrono::milliseconds(150));  // past one more flush
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  int wstatus = 0;
  ::waitpid(pid, &wstatus, 0);
  // The ranks die with their launcher (PR_SET_PDEATHSIG); wait until none is left.
  for (int i = 0; i < 100 && test::run_command("pgrep -f '[s]tudy_kill_resume.*killed.h5'").exit_code == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  {
    const auto status = cube::CubeReader(dir / "killed.h5").read_status();
    const auto not_run = std::count(status.begin(), status.end(), cube::kStatusNotRun);
    EXPECT_GT(not_run, 0) << "the study finished before it was killed: make it longer";
    EXPECT_LT(not_run, static_cast<long>(status.size())) << "nothing was flushed before the kill";
  }
  const auto resumed = test::run_command("cd " + quoted(dir) + " && " + mpirun(2) + pcrf() + " study " + quoted(study) +
                                         " -o killed.h5 --resume --progress-interval 0");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("already done"), std::string::npos) << resumed.err;
  const auto whole = test::run_command("cd " + quoted(dir) + " && " + mpirun(2) + pcrf() + " study " + quoted(study) +
                                       " -o whole.h5 --progress-interval 0");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  expect_same_cube(dir / "whole.h5", dir / "killed.h5");
}

TEST(StudyCommand, ASignalToMpirunKeepsTheComputedCases) {
  PCRF_REQUIRE_MPIRUN();
  // Open MPI forwards SIGINT and SIGTERM to the ranks as SIGTERM and SIGKILLs them about a
  // second later (odls_base_sigkill_timeout). Batches of 4000 cases (~1.5 s each with the
  // purpose-built integrator) outlast that: the ranks must report the cases done and rank 0
  // write them at once.
  const auto dir = test::scratch_dir("study_mpirun_signal");
  const auto study = test::write_file(dir, "sig.toml",
                                      "[[records]]\nsynthetic = [\"stochastic:seed=4,pga_g=1.4,duration_s=60\", "
                                      "\"stochastic:seed=5,pga_g=1.2,duration_s=60\"]\n[axes]\nscale = [0.9, 1.1, 1.3]\n"
                                      "kappa = {from = 1.0, to = 3.0, count = 300}\ntan_alpha = {from = 0.16, to = 0.24, count = 10}\n");
  const auto err = dir / "sig.err";
  for (const int signal : {SIGINT, SIGTERM}) {
    std::filesystem::remove(dir / "sig.h5");
    const pid_t pid = spawn_shell("cd " + quoted(dir) + " && exec " + mpirun(2) + pcrf() + " study " + quoted(study) +
                                  " -o sig.h5 --flush-interval-s 1000 --batch-size 4000 --progress-interval-s 0.05 2>" +
                                  quoted(err));
    ASSERT_GT(pid, 0);
    wait_for_a_tenth(err);  // the first batch is back (4000 of 18000)
    ASSERT_EQ(::kill(pid, signal), 0);
    ::waitpid(pid, nullptr, 0);
    const long reported = last_progress(err).first;  // cases rank 0 had received when it last said
    ASSERT_TRUE(std::filesystem::exists(dir / "sig.h5"));
    const auto status = cube::CubeReader(dir / "sig.h5").read_status();
    const long saved = static_cast<long>(std::count_if(status.begin(), status.end(), [](std::int8_t s) { return s != cube::kStatusNotRun; }));
    EXPECT_GE(saved, reported) << "signal " << signal << ": cases computed were lost";
    EXPECT_GT(saved, 0);
    EXPECT_LT(saved, 18000) << "the study finished before the signal: make it longer";
  }
}

struct BadStudy {
  std::string name;
  std::string text;
  std::string message;
};

std::vector<BadStudy> bad_study_corpus(const std::filesystem::path& dir) {
  test::write_file(dir, "garbage.AT2", "not\na\nPEER\nfile at all\n1 2 3\n");
  test::write_file(dir, "dt.AT2", "PEER\nX\nACCELERATION IN UNITS OF G\nNPTS=  3, DT= 1e300 SEC\n0.1 0.2 0.1\n");
  const std::string pulse = std::string("[[records]]\nsynthetic = \"") + kPulse + "\"\n";
  return {
      {"unknown_key.toml", pulse + "[axes]\nkapa = [1, 2]\n", "unknown_key.toml:4: [axes] kapa: unknown key (did you mean 'kappa'?)"},
      {"unknown_table.toml", pulse + "[solvr]\nrtol = 1e-6\n", "unknown_table.toml:3: solvr: unknown key (did you mean 'solver'?)"},
      {"wrong_type.toml", pulse + "[physics]\ntail_s = \"long\"\n", "wrong_type.toml:4: [physics] tail_s: unknown value \"long\" (expected number ≥ 0 [s] or \"until-rest\")"},
      {"empty_list.toml", pulse + "[axes]\nscale = []\n", "empty_list.toml:4: [axes] scale: empty list"},
      {"backwards.toml", pulse + "[axes]\nlambda = { from = 3, to = 2, count = 4 }\n", "[axes] lambda.to: the range runs backwards"},
      {"zero_count.toml", pulse + "[axes]\nlambda = { from = 2, to = 3, count = 0 }\n", "[axes] lambda.count: must be at least 1 (got 0)"},
      {"negative.toml", pulse + "[axes]\nkappa = [-1.0, 2.0]\n", "negative.toml:4: [axes] kappa: value -1 must be positive"},
      {"missing_record.toml", "[[records]]\nfile = \"records/ER99.AT2\"\n", "missing_record.toml:2: [[records]] #1 file: file not found:"},
      {"no_match.toml", "[[records]]\nfiles = [\"records/*.AT2\"]\n", "no_match.toml:2: [[records]] #1 files: no file matches"},
      {"unreadable_record.toml", "[[records]]\nfile = \"garbage.AT2\"\n",
       "unreadable_record.toml:2: [[records]] #1 file: cannot load record \"garbage\""},
      {"bad_synthetic.toml", "[[records]]\nsynthetic = \"square:amplitude_g=1\"\n",
       "bad_synthetic.toml:2: [[records]] #1 synthetic: cannot load record \"square:amplitude_g=1\""},
      {"history.toml", pulse + "[axes]\nkappa = [1, 2]\n[[outputs.histories]]\nlabel = \"h\"\nkappa = 3\n",
       "history.toml:6: [[outputs.histories]] #1 label: history \"h\": kappa 3 is not on the kappa axis"},
      {"not_toml.toml", pulse + "[axes\n", "not_toml.toml:3: not valid TOML"},
      {"theta0.toml", pulse + "[physics]\ntheta0_rad = 100\n",
       "theta0.toml:4: [physics] theta0_rad: |θ₀| = 100 rad is not below this frame's overturning angle"},
      {"folder_record.toml", "[[records]]\nfile = \".\"\n", "folder_record.toml:2: [[records]] #1 file: not a regular file"},
      {"absurd_dt.toml", "[[records]]\nfile = \"dt.AT2\"\n", "dt.AT2:4: sample interval 1e+300 s is outside"},
      {"negative_flush.toml", pulse + "[run]\nflush_interval_s = -1\n",
       "negative_flush.toml:4: [run] flush_interval_s: must be positive (got -1)"},
  };
}

TEST(StudyCommand, BadStudiesFailWithTheirMessageExitCode2AndNoOutput) {
  const auto dir = test::scratch_dir("study_bad");
  for (const auto& bad : bad_study_corpus(dir)) {
    const auto r = run_study(dir, bad.name, bad.text, "-o out.h5");
    EXPECT_EQ(r.exit_code, 2) << bad.name << ": " << r.err;
    EXPECT_EQ(r.err.rfind("pcrf: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
    EXPECT_NE(r.err.find(bad.message), std::string::npos) << bad.name << "\ngot: " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.h5")) << bad.name;
  }
  const auto missing = test::run_command(pcrf() + " study " + quoted(dir / "nowhere.toml"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nowhere.toml: no such study file"), std::string::npos) << missing.err;
  const auto folder = test::run_command(pcrf() + " study " + quoted(dir));
  EXPECT_EQ(folder.exit_code, 2);
  EXPECT_NE(folder.err.find(": not a regular file"), std::string::npos) << folder.err;
  for (const char* flag : {"--flush-interval -1", "--progress-interval-s -1", "--batch-size -3", "--flush-interval nan"}) {
    const auto bad_flag = run_study(dir, "ok.toml", std::string("[[records]]\nsynthetic = \"") + kPulse + "\"\n",
                                    std::string("-o out.h5 ") + flag);
    EXPECT_EQ(bad_flag.exit_code, 2) << flag << ": " << bad_flag.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.h5")) << flag;
  }
}

TEST(StudyCommand, InvalidFramesBecomeCasesAndTheStudyGoesOn) {
  // λ = 0.1 < tan α: the columns overlap; λ_h = 0.7 at tan α = 0.8: r < 0. Neither aborts.
  const auto dir = test::scratch_dir("study_invalid_frames");
  const std::string text = std::string("[[records]]\nsynthetic = \"") + kPulse + "\"\n[axes]\nscale = [1, 2]\n"
                           "lambda = [0.1, 2.0]\ntan_alpha = [0.2, 0.8]\nlambda_h = [0.2, 0.7]\n";
  const auto check = run_study(dir, "invalid.toml", text, "--check");
  ASSERT_EQ(check.exit_code, 0) << check.err;
  // λ = 0.1 fails with both tan α (4 frames), λ = 2 with tan α = 0.8, λ_h = 0.7 (1 frame): × 2 scales.
  EXPECT_NE(check.out.find("10 cases (5 frames) lie outside the model's domain"), std::string::npos) << check.out;
  const auto r = run_study(dir, "invalid.toml", text, "-o invalid.h5 --progress-interval 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "invalid.h5");
  const auto status = cube.read_status();
  EXPECT_EQ(std::count(status.begin(), status.end(), 6), 10);  // invalid_frame
  EXPECT_EQ(std::count(status.begin(), status.end(), cube::kStatusNotRun), 0);
  bool named = false;
  for (const auto& [index, note] : cube.read_notes()) named = named || note.find("coefficient of restitution") != std::string::npos;
  EXPECT_TRUE(named);
  const auto single = test::run_command(pcrf() + " run --synthetic '" + kPulse + "' --lambda 2 --tan-alpha 0.8 --lambda-h 0.7");
  EXPECT_EQ(single.exit_code, 2);  // a single run keeps its error
  EXPECT_NE(single.err.find("coefficient of restitution"), std::string::npos) << single.err;
}

TEST(StudyCommand, ARunBuildsNoFrameUpFrontUnlessItsInputNeedsIt) {
  // A run leaves the frames to the workers (each built once, by the case that needs it);
  // --check builds every frame to count the invalid ones; a displaced start checks every
  // frame's overturning angle before the run, an input error.
  const std::string text = std::string("[[records]]\nsynthetic = \"") + kPulse + "\"\n[axes]\nscale = [1, 2]\n"
                           "lambda = [0.1, 2.0]\ntan_alpha = [0.2, 0.8]\nlambda_h = [0.2, 0.7]\n";
  const study::Study plain = study::parse_study(text, "invalid.toml", ".");
  const study::CaseSpace space(plain);
  study::RecordCache records(plain.records);
  const auto run = study::check_study(plain, space, records, study::FrameCheck::kWhereNeeded);
  EXPECT_FALSE(run.frames_checked);
  EXPECT_EQ(run.invalid_frames, 0);
  const auto every = study::check_study(plain, space, records, study::FrameCheck::kEveryFrame);
  EXPECT_TRUE(every.frames_checked);
  EXPECT_EQ(every.invalid_frames, 5);
  EXPECT_EQ(every.invalid_cases, 10);
  EXPECT_EQ(every.fingerprint, run.fingerprint);
  const study::Study displaced = study::parse_study(text + "[physics]\ntheta0_rad = 1.5\n", "displaced.toml", ".");
  const study::CaseSpace displaced_space(displaced);
  study::RecordCache displaced_records(displaced.records);
  try {
    (void)study::check_study(displaced, displaced_space, displaced_records, study::FrameCheck::kWhereNeeded);
    ADD_FAILURE() << "a start beyond the overturning angle passed the check of a run";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("displaced.toml:9: [physics] theta0_rad:"), std::string::npos) << e.what();
  }
}

TEST(StudyCommand, AnOutputIsNeverOneOfTheInputs) {
  const auto dir = test::scratch_dir("study_output_input");
  const auto record = test::write_file(dir, "rec.AT2", "PEER\nX\nACCELERATION IN UNITS OF G\nNPTS=  3, DT= .01 SEC\n0.1 0.2 0.1\n");
  const std::string text = "[[records]]\nfile = \"rec.AT2\"\n";
  const auto self = run_study(dir, "self.toml", text, "-o self.toml --overwrite");
  EXPECT_EQ(self.exit_code, 2);
  EXPECT_NE(self.err.find("--output names the study file itself"), std::string::npos) << self.err;
  EXPECT_EQ(test::run_command("head -1 " + quoted(dir / "self.toml")).out, "[[records]]\n");
  const auto rec = run_study(dir, "self.toml", text, "-o ./rec.AT2 --overwrite");
  EXPECT_EQ(rec.exit_code, 2);
  EXPECT_NE(rec.err.find("--output names the record file of \"rec\""), std::string::npos) << rec.err;
  EXPECT_EQ(test::run_command("head -1 " + quoted(record)).out, "PEER\n");
  // A study far beyond the machine's memory is refused at --check, naming the file and line.
  const auto huge = run_study(dir, "huge.toml", std::string("[[records]]\nsynthetic = \"") + kPulse + "\"\n[axes]\n"
                              "scale = {from = 0.1, to = 1, count = 1000}\nkappa = {from = 1, to = 2, count = 1000}\n"
                              "lambda = {from = 1.5, to = 2.5, count = 1000}\ntan_alpha = {from = 0.1, to = 0.2, count = 1000}\n",
                              "--check");
  EXPECT_EQ(huge.exit_code, 2);
  EXPECT_NE(huge.err.find("huge.toml:3: axes: 1e+09 frames and 1e+12 cases need about"), std::string::npos) << huge.err;
}

TEST(StudyCommand, SigtermFlushesAndSaysHowToResume) {
  const auto dir = test::scratch_dir("study_sigterm");
  const std::string text = std::string("[[records]]\nsynthetic = [\"") + kPulse + "\", \"" + kPulse2 + "\", \"" + kNoise +
                           "\"]\n[axes]\nscale = [0.9, 1.1, 1.3]\nkappa = {from = 1.0, to = 3.0, count = 9}\n"
                           "tan_alpha = {from = 0.16, to = 0.24, count = 9}\n";
  const auto study = test::write_file(dir, "sig.toml", text);
  const auto err = dir / "sig.err";
  // A long flush interval: without the signal's flush, the cube would hold nothing.
  const std::string command = "cd " + quoted(dir) + " && exec " + pcrf() + " study " + quoted(study) +
                              " -o sig.h5 --flush-interval-s 1000 --progress-interval-s 0.05 2>" + quoted(err);
  const pid_t pid = spawn_shell(command);
  ASSERT_GT(pid, 0);
  EXPECT_EQ(stop_after_a_tenth(pid, err), 128 + SIGTERM);
  std::ifstream in(err);
  std::stringstream text_err;
  text_err << in.rdbuf();
  const std::regex saved(R"(stopped by SIGTERM: (\d+) of (\d+) cases saved in sig\.h5; continue with: pcrf study .*sig\.toml -o sig\.h5 --resume)");
  std::smatch m;
  const std::string e = text_err.str();
  ASSERT_TRUE(std::regex_search(e, m, saved)) << e;
  const auto status = cube::CubeReader(dir / "sig.h5").read_status();
  EXPECT_EQ(std::count_if(status.begin(), status.end(), [](std::int8_t s) { return s != cube::kStatusNotRun; }),
            std::stol(m[1].str()));
  EXPECT_GT(std::stol(m[1].str()), 0);
  const auto resumed = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study sig.toml -o sig.h5 --resume --progress-interval 0");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  ASSERT_EQ(test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study sig.toml -o whole.h5 --progress-interval 0").exit_code, 0);
  expect_same_cube(dir / "whole.h5", dir / "sig.h5");
}

TEST(StudyCommand, BadStudyUnderMpirunExitsWith2AndReportsOnce) {
  PCRF_REQUIRE_MPIRUN();
  const auto dir = test::scratch_dir("study_bad_mpi");
  const auto r = run_study(dir, "bad.toml", "[[records]]\nsynthetic = \"sine:cycles=2\"\n[axes]\nkapa = 1\n", "-o out.h5",
                           mpirun(2));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const std::string line = "pcrf: error: " + (dir / "bad.toml").string() + ":4: [axes] kapa: unknown key";
  const auto first = r.err.find(line);
  EXPECT_NE(first, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(line, first + 1), std::string::npos) << "reported twice:\n" << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

TEST(StudyCommand, RefusesToOverwriteOrToResumeAnotherStudy) {
  const auto dir = test::scratch_dir("study_protect");
  const std::string text = std::string("[[records]]\nsynthetic = \"") + kPulse + "\"\n[axes]\nkappa = [1.5, 2.5]\n";
  ASSERT_EQ(run_study(dir, "a.toml", text, "-o cube.h5 --progress-interval 0").exit_code, 0);
  const auto again = run_study(dir, "a.toml", text, "-o cube.h5");
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.err.find("cube.h5: already exists; use --resume to continue it or --overwrite to replace it"),
            std::string::npos) << again.err;
  // Comments and layout are not the study: the same study resumes (nothing left to do).
  const auto same = run_study(dir, "a.toml", "# a comment\n" + text, "-o cube.h5 --resume");
  EXPECT_EQ(same.exit_code, 0) << same.err;
  const auto other = run_study(dir, "b.toml", text + "tan_alpha = [0.18]\n", "-o cube.h5 --resume");
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.err.find("cube.h5: was made by a different study"), std::string::npos) << other.err;
  const auto replaced = run_study(dir, "b.toml", text + "tan_alpha = [0.18]\n", "-o cube.h5 --overwrite --progress-interval 0");
  EXPECT_EQ(replaced.exit_code, 0) << replaced.err;
  EXPECT_EQ(cube::CubeReader(dir / "cube.h5").layout().find_coordinate("tan_alpha")->numbers,
            std::vector<double>{0.18});
}

TEST(StudyCommand, ExampleStudiesAreValid) {
  const std::map<std::string, std::string> expected = {{"demo.toml", ": ok, 324 cases"},
                                                       {"extremes.toml", ": ok, 7776 cases"},
                                                       // 75 pulses × (the frame and the block) × 20 runs
                                                       {"rocking_spectrum.toml", ": ok, 3000 cases"}};
  for (const auto& [file, text] : expected) {
    const auto r = test::run_command(pcrf() + " study " + quoted(test::source_dir() / "studies" / file) + " --check");
    EXPECT_EQ(r.exit_code, 0) << file << ": " << r.err;
    EXPECT_NE(r.out.find(text), std::string::npos) << file << ": " << r.out;
  }
}

/// The number of MANIFEST.csv rows whose file lies below `folder` ("ngawest2_ff_youtian95/").
std::size_t manifest_rows_in(const std::filesystem::path& records, const std::string& folder) {
  std::ifstream manifest(records / "MANIFEST.csv");
  std::size_t rows = 0;
  for (std::string line; std::getline(manifest, line);) rows += line.find("," + folder) != std::string::npos;
  return rows;
}

TEST(StudyCommand, PaperStudiesFindTheirRecords) {
  PCRF_REQUIRE_RECORDS(records);
  // The study files name their records relative to themselves: ../../shared/records.
  if (!std::filesystem::is_directory(test::source_dir() / ".." / "shared" / "records"))
    GTEST_SKIP() << "../shared/records not beside the checkout";
  const auto studies = test::source_dir() / "studies";
  // The far-field study reads every NGA-West2 component the records index lists (44 when it
  // was written): 3 frames × 16 runs at most each.
  const std::size_t far_field_components = manifest_rows_in(records, "ngawest2_ff_youtian95/");
  ASSERT_GT(far_field_components, 0u);
  const std::map<std::string, std::string> expected = {
      {"paper_table3.toml", ": ok, 13 cases"},
      {"paper_section7.toml", ": ok, "},
      {"ida.toml", ": ok, "},
      {"fema_p695_ida.toml", ": ok, " + std::to_string(far_field_components * 3 * 16) + " cases"},
      {"sensitivity.toml", ": ok, 33280 cases"},   // 13 records × 256 × (8 + 2) frames
      {"risk.toml", ": ok, " + std::to_string(far_field_components * 2 * 10) + " cases"},
      {"risk_stripes.toml", ": ok, " + std::to_string(far_field_components * 6) + " cases"},  // six return periods
      {"model_uncertainty.toml", ": ok, " + std::to_string(far_field_components * 16 * 10) + " cases"},  // 16 LHS frames
      {"selection_stripes/selection_stripes.toml", ": ok, 40 cases"},  // ten pairs selected per stripe × four stripes
      {"numerics_audit/exact.toml", ": ok, 11 cases"},
      {"numerics_audit/fixed_rk4_h1e-2.toml", ": ok, 11 cases"},
      {"numerics_audit/fixed_rk4_h1e-3.toml", ": ok, 11 cases"},
      {"numerics_audit/fixed_rk4_h1e-4.toml", ": ok, 11 cases"}};
  for (const auto& [file, text] : expected) {
    const auto r = test::run_command(pcrf() + " study " + quoted(studies / file) + " --check");
    EXPECT_EQ(r.exit_code, 0) << file << ": " << r.err;
    EXPECT_NE(r.out.find(text), std::string::npos) << file << ": " << r.out;
  }
}

}  // namespace
TEST(StudyCommand, AnUnusableTmpdirIsNamedBeforeMpiStarts) {
  const auto dir = test::scratch_dir("study_tmpdir");
  test::write_file(dir, "s.toml", small_grid_study());
  test::write_file(dir, "a_file", "");
  for (const std::string tmpdir : {"missing_folder", "a_file"}) {
    const auto r = test::run_command("cd " + quoted(dir) + " && TMPDIR=" + tmpdir + " " + pcrf() + " study s.toml -o x.h5");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("pcrf: error: TMPDIR " + tmpdir + " is not a writable folder (", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("); Open MPI needs one"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "x.h5"));
}

}  // namespace pcrf::study_test
