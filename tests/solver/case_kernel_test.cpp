// The case kernel compiled for the host (kernel_host_group, src/solver/device/case_kernel.hpp)
// against the CPU engine (solve_case, integrator dopri5), bit for bit: every metric, status,
// message, impact count and solver counter. Covered: the rigid rockers (Housner's block, the
// Makris–Vassiliou frame) and the prestressed frame (its table); a case the kernel does not
// cover is refused with its reason, never
// answered. The designs: Latin hypercubes of 10³ frames of each scene under a PEER
// record at twice the design's median uplift threshold, and the work-precision study's eleven
// paper records at 1.2× and 2× each frame's threshold (skipped without ../shared/records); short
// synthetic records under every preset's tolerances, with and without ω peaks, displaced
// starts, a fixed tail and a largest step. The 10³-frame designs under all eleven records:
// -DPCRF_KERNEL_LONG_TEST=ON, label kernel_long.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "batch_design.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/solver/case_group.hpp"
#include "solver_test_support.hpp"
#include "support/test_support.hpp"

namespace pcrf {
namespace {

SolverSettings dopri5(const char* preset) {
  SolverSettings s = preset_settings(preset);
  s.integrator = Integrator::kDormandPrince5;
  return s;
}

/// Median uplift threshold of a design [m/s²].
double median_threshold(const std::vector<PreparedFrame*>& frames) {
  std::vector<double> t;
  for (PreparedFrame* f : frames) t.push_back(f->scene().uplift_threshold_m_s2());
  std::nth_element(t.begin(), t.begin() + static_cast<long>(t.size() / 2), t.end());
  return t[t.size() / 2];
}

/// Cases the kernel refused because a prestressed frame's stage fell outside its table (a
/// step across θ₁ = 0 that overshoots by more than a cell: the CPU evaluates the exact terms
/// there). Measured: only under the `fast` preset's long steps (80 of its 288 prestressed
/// cases here), none under `balanced` and `reference`.
long table_refusals = 0;

/// Every case of `frames` under `record` by the kernel and by solve_case; returns how many
/// rocked. A case is answered bit for bit, or, where `may_leave_table`, refused for the
/// table's reason alone.
long expect_kernel_is_solve_case(const std::vector<PreparedFrame*>& frames, const Excitation& record,
                                 const SolverSettings& solver, const OutputRequest& request, const std::string& where,
                                 bool may_leave_table = false) {
  const auto kernel = kernel_host_group();
  const std::vector<GroupCase> answers = kernel->solve(frames, record, solver, request);
  EXPECT_EQ(answers.size(), frames.size());
  long rocked = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const CaseResult one = solve_case(*frames[i], record, solver, request);
    rocked += one.impacts > 0 ? 1 : 0;
    if (may_leave_table && answers[i].outcome == GroupOutcome::kRefused &&
        answers[i].result.message.find("table does not hold") != std::string::npos) {
      EXPECT_FALSE(frames[i]->scene().rocker_coefficients().has_value()) << where << ": a rigid rocker has no table";
      ++table_refusals;
      continue;
    }
    EXPECT_EQ(answers[i].outcome, GroupOutcome::kSolved) << answers[i].result.message;
    test::expect_same(answers[i].result, one, 0.0, where + ", case " + std::to_string(i));
    if (::testing::Test::HasFailure()) return rocked;  // one case's story is enough
  }
  return rocked;
}

std::vector<PreparedFrame*> views_of(const std::vector<std::shared_ptr<PreparedFrame>>& frames) {
  std::vector<PreparedFrame*> v;
  for (const auto& f : frames) v.push_back(f.get());
  return v;
}

struct Scene {
  test::SceneKind kind;
  const char* name;
};

void PrintTo(const Scene& s, std::ostream* os) { *os << s.name; }

class CaseKernelOnEveryScene : public ::testing::TestWithParam<Scene> {};

TEST_P(CaseKernelOnEveryScene, SyntheticRecordsUnderEveryPresetAreSolveCaseBitForBit) {
  PhysicsOptions until_rest;
  until_rest.max_tail_s = 4.0;
  PhysicsOptions fixed_tail = until_rest;
  fixed_tail.tail_s = 1.5;
  for (const PhysicsOptions& physics : {until_rest, fixed_tail}) {
    const auto frames = test::design(GetParam().kind, 24, physics);
    const auto views = views_of(frames);
    const double target_m_s2 = 2.0 * median_threshold(views);
    long rocked = 0;
    for (std::uint64_t seed : {3, 5, 8}) {
      const GroundMotion raw = test::strong_record(seed, 3.0);
      const GroundMotion record = raw.scaled(target_m_s2 / raw.pga_m_s2());
      for (const char* preset : {"fast", "balanced", "reference"}) {
        for (const bool omega_peak : {false, true}) {
          OutputRequest request;
          request.omega_peak = omega_peak;
          SolverSettings solver = dopri5(preset);
          const std::string where = std::string(preset) + (omega_peak ? " ω peaks" : "") + " seed " + std::to_string(seed);
          const bool fast = std::string(preset) == "fast";
          rocked += expect_kernel_is_solve_case(views, record, solver, request, where, fast);
          if (HasFailure()) return;
        }
      }
      SolverSettings short_steps = dopri5("balanced");
      short_steps.max_step_s = 0.003;
      rocked += expect_kernel_is_solve_case(views, record, short_steps, {}, "max_step_s 0.003");
      if (HasFailure()) return;
    }
    EXPECT_GT(rocked, 24L * 3);  // most cases rock, not just rest
  }
  // The fast preset's refusals: the prestressed frame's alone, and not most of its cases.
  if (GetParam().kind == test::SceneKind::kPrestressedFrame) {
    EXPECT_LT(table_refusals, 2L * 3 * 2 * 24 / 2);  // of 2 tails × 3 records × 2 requests × 24 frames under fast
  } else {
    EXPECT_EQ(table_refusals, 0);
  }
}

TEST_P(CaseKernelOnEveryScene, DisplacedStartsAndFailuresAreSolveCaseBitForBit) {
  PhysicsOptions physics;
  physics.max_tail_s = 3.0;
  physics.theta0_rad = 0.05;
  physics.omega0_rad_s = -0.2;
  const auto frames = test::design(GetParam().kind, 12, physics);
  const auto views = views_of(frames);
  const GroundMotion quiet = test::quiet_record(2.0);
  OutputRequest omega;
  omega.omega_peak = true;
  EXPECT_EQ(expect_kernel_is_solve_case(views, quiet, dopri5("balanced"), omega, "displaced, free rocking"),
            static_cast<long>(views.size()));  // every displaced frame rocks (impacts) before it rests
  // A step budget that ends every rocking case: the failure and its message are the CPU's.
  SolverSettings few_steps = dopri5("balanced");
  few_steps.max_steps = 40;
  const GroundMotion raw = test::strong_record(5, 3.0);
  const GroundMotion record = raw.scaled(2.0 * median_threshold(views) / raw.pga_m_s2());
  expect_kernel_is_solve_case(views, record, few_steps, {}, "max_steps 40");
  long failed = 0;
  for (PreparedFrame* f : views) failed += solve_case(*f, record, few_steps, {}).status == CaseStatus::kSolverFailure;
  EXPECT_GT(failed, 0);
}

TEST_P(CaseKernelOnEveryScene, TenToTheThreeFramesUnderAPeerRecordAreSolveCaseBitForBit) {
  PCRF_REQUIRE_RECORDS(records);
  const auto frames = test::design(GetParam().kind, 1000, PhysicsOptions{});
  const auto views = views_of(frames);
  const GroundMotion raw = read_at2(records / "paper" / "ER3_BOL090.AT2");
  const GroundMotion record = raw.scaled(2.0 * median_threshold(views) / raw.pga_m_s2());
  const long rocked = expect_kernel_is_solve_case(views, record, dopri5("balanced"), {}, "ER3 at 2x");
  if (!HasFailure()) {
    EXPECT_GT(rocked, 500L);
  }
}

TEST_P(CaseKernelOnEveryScene, TheWorkPrecisionRecordsAreSolveCaseBitForBit) {
  PCRF_REQUIRE_RECORDS(records);
  const auto frames = test::design(GetParam().kind, 4, PhysicsOptions{});
  const char* const names[] = {"ER1_MUL279", "ER2_LOS270", "ER3_BOL090",    "ER4_H-E11230", "ER5_NIS000", "ER6_DZC270",
                               "ER7_CAP000", "ER8_G03000", "ER9_B-POE270", "ER10_RIO360",  "ER11_CHY101-N"};
  long rocked = 0;
  for (const char* name : names) {
    const GroundMotion raw = read_at2(records / "paper" / (std::string(name) + ".AT2"));
    for (const auto& frame : frames) {
      for (const double ratio : {1.2, 2.0}) {
        const GroundMotion record = raw.scaled(ratio * frame->scene().uplift_threshold_m_s2() / raw.pga_m_s2());
        OutputRequest request;
        request.omega_peak = true;
        rocked += expect_kernel_is_solve_case({frame.get()}, record, dopri5("balanced"), request,
                                              std::string(name) + " at " + std::to_string(ratio));
        if (HasFailure()) return;
      }
    }
  }
  EXPECT_GT(rocked, 11L * 4);
}

INSTANTIATE_TEST_SUITE_P(Scenes, CaseKernelOnEveryScene,
                         ::testing::Values(Scene{test::SceneKind::kBlock, "block"},
                                           Scene{test::SceneKind::kRockingFrame, "rocking_frame"},
                                           Scene{test::SceneKind::kPrestressedFrame, "prestressed_frame"}),
                         [](const auto& p) { return std::string(p.param.name); });

/// A kernel that refuses answers nothing: each refused case says why, and the reason names
/// what the kernel does not take.
TEST(CaseKernel, RefusesWhatItDoesNotCoverWithItsReason) {
  const auto kernel = kernel_host_group();
  EXPECT_EQ(kernel->name(), "kernel-host");
  const GroundMotion record = test::strong_record(5, 2.0);
  auto blocks = test::design(test::SceneKind::kBlock, 2, PhysicsOptions{});
  auto prestressed = test::design(test::SceneKind::kPrestressedFrame, 1, PhysicsOptions{});
  std::vector<PreparedFrame*> views = {blocks[0].get(), prestressed[0].get(), blocks[1].get()};
  const auto expect_refused = [](const GroupCase& c, const std::string& words) {
    EXPECT_EQ(c.outcome, GroupOutcome::kRefused);
    EXPECT_NE(c.result.message.find(words), std::string::npos) << c.result.message;
    EXPECT_TRUE(std::isnan(c.result.theta_max_rad));
  };
  // Every scene is covered: a block, a prestressed frame and a block solved together.
  const auto mixed = kernel->solve(views, record, dopri5("balanced"), {});
  ASSERT_EQ(mixed.size(), 3U);
  for (const GroupCase& c : mixed) EXPECT_EQ(c.outcome, GroupOutcome::kSolved) << c.result.message;
  // Settings it does not take: every case refused.
  SolverSettings taylor = preset_settings("balanced");
  taylor.integrator = Integrator::kTaylor;
  for (const GroupCase& c : kernel->solve(views, record, taylor, {})) expect_refused(c, "dopri5 only");
  SolverSettings verdict = dopri5("balanced");
  verdict.verdict_check = true;
  for (const GroupCase& c : kernel->solve(views, record, verdict, {})) expect_refused(c, "verdict check");
  SolverSettings timed = dopri5("balanced");
  timed.wall_time_limit_s = 5.0;
  for (const GroupCase& c : kernel->solve(views, record, timed, {})) expect_refused(c, "wall-time limit");
  const GroundMotion vertical = test::strong_record(6, 2.0);
  for (const GroupCase& c : kernel->solve(views, Excitation(record, &vertical), dopri5("balanced"), {}))
    expect_refused(c, "horizontal record only");
  // A case solve_case refuses (|θ₀| beyond the overturning angle): refused with its message,
  // the good case beside it solved.
  PhysicsOptions impossible;
  impossible.theta0_rad = 2.0;
  auto bad = test::design(test::SceneKind::kBlock, 1, impossible);
  const std::vector<PreparedFrame*> bad_view = {bad[0].get(), blocks[0].get()};
  const auto answers = kernel->solve(bad_view, record, dopri5("balanced"), {});
  expect_refused(answers[0], "overturning angle");
  EXPECT_EQ(answers[1].outcome, GroupOutcome::kSolved);
}

TEST(CaseKernel, GpuGroupSaysWhyItIsAbsent) {
  std::string why;
  const auto gpu = gpu_group(why);
  if (gpu) {
    EXPECT_EQ(gpu->name(), "gpu");
  } else {
    EXPECT_FALSE(why.empty());
  }
}

}  // namespace
}  // namespace pcrf
