/// \file sobol_indices.hpp
/// \brief First-order and total Sobol' sensitivity indices from a Saltelli design, with
/// bootstrap intervals. Knows numbers only: no cube, no file.
///
/// Given f(A_j), f(B_j) and f(A_B^(i)_j) for j = 1 … N (A_B^(i): A with column i from B),
///   V      = variance of all f(A_j) and f(B_j) together,
///   S1_i   = (1/N) Σ_j (f(B_j) − f₀) (f(A_B^(i)_j) − f(A_j)) / V  (Saltelli et al. 2010),
///            f₀ the mean of the f(A_j), f(B_j): centring leaves the expectation unchanged
///            (the bracket has mean 0) and removes the variance the output's mean adds,
///   ST_i   = (1/2N) Σ_j (f(A_j) − f(A_B^(i)_j))² / V            (Jansen 1999).
/// Intervals: resample the N rows with replacement, recompute, take percentiles.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcrf::analysis {

struct SobolIndex {
  double s1 = 0.0, s1_low = 0.0, s1_high = 0.0;  ///< first order, and its interval
  double st = 0.0, st_low = 0.0, st_high = 0.0;  ///< total, and its interval
};

/// Model outputs of a Saltelli design: f_a[j], f_b[j], f_ab[i][j].
struct SaltelliOutputs {
  std::vector<double> f_a;
  std::vector<double> f_b;
  std::vector<std::vector<double>> f_ab;  ///< one vector per parameter
};

/// One index per parameter. `confidence` 0.9: 5 %–95 % intervals. A zero variance gives
/// NaN indices (the output does not vary: nothing to apportion).
std::vector<SobolIndex> sobol_indices(const SaltelliOutputs& outputs, std::size_t resamples = 1000,
                                      double confidence = 0.9, std::uint64_t seed = 20101);

/// Error of an index estimate that is small enough to read (the scale of sobol_caution).
inline constexpr double kSobolReadableError = 0.05;

/// A caution when an index estimated from `samples` base samples cannot be right as it
/// stands: S1 above ST beyond their intervals (S1_low > ST_high; S1 ≤ ST always holds),
/// or S1 or ST negative beyond its interval (high end < 0). It states the inconsistency m
/// (S1 − ST, or −S) and the base samples that would bring it under kSobolReadableError if
/// the error falls as 1/√N: N·(m / 0.05)², rounded up to a power of two. "" otherwise.
std::string sobol_caution(const SobolIndex& index, std::size_t samples);

}  // namespace pcrf::analysis
