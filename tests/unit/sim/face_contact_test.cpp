// The resting-face fast path (a frictionless body, or one sliding without turning, held on >= 3
// points gets its contact wrench from a 3×3 solve instead of the LCP) against the general LCP,
// which stays the reference: the same motion to round-off, on a face, sliding with friction,
// through tipping, and across a whole drop.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_fixtures.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

WorldDef spinning_on_a_face(bool general) {
  WorldDef def = test::world_def(Integrator::Rk4, 1e-5, true);
  def.general_contact_only = general;
  BodyDef b = test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 0.5, 0));
  b.velocity = Vec3(1.0, 0.0, 0.5);
  b.angular_velocity = Vec3(0.0, 1.0, 0.0);
  def.bodies.push_back(b);
  return def;
}

TEST(FaceContact, SpinningOnAFaceMatchesTheGeneralLcp) {
  // 2·10^4 steps (0.2 s) of a box sliding and spinning on its face: the face stays on the floor, so
  // the wrench is N = m g at the centre; both paths give that to round-off (1e-12 m, 1e-12
  // rad/s), and the box neither sinks nor lifts.
  World fast(spinning_on_a_face(false)), general(spinning_on_a_face(true));
  for (int i = 0; i < 20000; ++i) {
    fast.step();
    general.step();
  }
  const RigidBody &a = fast.bodies()[0], &b = general.bodies()[0];
  EXPECT_LT((a.state.x - b.state.x).norm(), 1e-12);
  EXPECT_LT((a.angular_velocity() - b.angular_velocity()).norm(), 1e-12);
  EXPECT_NEAR(a.state.x.y(), 0.5, 1e-9);
  EXPECT_NEAR(a.state.x.x(), 0.2, 1e-9);  // v = (1, 0, 0.5) for 0.2 s, frictionless
  EXPECT_NEAR(a.angular_velocity().y(), 1.0, 1e-9);
  // And it is the cheap path: the same evaluations, far less work per evaluation (bench_step).
  EXPECT_EQ(fast.derivative_evaluations(), general.derivative_evaluations());
}

TEST(FaceContact, SlidingWithFrictionMatchesTheGeneralLcp) {
  // A face sliding without turning, mu = 0.5: every point's force acts along the same n − mu û,
  // so the wrench is again a 3×3 solve. 0.3 s at dt = 1e-5 (it slides 0.88 m of its 1.15 m):
  // the same motion to round-off, decelerating at mu g, and the face neither sinks nor lifts.
  auto run = [](bool general) {
    WorldDef def = test::world_def(Integrator::Rk4, 1e-5, true);
    def.general_contact_only = general;
    def.floor->friction = 0.5;
    BodyDef b = test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 0.5, 0));
    b.velocity = Vec3(3.0, 0.0, 1.5);
    def.bodies.push_back(b);
    World w(def);
    for (int i = 0; i < 30000; ++i) w.step();
    return w;
  };
  const World fast = run(false), general = run(true);
  const RigidBody &a = fast.bodies()[0], &g = general.bodies()[0];
  EXPECT_LT((a.state.x - g.state.x).norm(), 1e-12);
  EXPECT_LT((a.velocity() - g.velocity()).norm(), 1e-12);
  EXPECT_LT(a.angular_velocity().norm(), 1e-12);
  EXPECT_NEAR(a.state.x.y(), 0.5, 1e-12);
  const double v0 = std::hypot(3.0, 1.5), t = fast.time();
  EXPECT_NEAR(a.velocity().norm(), v0 - 0.5 * 9.81 * t, 1e-9);
  EXPECT_EQ(fast.derivative_evaluations(), general.derivative_evaluations());
}

TEST(FaceContact, WholeDropMatchesTheGeneralLcp) {
  // The default drop: corner and edge impacts, rocking (2-point sets: LCP), landing on a face
  // (4 points: the fast path) and rest. Round-off differences are amplified by the chaotic
  // rocking phase; the tolerance, 1e-8 m, is that of the other same-physics comparisons.
  for (Integrator integrator : {Integrator::Rk4, Integrator::Midpoint, Integrator::Adaptive}) {
    World w[2] = {
        World([&] {
          WorldDef def = test::world_def(integrator, 0.001, true);
          BodyDef b = test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 3, 0));
          b.orientation = Quat(Eigen::AngleAxisd(radians(30.0), Vec3(1, 0, 1).normalized()));
          b.angular_velocity = Vec3(0, 0, 2);
          def.bodies.push_back(b);
          return def;
        }()),
        World([&] {
          WorldDef def = test::world_def(integrator, 0.001, true);
          def.general_contact_only = true;
          BodyDef b = test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 3, 0));
          b.orientation = Quat(Eigen::AngleAxisd(radians(30.0), Vec3(1, 0, 1).normalized()));
          b.angular_velocity = Vec3(0, 0, 2);
          def.bodies.push_back(b);
          return def;
        }())};
    double worst = 0.0;
    for (int i = 0; i < 4000; ++i) {
      w[0].step();
      w[1].step();
      worst = std::max(worst, (w[0].bodies()[0].state.x - w[1].bodies()[0].state.x).norm());
    }
    EXPECT_LT(worst, 1e-8) << to_string(integrator);
    EXPECT_EQ(w[0].bodies()[0].at_rest, w[1].bodies()[0].at_rest) << to_string(integrator);
  }
}

TEST(FaceContact, TippingBoxLeavesTheFastPathToTheLcp) {
  // A box on its face pushed by a strong spin about a horizontal axis: the required centre of
  // pressure leaves the face, the wrench is refused, and the LCP lets an edge lift — as the
  // general path does.
  auto run = [](bool general) {
    WorldDef def = test::world_def(Integrator::Rk4, 1e-4, true);
    def.general_contact_only = general;
    BodyDef b = test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 0.5, 0));
    b.angular_velocity = Vec3(0.0, 0.0, 6.0);
    def.bodies.push_back(b);
    World w(def);
    for (int i = 0; i < 5000; ++i) w.step();
    return w;
  };
  const World fast = run(false), general = run(true);
  EXPECT_LT((fast.bodies()[0].state.x - general.bodies()[0].state.x).norm(), 1e-9);
  EXPECT_GT(fast.contact_stats().impacts, 0);  // it tipped over and landed again
}

}  // namespace
}  // namespace tumble
