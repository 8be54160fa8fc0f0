// Every row of a table reaches every front end (docs/developer.md, "What a new thing costs"):
// a station's components, the scenes and their parameters, the [physics] and [solver]
// settings are each a `pcrf run` flag, a Python keyword and a study key, read from the row.
// A row the front ends do not take fails here, whichever front end forgot it.
#include <gtest/gtest.h>

#include <string>

#include "pcrf/excitation/station_record.hpp"
#include "pcrf/model/scene_catalog.hpp"
#include "pcrf/solver/settings.hpp"
#include "pcrf/user_error.hpp"
#include "study/study_test_support.hpp"
#include "support/setting_values.hpp"

namespace pcrf {
namespace {

using study_test::pcrf;
using study_test::quoted;
namespace fs = std::filesystem;

const std::string kSine = "sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=2";

/// Runs `script` in the Python that has the module; nullopt when it does not import.
std::optional<test::CommandResult> python(const fs::path& dir, const std::string& script) {
  const std::string run = "cd " + quoted(dir) + " && PYTHONPATH=" + quoted(test::pcrf_executable().parent_path() / "python") +
                          " '" + PCRF_PYTHON + "' ";
  if (test::run_command(run + "-c 'import pcrf'").exit_code != 0) return std::nullopt;
  test::write_file(dir, "script.py", "import pcrf\n" + script);
  return test::run_command(run + "script.py");
}

test::CommandResult check_study(const fs::path& dir, const std::string& text) {
  test::write_file(dir, "s.toml", "[study]\nname = \"s\"\n" + text + "[axes]\nscale = [1]\n");
  return test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study s.toml --check");
}

/// The fingerprint `pcrf study --check` prints.
std::string fingerprint(const std::string& out) {
  const auto at = out.find("fingerprint ");
  return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
}

/// A few samples of acceleration in m/s², as a two-column file.
void write_motion(const fs::path& dir, const std::string& name, int period) {
  std::string text;
  for (int i = 0; i < 50; ++i) text += std::to_string(0.01 * i) + " " + std::to_string(0.3 * (i % period - 3)) + "\n";
  test::write_file(dir, name, text);
}

// Each component's file is read by every front end: `pcrf run` names a missing one, `pcrf
// record` and Python report its measures under the row's key, a study's fingerprint follows it.
TEST(FrontEnds, EveryStationComponentIsAFlagAKeywordAndAStudyKey) {
  const auto dir = test::scratch_dir("front_ends_components");
  write_motion(dir, "h1.txt", 7);
  write_motion(dir, "c.txt", 7);
  write_motion(dir, "c2.txt", 6);
  const std::string azimuths = " --azimuth-deg 0 --h2-azimuth-deg 90";
  std::string script;
  for (const auto& c : kStationComponents) {
    const std::string flag = flag_name(c.keyword), record_flag(c.record_flag), key(c.key);
    const std::string run = pcrf() + " run --units m/s2 --record h1.txt" + azimuths + " " + flag + " ";
    EXPECT_EQ(test::run_command("cd " + quoted(dir) + " && " + run + "c.txt").exit_code, 0) << flag;
    const auto missing = test::run_command("cd " + quoted(dir) + " && " + run + "missing.txt");
    EXPECT_EQ(missing.exit_code, 2) << flag;
    EXPECT_NE(missing.err.find("missing.txt"), std::string::npos) << flag << ": " << missing.err;
    const auto measures = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " record h1.txt --units m/s2" + azimuths +
                                            " " + record_flag + " c.txt");
    ASSERT_EQ(measures.exit_code, 0) << record_flag << ": " << measures.err;
    EXPECT_NE(measures.out.find("\"" + std::string(c.measures_key) + "\": {"), std::string::npos) << measures.out;
    const std::string records = "[[records]]\nh1 = \"h1.txt\"\nunits = \"m/s2\"\naz1_deg = 0\naz2_deg = 90\n" + key + " = ";
    const auto study = check_study(dir, records + "\"c.txt\"\n"), other = check_study(dir, records + "\"c2.txt\"\n");
    EXPECT_EQ(study.exit_code, 0) << key << ": " << study.err;
    EXPECT_NE(fingerprint(study.out), fingerprint(other.out)) << key << ": the study reads its file";
    script += "m = pcrf.record_measures('h1.txt', units='m/s2', azimuth_deg=0, h2_azimuth_deg=90, " +
              std::string(c.keyword) + "='c.txt')\nassert '" + std::string(c.measures_key) + "' in m, m\n" +
              "pcrf.run(a, dt_s=0.01, " + std::string(c.array_keyword) + "=a)\n";
  }
  const auto r = python(dir, "a = [0.03 * (i % 7 - 3) for i in range(50)]\n" + script);
  if (!r) GTEST_SKIP() << "the Python module does not import";
  EXPECT_EQ(r->exit_code, 0) << r->err;
}

// Each parameter of each scene is taken by every front end: a value that is not a number is
// refused naming the parameter, never as an unknown name.
TEST(FrontEnds, EverySceneParameterIsAFlagAKeywordAndAStudyKey) {
  const auto dir = test::scratch_dir("front_ends_scenes");
  std::string script = "def refused(call, key):\n    try:\n        call()\n    except pcrf.InputError as e:\n"
                       "        assert key in str(e) and 'unknown' not in str(e), str(e)\n        return\n"
                       "    raise AssertionError(key + ' taken')\n";
  for (const auto& model : scene_models()) {
    const std::string name(model.name);
    EXPECT_EQ(test::run_command(pcrf() + " run --synthetic '" + kSine + "' --model " + name).exit_code, 0) << name;
    for (const auto& p : model.parameters) {
      const std::string key(p.name), flag = flag_name(p.name);
      const auto cli = test::run_command(pcrf() + " run --synthetic '" + kSine + "' --model " + name + " " + flag + " x");
      EXPECT_EQ(cli.exit_code, 2) << flag;
      EXPECT_NE(cli.err.find("convert: " + flag), std::string::npos) << name << ": " << cli.err;
      const auto study = check_study(dir, "[[records]]\nsynthetic = \"" + kSine + "\"\n[frame]\nmodel = \"" + name + "\"\n" + key +
                                              " = \"x\"\n");
      EXPECT_EQ(study.exit_code, 2) << key;
      EXPECT_NE(study.err.find("[frame] " + key + ": expected a number"), std::string::npos) << name << ": " << study.err;
      script += "refused(lambda: pcrf.Frame(model='" + name + "', **{'" + key + "': 'x'}), '" + key + "')\n";
      script += "refused(lambda: pcrf.run(synthetic='" + kSine + "', model='" + name + "', frame={'" + key + "': 'x'}), 'frame')\n";
    }
  }
  const auto r = python(dir, script);
  if (!r) GTEST_SKIP() << "the Python module does not import";
  EXPECT_EQ(r->exit_code, 0) << r->err;
}

/// `value` as a Python literal.
std::string python_literal(const SettingValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "True" : "False";
  return test::toml_literal(value);
}

// The command line's flags and the study's keys of each setting have their tests
// (RunCommandSettings.Every*KeyIsAFlag, Settings.*Fingerprint*); Python's keywords here.
template <class Target>
std::string python_settings_calls(const SettingTable<Target>& table) {
  std::string script;
  for (const auto& s : table.settings)
    script += "pcrf.run(synthetic='" + kSine + "', **{'" + std::string(s.key) + "': " +
              python_literal(test::other_value(s, s.get(table.defaults))) + "})\n";
  return script;
}

TEST(FrontEnds, EveryPhysicsAndSolverSettingIsAPythonKeyword) {
  const auto dir = test::scratch_dir("front_ends_settings");
  const auto r = python(dir, python_settings_calls(physics_settings()) + python_settings_calls(solver_settings()) +
                                 "print('done')\n");
  if (!r) GTEST_SKIP() << "the Python module does not import";
  EXPECT_EQ(r->exit_code, 0) << r->err;
  EXPECT_EQ(r->out, "done\n");
}

}  // namespace
}  // namespace pcrf
