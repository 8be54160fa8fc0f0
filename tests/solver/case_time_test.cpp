// A case's cpu_time_s is its own: the CPU time of the thread that solved it, or its share of
// a lane batch's. Summed over cases it is at most the process's CPU time (getrusage), one
// case at a time and in lanes alike; a wall clock around each case would count the lane-mates'
// work once per lane (W times over) and every time the process waits.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <sys/resource.h>

#include "batch_design.hpp"
#include "pcrf/solver/batch_solver.hpp"
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

/// User + system CPU time of this process, every thread [s].
double process_cpu_s() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

/// getrusage's resolution [s]: its microseconds, once for each of the two readings.
constexpr double kRusageResolution_s = 2e-6;

struct Batch {
  std::vector<std::shared_ptr<PreparedFrame>> frames;
  std::vector<PreparedFrame*> views;
  GroundMotion record = test::strong_record(5, 4.0);
  Batch() {
    PhysicsOptions physics;
    physics.max_tail_s = 4.0;
    frames = test::design(test::SceneKind::kBlock, 24, physics);
    for (auto& f : frames) views.push_back(f.get());
    // About twice the design's uplift thresholds: most cases rock.
    record = record.scaled(2.0 * frames.front()->scene().uplift_threshold_m_s2() / record.pga_m_s2());
  }
};

/// Σ cpu_time_s of `results`, each checked to be a time.
double summed_cpu_s(const std::vector<CaseResult>& results) {
  double sum_s = 0.0;
  for (const CaseResult& r : results) {
    EXPECT_TRUE(std::isfinite(r.cpu_time_s));
    EXPECT_GE(r.cpu_time_s, 0.0);
    sum_s += r.cpu_time_s;
  }
  return sum_s;
}

TEST(CaseTime, OneCaseAtATimeSumsToAtMostTheProcessCpu) {
  const Batch b;
  std::vector<CaseResult> results;
  const double before_s = process_cpu_s();
  for (PreparedFrame* f : b.views) results.push_back(solve_case(*f, b.record, preset_settings("balanced"), {}));
  const double spent_s = process_cpu_s() - before_s;
  const double sum_s = summed_cpu_s(results);
  EXPECT_GT(sum_s, 0.0);
  EXPECT_LE(sum_s, spent_s + kRusageResolution_s);
}

TEST(CaseTime, LaneSharesSumToAtMostTheProcessCpu) {
  const Batch b;
  SolverSettings solver = preset_settings("balanced");
  solver.integrator = Integrator::kDormandPrince5;  // the lanes' integrator
  for (int lanes : {1, 4, 8}) {
    SCOPED_TRACE("lanes " + std::to_string(lanes));
    BatchOptions options;
    options.lanes = lanes;
    BatchStats stats;
    const double before_s = process_cpu_s();
    const std::vector<CaseResult> results = solve_batch(b.views, b.record, solver, {}, options, &stats);
    const double spent_s = process_cpu_s() - before_s;
    ASSERT_GT(stats.cases - stats.rest_cases - stats.scalar_cases, 4);  // most went through the lanes
    const double sum_s = summed_cpu_s(results);
    EXPECT_GT(sum_s, 0.0);
    EXPECT_LE(sum_s, spent_s + kRusageResolution_s);
    // The shares account for the batch: nearly all of its CPU is some case's.
    EXPECT_GT(sum_s, 0.5 * spent_s);
    for (std::size_t i = 0; i < results.size(); ++i) {
      if (results[i].impacts > 0) {
        EXPECT_GT(results[i].cpu_time_s, 0.0) << "case " << i;
      }
    }
  }
  // Taylor steps run one case at a time inside the batch: their time is their own.
  const double before_s = process_cpu_s();
  const std::vector<CaseResult> taylor = solve_batch(b.views, b.record, preset_settings("balanced"), {}, {}, nullptr);
  EXPECT_LE(summed_cpu_s(taylor), process_cpu_s() - before_s + kRusageResolution_s);
}

}  // namespace
}  // namespace pcrf
