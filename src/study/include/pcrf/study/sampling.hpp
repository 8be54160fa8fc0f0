/// \file sampling.hpp
/// \brief Sampling plans over the unit hypercube [0, 1)^d: Latin hypercube, Sobol'
/// low-discrepancy points (optionally Owen-scrambled), and the Saltelli design for Sobol'
/// sensitivity indices. Pure functions of (N, d, seed): the same call gives the same points.
///
/// Each design is evaluable by index (LatinHypercube, SobolSequence, SaltelliRows): point j's
/// coordinate i is computed from (j, i) with nothing held per point, so that a plan of 10^8
/// frames holds a few hundred bytes (issue 38). The whole-matrix functions below are those
/// designs evaluated at every index.
///
/// Each design also fills a run of one coordinate at once (`column`): the values of `at` for
/// consecutive indices, bit for bit, computed in a tight loop (the worker that seals a unit of
/// the cube asks for its chunk of a coordinate, 16 384 values, cube::coordinate_chunk_values).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pcrf::study {

/// N points, row-major: point j, dimension i at [j * d + i].
using UnitPoints = std::vector<double>;

/// A bijection of [0, n) evaluable by index: a balanced Feistel network (Luby and Rackoff
/// 1988: four rounds of pseudorandom round functions make a pseudorandom permutation) on the
/// smallest even number of bits that holds n, its round function a keyed 64-bit mixer
/// (splitmix64's finaliser), restricted to [0, n) by cycle-walking (Black and Rogaway 2002,
/// "Ciphers with arbitrary finite domains", CT-RSA: apply the permutation of the larger
/// domain again until the value falls in [0, n); fewer than 4 applications on average, as the
/// larger domain is under 4n). Every operation is invertible, so the result is a bijection.
class IndexPermutation {
 public:
  /// The permutation of [0, n) chosen by `key` (n >= 1).
  IndexPermutation(std::uint64_t n, std::uint64_t key);
  /// The image of j < n.
  std::uint64_t operator()(std::uint64_t j) const;
  /// The images of first, first + 1, … into out (first + out.size() <= n), the same values,
  /// their encryptions computed in lanes (AVX2 where the CPU has it): 25 to 27 instructions
  /// an encryption instead of 72, measured with callgrind in a study (issue 38).
  void images(std::uint64_t first, std::span<std::uint64_t> out) const;
  /// The image of j under each of `permutations`, all of one n, into out (as many), the
  /// first encryptions in lanes likewise (36 instructions each for 8 of them): for a point
  /// of 8 dimensions, 495 instructions instead of 624 at n = 2^18, 1107 instead of 1220 at
  /// n = 2^17 (cycle-walking twice on average).
  static void images_of(std::uint64_t j, std::span<const IndexPermutation> permutations, std::span<std::uint64_t> out);

 private:
  static constexpr int kRounds = 4;
  std::uint64_t n_ = 1;
  unsigned half_bits_ = 1;
  std::uint64_t half_mask_ = 1;
  std::array<std::uint64_t, kRounds> round_keys_{};
  std::uint64_t encrypt(std::uint64_t x) const;  // on [0, 4^half_bits)
};

/// A counter-based hash (splitmix64's finaliser over a sequence of words): a uniform 64-bit
/// value from (seed, a, b), the same on every machine.
std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t a, std::uint64_t b);

/// Latin hypercube evaluable by index: in dimension i, point j lies in stratum
/// π_i(j) (IndexPermutation keyed by (seed, i)), at a position inside it drawn by
/// counter_hash(seed_i, seed, j) with seed_i = counter_hash(seed, "LHS", i): the N values of
/// every dimension fall one in each of the N strata [k/N, (k+1)/N). Defined in issue 38
/// (before it, an mt19937_64 shuffle that had to hold every point: the points differ, and
/// the fingerprint says which construction drew them).
class LatinHypercube {
 public:
  LatinHypercube(std::uint64_t n, std::size_t d, std::uint64_t seed);
  std::uint64_t size() const { return n_; }
  std::size_t dimensions() const { return permutations_.size(); }
  /// The stratum of point j in dimension i: a value in [0, N), each taken once over j.
  std::uint64_t stratum(std::uint64_t j, std::size_t i) const { return permutations_[i](j); }
  /// Point j's unit coordinate i, in [stratum/N, (stratum+1)/N).
  double at(std::uint64_t j, std::size_t i) const;
  /// at(first + m, i) into out[m] for every m (first + out.size() <= N).
  void column(std::size_t i, std::uint64_t first, std::span<double> out) const;
  /// at(j, first + s) into out[s] for every s (first + out.size() <= dimensions()).
  void row(std::uint64_t j, std::size_t first, std::span<double> out) const;

 private:
  std::uint64_t n_;
  std::vector<IndexPermutation> permutations_;
  /// Per dimension, the jitter hash's state after its first two words (seed_i, seed): the
  /// same for every j, so each value mixes once, not three times (issue 38: a third of the
  /// 300 instructions a value cost at the cube's creation went to those two mixes).
  std::vector<std::uint64_t> jitter_states_;
};

/// The Sobol' sequence of UnitPoints sobol_points (the same bits), evaluable by index: point
/// j is the XOR of the direction numbers v_r over the bits r of j's Gray code (Antonov and
/// Saleev 1979, the order Boost.Random's engine steps through), the direction numbers read
/// from Boost's engine once.
class SobolSequence {
 public:
  SobolSequence(std::size_t d, bool scramble, std::uint64_t seed);
  std::size_t dimensions() const { return seeds_.size(); }
  /// Point j's unit coordinate i (j < 2^32).
  double at(std::uint64_t j, std::size_t i) const;
  /// at(first + m, i) into out[m] for every m (first + out.size() <= 2^32).
  void column(std::size_t i, std::uint64_t first, std::span<double> out) const;

 private:
  std::vector<std::array<std::uint32_t, 32>> directions_;  ///< per dimension, v_0 … v_31
  std::vector<std::uint32_t> seeds_;                       ///< per dimension; used when scrambled
  bool scramble_ = false;
  std::uint32_t unscrambled(std::uint64_t j, std::size_t i) const;  ///< the XOR of v_r over gray(j)
  double unit(std::uint32_t unscrambled, std::size_t i) const;     ///< scrambled when asked, in [0, 1)
};

/// Latin hypercube: in every dimension, the N values fall one in each of the N strata
/// [k/N, (k+1)/N), at a uniform position inside it, strata permuted independently
/// (LatinHypercube at every index).
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

/// The rows of saltelli_design evaluable by index (the same values): row r's coordinate i is
/// the 2d-dimensional Sobol' point r / (d + 2)'s coordinate i (from A) or d + i (from B).
class SaltelliRows {
 public:
  SaltelliRows(std::size_t d, bool scramble, std::uint64_t seed) : d_(d), base_(2 * d, scramble, seed) {}
  double at(std::uint64_t row, std::size_t i) const {
    const std::uint64_t j = row / (d_ + 2), block = row % (d_ + 2);
    const bool from_b = block == 1 || (block >= 2 && i == block - 2);
    return base_.at(j, from_b ? d_ + i : i);
  }
  /// at(first + m, i) into out[m] for every m.
  void column(std::size_t i, std::uint64_t first, std::span<double> out) const;

 private:
  std::size_t d_;
  SobolSequence base_;
};

}  // namespace pcrf::study
