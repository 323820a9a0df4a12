// Bodies resting and sliding on each other: stacks that stay, friction between bodies, fixed
// ramps, a rolling ball, and islands that sleep.
#include <gtest/gtest.h>

#include <cmath>

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

TEST(Friction, SphereLaunchedSlidingEndsRollingAtFiveSevenths) {
  // Friction at the contact conserves the angular momentum about the contact point, m v r + I ω:
  // the ball ends rolling at v0 / (1 + 2/5) = 5/7 v0, after 2 v0 / (7 mu g).
  WorldDef def = ground();
  const double r = 0.1, v0 = 2.0, mu = 0.2;
  def.floor->friction = mu;
  BodyDef ball = test::sphere_def(r, 1.0, Vec3(0, r, 0));
  ball.velocity = Vec3(v0, 0, 0);
  def.bodies = {ball};
  World w(def);
  const double t_roll = 2 * v0 / (7 * mu * g);
  auto slip = [&] {
    const RigidBody& b = w.bodies()[0];
    return (b.velocity() + b.angular_velocity().cross(Vec3(0, -r, 0))).norm();
  };
  while (w.time() < t_roll - 2 * def.dt_s) w.step();
  EXPECT_GT(slip(), 1e-3);
  while (w.time() < t_roll + 2 * def.dt_s) w.step();
  EXPECT_LT(slip(), 1e-9);
  while (w.time() < 1.0) w.step();
  EXPECT_NEAR(w.bodies()[0].velocity().x(), 5.0 / 7.0 * v0, 1e-9);
  EXPECT_NEAR(w.bodies()[0].state.x.y(), r, 1e-9);
}

}  // namespace
}  // namespace tumble
