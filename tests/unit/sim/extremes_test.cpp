// Stability at the extremes: steps from 1e-6 s to the seed's 1/30 s, spins to 1000 rad/s,
// inertia ratios to 1e4, masses from 1e-3 to 1e6 kg, bodies and drops from 1 mm to 1 km,
// restitution 0 and 1, runs of 10^6 steps. Physics has no preferred scale, so scaled scenes must
// be scaled copies of each other.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sim_fixtures.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

constexpr double g = 9.81;

// The default scene's drop (a box with a 30° tilt and a spin, e = 0.5) scaled by s: lengths × s,
// times × √s (so speeds × √s and rates × 1/√s).
WorldDef scaled_drop(double s, double mass = 1.0) {
  const double r = std::sqrt(s);
  WorldDef def = test::world_def(Integrator::Rk4, 0.001 * r, /*floor=*/true);
  BodyDef b = test::box_def(Vec3(s, s, s), mass, Vec3(0, 3.0 * s, 0));
  b.orientation = Quat(Eigen::AngleAxisd(radians(30.0), Vec3(1, 0, 1).normalized()));
  b.angular_velocity = Vec3(0, 0, 2.0 / r);
  def.bodies.push_back(b);
  return def;
}

std::vector<Vec3> positions(World& w, long steps) {
  std::vector<Vec3> out;
  for (long i = 0; i < steps; ++i) {
    w.step();
    out.push_back(w.bodies()[0].state.x);
  }
  return out;
}

class ScaleInvariance : public ::testing::TestWithParam<double> {};

TEST_P(ScaleInvariance, ScaledDropIsAScaledCopyAndRestsAtHalfItsSize) {
  // 4000 steps of the 1 m drop (4 s: flight, 27 impacts, rocking, rest) against the same steps of
  // the scaled drop. Contact tolerances scale with the body, so every decision (impact, rest
  // speed, hold, sleep) is taken at the same step; what remains is the round-off of scaling
  // (measured 1e-10 of the size at 1 mm, 3e-12 at 1 km, across the chaotic rocking phase).
  // Tolerance 1e-8 of the size.
  const double s = GetParam();
  World unit_world(scaled_drop(1.0));
  const std::vector<Vec3> unit = positions(unit_world, 4000);
  World scaled_world(scaled_drop(s));
  const std::vector<Vec3> scaled = positions(scaled_world, 4000);
  double worst = 0.0;
  for (std::size_t i = 0; i < unit.size(); ++i)
    worst = std::max(worst, (scaled[i] / s - unit[i]).norm());
  EXPECT_LT(worst, 1e-8) << "scale " << s;
  // At rest on a face: the centre at half the edge, within the touch tolerance 1e-6 s.
  EXPECT_TRUE(scaled_world.bodies()[0].at_rest);
  EXPECT_NEAR(scaled.back().y() / s, 0.5, 1.1e-6);
  // The same bounces (impacts faster than the rest speed); inelastic micro-impacts of the rocking
  // phase, at round-off speeds, may differ by a few.
  auto bounces = [](const World& w) {
    long n = 0;
    for (const ImpactEvent& e : w.contact_stats().events)
      n += e.approach_speed_mps >= w.tolerances(0).rest_speed_mps;
    return n;
  };
  EXPECT_EQ(bounces(scaled_world), bounces(unit_world));
  EXPECT_GT(bounces(unit_world), 3);
  EXPECT_TRUE(scaled_world.diagnostics().empty());
}

INSTANTIATE_TEST_SUITE_P(MillimetreToKilometre, ScaleInvariance, ::testing::Values(1e-3, 1e3));

TEST(Extremes, MassDoesNotChangeTheMotion) {
  // Every force here is proportional to the mass (gravity, contact), so the path of a 1 g and a
  // 1000 t box is that of the 1 kg one; only the round-off of P = m v differs (1e-9 m).
  World unit_world(scaled_drop(1.0, 1.0));
  const std::vector<Vec3> unit = positions(unit_world, 4000);
  for (double mass : {1e-3, 1e6}) {
    World other_world(scaled_drop(1.0, mass));
    const std::vector<Vec3> other = positions(other_world, 4000);
    double worst = 0.0;
    for (std::size_t i = 0; i < unit.size(); ++i)
      worst = std::max(worst, (other[i] - unit[i]).norm());
    EXPECT_LT(worst, 1e-9) << "mass " << mass;
  }
}

class StepRange : public ::testing::TestWithParam<double> {};

TEST_P(StepRange, FirstImpactIsAtTheFreeFallTimeForAnyStep) {
  // The impact time is located inside the step, so it does not depend on dt: a particle dropped
  // from 1 m meets the floor at sqrt(2h/g) to 1e-11 s for every dt from 1e-6 s to 1/30 s.
  const double dt = GetParam();
  WorldDef def = test::world_def(Integrator::Rk4, dt, true);
  def.bodies.push_back(test::particle_def(1.0, Vec3(0, 1.0, 0)));
  World w(def);
  const double t_i = std::sqrt(2.0 / g);
  while (w.contact_stats().events.empty()) w.step();
  EXPECT_NEAR(w.contact_stats().events[0].t_s, t_i, 1e-11) << "dt " << dt;
  EXPECT_NEAR(w.contact_stats().events[0].approach_speed_mps, g * t_i, 1e-9) << "dt " << dt;
}

INSTANTIATE_TEST_SUITE_P(MicrosecondToSeed, StepRange,
                         ::testing::Values(1e-6, 1e-4, 1e-2, 1.0 / 30.0));

TEST(Extremes, DropsFromAMillimetreAndAKilometre) {
  // Apex after the first bounce: e² h exactly (parabolas, exact impact time), relative 1e-9.
  for (double h : {1e-3, 1e3}) {
    WorldDef def = test::world_def(Integrator::Rk4, 0.001, true);
    BodyDef p = test::particle_def(1.0, Vec3(0, h, 0));
    p.restitution = 0.5;
    def.bodies.push_back(p);
    World w(def);
    while (w.contact_stats().events.empty()) w.step();
    double apex = 0.0;
    while (w.bodies()[0].velocity().y() > 0.0 || w.contact_stats().impacts == 0) {
      w.step();
      const RigidBody& b = w.bodies()[0];
      const double vy = b.velocity().y();
      apex = std::max(apex, b.state.x.y() + (vy > 0 ? vy * vy / (2 * g) : 0.0));
    }
    EXPECT_NEAR(apex, 0.25 * h, 1e-9 * h) << "drop " << h;
  }
}

TEST(Extremes, SpinOf1000RadPerSecondKeepsMomentumAndEnergy) {
  // A fast tumble (|ω| ≈ 1000 rad/s) with rk4 at dt = 1e-4 (0.1 rad per step): L exactly
  // constant, energy within 1e-5 over 1 s of 10^4 steps (measured 4.2e-6: rk4's energy error per
  // step goes as (dt·|ω|)^5, ~4e-10 here).
  WorldDef def = test::world_def(Integrator::Rk4, 1e-4, false);
  def.gravity.setZero();
  BodyDef b = test::box_def(Vec3(1, 2, 3), 1.0, Vec3::Zero());
  b.angular_velocity = Vec3(30.0, 1000.0, 20.0);
  def.bodies.push_back(b);
  World w(def);
  const Vec3 L0 = w.bodies()[0].state.L;
  const double e0 = w.total_energy();
  for (int i = 0; i < 10000; ++i) w.step();
  EXPECT_EQ(w.bodies()[0].state.L, L0);
  EXPECT_NEAR(w.total_energy() / e0, 1.0, 1e-5);
  EXPECT_TRUE(w.diagnostics().empty());
  // The same spin at dt = 1e-2 (10 rad per step) is beyond rk4 and must be flagged, not silent.
  def.dt_s = 1e-2;
  World coarse(def);
  for (int i = 0; i < 10; ++i) coarse.step();
  EXPECT_TRUE(coarse.diagnostics().has("step_too_large_for_spin"));
}

TEST(Extremes, NeedleAndPlateWithInertiaRatio1e4) {
  // A needle 1 m × 7 mm × 7 mm (I_max / I_min ≈ 1e4) and a 1 m × 1 m × 1 cm plate, tumbling and
  // dropped: torque-free, L is exact and energy holds to 1e-8; dropped, each comes to rest lying
  // on its largest face, no point deeper than the touch tolerance.
  for (const Vec3& size : {Vec3(1.0, 0.00707, 0.00707), Vec3(1.0, 0.01, 1.0)}) {
    const Vec3 I = box_inertia(1.0, size);
    ASSERT_GT(I.maxCoeff() / I.minCoeff(), size.y() < 0.01 ? 9.9e3 : 1.9);
    WorldDef free = test::world_def(Integrator::Rk4, 1e-4, false);
    free.gravity.setZero();
    BodyDef b = test::box_def(size, 1.0, Vec3::Zero());
    b.angular_velocity = Vec3(5.0, 0.3, 0.2);  // mostly about the needle's long axis
    free.bodies.push_back(b);
    World tumbling(free);
    const double e0 = tumbling.total_energy();
    for (int i = 0; i < 10000; ++i) tumbling.step();
    EXPECT_NEAR(tumbling.total_energy() / e0, 1.0, 1e-8) << size.transpose();

    WorldDef drop = test::world_def(Integrator::Rk4, 1e-4, true);
    BodyDef d = test::box_def(size, 1.0, Vec3(0, 1.0, 0));
    d.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 0.5, 0.2).normalized()));
    drop.bodies.push_back(d);
    World dropped(drop);
    double deepest = 0.0;
    for (int i = 0; i < 60000 && !dropped.bodies()[0].at_rest; ++i) {
      dropped.step();
      const RigidBody& body = dropped.bodies()[0];
      for (const Vec3& v : body.vertices())
        deepest = std::min(deepest, (body.state.x + body.state.R * v).y());
    }
    EXPECT_TRUE(dropped.bodies()[0].at_rest) << size.transpose();
    EXPECT_NEAR(dropped.bodies()[0].state.x.y(), size.y() / 2.0, 1e-5) << size.transpose();
    EXPECT_GT(deepest, -dropped.tolerances(0).touch_m) << size.transpose();
  }
}

TEST(Extremes, ElasticBouncesKeepTheirEnergyOver100Bounces) {
  // e = 1: each impact reverses the normal velocity exactly and rk4 integrates the parabolas
  // exactly, so after 100 bounces (90 s) the energy is that of the start to 1e-9 (relative).
  for (bool box : {false, true}) {
    WorldDef def = test::world_def(Integrator::Rk4, 0.001, true);
    BodyDef b = box ? test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 1.5, 0))
                    : test::particle_def(1.0, Vec3(0, 1.0, 0));
    b.restitution = 1.0;
    def.bodies.push_back(b);
    World w(def);
    const double e0 = w.total_energy();
    while (w.contact_stats().impacts < 100) w.step();
    EXPECT_NEAR(w.total_energy() / e0, 1.0, 1e-9) << (box ? "box" : "particle");
    EXPECT_LT(w.bodies()[0].state.L.norm(), 1e-12);  // a flat landing never spins
  }
}

TEST(Extremes, InelasticContactStopsAtTheFirstImpact) {
  // e = 0: the first impact takes the normal velocity to zero, and the body stays on the floor.
  for (bool box : {false, true}) {
    WorldDef def = test::world_def(Integrator::Rk4, 0.001, true);
    BodyDef b = box ? test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 1.5, 0))
                    : test::particle_def(1.0, Vec3(0, 1.0, 0));
    b.restitution = 0.0;
    def.bodies.push_back(b);
    World w(def);
    for (int i = 0; i < 2000; ++i) w.step();
    EXPECT_EQ(w.contact_stats().impacts, 1) << (box ? "box" : "particle");
    EXPECT_NEAR(w.bodies()[0].state.x.y(), box ? 0.5 : 0.0, 1e-9);
    EXPECT_NEAR(w.bodies()[0].velocity().y(), 0.0, 1e-9);
  }
}

TEST(Extremes, AMillionStepsOfTumbling) {
  // 10^6 rk4 steps (1000 s) of a torque-free tumble: L bit-for-bit constant, |q| = 1 to
  // round-off, energy drift below 1e-6 (rk4's error accumulates linearly: ~1e-12 per second
  // here).
  WorldDef def = test::world_def(Integrator::Rk4, 0.001, false);
  def.gravity.setZero();
  BodyDef b = test::box_def(Vec3(1, 2, 3), 1.0, Vec3::Zero());
  b.angular_velocity = Vec3(1.0, 0.7, 1.3);
  def.bodies.push_back(b);
  World w(def);
  const Vec3 L0 = w.bodies()[0].state.L;
  const double e0 = w.total_energy();
  for (long i = 0; i < 1000000; ++i) w.step();
  EXPECT_EQ(w.bodies()[0].state.L, L0);
  EXPECT_NEAR(w.bodies()[0].state.q.norm(), 1.0, 1e-15);
  EXPECT_NEAR(w.total_energy() / e0, 1.0, 1e-6);
  EXPECT_TRUE(w.diagnostics().empty());
}

}  // namespace
}  // namespace tumble
