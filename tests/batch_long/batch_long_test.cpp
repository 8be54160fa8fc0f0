// Lockstep batches against the one-case solver at scale (issue 28's equality check): for
// each scene, a Latin hypercube of 10³ frames under three PEER far-field records, each scaled
// to twice the design's median uplift threshold; every case at W = 1, 2, 4 and 8 (the widest
// kernel set the CPU runs for each W, the C library's sin/cos) must give solve_case's answer
// bit for bit: every metric, status, impact count and solver counter.
//
// Opt-in (label batch_long, a few minutes on one core): configure with
// -DPCRF_BATCH_LONG_TEST=ON, then `ctest --test-dir build -L batch_long`. Skips cleanly
// without ../shared/records.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pcrf/record/record_readers.hpp"
#include "pcrf/solver/batch_solver.hpp"
#include "solver/batch_design.hpp"
#include "support/test_support.hpp"

namespace pcrf {
namespace {

constexpr std::size_t kFrames = 1000;
const char* const kRecords[] = {"ER1_MUL279", "ER3_BOL090", "ER7_CAP000"};

struct Variant {
  test::SceneKind kind;
  const char* scene;
};

/// gtest prints a parameter by this, not by its bytes.
void PrintTo(const Variant& v, std::ostream* os) { *os << v.scene; }

class BatchLong : public ::testing::TestWithParam<Variant> {};

TEST_P(BatchLong, TenToTheThreeFramesUnderThreeRecordsAreTheOneCaseSolverBitForBit) {
  PCRF_REQUIRE_RECORDS(records);
  const auto frames = test::design(GetParam().kind, kFrames, PhysicsOptions{});
  std::vector<PreparedFrame*> views;
  std::vector<double> thresholds;
  for (const auto& f : frames) views.push_back(f.get()), thresholds.push_back(f->scene().uplift_threshold_m_s2());
  std::nth_element(thresholds.begin(), thresholds.begin() + kFrames / 2, thresholds.end());
  const double target_m_s2 = 2.0 * thresholds[kFrames / 2];
  const SolverSettings solver = preset_settings("balanced");
  long rocking = 0, compared = 0;
  for (const char* name : kRecords) {
    const GroundMotion raw = read_at2(records / "paper" / (std::string(name) + ".AT2"));
    const GroundMotion record = raw.scaled(target_m_s2 / raw.pga_m_s2());
    std::vector<CaseResult> one;
    for (PreparedFrame* f : views) one.push_back(solve_case(*f, record, solver, OutputRequest{}));
    for (const CaseResult& c : one) rocking += c.impacts > 0 ? 1 : 0;
    for (int lanes : {1, 2, 4, 8}) {
      BatchOptions options;
      options.lanes = lanes;
      BatchStats stats;
      const auto batch = solve_batch(views, record, solver, OutputRequest{}, options, &stats);
      ASSERT_EQ(batch.size(), one.size());
      const std::string where = std::string(name) + ", " + stats.kernels + " W " + std::to_string(lanes);
      for (std::size_t i = 0; i < batch.size(); ++i) {
        test::expect_same(batch[i], one[i], 0.0, where + ", case " + std::to_string(i));
        if (::testing::Test::HasFailure()) return;  // one case's story is enough
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, static_cast<long>(4 * std::size(kRecords) * kFrames));
  EXPECT_GT(rocking, static_cast<long>(kFrames));  // the design rocks under most records, not just rests
}

INSTANTIATE_TEST_SUITE_P(Scenes, BatchLong,
                         ::testing::Values(Variant{test::SceneKind::kBlock, "block"},
                                           Variant{test::SceneKind::kRockingFrame, "rocking_frame"},
                                           Variant{test::SceneKind::kPrestressedFrame, "prestressed_frame"}),
                         [](const auto& p) { return std::string(p.param.scene); });

}  // namespace
}  // namespace pcrf
