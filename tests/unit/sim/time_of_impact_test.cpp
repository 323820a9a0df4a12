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

}  // namespace
}  // namespace tumble
