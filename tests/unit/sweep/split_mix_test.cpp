// The sweep's generator is defined to the bit: these tests pin it to SplitMix64's published
// outputs and to its own definitions, so a plan draws the same values on every machine.
#include "tumble/split_mix.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace tumble {
namespace {

TEST(SplitMix64, MatchesTheReferenceOutputsForSeed1234567) {
  // The first outputs of Vigna's splitmix64.c seeded with 1234567 (the usual test vector).
  SplitMix64 random(1234567);
  const std::vector<std::uint64_t> expected = {6457827717110365317ULL, 3203168211198807973ULL,
                                               9817491932198370423ULL, 4593380528125082431ULL,
                                               16408922859458223821ULL};
  for (const std::uint64_t e : expected) EXPECT_EQ(random.next(), e);
}

TEST(SplitMix64, StreamIsThreeChainedOutputsOfSeedJobAndKey) {
  const auto first = [](std::uint64_t s) { return SplitMix64(s).next(); };
  for (const std::uint64_t job : {0ULL, 1ULL, 99ULL}) {
    SplitMix64 a = SplitMix64::stream(7, job, 2);
    SplitMix64 b(first(first(first(7) ^ job) ^ 2));
    for (int i = 0; i < 4; ++i) EXPECT_EQ(a.next(), b.next());
  }
}

TEST(SplitMix64, UniformIsTheTop53BitsScaledExactly) {
  SplitMix64 bits(42), draws(42);
  for (int i = 0; i < 100; ++i) {
    const double u = static_cast<double>(bits.next() >> 11) / 9007199254740992.0;  // 2^53
    EXPECT_EQ(draws.uniform01(), u);  // exact: both are k * 2^-53
  }
}

TEST(SplitMix64, FixedDrawsOfAPlanStream) {
  // docs/sweeps.md's example (seed 7, "body.box.orientation.degrees" = { uniform = [0, 90] }),
  // jobs 0, 1 and 2, and key 1 of job 0. The expected values come from an independent Python
  // implementation of the definitions (docs/sweeps.md); uniform draws need no libm, so these are
  // the same bits on every IEEE-754 machine: compared exactly.
  EXPECT_EQ(SplitMix64::stream(7, 0, 0).next(), 0x2bf6f81349ecc50eULL);
  EXPECT_EQ(SplitMix64::stream(7, 0, 0).uniform(0.0, 90.0), 15.456347869706617);
  EXPECT_EQ(SplitMix64::stream(7, 1, 0).uniform(0.0, 90.0), 17.769376478204183);
  EXPECT_EQ(SplitMix64::stream(7, 2, 0).uniform(0.0, 90.0), 38.31701425325208);
  EXPECT_EQ(SplitMix64::stream(7, 0, 1).uniform(0.0, 90.0), 1.5593578484652415);
}

TEST(SplitMix64, UniformMeanAndRangeOn100kDraws) {
  SplitMix64 random(1);
  double sum = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double x = random.uniform(-2.0, 6.0);
    ASSERT_GE(x, -2.0);
    ASSERT_LT(x, 6.0);
    sum += x;
  }
  // The mean is 2, the standard error 8/sqrt(12)/sqrt(1e5) = 0.0073: 5 sigma is 0.037.
  EXPECT_NEAR(sum / 100000.0, 2.0, 0.037);
}

TEST(SplitMix64, NormalMomentsOn100kDraws) {
  SplitMix64 random(3);
  double sum = 0.0, squares = 0.0;
  constexpr int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double x = random.normal(1.5, 0.5);
    ASSERT_TRUE(std::isfinite(x));
    sum += x;
    squares += x * x;
  }
  const double mean = sum / n, sd = std::sqrt(squares / n - mean * mean);
  // Standard errors: 0.5/sqrt(n) = 0.0016 for the mean, about 0.5/sqrt(2n) = 0.0011 for the
  // sd; 5 sigma each.
  EXPECT_NEAR(mean, 1.5, 0.008);
  EXPECT_NEAR(sd, 0.5, 0.0056);
}

TEST(SplitMix64, IntegerCoversItsClosedRangeEvenly) {
  SplitMix64 random(5);
  std::vector<int> counts(7, 0);
  constexpr int n = 70000;
  for (int i = 0; i < n; ++i) {
    const std::int64_t k = random.integer(-3, 3);
    ASSERT_GE(k, -3);
    ASSERT_LE(k, 3);
    ++counts[static_cast<std::size_t>(k + 3)];
  }
  // Each count is binomial(n, 1/7): mean 10000, sd 92.6; 5 sigma is 463.
  for (const int c : counts) EXPECT_NEAR(c, 10000, 463);
  EXPECT_EQ(random.integer(4, 4), 4);
  SplitMix64 full(9), bits(9);
  EXPECT_EQ(static_cast<std::uint64_t>(full.integer(INT64_MIN, INT64_MAX)), bits.next());
}

}  // namespace
}  // namespace tumble
