// Lockstep batches (pcrf/solver/batch_solver.hpp): the same answers as the one-case
// solver for every case of a random design of each scene, at W = 1, 2, 4 and 8, with every
// kernel set this CPU runs, with the one-case sin/cos (rocker_sincos) a register at a time
// and lane by lane, and with the two other vectorised sin/cos. Short synthetic records keep it to
// seconds; the 10³-frame designs under three PEER records are tests/batch_long's (opt-in).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <numbers>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "batch_design.hpp"
#include "pcrf/solver/batch_solver.hpp"
#include "solver/lanes/lane_arrays.hpp"
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

using test::design;
using test::expect_same;
using test::SceneKind;

struct Design {
  SceneKind kind;
  std::vector<std::shared_ptr<PreparedFrame>> frames;
  std::vector<PreparedFrame*> views;
  std::vector<GroundMotion> records;
  SolverSettings solver = dopri5_balanced();  // the lanes' integrator (Taylor steps are one case at a time)
  OutputRequest request;
  std::vector<std::vector<CaseResult>> one_case;

  static SolverSettings dopri5_balanced() {
    SolverSettings s = preset_settings("balanced");
    s.integrator = Integrator::kDormandPrince5;
    return s;
  }  ///< per record, solve_case's answers

  Design(SceneKind k, std::size_t n) : kind(k) {
    PhysicsOptions physics;
    physics.max_tail_s = 4.0;
    frames = design(k, n, physics);
    for (auto& f : frames) views.push_back(f.get());
    // Three short records, each at about twice the design's median uplift threshold: some
    // cases stay at rest, most rock, a few overturn or fracture.
    std::vector<double> thresholds;
    for (auto& f : frames) thresholds.push_back(f->scene().uplift_threshold_m_s2());
    std::nth_element(thresholds.begin(), thresholds.begin() + static_cast<long>(n / 2), thresholds.end());
    const double target = 2.0 * thresholds[n / 2];
    for (std::uint64_t seed : {3, 5, 8}) {
      const GroundMotion raw = test::strong_record(seed, 3.0);
      records.push_back(raw.scaled(target / raw.pga_m_s2()));
    }
    for (const GroundMotion& r : records) {
      one_case.emplace_back();
      for (auto& f : frames) one_case.back().push_back(solve_case(*f, r, solver, request));
    }
  }
};

Design& design_of(SceneKind kind) {
  static Design block(SceneKind::kBlock, 24), rocking(SceneKind::kRockingFrame, 24),
      prestressed(SceneKind::kPrestressedFrame, 16);
  return kind == SceneKind::kBlock ? block : kind == SceneKind::kRockingFrame ? rocking : prestressed;
}

struct Variant {
  SceneKind kind;
  const char* scene;
};

/// gtest prints a parameter by this, not by its bytes (whose padding valgrind flags).
void PrintTo(const Variant& v, std::ostream* os) { *os << v.scene; }

class BatchOnEveryScene : public ::testing::TestWithParam<Variant> {};

/// Runs `check(results, record index, label)` for every kernel set this CPU runs, at
/// W = 1, 2, 4, 8 (and 3: a lane count that is no register width), with `trig`.
template <class Check>
void on_every_kernel_set(Design& d, const char* trig, Check check) {
  int runs = 0;
  for (const char* kernels : {"scalar", "sse2", "avx2", "avx512f", "neon64", ""}) {
    for (int lanes : {1, 2, 3, 4, 8}) {
      BatchOptions options;
      options.lanes = lanes;
      options.kernels = kernels;
      options.trig = trig;
      for (std::size_t r = 0; r < d.records.size(); ++r) {
        BatchStats stats;
        std::vector<CaseResult> results;
        try {
          results = solve_batch(d.views, d.records[r], d.solver, d.request, options, &stats);
        } catch (const std::invalid_argument&) {
          break;  // a kernel set or sin/cos this CPU or build does not have
        }
        ASSERT_EQ(results.size(), d.frames.size());
        EXPECT_EQ(stats.cases, static_cast<long>(d.frames.size()));
        EXPECT_GT(stats.occupancy(), 0.0);
        EXPECT_LE(stats.occupancy(), 1.0);
        check(results, r, stats.kernels + "/" + stats.trig + " W " + std::to_string(lanes) + ", record " +
                              std::to_string(r));
        ++runs;
      }
    }
  }
  EXPECT_GE(runs, 15);  // the scalar set at least, on every record
}

TEST_P(BatchOnEveryScene, LanesAreTheOneCaseSolverBitForBit) {
  Design& d = design_of(GetParam().kind);
  int rocking = 0;
  for (const auto& per_record : d.one_case)
    for (const CaseResult& c : per_record) rocking += c.impacts > 0 ? 1 : 0;
  EXPECT_GT(rocking, static_cast<int>(d.frames.size()));  // the design rocks, not just rests
  for (const char* trig : {"", "scalar"}) {  // the one-case sin/cos, a register at a time and lane by lane
    on_every_kernel_set(d, trig, [&](const std::vector<CaseResult>& results, std::size_t r, const std::string& where) {
      for (std::size_t i = 0; i < results.size(); ++i)
        expect_same(results[i], d.one_case[r][i], 0.0, where + ", case " + std::to_string(i));
    });
  }
}

TEST_P(BatchOnEveryScene, VectorisedSinCosKeepsEveryVerdictAndMovesLessThanTheTolerance) {
  // Another vectorised sin/cos differs from rocker_sincos in the last bit now and then; where
  // that flips a step's acceptance the answer moves by about the integration error. The
  // statuses and impacts stay; every metric stays within 10 rtol.
  if (GetParam().kind == SceneKind::kPrestressedFrame) GTEST_SKIP() << "its right-hand side has no sin/cos";
  Design& d = design_of(GetParam().kind);
  for (const char* trig : {"sleef", "xsimd"}) {
    on_every_kernel_set(d, trig, [&](const std::vector<CaseResult>& results, std::size_t r, const std::string& where) {
      for (std::size_t i = 0; i < results.size(); ++i)
        expect_same(results[i], d.one_case[r][i], 10.0 * d.solver.rtol, where + ", case " + std::to_string(i));
    });
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, BatchOnEveryScene,
                         ::testing::Values(Variant{SceneKind::kBlock, "block"},
                                           Variant{SceneKind::kRockingFrame, "rocking_frame"},
                                           Variant{SceneKind::kPrestressedFrame, "prestressed_frame"}),
                         [](const auto& p) { return std::string(p.param.scene); });

TEST(BatchSolver, EveryKernelSetsSinCosIsTheOneCaseSinCosBitForBit) {
  // The kernels' default sin/cos must be rocker_sincos's bits, whatever the register:
  // arguments over the rockers' range α ± φ (small, near ±π/2, beyond) and a few
  // far outside it.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-3.5, 3.5);
  std::vector<double> x;
  for (int i = 0; i < 20000; ++i) x.push_back(i % 4 == 0 ? 1e-4 * u(rng) : u(rng));
  for (double v : {0.0, -0.0, 1e-300, 0.5 * std::numbers::pi, -0.5 * std::numbers::pi, std::numbers::pi, 1e3, -7e5}) x.push_back(v);
  std::vector<double> s0(x.size()), c0(x.size());
  // The reference: the scalar set's, one double at a time (compiled as the model's, without
  // fused multiply-add; the lanes' answers equal to the model's say the rest).
  detail::batch::choose_kernels(1, "scalar").sincos(x.data(), s0.data(), c0.data(), x.size());
  int sets = 0;
  for (const char* kernels : {"scalar", "sse2", "avx2", "avx512f", "neon64"}) {
    detail::batch::KernelSet set;
    try {
      set = detail::batch::choose_kernels(8, kernels);
    } catch (const std::invalid_argument&) {
      continue;  // not in this build or not run by this CPU
    }
    std::vector<double> s(x.size()), c(x.size());
    set.sincos(x.data(), s.data(), c.data(), x.size());
    int differ = 0;
    for (std::size_t i = 0; i < x.size(); ++i)
      differ += std::memcmp(&s[i], &s0[i], sizeof(double)) != 0 || std::memcmp(&c[i], &c0[i], sizeof(double)) != 0;
    EXPECT_EQ(differ, 0) << kernels;
    ++sets;
  }
  EXPECT_GE(sets, 1);
  EXPECT_NEAR(s0[1], std::sin(x[1]), 1e-15);  // and it is sin and cos
  EXPECT_NEAR(c0[1], std::cos(x[1]), 1e-15);
}

TEST(BatchSolver, OtherIntegratorsAndVerdictChecksGoCaseByCase) {
  auto frame = prepare_frame(basic_frame(), PhysicsOptions{});
  PreparedFrame* views[] = {frame.get()};
  const GroundMotion record = test::strong_record(3, 2.0);
  SolverSettings s = preset_settings("balanced");
  s.verdict_check = true;
  BatchStats stats;
  const auto results = solve_batch(views, record, s, {}, BatchOptions{}, &stats);
  EXPECT_EQ(stats.scalar_cases, 1);
  EXPECT_FALSE(std::isnan(results[0].status_stable));
  EXPECT_FALSE(batch_integrates(preset_settings("reference")));
}

TEST(BatchSolver, RejectsBadOptions) {
  auto frame = prepare_frame(basic_frame(), PhysicsOptions{});
  PreparedFrame* views[] = {frame.get()};
  const GroundMotion record = test::strong_record(3, 1.0);
  const SolverSettings s = preset_settings("balanced");
  BatchOptions zero;
  zero.lanes = 0;
  EXPECT_THROW(solve_batch(views, record, s, {}, zero), std::invalid_argument);
  BatchOptions unknown;
  unknown.kernels = "mmx";
  EXPECT_THROW(solve_batch(views, record, s, {}, unknown), std::invalid_argument);
  BatchOptions trig;
  trig.trig = "cordic";
  EXPECT_THROW(solve_batch(views, record, s, {}, trig), std::invalid_argument);
}

}  // namespace
}  // namespace pcrf
