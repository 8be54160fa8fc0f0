/// \file batch_design.hpp
/// \brief What the batch tests share: Latin-hypercube designs of each scene, and the check
/// that a batch's answer is the one-case solver's (tests/solver/batch_solver_test.cpp,
/// tests/batch_long/batch_long_test.cpp).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/model/rigid_rocker.hpp"
#include "solver/case/prepared_frame.hpp"  // private to the solver: the tests read the scene

namespace pcrf::test {

/// A Latin hypercube of n points in [0, 1)^d.
inline std::vector<std::vector<double>> latin_hypercube(std::size_t n, std::size_t d, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::vector<double>> points(n, std::vector<double>(d));
  for (std::size_t j = 0; j < d; ++j) {
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    for (std::size_t i = 0; i < n; ++i) points[i][j] = (static_cast<double>(order[i]) + u(rng)) / static_cast<double>(n);
  }
  return points;
}

inline double between(double lo, double hi, double x) { return lo + (hi - lo) * x; }

enum class SceneKind { kBlock, kRockingFrame, kPrestressedFrame };

/// n distinct prepared frames of one scene from a Latin hypercube.
inline std::vector<std::shared_ptr<PreparedFrame>> design(SceneKind kind, std::size_t n, const PhysicsOptions& physics) {
  std::vector<std::shared_ptr<PreparedFrame>> frames;
  for (const auto& x : latin_hypercube(n, 3, 17 + static_cast<std::uint64_t>(kind))) {
    if (kind == SceneKind::kPrestressedFrame) {
      FrameParameters p;
      p.tan_alpha = between(0.15, 0.3, x[0]);
      p.pi_sigma_c = between(0.0, 10.0, x[1]);
      p.kappa = between(0.5, 3.0, x[2]);
      frames.push_back(prepare_frame(make_frame(p), physics));
    } else {
      RockerParameters p;
      p.slenderness_rad = between(0.12, 0.3, x[0]);
      p.size_m = between(0.4, 3.0, x[1]);
      p.beam_mass_ratio = kind == SceneKind::kBlock ? 0.0 : between(0.2, 2.0, x[2]);
      frames.push_back(prepare_scene(std::make_unique<RigidRocker>(p), physics));
    }
  }
  return frames;
}

/// |a − b| ≤ tol·max(|a|, |b|), NaN matching NaN.
inline ::testing::AssertionResult close(const char* name, double a, double b, double tol) {
  if (std::isnan(a) && std::isnan(b)) return ::testing::AssertionSuccess();
  if (a == b || std::abs(a - b) <= tol * std::max(std::abs(a), std::abs(b))) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << name << ": batch " << a << ", one case " << b << " (relative "
                                       << std::abs(a - b) / std::max(std::abs(a), std::abs(b)) << ")";
}

/// Every metric of `batch` against `one`: to `tol` relative, or bit for bit (tol 0, counts too).
inline void expect_same(const CaseResult& batch, const CaseResult& one, double tol, const std::string& where) {
  SCOPED_TRACE(where);
  EXPECT_EQ(batch.status, one.status) << batch.message << " | " << one.message;
  EXPECT_EQ(batch.impacts, one.impacts);
  EXPECT_EQ(batch.message, one.message);
  for (const MetricInfo& m : all_metrics()) {
    if (m.name == "cpu_time_s") continue;
    const bool counter = m.is_count && m.name != "impacts";
    if (counter && tol > 0.0) continue;  // solver counters: equal only bit for bit
    EXPECT_TRUE(close(std::string(m.name).c_str(), m.get(batch), m.get(one), tol));
  }
}

}  // namespace pcrf::test
