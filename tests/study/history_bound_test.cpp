// A study's [[outputs.histories]] dt_s is bounded as `pcrf run --history-dt-s` is (issue 41,
// item 2): more than kMaxHistoryRows rows over the case's record and tail is refused by
// --check and by the run, before any case, naming the history; the bound's interval runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "pcrf/solver/history.hpp"
#include "study/study_test_support.hpp"

namespace pcrf {
namespace {

namespace fs = std::filesystem;
using study_test::pcrf;
using study_test::quoted;

std::string study_with_history(const std::string& dt_s) {
  return "[[records]]\nsynthetic = \"sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=2\"\n[axes]\nscale = [1.0]\n"
         "[physics]\ntail_s = 0.5\n[outputs]\n[[outputs.histories]]\nlabel = \"one\"\nscale = 1.0\ndt_s = " + dt_s + "\n";
}

TEST(HistoryBound, AStudysHistoryIntervalBeyondTheBoundIsRefusedUpFront) {
  const auto dir = test::scratch_dir("history_bound");
  test::write_file(dir, "fine.toml", study_with_history("1e-12"));
  for (const std::string how : {"--check", "-o fine.h5"}) {
    const auto r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study fine.toml " + how);
    EXPECT_EQ(r.exit_code, 2) << how << "\n" << r.err;
    EXPECT_NE(r.err.find("fine.toml:9: [[outputs.histories]] #1 label: history \"one\": dt_s: 2.5 s of case (record and tail) "
                         "at 1e-12 s give 2.5e+12 rows, more than 1e+07"),
              std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "fine.h5"));
  test::write_file(dir, "ok.toml", study_with_history("0.001"));
  const auto ok = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study ok.toml -o ok.h5");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

}  // namespace
}  // namespace pcrf
