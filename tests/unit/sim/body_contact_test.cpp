// Bodies that meet each other: impacts located in time and resolved over the bodies they join,
// against the textbook results (collinear and oblique impacts, Newton's cradle), tunnelling,
// and resting contact between bodies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "../../../src/sim/collide.hpp"
#include "sim_fixtures.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

WorldDef space(double dt = 1e-3) {
  WorldDef w = test::world_def(Integrator::Rk4, dt, /*floor=*/false);
  w.gravity = Vec3::Zero();
  return w;
}

Vec3 total_momentum(const World& w) {
  Vec3 p = Vec3::Zero();
  for (const RigidBody& b : w.bodies()) p += b.state.P;
  return p;
}

double kinetic(const World& w) {
  double e = 0.0;
  for (const RigidBody& b : w.bodies()) e += b.energy(Vec3::Zero());
  return e;
}

TEST(PairImpact, HeadOnBoxesExchangeMomentumByNewtonsLaw) {
  // Equal unit boxes face to face, e = 0.5, the left one at v: afterwards v1 = (1 − e) v / 2,
  // v2 = (1 + e) v / 2 (momentum conserved, relative speed reversed times e). The gap of
  // 0.5 m closes at t = 0.5 / v exactly (free flight is exact under rk4).
  WorldDef def = space();
  const double v = 2.0, e = 0.5;
  BodyDef a = test::box_def(Vec3::Ones(), 1.0, Vec3(-1.0, 0, 0));
  a.velocity = Vec3(v, 0, 0);
  a.restitution = e;
  BodyDef b = test::box_def(Vec3::Ones(), 1.0, Vec3(0.5, 0, 0));
  b.restitution = e;
  def.bodies = {a, b};
  World w(def);
  const Vec3 p0 = total_momentum(w);
  while (w.time() < 0.5) w.step();
  ASSERT_EQ(w.contact_stats().impacts, 1);
  const ImpactEvent& hit = w.contact_stats().events.at(0);
  EXPECT_NEAR(hit.t_s, 0.5 / v, 1e-10);  // located to toi_time (1e-12 s) plus round-off
  EXPECT_NEAR(w.bodies()[0].velocity().x(), (1 - e) * v / 2, 1e-12);
  EXPECT_NEAR(w.bodies()[1].velocity().x(), (1 + e) * v / 2, 1e-12);
  for (const RigidBody& body : w.bodies()) EXPECT_LT(body.angular_velocity().norm(), 1e-12);
  EXPECT_LT((total_momentum(w) - p0).norm(), 1e-12 * p0.norm());
  ASSERT_EQ(w.contact_stats().pairs.size(), 1u);
  EXPECT_EQ(w.contact_stats().pairs[0].impacts, 1);
}

TEST(PairImpact, ObliqueElasticSpheresLeaveAtRightAngles) {
  // Equal spheres, elastic, frictionless, impact parameter one radius: the line of centres at
  // impact is 30° off the motion (sin θ = b / 2r), the struck ball leaves along it at v cos 30°
  // and the striker at v sin 30°, at right angles to it.
  WorldDef def = space();
  const double r = 0.1, v = 1.0;
  BodyDef a = test::sphere_def(r, 1.0, Vec3(-1.0, r, 0));
  a.velocity = Vec3(v, 0, 0);
  a.restitution = 1.0;
  BodyDef b = test::sphere_def(r, 1.0, Vec3(0, 0, 0));
  b.restitution = 1.0;
  def.bodies = {a, b};
  World w(def);
  const double e0 = kinetic(w);
  while (w.time() < 1.5) w.step();
  ASSERT_EQ(w.contact_stats().impacts, 1);
  const Vec3 va = w.bodies()[0].velocity(), vb = w.bodies()[1].velocity();
  EXPECT_NEAR(va.dot(vb), 0.0, 1e-12);
  EXPECT_NEAR(vb.norm(), v * std::cos(kPi / 6), 1e-12);
  EXPECT_NEAR(va.norm(), v * std::sin(kPi / 6), 1e-12);
  // Along the line of centres at impact: 30° below the x axis.
  EXPECT_NEAR(std::atan2(vb.y(), vb.x()), -kPi / 6, 1e-9);
  EXPECT_NEAR(kinetic(w), e0, 1e-12 * e0);
  EXPECT_LT(w.bodies()[1].angular_velocity().norm(), 1e-12);  // frictionless: no spin
}

// Five equal elastic balls on the x axis, `in` of them moving at v into the rest. `gap` between
// neighbours (0: touching).
World cradle(int in, double gap) {
  WorldDef def = space();
  const double r = 0.05, v = 1.0;
  for (int i = 0; i < 5; ++i) {
    BodyDef b = test::sphere_def(r, 0.2, Vec3(i * (2 * r + gap) - (i < in ? 0.1 : 0.0), 0, 0));
    b.name = "ball" + std::to_string(i);
    b.restitution = 1.0;
    if (i < in) b.velocity = Vec3(v, 0, 0);
    def.bodies.push_back(b);
  }
  World w(def);
  while (w.time() < 0.3) w.step();
  return w;
}

TEST(NewtonsCradle, OneBallInOneBallOutWithGaps) {
  const World w = cradle(1, 1e-4);
  for (int i = 0; i < 4; ++i) EXPECT_LT(w.bodies()[i].velocity().norm(), 1e-6) << i;
  EXPECT_NEAR(w.bodies()[4].velocity().x(), 1.0, 1e-9);
}

TEST(NewtonsCradle, OneBallInOneBallOutTouching) {
  const World w = cradle(1, 0.0);
  for (int i = 0; i < 4; ++i) EXPECT_LT(w.bodies()[i].velocity().norm(), 1e-6) << i;
  EXPECT_NEAR(w.bodies()[4].velocity().x(), 1.0, 1e-9);
}

TEST(NewtonsCradle, TwoBallsInTwoBallsOut) {
  const World w = cradle(2, 0.0);
  for (int i = 0; i < 3; ++i) EXPECT_LT(w.bodies()[i].velocity().norm(), 1e-6) << i;
  EXPECT_NEAR(w.bodies()[3].velocity().x(), 1.0, 1e-9);
  EXPECT_NEAR(w.bodies()[4].velocity().x(), 1.0, 1e-9);
}

TEST(Tunnelling, FastSpinningSmallBoxBouncesOffAThinWall) {
  // A 1 cm box at 100 m/s spinning at 50 rad/s, dt = 0.01 s: it would cross the 1 cm wall in a
  // tenth of a step. Conservative advancement finds the impact; it bounces back.
  WorldDef def = space(0.01);
  BodyDef box = test::box_def(Vec3::Constant(0.01), 0.001, Vec3(-0.5, 0, 0));
  box.velocity = Vec3(100, 0, 0);
  box.angular_velocity = Vec3(0, 0, 50);
  box.restitution = 0.5;
  def.bodies = {box, test::fixed_box_def(Vec3(0.01, 0.5, 0.5), Vec3(0, 0, 0))};
  World w(def);
  for (int i = 0; i < 20; ++i) w.step();
  EXPECT_GE(w.contact_stats().impacts, 1);
  EXPECT_LT(w.bodies()[0].state.x.x(), -0.005);  // still on its own side
  EXPECT_LT(w.bodies()[0].velocity().x(), 0.0);  // going back
  EXPECT_EQ(w.bodies()[1].state.x, Vec3::Zero());  // the wall never moves
}

TEST(RestingContact, ABallPressedOnASpinningFaceSlidesAsABeadOnARotatingRod) {
  // No gravity. A heavy 1 × 4 × 4 m box spins about z at ω = 2 rad/s; a 0.5 m ball touches its
  // +x face at the face's centre, moving along the face (its frame's −y') at u = 3 m/s, faster
  // than ωR/2 (R = 1 m from the axis), so the face presses it (N/m = −ω²R − 2ω ẏ' > 0).
  // Frictionless, the ball is a bead on a rotating rod: in the face's frame x' = R and
  // ÿ' = ω² y', so y'(t) = −(u/ω) sinh ωt; over 0.5 s it slides 1.76 m of the face's 2.
  // The contact turns with the face at |ṅ| = ω: held without the ball's −r|ṅ|² (its touching
  // point swings with the normal), it was pressed 2 m/s² too little and sank in, an impact every
  // few tens of microseconds.
  const double omega = 2.0, u = 3.0, r = 0.5, R = 0.5 + r;
  WorldDef def = space(1e-3);
  BodyDef box = test::box_def(Vec3(1, 4, 4), 1e9, Vec3::Zero());
  box.angular_velocity = Vec3(0, 0, omega);
  box.friction = 0.0;
  BodyDef ball = test::sphere_def(r, 1.0, Vec3(R, 0, 0));
  ball.velocity = Vec3(0, omega * R - u, 0);
  ball.friction = 0.0;
  def.bodies = {box, ball};
  World w(def);
  while (w.time() < 0.5 - 1e-12) w.step();
  const RigidBody& b = w.bodies()[0];
  const Vec3 local = b.state.R.transpose() * (w.bodies()[1].state.x - b.state.x);
  // rk4 at 1 ms on a smooth motion: far below the touch distance (4e-6 m for the box).
  EXPECT_NEAR(local.x(), R, 1e-9);
  EXPECT_NEAR(local.y(), -(u / omega) * std::sinh(omega * 0.5), 1e-9);
  EXPECT_NEAR(local.z(), 0.0, 1e-12);
  EXPECT_EQ(w.contact_stats().impacts, 0);
  EXPECT_LE(w.contact_stats().deepest_penetration_m, 1e-12);
}

TEST(PairImpact, EnergyIsNeverGainedAndRunsAreDeterministic) {
  // Four boxes thrown at each other with spin, under gravity onto a floor: every contact event
  // may only remove energy, and the same scene gives the same bits.
  auto run = [] {
    WorldDef def = test::world_def(Integrator::Rk4, 1e-3, true);
    for (int i = 0; i < 4; ++i) {
      BodyDef b = test::box_def(Vec3(0.3, 0.2, 0.25), 1.0 + i, Vec3(0.45 * i, 0.5 + 0.3 * i, 0.05 * i));
      b.name = "die" + std::to_string(i);
      b.velocity = Vec3(i % 2 ? -1.0 : 1.0, 0.0, 0.3);
      b.angular_velocity = Vec3(1.0 * i, 2.0, -1.0);
      b.orientation = Quat(Eigen::AngleAxisd(0.3 * i, Vec3(1, 1, 0).normalized()));
      def.bodies.push_back(b);
    }
    World w(def);
    while (w.time() < 1.0) w.step();
    return w;
  };
  const World a = run(), b = run();
  EXPECT_GT(a.contact_stats().impacts, 3);
  EXPECT_LE(a.contact_stats().max_energy_gain_J, 1e-9);
  for (std::size_t i = 0; i < a.bodies().size(); ++i)
    EXPECT_TRUE(same_pose(a.bodies()[i].state, b.bodies()[i].state));
}

// Five dominoes 7.5 × 48 × 24 mm (650 kg/m³) standing 30 mm apart on a floor (friction 0.6,
// restitution 0.1), the first tipped about its front bottom edge; dt 5e-4, rk4.
WorldDef five_dominoes(double friction, std::optional<double> restitution) {
  WorldDef def = test::world_def(Integrator::Rk4, 5e-4, /*floor=*/true, 0.1);
  def.floor->friction = 0.6;
  const Vec3 size(0.0075, 0.048, 0.024);
  for (int i = 0; i < 5; ++i) {
    BodyDef d = test::box_def(size, 650.0 * size.prod(), Vec3(0.03 * i, 0.024, 0.0));
    d.friction = friction;
    if (restitution) d.restitution = *restitution;
    if (i == 0) {
      d.velocity = Vec3(0.096, 0.015, 0.0);
      d.angular_velocity = Vec3(0.0, 0.0, -4.0);
    }
    def.bodies.push_back(d);
  }
  return def;
}

TEST(Islands, ARowOfThinPlatesIsNotOneIsland) {
  // Dominoes 7.5 mm thick stand 30 mm apart: their bounding spheres (27 mm) overlap, their
  // boxes do not. Until the pushed one reaches the next (at 0.129 s), the others sleep: their
  // exact motion is none, and they are not stepped at all.
  World w(five_dominoes(0.4, /*restitution=*/std::nullopt));
  const World start = w;
  for (int k = 0; k < 200; ++k) w.step();  // 0.1 s
  EXPECT_FALSE(w.bodies()[0].at_rest);
  for (int i = 1; i < 5; ++i) {
    SCOPED_TRACE(i);
    EXPECT_TRUE(w.bodies()[i].at_rest);
    EXPECT_TRUE(same_pose(w.bodies()[i].state, start.bodies()[i].state));
  }
  EXPECT_EQ(w.contact_stats().impacts, 0);
}

TEST(Islands, TiltedDiceWhoseBoxesOverlapButWhichCannotMeetAreSteppedAlone) {
  // Two 0.2 m dice 0.3 m apart along x and 0.1 m in height, each with a diagonal along x: each
  // one's world box reaches 0.173 m from its centre along x and 0.158 m across, so their boxes
  // overlap (as the hundred dice, turning on their lattice, had theirs, and were one
  // island before any touched), while they are 0.052 m apart. Dropped on a corner each and
  // moving apart, they land, tumble and rest without coming nearer, so each must follow, to
  // the bit, the path it follows in a world of its own. Stepped as one island they did not:
  // the island's floor impacts and a lone body's are the same law, not the same arithmetic.
  WorldDef def = test::world_def(Integrator::Rk4, 1e-3, /*floor=*/true);
  const Vec3 size = Vec3::Constant(0.2);
  for (int i = 0; i < 2; ++i) {
    BodyDef d = test::box_def(size, 8.0, Vec3(0.3 * i, 0.3 + 0.1 * i, 0.0));
    d.orientation = Quat::FromTwoVectors(Vec3::Ones().normalized(), Vec3::UnitX());
    d.velocity = Vec3(i ? 0.15 : -0.15, 0.0, 0.0);
    d.restitution = 0.3;
    d.friction = 0.5;
    def.bodies.push_back(d);
  }
  const RigidBody a(def.bodies[0]), b(def.bodies[1]);
  const Vec3 reach = a.half_extent_world(a.state.R) + b.half_extent_world(b.state.R);
  ASSERT_GT(reach.x(), 0.3);  // their boxes overlap
  ASSERT_GT(reach.y(), 0.1);
  ASSERT_NEAR(separation(a, pose_of(a.state), b, pose_of(b.state)), 0.052, 1e-3);
  World both(def);
  std::vector<World> alone;
  for (int i = 0; i < 2; ++i) {
    WorldDef one = def;
    one.bodies = {def.bodies[static_cast<std::size_t>(i)]};
    alone.emplace_back(one);
  }
  for (int k = 0; k < 800; ++k) {  // 0.8 s: landed on a corner, tumbled, at rest
    both.step();
    for (std::size_t i = 0; i < 2; ++i) {
      alone[i].step();
      ASSERT_TRUE(same_pose(both.bodies()[i].state, alone[i].bodies()[0].state))
          << "die " << i << " at step " << k;
    }
  }
  EXPECT_GT(both.contact_stats().impacts, 2);
  EXPECT_TRUE(both.bodies()[0].at_rest && both.bodies()[1].at_rest);
}

TEST(Islands, ARowOfDominoesFallsInItsPlane) {
  // The scene is exactly planar (every domino centred on z = 0, the push in the x–y plane), so
  // the fall must stay in that plane to round-off. Each leaning domino's edge on the next one's
  // face is two contacts, one at each end, with sliding friction; where its LCP has a lopsided
  // answer as well as the symmetric one, freeing one end and keeping the other turned the row
  // out of its plane (2.2 rad/s by 0.3 s, and 97 impacts where 21 belong). Measured: 1.5e-13
  // of out-of-plane motion at 0.3 s; 1e-9 leaves four orders of round-off growth.
  const Vec3 size(0.0075, 0.048, 0.024);
  World w(five_dominoes(0.6, 0.1));
  for (int k = 0; k < 600; ++k) {  // 0.3 s: the push has reached the fourth domino
    w.step();
    for (std::size_t i = 0; i < w.bodies().size(); ++i) {
      const RigidBody& b = w.bodies()[i];
      const double off_plane = std::max({std::abs(b.state.x.z()), std::abs(b.velocity().z()),
                                         std::abs(b.angular_velocity().x()) * size.y(),
                                         std::abs(b.angular_velocity().y()) * size.y()});
      ASSERT_LT(off_plane, 1e-9) << "domino " << i << " at step " << k;
    }
  }
  EXPECT_GT(w.contact_stats().impacts, 0);
  EXPECT_LE(w.contact_stats().impacts, 40);  // 21
  EXPECT_LE(w.contact_stats().max_energy_gain_J, 1e-9);
  EXPECT_FALSE(w.bodies()[3].at_rest);  // the fourth has been struck
}

// 20 × 5 × 10 cm, spinning at 200 rad/s about z (0.2 rad a step of 1 ms; its corners sweep
// round at 20.6 m/s, 10.3 cm out), let go at rest, turned so that a corner passes the bottom
// 1 µm below the floor halfway through the 33rd step (t = 32.5 ms, the centre coming down at
// 0.32 m/s). That corner is in the floor for some 0.2 ms, in and out inside the step: only
// an advancement that watches it finds it; the step's ends do not, and the next corner
// round comes in 12 ms later at 6.4 m/s.
constexpr double kGrazeT = 0.0325;
WorldDef grazing_spinner(bool beside_a_wall) {
  WorldDef def = test::world_def(Integrator::Rk4, 1e-3, /*floor=*/true);
  def.floor->friction = 0.5;
  const double sweep = std::hypot(0.1, 0.025);
  const double graze = 1e-6, spin = 200.0;
  const double fall = 0.5 * 9.81 * kGrazeT * kGrazeT - graze;
  BodyDef box = test::box_def(Vec3(0.2, 0.05, 0.1), 1.0, Vec3(0.0, sweep + fall, 0.0));
  box.angular_velocity = Vec3(0.0, 0.0, spin);
  // The corner (0.1, -0.025) at the bottom (-π/2) at kGrazeT.
  const double angle = -0.5 * kPi - std::atan2(-0.025, 0.1) - spin * kGrazeT;
  box.orientation = Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
  def.bodies = {box};
  // A wall along the box's plane of motion (x–y), 3 cm from its 10 cm side: in the same island
  // (the broad phase grows a body by twice its fastest point's travel in a step, 4.6 cm), and
  // never touched as the box moves and turns in that plane. Its own advancement steps the
  // whole step: it cannot find the corner for the floor.
  if (beside_a_wall)
    def.bodies.push_back(
        test::fixed_box_def(Vec3(2.0, 1.0, 0.01), Vec3(0.0, 0.5, 0.05 + 0.03 + 0.005)));
  return def;
}

TEST(Tunnelling, ACornerThatGrazesTheFloorInsideAStepIsAnImpact) {
  World w(grazing_spinner(/*beside_a_wall=*/true));
  while (w.time() < 0.04) w.step();
  const std::vector<ImpactEvent>& events = w.contact_stats().events;
  ASSERT_FALSE(events.empty());
  // The corner comes within 1 µm of its lowest 0.1 ms before it gets there.
  EXPECT_GT(events.front().t_s, kGrazeT - 2e-4);
  EXPECT_LT(events.front().t_s, kGrazeT);
  EXPECT_EQ(events.front().other, kFloorBody);
  EXPECT_EQ(w.contact_stats().pairs.size(), 1u);  // the floor only: the wall is never touched
  EXPECT_LT(w.contact_stats().deepest_penetration_m, 1e-9);
  // Alone, the single-body step finds the same impact at the same time: the same equations
  // integrated by other arithmetic (1e-9 s, 1e-6 of the speed leave room for round-off).
  World alone(grazing_spinner(/*beside_a_wall=*/false));
  while (alone.time() < 0.04) alone.step();
  ASSERT_FALSE(alone.contact_stats().events.empty());
  EXPECT_NEAR(alone.contact_stats().events.front().t_s, events.front().t_s, 1e-9);
  EXPECT_NEAR(alone.contact_stats().events.front().approach_speed_mps,
              events.front().approach_speed_mps, 1e-6 * events.front().approach_speed_mps);
}

TEST(WorldPoll, IsCalledBeforeEveryStepAndStopsTheRunWhenItThrows) {
  WorldDef def = space();
  def.bodies = {test::box_def(Vec3::Ones(), 1.0, Vec3::Zero())};
  int calls = 0;
  def.poll = [&calls] {
    if (++calls == 4) throw std::runtime_error("stop");
  };
  World w(def);
  w.step();
  w.step();
  w.step();
  EXPECT_THROW(w.step(), std::runtime_error);
  EXPECT_EQ(calls, 4);
  EXPECT_EQ(w.step_count(), 3);
}

}  // namespace
}  // namespace tumble
