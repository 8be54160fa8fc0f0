// The Feistel network of IndexPermutation (pcrf/study/sampling.hpp), written once for the
// one-value path (sampling.cpp) and for the lanes compiled with another instruction set
// (feistel_avx2.cpp). The functions have internal linkage: each translation unit keeps its
// own copy, built with its own flags, so no AVX2 copy can stand in where the CPU lacks it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace pcrf::study::detail {

/// A permutation's round keys (four rounds: Luby and Rackoff's pseudorandom permutation).
using FeistelKeys = std::array<std::uint64_t, 4>;

/// splitmix64's finaliser (Steele, Lea and Flood 2014): a bijective 64-bit mixer.
static inline std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  x ^= x >> 31;
  return x;
}

/// One encryption of x < 4^half_bits: four balanced rounds on its halves.
static inline std::uint64_t feistel_encrypt(std::uint64_t x, const FeistelKeys& keys, unsigned half_bits,
                                            std::uint64_t half_mask) {
  std::uint64_t left = x >> half_bits, right = x & half_mask;
  for (const std::uint64_t k : keys) {
    const std::uint64_t next = (left ^ mix64(right ^ k)) & half_mask;
    left = right;
    right = next;
  }
  return (left << half_bits) | right;
}

/// x[m] = feistel_encrypt(x[m], …) for every m: a loop with no branch, which the compiler
/// vectorises where the instruction set has the lanes for it.
static inline void feistel_encrypt_each(std::span<std::uint64_t> x, const FeistelKeys& keys, unsigned half_bits,
                                        std::uint64_t half_mask) {
  for (std::uint64_t& value : x) value = feistel_encrypt(value, keys, half_bits, half_mask);
}

/// x[m] = feistel_encrypt(x[m], keys[m], …) for every m: the values of several permutations
/// of one domain (a Latin hypercube's dimensions at one point), vectorised likewise.
static inline void feistel_encrypt_keyed(std::span<std::uint64_t> x, const FeistelKeys* keys, unsigned half_bits,
                                         std::uint64_t half_mask) {
  for (std::size_t m = 0; m < x.size(); ++m) x[m] = feistel_encrypt(x[m], keys[m], half_bits, half_mask);
}

/// feistel_encrypt_each compiled for AVX2 (feistel_avx2.cpp; only in x86-64 builds, where
/// PCRF_FEISTEL_AVX2 is defined): call it only where the CPU has AVX2.
void feistel_encrypt_each_avx2(std::span<std::uint64_t> x, const FeistelKeys& keys, unsigned half_bits,
                               std::uint64_t half_mask);
/// feistel_encrypt_keyed compiled for AVX2, likewise.
void feistel_encrypt_keyed_avx2(std::span<std::uint64_t> x, const FeistelKeys* keys, unsigned half_bits,
                                std::uint64_t half_mask);

}  // namespace pcrf::study::detail
