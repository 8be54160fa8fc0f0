// How big a study is, from its file alone: every plan counted; a study too large for rank 0
// is refused with one FILE:LINE: key: line (plan.samples, ida.max_runs, axes) before any
// plan is drawn; and no numeric key, however huge, reaches an internal error.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/user_error.hpp"
#include "pcrf/study/study_parser.hpp"
#include "pcrf/run/study_run.hpp"
#include "pcrf/study/study_size.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

const std::string kRecord = std::string("[[records]]\nsynthetic = [\"") + kPulse + "\", \"" + kPulse2 + "\"]\n";

study::StudySize size_of(const std::string& text) { return study::study_size(study::parse_study(text, "s.toml", ".")); }

TEST(StudySize, EveryPlanIsCountedFromTheFile) {
  auto grid = size_of(kRecord + "[axes]\nscale = [1, 2, 3]\nkappa = [1, 2]\ntan_alpha = [0.1, 0.2]\n");
  EXPECT_EQ(grid.frames, 4.0);
  EXPECT_EQ(grid.cases, 4.0 * 2 * 3);
  auto lhs = size_of(kRecord + "[plan]\nkind = \"lhs\"\nsamples = 7\n[axes]\nkappa = {from = 1, to = 2}\n");
  EXPECT_EQ(lhs.frames, 7.0);
  EXPECT_EQ(lhs.cases, 14.0);
  auto saltelli = size_of(kRecord + "[plan]\nkind = \"saltelli\"\nsamples = 8\n[axes]\nkappa = {from = 1, to = 2}\n"
                                    "tan_alpha = {from = 0.1, to = 0.2}\n");
  EXPECT_EQ(saltelli.frames, 8.0 * 4);
  auto ida = size_of(kRecord + "[intensity]\nmeasure = \"pga_g\"\n[ida]\nstart = 0.1\nmax_intensity = 2\nmax_runs = 5\n"
                               "[axes]\nkappa = [1, 2, 3]\n");
  EXPECT_EQ(ida.cases, 3.0 * 2 * 5);
}

test::CommandResult check(const std::filesystem::path& dir, const std::string& text) {
  test::write_file(dir, "s.toml", text);
  return test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study s.toml --check");
}

TEST(StudySize, HugeStudiesAreRefusedWithTheirKeyAndLine) {
  const auto dir = test::scratch_dir("study_size_huge");
  const std::vector<std::pair<std::string, std::string>> corpus = {
      {kRecord + "[plan]\nkind = \"lhs\"\nsamples = 100000000000\n[axes]\nkappa = {from = 1, to = 2}\n", "s.toml:5: [plan] samples: "},
      {kRecord + "[plan]\nkind = \"sobol\"\nsamples = 9223372036854775807\n[axes]\nkappa = {from = 1, to = 2}\n",
       "s.toml:5: [plan] samples: "},
      {kRecord + "[plan]\nkind = \"saltelli\"\nsamples = 1000000000000\n[axes]\nkappa = {from = 1, to = 2}\n"
                 "tan_alpha = {from = 0.1, to = 0.2}\n",
       "s.toml:5: [plan] samples: "},
      {kRecord + "[intensity]\nmeasure = \"pga_g\"\n[ida]\nstart = 0.1\nmax_intensity = 2\nmax_runs = 100000000\n"
                 "[axes]\nkappa = [1, 2]\n",
       "s.toml:8: [ida] max_runs: at most 1000000 runs per curve"},
      {kRecord + "[intensity]\nmeasure = \"pga_g\"\n[ida]\nstart = 0.1\nmax_intensity = 2\nmax_runs = 1000000\n"
                 "[axes]\nkappa = {from = 1, to = 3, count = 100000}\n",
       "s.toml:8: [ida] max_runs: "},
      {kRecord + "[axes]\nkappa = {from = 1, to = 3, count = 100000}\ntan_alpha = {from = 0.1, to = 0.2, count = 100000}\n",
       "s.toml:3: axes: "},
  };
  for (const auto& [text, says] : corpus) {
    const auto r = check(dir, text);
    EXPECT_EQ(r.exit_code, 2) << text << r.err;
    EXPECT_EQ(r.err.find("pcrf: error: " + says), 0u) << text << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

/// `pcrf study FILE --check` in this process (a process per value would take a minute):
/// "" when it passes, its one-line message when refused; an exception of any other kind (an
/// internal error: bad_alloc, …) fails the test.
std::string check_in_process(const std::filesystem::path& dir, const std::string& text, const std::string& what) {
  static parallel::MpiSession mpi;  // one rank, no launcher
  run::StudyRunOptions options;
  options.study_file = test::write_file(dir, "s.toml", text);
  options.check_only = true;
  try {
    (void)run::run_study(options, mpi);
    return "";
  } catch (const UserError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << what << ": " << message;
    return message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": internal error: " << e.what();
    return e.what();
  }
}

/// Each numeric key of a settings table with values no study means: refused in one line, or
/// accepted; never an internal error (bad_alloc, an exception escaping).
template <class Target>
void sweep(const std::filesystem::path& dir, const SettingTable<Target>& table, const std::string& base,
           const std::string& required = "") {
  const std::vector<std::string> huge = {"1e300", "-1e300", "inf", "-inf", "nan", "9223372036854775807",
                                         "-9223372036854775808", "4294967297"};
  for (const auto& setting : table.settings) {
    if (setting.type != SettingType::kNumber && setting.type != SettingType::kInteger) continue;
    for (const auto& value : huge) {
      std::string body = "[" + std::string(table.name) + "]\n" + std::string(setting.key) + " = " + value + "\n";
      // Required keys of the table other than the one swept, at ordinary values.
      std::istringstream lines(required);
      for (std::string line; std::getline(lines, line);)
        if (line.rfind(std::string(setting.key) + " ", 0) != 0) body += line + "\n";
      (void)check_in_process(dir, base + body, std::string(table.name) + "." + std::string(setting.key) + " = " + value);
    }
  }
}

TEST(StudySize, NoNumericKeyReachesAnInternalError) {
  const auto dir = test::scratch_dir("study_size_sweep");
  const std::string grid = kRecord + "[axes]\nkappa = [1, 2]\n";
  ASSERT_EQ(check_in_process(dir, grid, "the base study"), "");  // the sweep's refusals are the values'
  EXPECT_NE(check_in_process(dir, grid + "[physics]\ntheta0_rad = 1e300\n", "theta0_rad"), "");
  sweep(dir, physics_settings(), grid);
  sweep(dir, solver_settings(), grid);
  sweep(dir, study::run_settings(), grid);
  sweep(dir, intensity_settings(), kRecord + "[axes]\nintensity = [0.5]\n", "measure = \"sa_g\"");
  sweep(dir, study::ida_settings(), kRecord + "[intensity]\nmeasure = \"sa_g\"\nperiod_s = 0.5\n[axes]\nkappa = [1, 2]\n",
        "start = 0.1\nmax_intensity = 2");
  for (const std::string value : {"9223372036854775807", "4294967297", "100000000000", "1e300"}) {
    const std::string samples = check_in_process(dir, kRecord + "[plan]\nkind = \"saltelli\"\nsamples = " + value +
                                                          "\n[axes]\nkappa = {from = 1, to = 2}\ntan_alpha = {from = 0.1, to = 0.2}\n",
                                                 "samples " + value);
    EXPECT_NE(samples, "") << value;
    const std::string count = check_in_process(dir, kRecord + "[axes]\nkappa = {from = 1, to = 2, count = " + value + "}\n",
                                               "count " + value);
    EXPECT_NE(count, "") << value;
  }
}

}  // namespace
}  // namespace pcrf::study_test
