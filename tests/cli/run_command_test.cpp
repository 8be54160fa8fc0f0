// `pcrf run` end to end: JSON on stdout, the history CSV, one-line errors with exit 2.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/solver/history.hpp"
#include "pcrf/solver/settings.hpp"
#include "support/setting_values.hpp"
#include "support/test_support.hpp"

namespace pcrf {
namespace {

std::string pcrf() { return test::pcrf_executable().string(); }

TEST(RunCommand, PrintsOneJsonObjectWithTheResultKeys) {
  const auto r = test::run_command(pcrf() + " run --synthetic 'sine:amplitude_g=1.5,period_s=0.5,cycles=2'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.front(), '{');
  EXPECT_EQ(r.out.find('\n'), r.out.size() - 1);  // one line
  for (const char* key : {"lambda_g", "uplift_threshold_g", "restitution", "t_trigger_paper_s", "t_uplift_s",
                          "theta_max_rad", "t_theta_max_s", "omega_max_rad_s", "t_omega_max_s",
                          "strain_column_max", "strain_beam_max", "impacts", "status", "steps", "rhs_evals",
                          "root_evals", "cpu_time_s"}) {
    EXPECT_NE(r.out.find("\"" + std::string(key) + "\":"), std::string::npos) << key;
  }
  EXPECT_NE(r.out.find("\"status\": \"at_rest\""), std::string::npos) << r.out;
}

TEST(RunCommand, AFrameStillRockingAtItsEndIsNotedOnStderrWithTheSettingThatHelps) {
  // Issue 29: `pcrf run --tail-s 0` reported rocking_at_end and said nothing. The note names
  // tail_s for a fixed tail and max_tail_s for an until-rest one; a case at rest says nothing.
  const std::string base = pcrf() + " run --synthetic 'sine:amplitude_g=1.2,period_s=0.8,cycles=3,duration_s=2.4'";
  const auto fixed = test::run_command(base + " --tail-s 0");
  ASSERT_EQ(fixed.exit_code, 0) << fixed.err;
  ASSERT_NE(fixed.out.find("\"status\": \"rocking_at_end\""), std::string::npos) << fixed.out;
  EXPECT_NE(fixed.err.find("rocking_at_end"), std::string::npos) << fixed.err;
  EXPECT_NE(fixed.err.find("a longer physics.tail_s"), std::string::npos) << fixed.err;
  EXPECT_EQ(fixed.err.find('\n'), fixed.err.size() - 1) << fixed.err;  // one line
  const auto capped = test::run_command(base + " --max-tail-s 0.01");
  ASSERT_EQ(capped.exit_code, 0) << capped.err;
  ASSERT_NE(capped.out.find("\"status\": \"rocking_at_end\""), std::string::npos) << capped.out;
  EXPECT_NE(capped.err.find("a longer physics.max_tail_s"), std::string::npos) << capped.err;
  const auto rest = test::run_command(base);
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  ASSERT_NE(rest.out.find("\"status\": \"at_rest\""), std::string::npos) << rest.out;
  EXPECT_EQ(rest.err, "");
}

TEST(RunCommand, FrameParametersChangeTheResult) {
  const std::string base = pcrf() + " run --synthetic 'sine:amplitude_g=1.5,period_s=0.5,cycles=2'";
  const auto a = test::run_command(base);
  const auto b = test::run_command(base + " --kappa 3 --tan-alpha 0.25");
  ASSERT_EQ(a.exit_code, 0);
  ASSERT_EQ(b.exit_code, 0);
  EXPECT_NE(a.out, b.out);
}

TEST(RunCommand, WritesTheHistoryCsvAtTheAskedInterval) {
  const auto dir = test::scratch_dir("run_history");
  const auto csv = dir / "h.csv";
  const std::string base = pcrf() + " run --synthetic 'sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=3' --overwrite --history " +
                           csv.string();
  std::string expected_header;
  for (const auto& c : history_columns()) expected_header += (expected_header.empty() ? "" : ",") + std::string(c.name);
  for (const auto& [flag, minimum_rows] : {std::pair{"", 601}, std::pair{" --history-dt-s 0.001", 3001}}) {
    const auto r = test::run_command(base + flag);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, expected_header);
    int rows = 0;
    double last_t = -1.0;
    for (std::string line; std::getline(in, line); ++rows) {
      const double t = std::stod(line.substr(0, line.find(',')));
      EXPECT_GT(t, last_t) << line;
      last_t = t;
    }
    EXPECT_GE(rows, minimum_rows) << flag;  // every output time (3 s) plus the events
  }
  EXPECT_EQ(test::run_command(base + " --history-dt-s 0").exit_code, 2);
}

TEST(RunCommand, ReadsAPeerRecord) {
  PCRF_REQUIRE_RECORDS(records);
  const std::string record = (records / "paper" / "ER7_CAP000.AT2").string();
  const auto r = test::run_command(pcrf() + " run --record " + record);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"t_trigger_paper_s\": 2.69"), std::string::npos) << r.out;  // Table 3
  EXPECT_NE(r.out.find("\"t_uplift_s\": null"), std::string::npos) << r.out;  // PGA 0.53 g < 1.02 g
  const auto scaled = test::run_command(pcrf() + " run --record " + record + " --scale 2.5");
  ASSERT_EQ(scaled.exit_code, 0) << scaled.err;
  EXPECT_EQ(scaled.out.find("\"t_uplift_s\": null"), std::string::npos) << scaled.out;
}

struct BadArgs {
  std::string args;
  std::string says;  // a fragment of the one-line error
};

class RunCommandErrors : public ::testing::TestWithParam<BadArgs> {};

TEST_P(RunCommandErrors, OneLineAndExitCode2) {
  const auto r = test::run_command(pcrf() + " run " + GetParam().args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find(GetParam().says), std::string::npos) << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Corpus, RunCommandErrors,
    ::testing::Values(BadArgs{"", "--record FILE or --synthetic"},
                      BadArgs{"--record /no/such/file.AT2", "/no/such/file.AT2"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --kappa -1", "kappa"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --lambda-h 1.5", "--lambda-h"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --integrator euler", "euler"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --criterion maybe", "maybe"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --rtol 0", "rtol"},
                      BadArgs{"--synthetic 'quake:x=1'", "quake"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --kappa abc", "kappa"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --no-such-option", "no-such-option"},
                      BadArgs{"--record /tmp", "/tmp: not a regular file"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --theta0-rad 100", "--theta0-rad: |θ₀| = 100 rad"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --history /no/such/dir/h.csv",
                              "/no/such/dir/h.csv: cannot create a file in /no/such/dir: No such file or directory"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --zeno-time-s 0", "--zeno-time-s: must be positive"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --intensity 1 --measure pga_g --period-s 1",
                              "--period-s: pga_g has no oscillator: period_s belongs to sa_g"},
                      BadArgs{"--synthetic 'sine:amplitude_g=1' --intensity 1 --measure sa_g --period-s 0.001",
                              "--period-s: an oscillator period of 0.001 s is below 2·dt"}));

}  // namespace
}  // namespace pcrf

namespace pcrf {
namespace {

const std::string kPulse = " run --synthetic 'sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=2'";

/// Every [physics] and [solver] key of a study file is a `pcrf run` flag named after it,
/// takes a valid value and rejects an invalid one naming the flag.
template <class Target>
void expect_every_key_is_a_flag(const SettingTable<Target>& table) {
  for (const auto& s : table.settings) {
    const std::string flag = flag_name(s.key);
    const std::string value = test::toml_literal(test::other_value(s, s.get(table.defaults)));
    const std::string unquoted = value.front() == '"' ? value.substr(1, value.size() - 2) : value;
    const auto ok = test::run_command(pcrf() + kPulse + " " + flag + "=" + unquoted);
    EXPECT_EQ(ok.exit_code, 0) << flag << "=" << unquoted << ": " << ok.err;
    if (const auto bad = test::out_of_bound_text(s)) {
      const auto r = test::run_command(pcrf() + kPulse + " " + flag + "=" + *bad);
      EXPECT_EQ(r.exit_code, 2) << flag << "=" << *bad;
      EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
    }
  }
}

TEST(RunCommandSettings, EveryPhysicsKeyIsAFlag) { expect_every_key_is_a_flag(physics_settings()); }
TEST(RunCommandSettings, EverySolverKeyIsAFlag) { expect_every_key_is_a_flag(solver_settings()); }

TEST(RunCommandSettings, FlagsTakeEffectAndOlderSpellingsStillWork) {
  auto json_number = [](const std::string& json, const std::string& key) {
    const auto at = json.find("\"" + key + "\": ");
    return at == std::string::npos ? std::nan("") : std::stod(json.substr(at + key.size() + 4));
  };
  const auto base = test::run_command(pcrf() + kPulse + " --tail-s 0");
  const auto tail = test::run_command(pcrf() + kPulse + " --tail-s 1.5");
  const auto tail_old = test::run_command(pcrf() + kPulse + " --tail 1.5");
  ASSERT_EQ(base.exit_code, 0) << base.err;
  EXPECT_DOUBLE_EQ(json_number(tail.out, "t_end_s"), json_number(base.out, "t_end_s") + 1.5);
  EXPECT_EQ(json_number(tail_old.out, "t_end_s"), json_number(tail.out, "t_end_s"));
  // Without stops at the record samples the integrator steps across them: other steps (with
  // dopri5 more of them on this pulse, the error test rejecting steps over the kinks; with
  // ARKODE fewer). Either spelling of the flag takes effect, and the same.
  const auto no_stop = test::run_command(pcrf() + kPulse + " --tail-s 0 --no-stop-at-samples");
  const auto no_stop_eq = test::run_command(pcrf() + kPulse + " --tail-s 0 --stop-at-samples=false");
  EXPECT_NE(json_number(no_stop.out, "steps"), json_number(base.out, "steps"));
  EXPECT_EQ(json_number(no_stop_eq.out, "steps"), json_number(no_stop.out, "steps"));
  // The preset applies before single values, whatever the order on the command line.
  const auto loose = test::run_command(pcrf() + kPulse + " --rtol 1e-3 --preset reference");
  const auto loose_first = test::run_command(pcrf() + kPulse + " --preset reference --rtol 1e-3");
  EXPECT_EQ(json_number(loose.out, "steps"), json_number(loose_first.out, "steps"));
  EXPECT_NE(json_number(loose.out, "steps"), json_number(test::run_command(pcrf() + kPulse + " --preset reference").out, "steps"));
}

}  // namespace
}  // namespace pcrf

namespace pcrf {
namespace {

TEST(RecordCommand, PrintsTheIntensityMeasuresAsJson) {
  const auto dir = test::scratch_dir("record_command");
  const auto file = test::write_file(dir, "RSN9_TEST.AT2",
                                     "PEER NGA STRONG MOTION DATABASE RECORD\nSome Event, 1/2/2000, Some Station, 90\n"
                                     "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   4, DT=   .0100 SEC\n0.1 -0.3 0.2 0.0\n");
  const auto r = test::run_command(pcrf() + " record " + file.string() + " --period 0.5 --period 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"\"npts\": 4", "\"dt_s\": 0.01", "\"duration_s\": 0.03", "\"pga_g\": 0.3", "\"t_pga_s\": 0.01",
                          "\"pgv_m_s\": ", "\"pgd_m\": ", "\"arias_intensity_m_s\": ", "\"significant_duration_s\": ",
                          "\"periods_s\": [0.5, 1]", "\"sa_g\": [", "\"event\": \"Some Event\"", "\"station\": \"Some Station\"",
                          "\"component\": \"90\"", "\"rsn\": \"9\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
  const auto text = test::write_file(dir, "fema.txt", "0 0\n0 0.1\n0.01 0.2\n0.02 -0.4\n");
  const auto skipped = test::run_command(pcrf() + " record " + text.string() + " --skip-rows 1");
  ASSERT_EQ(skipped.exit_code, 0) << skipped.err;
  EXPECT_NE(skipped.out.find("\"t_pga_s\": 0.02"), std::string::npos) << skipped.out;
  EXPECT_NE(skipped.out.find("\"npts\": 3"), std::string::npos) << skipped.out;
  for (const auto& [period, says] : std::vector<std::pair<std::string, std::string>>{
           {"0", "--periods-s: the oscillator period must be above 0 s and at most 100 s, got 0 s"},
           {"inf", "--periods-s: the oscillator period must be above 0 s and at most 100 s, got inf s"},
           {"1e300", "at most 100 s, got 1e+300 s"},
           {"1e-9", "--periods-s: an oscillator period of 1e-09 s is below 2·dt = 0.02 s of the record"}}) {
    const auto bad = test::run_command(pcrf() + " record " + file.string() + " --period " + period);
    EXPECT_EQ(bad.exit_code, 2) << period << "\n" << bad.err;
    EXPECT_NE(bad.err.find(says), std::string::npos) << bad.err;
  }
  const auto huge = test::write_file(dir, "huge.txt", "0 1e300\n0.01 -1e300\n0.02 1e300\n");
  const auto overflow = test::run_command(pcrf() + " record " + huge.string());
  EXPECT_EQ(overflow.exit_code, 2) << overflow.out;
  EXPECT_NE(overflow.err.find("huge: its accelerations (PGA 1e+300 g) overflow the intensity measures"), std::string::npos)
      << overflow.err;
}

}  // namespace
}  // namespace pcrf

namespace pcrf {
namespace {

/// A four-sample AT2 file whose header names its component.
std::filesystem::path at2_component(const std::filesystem::path& dir, const std::string& name,
                                    const std::string& component, const std::string& values) {
  return test::write_file(dir, name,
                          "PEER NGA STRONG MOTION DATABASE RECORD\nSome Event, 1/2/2000, Some Station, " + component +
                              "\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   4, DT=   .0100 SEC\n" + values + "\n");
}

/// The number after `"key": ` in a JSON text.
double json_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\": ");
  EXPECT_NE(at, std::string::npos) << key << " in " << json;
  if (at == std::string::npos || json.compare(at + key.size() + 4, 4, "null") == 0) return NAN;
  return std::stod(json.substr(at + key.size() + 4));
}

TEST(RecordCommand, APairPrintsBothComponentsAndTheirRotD) {
  // All the motion on the 90° component: RotD100 is its PGA, RotD50 its PGA·cos 45°.
  const auto dir = test::scratch_dir("record_pair");
  const auto east = at2_component(dir, "RSN9_E.AT2", "90", "0.1 -0.4 0.2 0.0");
  const auto north = at2_component(dir, "RSN9_N.AT2", "0", "0.0 0.0 0.0 0.0");
  const auto r = test::run_command(pcrf() + " record " + east.string() + " --pair " + north.string() + " --period 0.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"azimuths_deg\": [90, 0]"), std::string::npos) << r.out;
  EXPECT_NEAR(json_number(r.out, "pga_rotd100_g"), 0.4, 1e-12);
  EXPECT_NEAR(json_number(r.out, "pga_rotd50_g"), 0.4 * std::sqrt(0.5), 1e-12);
  EXPECT_NE(r.out.find("\"pair\": {\"name\": \"RSN9_N\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"sa_rotd50_g\": ["), std::string::npos) << r.out;

  // A component whose header states no azimuth needs one given; parallel components are refused.
  const auto longitudinal = at2_component(dir, "RSN9_L.AT2", "CLW-LN", "0.1 0.2 0.3 0.1");
  const auto missing = test::run_command(pcrf() + " record " + longitudinal.string() + " --pair " + north.string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("give --azimuth-deg"), std::string::npos) << missing.err;
  const auto given = test::run_command(pcrf() + " record " + longitudinal.string() + " --pair " + north.string() +
                                       " --azimuth-deg 90");
  EXPECT_EQ(given.exit_code, 0) << given.err;
  const auto parallel = test::run_command(pcrf() + " record " + east.string() + " --pair " + north.string() +
                                          " --h2-azimuth-deg 270");
  EXPECT_EQ(parallel.exit_code, 2);
  EXPECT_NE(parallel.err.find("are parallel"), std::string::npos) << parallel.err;
}

}  // namespace
}  // namespace pcrf

namespace pcrf {
namespace {

TEST(FrameCommand, PrintsThePropertiesAndThePushoverCurve) {
  const auto text = test::run_command(pcrf() + " frame --points 5");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("uplift threshold (prestress included)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("rad (column tendon)"), std::string::npos) << text.out;
  const auto json = test::run_command(pcrf() + " frame --points 3 --json --kappa 2.5");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_EQ(json.out.find('\n'), json.out.size() - 1);
  for (const char* key : {"lambda_g", "uplift_threshold_g", "restitution", "frequency_parameter_rad_s",
                          "fracture_angle_rad", "overturn_angle_rad", "capacity_g", "capacity_theta_rad"})
    EXPECT_FALSE(std::isnan(json_number(json.out, key))) << key;
  EXPECT_NE(json.out.find("\"pushover_theta_rad\": [0, "), std::string::npos) << json.out;
  const auto bad = test::run_command(pcrf() + " frame --points 1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--points: must be at least 2"), std::string::npos) << bad.err;
  const auto impossible = test::run_command(pcrf() + " frame --lambda-h 1.5");
  EXPECT_EQ(impossible.exit_code, 2);
  EXPECT_NE(impossible.err.find("--lambda-h"), std::string::npos) << impossible.err;
}

}  // namespace
}  // namespace pcrf

namespace pcrf {
namespace {

TEST(RunCommand, TakesTheStationsComponentsAndAnIncidence) {
  // h1 along 90°, h2 along 0°, a vertical: at the incidence of h1 without the vertical the
  // result is h1's alone; with a vertical or another incidence it changes.
  const auto dir = test::scratch_dir("run_components");
  const std::string values = "0.0 0.9 1.4 -1.3 0.6 0.2 -0.1 0.0";
  auto at2 = [&](const std::string& name, const std::string& component, const std::string& v) {
    return test::write_file(dir, name,
                            "PEER NGA STRONG MOTION DATABASE RECORD\nSome Event, 1/2/2000, Some Station, " + component +
                                "\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   8, DT=   .0500 SEC\n" + v + "\n");
  };
  const auto h1 = at2("RSN9_E.AT2", "90", values), h2 = at2("RSN9_N.AT2", "0", "0.0 0.3 -0.5 0.8 -0.2 0.1 0.0 0.0");
  const auto up = at2("RSN9_UP.AT2", "UP", "0.0 0.2 -0.4 0.3 0.1 0.0 0.0 0.0");
  const std::string base = pcrf() + " run --scale 1.5 --record " + h1.string();
  const auto alone = test::run_command(base);
  const auto along = test::run_command(base + " --record-h2 " + h2.string() + " --incidence-deg 90");
  const auto turned = test::run_command(base + " --record-h2 " + h2.string() + " --incidence-deg 60");
  const auto shaken = test::run_command(base + " --record-up " + up.string());
  for (const auto* r : {&alone, &along, &turned, &shaken}) ASSERT_EQ(r->exit_code, 0) << r->err;
  ASSERT_GT(json_number(alone.out, "theta_max_rad"), 0.0);
  EXPECT_EQ(json_number(along.out, "theta_max_rad"), json_number(alone.out, "theta_max_rad"));
  EXPECT_NE(json_number(turned.out, "theta_max_rad"), json_number(alone.out, "theta_max_rad"));
  EXPECT_NE(json_number(shaken.out, "theta_max_rad"), json_number(alone.out, "theta_max_rad"));
  // Components that do not fit: a horizontal as the vertical, a vertical as the second
  // horizontal, an incidence without a pair, different sample intervals.
  const auto coarse = test::write_file(dir, "RSN9_C.AT2",
                                       "PEER NGA STRONG MOTION DATABASE RECORD\nSome Event, 1/2/2000, Some Station, 0"
                                       "\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   2, DT=   .0100 SEC\n0 0\n");
  const std::vector<std::pair<std::string, std::string>> bad = {
      {" --record-up " + h2.string(), "names a horizontal component ('0'), given as the vertical"},
      {" --record-h2 " + up.string(), "names a vertical component ('UP'), given as the second horizontal"},
      {" --incidence-deg 30", "has no second component"},
      {" --record-h2 " + coarse.string(), "sampled at different intervals"}};
  for (const auto& [flags, message] : bad) {
    const auto r = test::run_command(base + flags);
    EXPECT_EQ(r.exit_code, 2) << flags;
    EXPECT_NE(r.err.find(message), std::string::npos) << flags << ": " << r.err;
  }
}

}  // namespace
}  // namespace pcrf

namespace pcrf {
namespace {

TEST(RunCommand, SolvesTheCanonicalScenes) {
  const std::string pulse = " --synthetic 'pulse-sine:period_s=0.4,amplitude_g=0.6,duration_s=8'";
  const auto block = test::run_command(pcrf() + " run" + pulse + " --model block --slenderness-rad 0.2 --size-m 1.25");
  ASSERT_EQ(block.exit_code, 0) << block.err;
  EXPECT_NEAR(json_number(block.out, "uplift_threshold_g"), std::tan(0.2), 1e-15);
  EXPECT_NEAR(json_number(block.out, "restitution"), 1.0 - 1.5 * std::pow(std::sin(0.2), 2), 1e-15);
  EXPECT_TRUE(std::isnan(json_number(block.out, "strain_column_max"))) << "a block has no tendons: " << block.out;
  // The rocking frame with γ = 0.5 and R = 1 m is the block of R̂ = 1.25 m with the frame's r.
  const auto frame = test::run_command(pcrf() + " run" + pulse +
                                       " --model rocking-frame --slenderness-rad 0.2 --size-m 1 --beam-mass-ratio 0.5");
  const auto as_block = test::run_command(pcrf() + " run" + pulse + " --model block --slenderness-rad 0.2 --size-m 1.25" +
                                          " --restitution " + std::to_string(json_number(frame.out, "restitution")));
  ASSERT_EQ(frame.exit_code, 0) << frame.err;
  ASSERT_EQ(as_block.exit_code, 0) << as_block.err;
  EXPECT_NEAR(json_number(frame.out, "theta_max_rad"), json_number(as_block.out, "theta_max_rad"),
              1e-5 * json_number(frame.out, "theta_max_rad"));  // r passes through 6 printed digits
  const std::vector<std::pair<std::string, std::string>> bad = {
      // The scene catalogue's messages (the Python module's too), naming the flag given.
      {" --model block --kappa 2", "error: --kappa: does not apply to model \"block\" (it is a parameter of model \"pcrf\")"},
      {" --size-m 2", "error: --size-m: does not apply to model \"pcrf\""},
      {" --model block --slenderness-rad 1.6", "error: --slenderness-rad: must lie between 0 and pi/2"},
      {" --model block --beam-mass-ratio 1", "error: --beam-mass-ratio: does not apply to model \"block\" (it is a parameter of model \"rocking-frame\")"},
      {" --model block --restitution 1.5", "error: --given-restitution: must lie in [0, 1]"},
      {" --model pcrf --restitution 0.9", "error: --given-restitution: does not apply to model \"pcrf\""},
      {" --model cylinder", "unknown scene 'cylinder'"}};
  for (const auto& [flags, message] : bad) {
    const auto r = test::run_command(pcrf() + " run" + pulse + flags);
    EXPECT_EQ(r.exit_code, 2) << flags;
    EXPECT_NE(r.err.find(message), std::string::npos) << flags << ": " << r.err;
  }
}

}  // namespace
}  // namespace pcrf
