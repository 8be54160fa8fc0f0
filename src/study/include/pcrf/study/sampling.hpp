/// \file sampling.hpp
/// \brief Sampling plans over the unit hypercube [0, 1)^d: Latin hypercube, Sobol'
/// low-discrepancy points (optionally Owen-scrambled), and the Saltelli design for Sobol'
/// sensitivity indices. Pure functions of (N, d, seed): the same call gives the same points.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace pcrf::study {

/// N points, row-major: point j, dimension i at [j * d + i].
using UnitPoints = std::vector<double>;

/// Latin hypercube: in every dimension, the N values fall one in each of the N strata
/// [k/N, (k+1)/N), at a uniform position inside it, strata permuted independently.
UnitPoints latin_hypercube(std::size_t n, std::size_t d, std::uint64_t seed);

/// The first N points of the Sobol' sequence with Joe–Kuo direction numbers (Boost.Random's
/// `sobol_engine`, starting with the origin as the sequence does). With `scramble`, each
/// coordinate is Owen-scrambled (nested uniform scrambling, the hash-based form of Burley
/// 2020, JCGT 9(4)) with a per-dimension seed drawn from `seed`: the points stay a (t, m, s)-net
/// in base 2 but are no longer on the dyadic grid.
UnitPoints sobol_points(std::size_t n, std::size_t d, bool scramble, std::uint64_t seed);

/// The Saltelli (2010) design: two independent N × d matrices A and B (the two halves of a
/// 2d-dimensional Sobol' sequence) and, for each dimension i, A_B^(i) = A with column i from
/// B. Rows are grouped by sample: for j = 0 … N−1 the d + 2 rows A_j, B_j, A_B^(1)_j, …,
/// A_B^(d)_j, so N(d + 2) points in all.
struct SaltelliDesign {
  std::size_t n = 0, d = 0;
  UnitPoints points;                ///< N(d + 2) rows of d values
  /// Row r belongs to sample r / (d + 2), block r % (d + 2): 0 = A, 1 = B, 2 + i = A_B^(i).
  static std::size_t block(std::size_t row, std::size_t d) { return row % (d + 2); }
  static std::size_t sample(std::size_t row, std::size_t d) { return row / (d + 2); }
};
SaltelliDesign saltelli_design(std::size_t n, std::size_t d, bool scramble, std::uint64_t seed);

}  // namespace pcrf::study
