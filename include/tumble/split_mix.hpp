#pragma once
/// The random numbers of `tumble sweep`, defined here to the bit so that a plan gives the same
/// jobs on every machine and with every standard library (`std::*_distribution` differ between
/// them). The generator is SplitMix64 (Steele, Lea, Flood 2014: "Fast splittable pseudorandom
/// number generators"; the constants of Vigna's reference `splitmix64.c`). Each (plan seed, job
/// index, key index) owns one stream; see docs/sweeps.md for the definitions in full.

#include <cstdint>

namespace tumble {

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t state) : state_(state) {}

  /// The stream of key `key` of job `job` of a plan seeded `seed`: the state is
  /// mix(mix(mix(seed) ^ job) ^ key), mix being one SplitMix64 output from that state.
  static SplitMix64 stream(std::uint64_t seed, std::uint64_t job, std::uint64_t key);

  /// The next 64 random bits: state += 0x9e3779b97f4a7c15, then the mixing function.
  std::uint64_t next();
  /// A double in [0, 1): the top 53 bits of next() times 2^-53 (exact, every value equally likely).
  double uniform01();
  /// a + (b - a) * uniform01(): in [a, b) for a < b, exactly a for a == b.
  double uniform(double a, double b);
  /// Box–Muller: mean + sd * sqrt(-2 ln u1) * cos(2 pi u2), u1 = 1 - uniform01() in (0, 1],
  /// u2 = uniform01(); two draws per value. Uses the C library's log, cos and sqrt (sqrt is exact
  /// IEEE; glibc's log and cos are correctly rounded in practice), nothing else.
  double normal(double mean, double sd);
  /// An integer in [a, b], each equally likely: next() mod (b - a + 1), redrawn when it falls in
  /// the incomplete last block of 2^64 (so there is no bias). Requires a <= b.
  std::int64_t integer(std::int64_t a, std::int64_t b);

 private:
  std::uint64_t state_;
};

}  // namespace tumble
