// Counts and intervals from input have documented bounds, checked before anything is sized by
// them (issue 41, item 2): pushover points, the history interval, pulse periods that size a
// record from a NaN; and an error about a record names its file (item 9). Each was exit 0
// without bound, or an internal error, before.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/api/frame_input.hpp"
#include "pcrf/solver/history.hpp"
#include "pcrf/user_error.hpp"
#include "support/test_support.hpp"

namespace pcrf {
namespace {

namespace fs = std::filesystem;

std::string pcrf() { return test::pcrf_executable().string(); }

TEST(InputBounds, PushoverPointsAreAWholeNumberWithinTheirBound) {
  const std::string most = std::to_string(api::kMaxPushoverPoints);
  for (const auto& [points, says] : std::vector<std::pair<std::string, std::string>>{
           {"1e9", "--points: must be at most " + most + ", not 1e+09"},
           {"100001", "--points: must be at most " + most + ", not 100001"},
           {"1", "--points: must be at least 2 (and at most " + most + "), not 1"},
           {"2.5", "--points: must be a whole number, not 2.5"}}) {
    const auto r = test::run_command(pcrf() + " frame --points " + points);
    EXPECT_EQ(r.exit_code, 2) << points << "\n" << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << points << "\n" << r.err;
    EXPECT_EQ(r.out, "") << points;
  }
  const auto ok = test::run_command(pcrf() + " frame --points 3 --json");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  // The one check both front ends call.
  EXPECT_EQ(api::pushover_points(api::kMaxPushoverPoints), api::kMaxPushoverPoints);
  EXPECT_THROW(api::pushover_points(1e300), UserError);
  EXPECT_THROW(api::pushover_points(2.0 + 1e-9), UserError);
}

TEST(InputBounds, AHistoryIntervalThatWouldWriteTooManyRowsIsRefusedBeforeAnyRow) {
  const auto dir = test::scratch_dir("input_bounds_history");
  const fs::path out = dir / "h.csv";
  // 3 s of record and 0.5 s of tail at 1e-12 s: 3.5e12 rows (the run filled the disk).
  const auto r = test::run_command(pcrf() + " run --synthetic 'sine:amplitude_g=1.5,period_s=0.5,cycles=2' --tail-s 0.5 "
                                            "--history " + out.string() + " --history-dt-s 1e-12");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--history-dt-s: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("more than 1e+07: give an interval of at least"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(dir)) ADD_FAILURE() << "left behind: " << entry.path();
  // At the bound's interval it runs.
  const auto ok = test::run_command(pcrf() + " run --synthetic 'sine:amplitude_g=1.5,period_s=0.5,cycles=2' --tail-s 0.5 "
                                             "--history " + out.string() + " --history-dt-s 0.001");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_THROW(check_history_interval(60.0, 60.0 / kMaxHistoryRows / 2.0, 0.01), UserError);
  EXPECT_NO_THROW(check_history_interval(60.0, 0.0, 0.01));
  EXPECT_THROW(check_history_interval(60.0, 0.0, 1e-9), UserError);  // the record's own dt counts too
}

TEST(InputBounds, APulseWhosePeriodSizesNoRecordIsRefusedByKey) {
  for (const std::string kind : {"ricker-antisymmetric", "mavroeidis", "ricker", "pulse-sine"}) {
    const auto r = test::run_command(pcrf() + " run --synthetic '" + kind + ":amplitude_g=1,period_s=1e308' --tail-s 0");
    EXPECT_EQ(r.exit_code, 2) << kind << "\n" << r.err;
    EXPECT_NE(r.err.find("period_s"), std::string::npos) << kind << "\n" << r.err;
    EXPECT_NE(r.err.find(kind), std::string::npos) << kind << "\n" << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << kind << "\n" << r.err;
  }
}

TEST(InputBounds, ARecordWhoseValuesOverflowTheMeasuresIsNamedByItsFile) {
  const auto dir = test::scratch_dir("input_bounds_record");
  const auto huge = test::write_file(dir, "huge.txt", "0 1e300\n0.01 -1e300\n0.02 1e300\n");
  for (const std::string command : {" record ", " run --tail-s 0 --record "}) {
    const auto r = test::run_command(pcrf() + command + huge.string());
    EXPECT_EQ(r.exit_code, 2) << command << r.err;
    EXPECT_NE(r.err.find(huge.string() + ": its accelerations (PGA 1e+300 g) overflow"), std::string::npos) << r.err;
  }
}

TEST(InputBounds, ARecordWithAByteOrderMarkReadsAsWithout) {
  const auto dir = test::scratch_dir("input_bounds_bom");
  const std::string text = "0 0.1\n0.01 -0.2\n0.02 0.3\n0.03 -0.1\n";
  const auto plain = test::run_command(pcrf() + " record " + test::write_file(dir, "plain.txt", text).string());
  const auto marked = test::run_command(pcrf() + " record " + test::write_file(dir, "marked.txt", "\xEF\xBB\xBF" + text).string());
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(marked.exit_code, 0) << marked.err;
  EXPECT_EQ(marked.out.substr(marked.out.find("\"npts\"")), plain.out.substr(plain.out.find("\"npts\"")));
}

}  // namespace
}  // namespace pcrf
