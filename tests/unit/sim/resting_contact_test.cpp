// Bodies resting and sliding on each other: stacks that stay, friction between bodies, fixed
// ramps, a rolling ball, and islands that sleep.
#include <gtest/gtest.h>

#include <cmath>

#include "../../../src/sim/collide.hpp"
#include "sim_fixtures.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

constexpr double g = 9.81;

WorldDef ground(double dt = 1e-3) {
  return test::world_def(Integrator::Rk4, dt, /*floor=*/true);
}

// `n` cubes of edge `s` stacked on the floor, each `gap` above the one below.
WorldDef stack(int n, double s, double gap) {
  WorldDef def = ground();
  for (int k = 0; k < n; ++k) {
    BodyDef b = test::box_def(Vec3::Constant(s), 1.0, Vec3(0, 0.5 * s + k * (s + gap) + gap, 0));
    b.name = "box" + std::to_string(k);
    def.bodies.push_back(b);
  }
  return def;
}

TEST(Stack, TenBoxesAtRestStayForAMinute) {
  // Placed touching, the stack is in equilibrium at once: it sleeps, and its exact motion is
  // none. Every box within 1e-9 of its size of where it started after 60 s.
  const double s = 0.2;
  const WorldDef def = stack(10, s, 0.0);
  World w(def);
  while (w.time() < 60.0) w.step();
  for (std::size_t k = 0; k < def.bodies.size(); ++k)
    EXPECT_LT((w.bodies()[k].state.x - def.bodies[k].position).norm(), 1e-9 * s) << k;
}

TEST(Stack, APyramidOfTwentyRowsSleepsAtOnceAndStays) {
  // Issue 21's standing pyramid: 210 unit cubes of 1 kg, row r holding 20 − r at x = i −
  // (19 − r)/2, exactly touching (each box on the halves of two below, beside its neighbours:
  // 2 360 contact points), friction 0.5, restitution 0. It is in equilibrium on its normal
  // forces alone, and finding that must not cost an active-set search over the thousands of
  // friction-pyramid columns: it sleeps after one step, no box moves, nothing is deep.
  WorldDef def = test::world_def(Integrator::Rk4, 0.002, /*floor=*/true);
  def.floor->friction = 0.5;
  const int rows = 20;
  for (int r = 0; r < rows; ++r)
    for (int i = 0; i < rows - r; ++i) {
      BodyDef b = test::box_def(Vec3::Ones(), 1.0,
                                Vec3(i - 0.5 * (rows - r - 1), 0.5 + r, 0.0));
      b.name = "box_" + std::to_string(r) + "_" + std::to_string(i);
      b.friction = 0.5;
      b.restitution = 0.0;
      def.bodies.push_back(b);
    }
  World w(def);
  w.step();
  for (const RigidBody& b : w.bodies()) EXPECT_TRUE(b.at_rest) << b.name();
  while (w.time() < 2.0) w.step();
  for (std::size_t k = 0; k < def.bodies.size(); ++k) {
    EXPECT_EQ(w.bodies()[k].state.x, def.bodies[k].position) << def.bodies[k].name;
    EXPECT_TRUE(w.bodies()[k].at_rest) << def.bodies[k].name;
  }
  EXPECT_EQ(w.contact_stats().impacts, 0L);
  EXPECT_EQ(w.contact_stats().deepest_penetration_m, 0.0);
}

TEST(Stack, ASleepingPileStaysBitForBitAndItsCopiesShareTheirShapes) {
  // A world in which every body sleeps takes its steps without looking for islands (nothing
  // can wake it): it stays, bit for bit, as it was. And a copy of the world (one per sample,
  // one per kept framing world) shares each body's corners and faces instead of copying them.
  WorldDef def = stack(10, 0.2, 0.0);
  World w(def);
  w.step();
  for (const RigidBody& b : w.bodies()) ASSERT_TRUE(b.at_rest) << b.name();
  const World copy = w;
  for (int k = 0; k < 1000; ++k) w.step();
  for (std::size_t k = 0; k < def.bodies.size(); ++k) {
    EXPECT_EQ(w.bodies()[k].state.x, copy.bodies()[k].state.x) << k;
    EXPECT_EQ(w.bodies()[k].state.q.coeffs(), copy.bodies()[k].state.q.coeffs()) << k;
    EXPECT_EQ(&w.bodies()[k].vertices(), &copy.bodies()[k].vertices()) << k;
    EXPECT_EQ(&w.bodies()[k].faces(), &copy.bodies()[k].faces()) << k;
  }
  EXPECT_EQ(w.contact_stats().impacts, 0L);
}

TEST(Stack, DroppedFromMillimetreGapsSettlesStraightAndSpinFree) {
  const double s = 0.2;
  const WorldDef def = stack(5, s, 1e-3);
  World w(def);
  while (w.time() < 1.5) w.step();
  for (std::size_t k = 0; k < def.bodies.size(); ++k) {
    const RigidBody& b = w.bodies()[k];
    // Straight: no sideways drift, no turn (the landings are symmetric), resting on the one below.
    EXPECT_LT(std::hypot(b.state.x.x(), b.state.x.z()), 1e-9) << k;
    EXPECT_LT(test::angle_between(b.state.q, Quat::Identity()), 1e-9) << k;
    EXPECT_NEAR(b.state.x.y(), 0.5 * s + double(k) * s, 1e-6 * s) << k;
    EXPECT_LT(b.velocity().norm(), 1e-3) << k;
  }
  EXPECT_LE(w.contact_stats().max_energy_gain_J, 1e-9);
}

TEST(Friction, BoxSlidingOnAFixedBoxStopsAtVSquaredOverTwoMuG) {
  WorldDef def = ground();
  const double mu = 0.5, v0 = 1.0, s = 0.2;
  BodyDef table = test::fixed_box_def(Vec3(4, 0.2, 1), Vec3(0, 0.1, 0));
  table.friction = mu;
  BodyDef box = test::box_def(Vec3::Constant(s), 1.0, Vec3(-1.0, 0.2 + 0.5 * s, 0));
  box.velocity = Vec3(v0, 0, 0);
  box.friction = mu;  // the pair's: sqrt(mu mu) = mu
  def.bodies = {table, box};
  World w(def);
  // Deceleration mu g while it slides.
  while (w.time() < 0.1) w.step();
  EXPECT_NEAR(w.bodies()[1].velocity().x(), v0 - mu * g * 0.1, 1e-3 * v0);
  while (w.time() < 1.0) w.step();
  const double slid = w.bodies()[1].state.x.x() + 1.0;
  // Within one step of travel (the last stretch is stopped by a static friction impulse).
  EXPECT_NEAR(slid, v0 * v0 / (2 * mu * g), v0 * def.dt_s);
  EXPECT_LT(w.bodies()[1].velocity().norm(), 1e-6);
}

// A box sliding without friction on a fixed table at 0.1 m/s, leaving it upwards at `up`.
World leaving_box(double up) {
  WorldDef def = ground();
  const double s = 0.2;
  BodyDef table = test::fixed_box_def(Vec3(4, 0.2, 1), Vec3(0, 0.1, 0));
  table.friction = 0.0;
  BodyDef box = test::box_def(Vec3::Constant(s), 1.0, Vec3(-1.0, 0.2 + 0.5 * s, 0));
  box.velocity = Vec3(0.1, up, 0);
  box.friction = 0.0;
  def.bodies = {table, box};
  return World(def);
}

TEST(Lift, AFaceLeavingSlowerThanTheLiftSpeedIsStoppedNotLaunched) {
  // A 0.2 m box: lift speed sqrt(2e-3 g touch) = 6.3e-5 m/s, hold speed 1.4e-6 m/s. At 2e-5 m/s
  // it would rise 2e-11 m (1e-10 of its size) and land 4 µs later, an impact of its own.
  // It is stopped instead: no impact, on the table to 1e-9 of its size, its vertical
  // momentum gone (the kinetic energy of ½ m up², 2e-10 J, removed; none gained beyond
  // round-off).
  World w = leaving_box(2e-5);
  while (w.time() < 0.05) w.step();
  EXPECT_EQ(w.contact_stats().impacts, 0);
  EXPECT_NEAR(w.bodies()[1].state.x.y(), 0.3, 1e-9 * 0.2);
  EXPECT_LT(std::abs(w.bodies()[1].velocity().y()), 1e-12);
  EXPECT_NEAR(w.bodies()[1].velocity().x(), 0.1, 1e-12);
  EXPECT_LT(w.contact_stats().max_energy_gain_J, 1e-15);
}

TEST(Lift, AFaceLeavingFasterThanTheLiftSpeedFliesAndLandsAt2UpOverG) {
  // 1e-3 m/s (16 times the lift speed): it leaves, rises up²/2g = 5.1e-8 m, and its face lands
  // flat 2 up / g = 2.04e-4 s later, one impact at the speed it left with (to 1e-6 of it; the
  // landing is located to 1e-12 s).
  const double up = 1e-3;
  World w = leaving_box(up);
  while (w.time() < 0.05) w.step();
  ASSERT_EQ(w.contact_stats().impacts, 1);
  const ImpactEvent& e = w.contact_stats().events.front();
  EXPECT_NEAR(e.t_s, 2.0 * up / g, 1e-9);
  EXPECT_NEAR(e.approach_speed_mps, up, 1e-6 * up);
  EXPECT_NEAR(w.bodies()[1].state.x.y(), 0.3, 1e-9 * 0.2);
}

// A box resting on a fixed ramp tilted `degrees` about z, both with friction mu.
World ramp(double degrees, double mu) {
  WorldDef def = test::world_def(Integrator::Rk4, 1e-3, false);
  const double th = radians(degrees), s = 0.2;
  const Quat tilt(Eigen::AngleAxisd(th, Vec3::UnitZ()));
  const Vec3 n(-std::sin(th), std::cos(th), 0);
  BodyDef slope = test::fixed_box_def(Vec3(4, 0.2, 1), Vec3::Zero(), tilt);
  slope.friction = mu;
  BodyDef box = test::box_def(Vec3::Constant(s), 1.0, (0.1 + 0.5 * s) * n);
  box.orientation = tilt;
  box.friction = mu;
  def.bodies = {slope, box};
  return World(def);
}

TEST(Friction, NoCreepOnARampShallowerThanAtanMu) {
  World w = ramp(20.0, 0.5);  // atan 0.5 = 26.6°
  const Vec3 start = w.bodies()[1].state.x;
  while (w.time() < 2.0) w.step();
  EXPECT_LT((w.bodies()[1].state.x - start).norm(), 1e-9);
}

TEST(Friction, SlidesDownARampSteeperThanAtanMuAtGTimesSinMinusMuCos) {
  // Set on the ramp at rest, the box slides at once (static friction cannot hold it: the joint
  // sticking impulse leaves the cone) and its acceleration along the slope is
  // g (sin θ − μ cos θ) = 1.609 m/s² at 35°, μ = 0.5. Kinetic friction and the normal force are
  // constant, so rk4 follows it to round-off (1e-12 of the speed reached); flat on the slope,
  // held by all four corners: no lift, no rocking, no impact.
  const double th = radians(35.0), mu = 0.5;
  World w = ramp(35.0, mu);
  const Vec3 down(-std::cos(th), -std::sin(th), 0), n(-std::sin(th), std::cos(th), 0);
  const Vec3 start = w.bodies()[1].state.x;
  const double a = g * (std::sin(th) - mu * std::cos(th));
  while (w.time() < 0.5 - 1e-12) w.step();
  const RigidBody& b = w.bodies()[1];
  EXPECT_NEAR(b.velocity().dot(down), a * 0.5, 1e-12);
  EXPECT_NEAR((b.state.x - start).dot(down), 0.5 * a * 0.25, 1e-12);
  EXPECT_NEAR((b.state.x - start).dot(n), 0.0, 1e-12);
  EXPECT_LT(b.angular_velocity().norm(), 1e-12);
  EXPECT_EQ(w.contact_stats().impacts, 0L);
}

// A ball of radius r launched sliding at v0 without spin, on the floor (`on_table` false) or on
// a fixed box, both with friction mu. Kinetic friction mu m g decelerates its centre at mu g
// and spins it up at (mu m g r) / (2/5 m r²); the contact point stops slipping when
// v0 − mu g t = (5/2) mu g t, at t* = 2 v0 / (7 mu g), and from then on it rolls at 5/7 v0
// (static friction holds it with no force: a ball rolling on a level plane needs none).
void expect_rolls_at_five_sevenths(bool on_table) {
  const double mu = 0.3, v0 = 2.0, r = 0.1, base = on_table ? 0.2 : 0.0;
  WorldDef def = ground();
  def.floor->friction = mu;
  if (on_table) {
    BodyDef table = test::fixed_box_def(Vec3(4, 0.2, 1), Vec3(0, 0.1, 0));
    table.friction = mu;
    def.bodies.push_back(table);
  }
  BodyDef ball = test::sphere_def(r, 1.0, Vec3(0, base + r, 0));
  ball.velocity = Vec3(v0, 0, 0);
  ball.restitution = 0.0;
  ball.friction = mu;
  def.bodies.push_back(ball);
  World w(def);
  const std::size_t k = def.bodies.size() - 1;
  const double t_roll = 2.0 * v0 / (7.0 * mu * g);  // 0.194 s
  // Sliding: the centre decelerates at mu g. The step's rk4 is exact for a constant force, so
  // the only error is where the stretch ends (none before t*): 1e-9 v0.
  while (w.time() < 0.1 - 1e-12) w.step();
  EXPECT_NEAR(w.bodies()[k].velocity().x(), v0 - mu * g * w.time(), 1e-9 * v0);
  while (w.time() < 0.5 - 1e-12) w.step();
  const RigidBody& b = w.bodies()[k];
  // Rolling: 5/7 v0, its spin matching (v = −ω_z r), and the distance of sliding to t* then
  // rolling after it, to within the one step over which the slip stops (v0 dt).
  EXPECT_NEAR(b.velocity().x(), 5.0 / 7.0 * v0, 1e-9 * v0);
  EXPECT_NEAR(b.angular_velocity().z() * r, -5.0 / 7.0 * v0, 1e-9 * v0);
  const double slid = v0 * t_roll - 0.5 * mu * g * t_roll * t_roll;
  EXPECT_NEAR(b.state.x.x(), slid + 5.0 / 7.0 * v0 * (w.time() - t_roll), v0 * def.dt_s);
  EXPECT_NEAR(b.state.x.y(), base + r, 1e-9 * r);  // it neither sinks nor hops
  EXPECT_LE(w.contact_stats().max_energy_gain_J, 1e-12);
}

TEST(Friction, ASphereLaunchedSlidingOnTheFloorEndsRollingAtFiveSevenths) {
  expect_rolls_at_five_sevenths(false);
}

TEST(Friction, ASphereLaunchedSlidingOnAFixedBoxEndsRollingAtFiveSevenths) {
  expect_rolls_at_five_sevenths(true);
}

TEST(Stack, HeavyBoxOnALightOneDoesNotSink) {
  // 1000 kg set on 1 kg on the floor: held by exact contact forces, the light box is not pressed
  // in. Every box within the touch tolerance (1e-6 of the size) of where it started over 10 s.
  WorldDef def = ground();
  const double s = 0.2;
  BodyDef light = test::box_def(Vec3::Constant(s), 1.0, Vec3(0, 0.5 * s, 0));
  light.name = "light";
  BodyDef heavy = test::box_def(Vec3::Constant(s), 1000.0, Vec3(0, 1.5 * s, 0));
  heavy.name = "heavy";
  def.bodies = {light, heavy};
  World w(def);
  while (w.time() < 10.0) w.step();
  const double touch = ContactTolerances::for_body(s, def.gravity, def.dt_s).touch_m;
  EXPECT_LT(w.contact_stats().deepest_penetration_m, touch);
  EXPECT_NEAR(w.bodies()[0].state.x.y(), 0.5 * s, touch);
  EXPECT_NEAR(w.bodies()[1].state.x.y(), 1.5 * s, touch);
}

// A 50 kg ball on two 1 kg boxes on the floor, each set 1e-7 m into what it rests on (within the
// touch distance, 2e-7 m: held, and the held drift correction's to undo; the ball turns about
// the vertical, so the pile does not sleep at once). Corrected once in pair
// order, each move pressed a box into the next (a struck pyramid's pile carried 2.5e-6 m so,
// stretch after stretch); the corrections are swept until none finds more than 1e-3 of the touch
// distance. After one step every pair is apart to that, and the penetration counted is the
// 1e-7 m they were set in, not what the moves made on the way.
TEST(Stack, TheHeldDriftCorrectionLeavesAChainUnderAHeavyBallApart) {
  WorldDef def = ground();
  const double s = 0.2, in = 1e-7;
  BodyDef low = test::box_def(Vec3::Constant(s), 1.0, Vec3(0, 0.5 * s - in, 0));
  BodyDef high = test::box_def(Vec3::Constant(s), 1.0, Vec3(0, 1.5 * s - 2 * in, 0));
  BodyDef ball = test::sphere_def(0.5 * s, 50.0, Vec3(0, 2.5 * s - 3 * in, 0));
  ball.angular_velocity = Vec3(0, 1, 0);  // turning about the vertical: awake, going nowhere
  low.name = "low", high.name = "high", ball.name = "ball";
  def.bodies = {low, high, ball};
  World w(def);
  w.step();
  const double touch = ContactTolerances::for_body(s, def.gravity, def.dt_s).touch_m;
  ASSERT_GT(touch, in);
  const std::vector<RigidBody>& b = w.bodies();
  auto pose = [&](int i) { return pose_of(b[static_cast<std::size_t>(i)].state); };
  EXPECT_GT(plane_separation(0.0, b[0], pose(0)), -1e-3 * touch);
  EXPECT_GT(separation(b[0], pose(0), b[1], pose(1)), -1e-3 * touch);
  EXPECT_GT(separation(b[1], pose(1), b[2], pose(2)), -1e-3 * touch);
  EXPECT_NEAR(w.contact_stats().deepest_penetration_m, in, 1e-3 * touch);
}

// `heavy_kg` dropped from 1 mm onto a 1 kg box of the same 0.2 m size on the floor: every
// overlap stays below the touch tolerance, both end at rest where they belong, and no event
// gains more than `max_gain_J`.
void expect_drop_onto_a_light_box_rests(double heavy_kg, double max_gain_J) {
  WorldDef def = ground();
  const double s = 0.2;
  BodyDef light = test::box_def(Vec3::Constant(s), 1.0, Vec3(0, 0.5 * s, 0));
  BodyDef heavy = test::box_def(Vec3::Constant(s), heavy_kg, Vec3(0, 1.5 * s + 1e-3, 0));
  light.name = "light";
  heavy.name = "heavy";
  def.bodies = {light, heavy};
  World w(def);
  while (w.time() < 1.0) w.step();
  const double touch = ContactTolerances::for_body(s, def.gravity, def.dt_s).touch_m;
  EXPECT_LT(w.contact_stats().deepest_penetration_m, touch);
  EXPECT_NEAR(w.bodies()[0].state.x.y(), 0.5 * s, touch);
  EXPECT_NEAR(w.bodies()[1].state.x.y(), 1.5 * s, 2 * touch);
  EXPECT_LT(w.bodies()[0].velocity().norm(), 1e-9);
  EXPECT_LT(w.bodies()[1].velocity().norm(), 1e-9);
  EXPECT_LE(w.contact_stats().max_energy_gain_J, max_gain_J);
}

TEST(Stack, HeavyBoxDroppedOnALightOneDoesNotSink) {
  // 100 kg (where Jolt and DART sink through): the light box trades impulses with both (the
  // impact passes). Energy: at most the potential energy of lifting both by the touch
  // tolerance (the drift correction of resting contacts), 101 kg · g · 2e-7 m = 2e-4 J.
  expect_drop_onto_a_light_box_rests(100.0, 101.0 * g * 2e-7);
}

TEST(Stack, AThousandToOneDropIsResolvedWithoutAGainAndRests) {
  // 1000 kg. The impact's matrix over the eight corners (four on the floor, four between the
  // boxes) has dependent rows and a 1000:1 spread; Dantzig pivoting once ended off
  // complementarity there, an impulse that squeezed the light box out (167 kJ gained, both
  // thrown off at 7–9 m/s). An impact's answer now never gains energy (lcp.hpp,
  // solve_lcp_dissipative): one impact. Round-off of the drop's 3 kJ is 1e-12 J (8e-16 J
  // seen); 1e-9 J bounds it.
  expect_drop_onto_a_light_box_rests(1000.0, 1e-9);
}

TEST(Sleep, ABallDroppedOnASleepingStackWakesIt) {
  // Three boxes placed touching sleep at once; a ball dropped onto the top one, off its centre,
  // wakes the island: the top box takes part of the impact and moves, no contact is deeper
  // than the touch tolerance, and no event gains more than the potential energy of lifting
  // the island by it (the drift correction of resting contacts: 3.5 kg · g · 2e-7 m).
  const double s = 0.2;
  WorldDef def = stack(3, s, 0.0);
  BodyDef ball = test::sphere_def(0.05, 0.5, Vec3(0.02, 3 * s + 0.3, 0));
  ball.name = "ball";
  def.bodies.push_back(ball);
  World w(def);
  double moved = 0.0;
  while (w.time() < 0.3) {
    w.step();
    moved = std::max(moved, w.bodies()[2].velocity().norm());
  }
  EXPECT_GT(moved, 1e-2);  // the ball lands at 2.4 m/s; the top box leaves at ~0.08 m/s
  EXPECT_GE(w.contact_stats().impacts, 1);
  const double touch = ContactTolerances::for_body(0.1, def.gravity, def.dt_s).touch_m;
  EXPECT_LT(w.contact_stats().deepest_penetration_m, touch);
  EXPECT_LE(w.contact_stats().max_energy_gain_J, 3.5 * g * touch);
}

}  // namespace
}  // namespace tumble
