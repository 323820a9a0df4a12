#include "tumble/split_mix.hpp"

#include <cassert>
#include <cmath>
#include <numbers>

namespace tumble {
namespace {

// SplitMix64's output function (Vigna's splitmix64.c): a bijection on 64 bits that mixes every
// input bit into every output bit.
std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ULL;  // 2^64 / golden ratio, odd

// One SplitMix64 output from `state`: what SplitMix64(state).next() returns.
std::uint64_t first_output(std::uint64_t state) {
  return mix(state + kGolden);
}

}  // namespace

SplitMix64 SplitMix64::stream(std::uint64_t seed, std::uint64_t job, std::uint64_t key) {
  // Hashing each coordinate in turn (rather than adding them) keeps streams of neighbouring
  // jobs and keys unrelated: (job 1, key 0) and (job 0, key 1) start far apart.
  return SplitMix64(first_output(first_output(first_output(seed) ^ job) ^ key));
}

std::uint64_t SplitMix64::next() {
  state_ += kGolden;
  return mix(state_);
}

double SplitMix64::uniform01() {
  // 53 bits fill a double's significand exactly: the result is k * 2^-53, k in [0, 2^53).
  return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

double SplitMix64::uniform(double a, double b) {
  return a + (b - a) * uniform01();
}

double SplitMix64::normal(double mean, double sd) {
  // 1 - u is in (0, 1]: the logarithm never sees 0.
  const double u1 = 1.0 - uniform01();
  const double u2 = uniform01();
  return mean + sd * (std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2));
}

std::int64_t SplitMix64::integer(std::int64_t a, std::int64_t b) {
  assert(a <= b);
  // The span as unsigned arithmetic (wraps correctly for any a <= b); 0 means all 2^64 values.
  const std::uint64_t span = static_cast<std::uint64_t>(b) - static_cast<std::uint64_t>(a) + 1;
  if (span == 0) return static_cast<std::int64_t>(next());
  // Values at or above `limit` belong to an incomplete block of `span`: redraw them.
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % span;
  std::uint64_t x = next();
  while (x >= limit) x = next();
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) + x % span);
}

}  // namespace tumble
