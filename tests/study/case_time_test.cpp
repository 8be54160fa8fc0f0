// A study's per-case cpu_time_s, summed over its cube, is at most the CPU time of the `pcrf
// study` process that computed it (getrusage of the waited-for child), one case at a time and
// in lockstep lanes: each case counts only its own thread's time or its share of a lane batch.
// A wall clock around each case counted its lane-mates' time too (up to W times the study's CPU).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <sys/resource.h>

#include "pcrf/cube/cube_reader.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

/// User + system CPU time of the waited-for children of this process and theirs [s].
double children_cpu_s() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

TEST(StudyCaseTime, SummedCaseCpuIsAtMostTheStudyCpu) {
  const auto dir = test::scratch_dir("study_case_time");
  // 2 records × 2 scales × 4 κ × 4 tan α = 64 cases, nearly all rocking, 16 to a lane batch:
  // enough case time (about 50 ms) that a wall clock per case, summed, was 5.6 times the
  // process's CPU here (start-up, records and cube included).
  const std::string grid = std::string("[study]\nname = \"time\"\n\n") +
                           "[[records]]\nsynthetic = [\"stochastic:seed=4,pga_g=1.4,duration_s=20\", "
                           "\"stochastic:seed=5,pga_g=1.4,duration_s=20\"]\n\n"
                           "[axes]\nscale = [1.3, 1.8]\nkappa = [1.0, 1.5, 2.0, 2.5]\ntan_alpha = [0.16, 0.18, 0.20, 0.22]\n\n";
  for (const char* lanes : {"1", "8"}) {
    SCOPED_TRACE(std::string("lanes ") + lanes);
    const std::string cube = std::string("cube") + lanes + ".h5";
    const auto file = test::write_file(dir, std::string("time") + lanes + ".toml",
                                       grid + "[solver]\nintegrator = \"dopri5\"\n\n[run]\nlanes = " + lanes + "\n");
    const double before_s = children_cpu_s();
    const auto r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study " + quoted(file) + " -o " + cube +
                                     " --progress-interval 0");
    const double study_cpu_s = children_cpu_s() - before_s;
    ASSERT_EQ(r.exit_code, 0) << r.err;
    cube::CubeReader reader(dir / cube);
    const auto times = reader.read_metric("cpu_time_s");
    ASSERT_EQ(times.size(), 64u);
    double sum_s = 0.0;
    for (double t : times) {
      ASSERT_TRUE(std::isfinite(t));
      EXPECT_GE(t, 0.0);
      sum_s += t;
    }
    EXPECT_GT(sum_s, 0.0);
    EXPECT_LE(sum_s, study_cpu_s) << "cases " << sum_s << " s, the study process " << study_cpu_s << " s";
  }
}

}  // namespace
}  // namespace pcrf::study_test
