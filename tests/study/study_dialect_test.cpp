// A study's dialect of key paths (pcrf/user_error.hpp): the table's header, then the key, as
// the TOML file spells them; the same Where in the command line's and Python's dialects.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pcrf/study/study_parser.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {
namespace {

std::string study_text(const std::vector<std::string>& keys) { return key_path_text(keys, Dialect::kStudy); }

TEST(StudyDialect, AKeyOfATableFollowsItsHeader) {
  EXPECT_EQ(study_text({"physics", "tail_s"}), "[physics] tail_s");
  EXPECT_EQ(study_text({"intensity", "hazard"}), "[intensity] hazard");
  EXPECT_EQ(study_text({"plan", "samples"}), "[plan] samples");
  EXPECT_EQ(study_text({"axes", "kappa", "from"}), "[axes] kappa.from");  // a key of an inline table, dotted
  EXPECT_EQ(study_text({"records"}), "records");                          // a key outside any table
  EXPECT_EQ(study_text({}), "");
}

TEST(StudyDialect, AnEntryOfAnArrayOfTablesIsCountedFromOne) {
  EXPECT_EQ(study_text({"records", key_index(1), "file"}), "[[records]] #2 file");
  EXPECT_EQ(study_text({"outputs", "histories", key_index(0), "label"}), "[[outputs.histories]] #1 label");
  EXPECT_EQ(study_text({"cases", key_index(0), "kappa", "from"}), "[[cases]] #1 kappa.from");
  // A value of an inline array (or an entry that is not a table): its key, then its number.
  EXPECT_EQ(study_text({"axes", "pulse_period_s", key_index(3)}), "[axes] pulse_period_s #4");
  EXPECT_EQ(study_text({"records", key_index(2)}), "records #3");
  EXPECT_EQ(study_text({"outputs", "histories", key_index(0)}), "[outputs] histories #1");
}

TEST(StudyDialect, TheOtherFrontEndsSpellTheSamePathTheirWay) {
  const std::vector<std::string> keys{"records", key_index(1), "file"};
  EXPECT_EQ(key_path_text(keys, Dialect::kFlag), "--file");
  EXPECT_EQ(key_path_text(keys, Dialect::kKeyword), "records[1]['file']");
  EXPECT_EQ(key_path_text({"tail_s"}, Dialect::kKeyword), "tail_s=");
  EXPECT_EQ(last_key_name({"axes", "pulse_period_s", key_index(3)}), "pulse_period_s");
}

TEST(StudyDialect, AnErrorReadFromAFileNamesItsLineAndKeyAsTheFileDoes) {
  const UserError e(Where{{"physics", "tail_s"}, "s.toml", 4}, "must be positive (got -1)");
  EXPECT_STREQ(e.what(), "s.toml:4: [physics] tail_s: must be positive (got -1)");
  for (auto dialect : {Dialect::kStudy, Dialect::kFlag, Dialect::kKeyword})
    EXPECT_EQ(e.message(dialect), e.what());
  const UserError flagless("tail_s", "must be positive");
  EXPECT_EQ(flagless.message(Dialect::kFlag), "--tail-s: must be positive");
  EXPECT_EQ(flagless.message(Dialect::kKeyword), "tail_s=: must be positive");
  const UserError warning(Where{{"axes", "incidence_deg"}, "s.toml", 5}, "{} is in degrees", {"incidence_deg"});
  EXPECT_STREQ(warning.followed_by(" ([run] warnings_as_errors)").what(),
               "s.toml:5: [axes] incidence_deg: incidence_deg is in degrees ([run] warnings_as_errors)");
  // A layer that adds what it alone knows keeps the keys a problem names, for each front end.
  const UserError framed = UserError(Where{}, "give {}", {"mu_t"}).preceded_by("frame 3: ");
  EXPECT_EQ(framed.message(Dialect::kFlag), "frame 3: give --mu-t");
  EXPECT_EQ(framed.message(Dialect::kKeyword), "frame 3: give mu_t=");
}

TEST(StudyDialect, TheParserSaysWhichEntryOfAnArrayOfTables) {
  const std::string text =
      "[[records]]\nsynthetic = \"sine:amplitude_g=0.5,period_s=0.5\"\n"
      "[[records]]\nsynthetic = \"sine:amplitude_g=0.4,period_s=0.5\"\nunits = \"g\"\n";
  try {
    (void)study::parse_study(text, "s.toml", ".");
    FAIL() << "a synthetic record with units was accepted";
  } catch (const UserError& e) {
    EXPECT_EQ(e.message(Dialect::kFlag), "s.toml:5: [[records]] #2 units: only applies to record files");
    EXPECT_EQ((e.where().keys), (std::vector<std::string>{"records", key_index(1), "units"}));
    EXPECT_EQ(e.where().line, 5);
  }
}

}  // namespace
}  // namespace pcrf
