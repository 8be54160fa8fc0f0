// The case kernel compiled for the host against the CPU engine at scale (issue 40's equality
// check): for each scene (block, rocking frame, prestressed frame), a Latin hypercube of 10³ frames under the eleven paper records
// (the work-precision set's), each scaled to twice the design's median uplift threshold;
// every case by kernel_host_group must give solve_case's answer (integrator dopri5, balanced
// tolerances, ω peaks) bit for bit: every metric, status, message, impact count and counter.
//
// Opt-in (label kernel_long, a few minutes on one core): configure with
// -DPCRF_KERNEL_LONG_TEST=ON, then `ctest --test-dir build -L kernel_long`. Skips cleanly
// without ../shared/records.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "pcrf/record/record_readers.hpp"
#include "pcrf/solver/case_group.hpp"
#include "solver/batch_design.hpp"
#include "support/test_support.hpp"

namespace pcrf {
namespace {

constexpr std::size_t kFrames = 1000;
const char* const kRecords[] = {"ER1_MUL279", "ER2_LOS270", "ER3_BOL090",   "ER4_H-E11230", "ER5_NIS000",   "ER6_DZC270",
                                "ER7_CAP000", "ER8_G03000", "ER9_B-POE270", "ER10_RIO360",  "ER11_CHY101-N"};

struct Variant {
  test::SceneKind kind;
  const char* scene;
};

void PrintTo(const Variant& v, std::ostream* os) { *os << v.scene; }

class KernelLong : public ::testing::TestWithParam<Variant> {};

TEST_P(KernelLong, TenToTheThreeFramesUnderElevenRecordsAreTheOneCaseSolverBitForBit) {
  PCRF_REQUIRE_RECORDS(records);
  const auto frames = test::design(GetParam().kind, kFrames, PhysicsOptions{});
  std::vector<PreparedFrame*> views;
  std::vector<double> thresholds;
  for (const auto& f : frames) views.push_back(f.get()), thresholds.push_back(f->scene().uplift_threshold_m_s2());
  std::nth_element(thresholds.begin(), thresholds.begin() + kFrames / 2, thresholds.end());
  const double target_m_s2 = 2.0 * thresholds[kFrames / 2];
  SolverSettings solver = preset_settings("balanced");
  solver.integrator = Integrator::kDormandPrince5;
  OutputRequest request;
  request.omega_peak = true;
  const auto kernel = kernel_host_group();
  long rocking = 0, compared = 0;
  for (const char* name : kRecords) {
    const GroundMotion raw = read_at2(records / "paper" / (std::string(name) + ".AT2"));
    const GroundMotion record = raw.scaled(target_m_s2 / raw.pga_m_s2());
    const std::vector<GroupCase> answers = kernel->solve(views, record, solver, request);
    ASSERT_EQ(answers.size(), views.size());
    for (std::size_t i = 0; i < views.size(); ++i) {
      const CaseResult one = solve_case(*views[i], record, solver, request);
      ASSERT_EQ(answers[i].outcome, GroupOutcome::kSolved) << answers[i].result.message;
      test::expect_same(answers[i].result, one, 0.0, std::string(name) + ", case " + std::to_string(i));
      if (::testing::Test::HasFailure()) return;  // one case's story is enough
      rocking += one.impacts > 0 ? 1 : 0;
      ++compared;
    }
  }
  EXPECT_EQ(compared, static_cast<long>(std::size(kRecords) * kFrames));
  EXPECT_GT(rocking, static_cast<long>(kFrames));  // the design rocks under most records, not just rests
}

INSTANTIATE_TEST_SUITE_P(Scenes, KernelLong,
                         ::testing::Values(Variant{test::SceneKind::kBlock, "block"},
                                           Variant{test::SceneKind::kRockingFrame, "rocking_frame"},
                                           Variant{test::SceneKind::kPrestressedFrame, "prestressed_frame"}),
                         [](const auto& p) { return std::string(p.param.scene); });

}  // namespace
}  // namespace pcrf
