// Sampling at exact times never disturbs the fixed-step trajectory, and the state at a time
// depends on that time alone, not on which other times were sampled.
#include "tumble/sampler.hpp"

#include <gtest/gtest.h>

#include "sim_fixtures.hpp"

namespace tumble {
namespace {

WorldDef drop() {
  WorldDef def = test::world_def(Integrator::Rk4, 0.001, /*floor=*/true);
  BodyDef b = test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 3, 0));
  b.orientation = Quat(Eigen::AngleAxisd(0.5, Vec3(1, 0, 1).normalized()));
  b.angular_velocity = Vec3(0, 0, 2);
  def.bodies.push_back(b);
  return def;
}

bool same_bits(const BodyState& a, const BodyState& b) {
  return a.x == b.x && a.q.coeffs() == b.q.coeffs() && a.P == b.P && a.L == b.L;
}

TEST(Sampler, Rates24And60AgreeBitForBitAtCommonTimes) {
  World w24(drop()), w60(drop());
  Sampler s24(w24), s60(w60);
  // Common times of 24 Hz and 60 Hz are k/12: 2k/24 and 5k/60 are the same correctly rounded
  // double. The drop spans flight, impacts and rest within 4 s.
  for (int k = 0; k <= 48; ++k) {
    World a = s24.at((2.0 * k) / 24.0);
    if (k < 48) s24.at((2.0 * k + 1) / 24.0);
    World b = s60.at((5.0 * k) / 60.0);
    for (int j = 1; j < 5 && k < 48; ++j) s60.at((5.0 * k + j) / 60.0);
    ASSERT_TRUE(same_bits(a.bodies()[0].state, b.bodies()[0].state)) << "t = " << k / 12.0;
  }
}

TEST(Sampler, SamplingNeverDisturbsTheSteppedTrajectory) {
  World plain(drop()), sampled(drop());
  Sampler sampler(sampled);
  for (int k = 0; k < 37 * 3; ++k) sampler.at(k / 37.0);  // times off the step grid
  while (plain.step_count() < sampled.step_count()) plain.step();
  EXPECT_TRUE(same_bits(plain.bodies()[0].state, sampled.bodies()[0].state));
  EXPECT_EQ(plain.contact_stats().impacts, sampled.contact_stats().impacts);
}

TEST(Sampler, StepBoundaryTimesAreRecognised) {
  EXPECT_EQ(Sampler::steps_before(0.5, 0.001), 500);  // 0.5/0.001 is not exactly 500 in binary
  EXPECT_EQ(Sampler::steps_before(0.0005, 0.001), 0);
  EXPECT_EQ(Sampler::steps_before(1.0 / 60.0, 0.001), 16);
  EXPECT_EQ(sample_count(4.0, 60.0), 241);
  // k / rate < duration for every k kept, then the end: 1.005 s at 60 Hz is k = 0 … 60 and
  // 1.005 (62 samples; rounding 60.3 would drop t = 1), 1.05 s at 7 Hz is k = 0 … 7 and 1.05.
  EXPECT_EQ(sample_count(1.005, 60.0), 62);
  EXPECT_EQ(sample_count(1.05, 7.0), 9);
  EXPECT_EQ(sample_count(1.01, 60.0), 62);
  EXPECT_EQ(sample_count(1.0, 7.0), 8);
  EXPECT_EQ(sample_count(0.1, 30.0), 4);  // 3 / 30 is 0.1 exactly in binary: not before the end
  EXPECT_EQ(step_count_for(4.0, 0.001), 4000);
  EXPECT_EQ(step_count_for(1.0, 1.0 / 30.0), 30);
}

}  // namespace
}  // namespace tumble
