#include "../../../src/sim/time_of_impact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tumble {
namespace {

// A "state" is its time; its gap a function of it. `trials` counts the integrations a search
// would have made.
struct Info {
  int unused = 0;
};
struct Search {
  double lo = 0.0, at_lo = 0.0;
  Info info;
  int trials = 0;
  bool located = false;
};

template <class Gap>
Search run(double hi, double width, double noise, bool at_touch, const Gap& gap) {
  Search s;
  auto advance = [&](double t, Info*) {
    ++s.trials;
    return t;
  };
  s.located = locate_impact(s.lo, hi, std::max(gap(0.0), 0.0), gap(hi), width, noise, s.at_lo,
                            s.info, advance, gap, at_touch);
  return s;
}

constexpr double kNoise = 32.0 * std::numeric_limits<double>::epsilon() * 1.0;

// A corner coming down at 1e-5 m/s, 1.37e-8 m above the face where a 2 ms bracket starts: it
// touches 1.37 ms in. Without the stop at touch the bracket must shrink to 1.4e-13 s.
TEST(TimeOfImpact, ASlowApproachIsLocatedWhereItTouchesToRoundOffInFewTrials) {
  const double v = 1e-5, t_star = 1.37e-3;
  auto gap = [&](double t) { return v * (t_star - t); };
  const Search narrow = run(2e-3, 1.4e-13, kNoise, false, gap);
  const Search touch = run(2e-3, 1.4e-13, kNoise, true, gap);
  ASSERT_TRUE(narrow.located);
  ASSERT_TRUE(touch.located);
  // Both end not across, touching to round-off: the same place to within the noise.
  EXPECT_GE(gap(touch.lo), -kNoise);
  EXPECT_LE(gap(touch.lo), kNoise);
  EXPECT_NEAR(touch.lo, t_star, kNoise / v);
  EXPECT_NEAR(narrow.lo, t_star, 1.4e-13 + kNoise / v);
  EXPECT_LT(touch.trials, narrow.trials);
  EXPECT_LE(touch.trials, 8);
}

// A gap that starts at zero may be flat there (a vertex resting while another goes in): the
// search must not stop on the flat part, but find where the gap really goes below.
TEST(TimeOfImpact, AGapThatStartsAtZeroKeepsToTheBracketsWidth) {
  const double t_star = 1.2e-3;
  auto gap = [&](double t) { return t < t_star ? 0.0 : -0.5 * (t - t_star); };
  const Search s = run(2e-3, 1e-13, kNoise, true, gap);
  ASSERT_TRUE(s.located);
  EXPECT_NEAR(s.lo, t_star, 2e-13);
}

// A fast approach is located to the bracket's width as before, at_touch or not: the same time.
TEST(TimeOfImpact, AFastApproachIsLocatedAsBefore) {
  const double v = 3.0, t_star = 0.7e-3;
  auto gap = [&](double t) { return v * (t_star - t) + 0.2 * (t_star - t) * (t_star - t); };
  const Search a = run(1e-3, 1e-12, kNoise, false, gap);
  const Search b = run(1e-3, 1e-12, kNoise, true, gap);
  ASSERT_TRUE(a.located);
  ASSERT_TRUE(b.located);
  EXPECT_NEAR(a.lo, t_star, 1e-12);
  EXPECT_NEAR(b.lo, t_star, 1e-12);
  EXPECT_GE(gap(b.lo), -kNoise);
}

// The island step's path: the integrator's gap is the curve's off by its error (here 3e-14 m,
// a die's 1e-13 of its size over a stretch) and the curve's crossing is the guess. A slow corner
// (1e-3 m/s) and a fast one (2 m/s) are located as the plain search locates them, in two or
// three trials, fewer than it takes even on a gap this nearly straight (seven and four; 8.9 on
// average in a pile of dice); a guess off the bracket, or a wrong slope, falls back on it.
TEST(TimeOfImpact, AGuessFromTheCurveLocatesTheCrossingInTwoOrThreeTrials) {
  for (const double v : {1e-3, 2.0}) {
    const double t_star = 1.37e-3, error = 3e-14, width = 1.4e-13;
    auto curve = [&](double t) { return v * (t_star - t) + 0.1 * (t_star - t) * (t_star - t); };
    auto gap = [&](double t) { return curve(t) + error; };
    const Search plain = run(2e-3, width, kNoise, true, gap);
    Search guided;
    auto advance = [&](double t, Info*) {
      ++guided.trials;
      return t;
    };
    const double guess = t_star, slope = (curve(t_star + 1e-6) - curve(t_star - 1e-6)) / 2e-6;
    guided.located =
        locate_impact_from_guess(guided.lo, 2e-3, gap(0.0), gap(2e-3), width, kNoise,
                                 guided.at_lo, guided.info, advance, gap, guess, slope, true);
    ASSERT_TRUE(plain.located);
    ASSERT_TRUE(guided.located);
    EXPECT_GE(gap(guided.lo), -kNoise) << v;
    EXPECT_NEAR(guided.lo, plain.lo, width + kNoise / v) << v;
    EXPECT_LE(guided.trials, 3) << v;
    EXPECT_LT(guided.trials, plain.trials) << v;
    for (const auto& [bad_guess, bad_slope] : {std::pair(3e-3, slope), std::pair(guess, -slope)}) {
      Search fallback;
      auto count = [&](double t, Info*) {
        ++fallback.trials;
        return t;
      };
      fallback.located =
          locate_impact_from_guess(fallback.lo, 2e-3, gap(0.0), gap(2e-3), width, kNoise,
                                   fallback.at_lo, fallback.info, count, gap, bad_guess,
                                   bad_slope, true);
      ASSERT_TRUE(fallback.located) << v;
      EXPECT_GE(gap(fallback.lo), -kNoise) << v;
      EXPECT_NEAR(fallback.lo, t_star + error / v, width + kNoise / v) << v;
    }
  }
}

}  // namespace
}  // namespace tumble
