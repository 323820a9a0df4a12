// The error metrics: distances of body points (metres and pixels), orientation angles, energy
// drift over contact-free stretches, and the in-order alignment of bounces.
#include "../../../src/study/run_comparison.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tumble::study {
namespace {

BodySample body(const Vec3& centre, double energy = 0.0, bool touching = false) {
  BodySample s;
  for (const Vec3& corner : {Vec3(-0.5, 0, 0), Vec3(0.5, 0, 0)}) {
    s.points.push_back(centre + corner);
    s.pixels.emplace_back(Eigen::Vector2d(100.0 * (centre + corner).x(), 0.0));
  }
  s.energy_J = energy;
  s.touching = touching;
  return s;
}

RunRecord record(const std::vector<BodySample>& samples) {
  RunRecord r;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    r.times.push_back(static_cast<double>(k));
    r.samples.push_back({samples[k]});
  }
  r.rest_speed_mps = {0.01};
  return r;
}

TEST(RunErrors, LargestPointDistanceOverAllSamples) {
  const RunRecord ref = record({body(Vec3(0, 1, 0)), body(Vec3(0, 2, 0)), body(Vec3(0, 3, 0))});
  const RunRecord run = record({body(Vec3(0, 1, 0)), body(Vec3(0.3, 2.4, 0)), body(Vec3(0, 3, 0))});
  const RunErrors e = compare_runs(run, ref, 1.0);
  EXPECT_DOUBLE_EQ(e.position_m, 0.5);  // (0.3, 0.4): a 3-4-5 triangle
  EXPECT_DOUBLE_EQ(e.pixel_px, 30.0);   // only x is on screen here, 100 px per metre
  EXPECT_EQ(e.orientation_rad, 0.0);
}

TEST(RunErrors, PointsBehindTheCameraAreLeftOut) {
  RunRecord ref = record({body(Vec3(0, 1, 0))});
  RunRecord run = record({body(Vec3(5, 1, 0))});
  run.samples[0][0].pixels = {std::nullopt, std::nullopt};
  EXPECT_EQ(compare_runs(run, ref, 1.0).pixel_px, 0.0);
  EXPECT_EQ(compare_runs(run, ref, 1.0).position_m, 5.0);
}

TEST(RunErrors, OrientationAsTheGeodesicAngle) {
  const Quat a(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
  const Quat b(Eigen::AngleAxisd(-0.2, Vec3::UnitZ()));
  EXPECT_NEAR(angle_between(a, b), 0.5, 1e-15);
  // q and -q are one rotation; tiny angles keep their digits.
  EXPECT_NEAR(angle_between(a, Quat(-a.coeffs())), 0.0, 1e-15);
  const Quat tiny(Eigen::AngleAxisd(1e-12, Vec3::UnitX()));
  EXPECT_NEAR(angle_between(Quat::Identity(), tiny), 1e-12, 1e-24);
}

TEST(EnergyDrift, MeasuredOverContactFreeStretchesOnly) {
  // Energies 10, 10.1, 10.3 | touching (a contact removes 5 J) | 5, 5.05. Scale: K₀ + m g ℓ with
  // K₀ = 0 here and m g ℓ = 10, so the first stretch drifts 0.3/10 and the second 0.05/10; the
  // jump across the contact does not count.
  RunRecord r =
      record({body(Vec3::Zero(), 10.0), body(Vec3::Zero(), 10.1), body(Vec3::Zero(), 10.3),
              body(Vec3::Zero(), 7.0, true), body(Vec3::Zero(), 5.0), body(Vec3::Zero(), 5.05)});
  EXPECT_NEAR(energy_drift(r, {10.0}), 0.03, 1e-15);
  // An impact between samples 1 and 2 splits the first stretch too: 0.1/10 and then 0.
  r.events.push_back({1.5, 0, 1.0});
  EXPECT_NEAR(energy_drift(r, {10.0}), 0.01, 1e-15);
}

TEST(BounceMatch, LateBouncesArePairedInOrder) {
  const BounceMatch m = match_bounces({1.1, 2.1, 3.1}, {1.0, 2.0, 3.0}, 1.0 / 60.0 * 10);
  EXPECT_EQ(m.matched, 3);
  EXPECT_EQ(m.missed + m.extra, 0);
  EXPECT_NEAR(*m.largest_dt_s, 0.1, 1e-12);
}

TEST(BounceMatch, AMissedBounceDoesNotShiftTheOthers) {
  // The run misses the reference's bounce at 2.0; pairing by index would pair 3.0 with 2.0 and
  // 4.0 with 3.0 (Δt = 1 s). The alignment skips it.
  const BounceMatch m = match_bounces({1.0, 3.0, 4.0, 5.0}, {1.0, 2.0, 3.0, 4.0, 5.0}, 1.0 / 60.0);
  EXPECT_EQ(m.matched, 4);
  EXPECT_EQ(m.missed, 1);
  EXPECT_EQ(m.extra, 0);
  EXPECT_EQ(*m.largest_dt_s, 0.0);
  const BounceMatch extra = match_bounces({1.0, 1.5, 2.0}, {1.0, 2.0}, 1.0 / 60.0);
  EXPECT_EQ(extra.extra, 1);
  EXPECT_EQ(extra.missed, 0);
  EXPECT_FALSE(match_bounces({}, {}, 1.0).largest_dt_s.has_value());
}

TEST(BounceMatch, OnlyBouncesFasterThanBothRestSpeedsCount) {
  RunRecord ref = record({body(Vec3::Zero())});
  RunRecord run = ref;
  ref.rest_speed_mps = {0.01};
  run.rest_speed_mps = {0.1};                    // a coarser dt: its rest speed 2 g dt is higher
  ref.events = {{0.5, 0, 2.0}, {0.7, 0, 0.05}};  // the second is inelastic at the run's dt
  run.events = {{0.51, 0, 2.0}};
  const RunErrors e = compare_runs(run, ref, 1.0 / 60.0);
  EXPECT_EQ(e.bounces, 1);
  EXPECT_EQ(e.missed, 0);
  EXPECT_NEAR(*e.impact_time_s, 0.01, 1e-15);
}

TEST(BounceMatch, ImpactsAreMatchedPairByPair) {
  // Two bodies. The reference has body 1 hit body 0 at 0.5 s, then the floor at 0.8 s; the run
  // has body 1 hit the floor at 0.5 s instead (it missed its neighbour), then the floor at 0.8 s.
  // Matched per body the times would line up; matched per pair, the run misses the body–body
  // impact and adds a floor one.
  RunRecord ref = record({body(Vec3::Zero())});
  ref.rest_speed_mps = {0.01, 0.01};
  RunRecord run = ref;
  ref.events = {{0.5, 1, 2.0, 0}, {0.8, 1, 2.0, kFloorBody}};
  run.events = {{0.5, 1, 2.0, kFloorBody}, {0.8, 1, 2.0, kFloorBody}};
  const RunErrors e = compare_runs(run, ref, 0.1);
  EXPECT_EQ(e.bounces, 2);
  EXPECT_EQ(e.missed, 1);
  EXPECT_EQ(e.extra, 1);
  // Either side may record a body–body impact: (body 0, other 1) is the same pair as (1, 0).
  run.events = {{0.5, 0, 2.0, 1}, {0.8, 1, 2.0, kFloorBody}};
  const RunErrors same = compare_runs(run, ref, 0.1);
  EXPECT_EQ(same.missed, 0);
  EXPECT_EQ(same.extra, 0);
  EXPECT_NEAR(*same.impact_time_s, 0.0, 1e-15);
}

}  // namespace
}  // namespace tumble::study
