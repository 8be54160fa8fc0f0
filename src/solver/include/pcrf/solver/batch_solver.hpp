/// \file batch_solver.hpp
/// \brief Many cases under one excitation, solved in lockstep batches (docs/batches.md).
///
/// W lanes each hold one case (one prepared frame) under the same excitation. Every lane
/// keeps its own state, step size, error norm and events; the lanes take their Dormand–Prince
/// 5(4) step attempts together, one vector instruction doing the arithmetic of W lanes (the
/// rigid rockers' right-hand side included, with a vectorised sin/cos). A lane whose step
/// holds an event (impact, peak, uplift, stop, rest) handles it on its own, with the scalar
/// arithmetic of the one-case solver, and rejoins at its next step; a lane whose case has
/// ended takes the next case. The lanes share the record, not the clock: each stays in its
/// own record interval, and none waits for another.
///
/// Same answers as solve_case with the dopri5 integrator, bit for bit: every lane does that
/// integrator's arithmetic in the same order and rounding, with its sin/cos (rocker_sincos,
/// vectorised where built with SLEEF; BatchOptions::trig may trade it for another). Cases the batch does not take (another integrator, a
/// verdict check) are solved by solve_case, one by one.
///
/// The instruction set is chosen at run time among those this binary was built with
/// (SSE2, AVX2 + FMA, AVX-512F on x86-64; Advanced SIMD on arm64): the default build stays
/// portable.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "pcrf/excitation/excitation.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf {

struct BatchOptions {
  /// W, cases in flight together (≥ 1). 8: the fastest measured with exact answers
  /// (docs/batches.md), and two registers where AVX-512 is absent.
  int lanes = 8;
  /// Kernel set: "" the widest this CPU runs whose register holds at most `lanes` doubles;
  /// else "scalar", "sse2", "avx2", "avx512f" or "neon64".
  std::string kernels;
  /// sin/cos of the rigid rockers' right-hand side: "" the one-case solver's (rocker_sincos:
  /// the same answers bit for bit), a register at a time where built with SLEEF (its
  /// deterministic family), else lane by lane; "scalar" the same lane by lane (to measure
  /// what the vector one gains); "sleef" (SLEEF's fastest 1-ulp vector functions, with fused
  /// multiply-add; where built) or "xsimd" (xsimd's). Those two differ from the one-case
  /// sincos in the last bit now and then, and a step accepted by a hair may then be
  /// rejected: such a case's answer moves by about the integration error (docs/batches.md).
  std::string trig;
};

/// What a batch run did, for benchmarks (docs/batches.md).
struct BatchStats {
  std::string kernels;         ///< the kernel set used
  std::string trig;            ///< the sin/cos used ("sleef-cinz vector", "libm lane by lane", "sleef", …)
  int lanes = 0;               ///< W
  long kernel_calls = 0;       ///< vector step attempts, each over all W lanes
  long busy_lane_attempts = 0; ///< lane attempts that belonged to a case (occupancy's numerator)
  long accepted = 0;           ///< accepted steps
  long rejected = 0;           ///< rejected or failed attempts
  long root_searches = 0;      ///< accepted steps with a sign change to locate (scalar)
  long events = 0;             ///< root returns handled by the lane alone (peaks, impacts, stops)
  long flights = 0;            ///< flight starts (uplift, after an impact): scalar restarts
  long cases = 0;              ///< cases solved in lanes
  long rest_cases = 0;         ///< of which at rest throughout (no integration)
  long scalar_cases = 0;       ///< cases handed to solve_case
  /// Share of lane attempts that belonged to a case.
  double occupancy() const {
    return kernel_calls > 0 ? static_cast<double>(busy_lane_attempts) / static_cast<double>(kernel_calls * lanes) : 0.0;
  }
};

/// Solves frames[i] under `excitation` into result i, `options.lanes` cases at a time.
/// \throws std::invalid_argument as solve_case (invalid settings, an impossible initial
/// state), and for invalid options.
std::vector<CaseResult> solve_batch(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                                    const SolverSettings& solver, const OutputRequest& request,
                                    const BatchOptions& options, BatchStats* stats = nullptr);

/// True when solve_batch integrates these settings in lanes (else it calls solve_case).
bool batch_integrates(const SolverSettings& solver);

}  // namespace pcrf
