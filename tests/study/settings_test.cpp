// The setting descriptions drive the study file: every key changes the fingerprint (or, for
// [run], does not), every key becomes a cube attribute, and the README's key tables are the
// ones `pcrf settings` renders from the descriptions.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "pcrf/study/case_space.hpp"
#include "pcrf/study/fingerprint.hpp"
#include "pcrf/study/settings_doc.hpp"
#include "pcrf/run/study_cube.hpp"
#include "pcrf/study/study_parser.hpp"
#include "support/setting_values.hpp"
#include "support/test_support.hpp"

namespace pcrf::study {
namespace {

const std::string kRecords = "[[records]]\nsynthetic = \"sine:amplitude_g=1.5\"\n";

std::string fingerprint_of(const std::string& text) {
  const Study s = parse_study(text, "t.toml", test::source_dir());
  const CaseSpace space(s);
  RecordCache records(s.records);
  return study_fingerprint(s, space, records);
}

/// Sets each key of `table` in turn to another valid value; the fingerprint must change
/// exactly for the keys that change results.
template <class Target>
void expect_fingerprint_follows(const SettingTable<Target>& table) {
  const std::string base = fingerprint_of(kRecords);
  for (const auto& s : table.settings) {
    const auto value = test::other_value(s, s.get(table.defaults));
    const std::string text = kRecords + "[" + std::string(table.name) + "]\n" + std::string(s.key) + " = " +
                             test::toml_literal(value) + "\n";
    const bool changes_results = s.in_fingerprint || s.key == "preset";  // a preset changes the values it sets
    if (changes_results)
      EXPECT_NE(fingerprint_of(text), base) << table.name << "." << s.key;
    else
      EXPECT_EQ(fingerprint_of(text), base) << table.name << "." << s.key;
  }
}

TEST(Settings, EveryPhysicsAndSolverKeyChangesTheFingerprint) {
  expect_fingerprint_follows(physics_settings());
  expect_fingerprint_follows(solver_settings());
}

TEST(Settings, RunKeysStayOutOfTheFingerprint) {
  for (const auto& s : run_settings().settings) EXPECT_FALSE(s.in_fingerprint) << s.key;
  expect_fingerprint_follows(run_settings());
}

TEST(Settings, EveryPhysicsAndSolverKeyIsACubeAttribute) {
  const Study s = parse_study(kRecords, "t.toml", test::source_dir());
  const CaseSpace space(s);
  RecordCache records(s.records);
  const auto layout = run::make_cube_layout(s, space, records, "f");
  auto has = [&](const std::string& name) {
    for (const auto& a : layout.attributes)
      if (a.name == name) return true;
    return false;
  };
  for (const auto& k : physics_settings().settings) EXPECT_TRUE(has("physics_" + std::string(k.key))) << k.key;
  for (const auto& k : solver_settings().settings) EXPECT_TRUE(has("solver_" + std::string(k.key))) << k.key;
  EXPECT_EQ(layout.text_attribute("solver_preset"), "balanced");
}

TEST(Settings, BadValuesNameTheKey) {
  for (const auto& s : solver_settings().settings) {
    const auto bad = test::out_of_bound_text(s);
    if (!bad) continue;
    const std::string literal = s.type == SettingType::kNumber || s.type == SettingType::kInteger ? *bad : "\"" + *bad + "\"";
    try {
      parse_study(kRecords + "[solver]\n" + std::string(s.key) + " = " + literal + "\n", "t.toml", test::source_dir());
      ADD_FAILURE() << s.key << " = " << literal << " was accepted";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find("t.toml:4: [solver] " + std::string(s.key) + ":"), std::string::npos) << e.what();
    }
  }
}

TEST(Settings, ReadmeKeyTablesAreTheRenderedDescriptions) {
  std::ifstream in(test::source_dir() / "studies" / "README.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string readme = text.str();
  const std::string rendered = all_settings_markdown();
  const std::regex block(R"(<!-- settings:(\w+) -->\n[\s\S]*?<!-- /settings -->\n)");
  int found = 0;
  for (auto it = std::sregex_iterator(rendered.begin(), rendered.end(), block); it != std::sregex_iterator(); ++it) {
    ++found;
    EXPECT_NE(readme.find(it->str()), std::string::npos)
        << "studies/README.md: the [" << (*it)[1] << "] table differs from `pcrf settings`; paste its output:\n"
        << it->str();
  }
  EXPECT_EQ(found, 5);
}

}  // namespace
}  // namespace pcrf::study
