// The adaptive integrator (Dormand–Prince 5(4) with a PI controller): exact where the motion is
// polynomial, error following the tolerance, fewer evaluations than rk4 at equal error, impacts
// located as with the fixed-step integrators, deterministic, statistics reported.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_fixtures.hpp"
#include "tumble/sampler.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

constexpr double g = 9.81;

WorldDef tumbling_def(Integrator integrator, double dt, double tolerance) {
  WorldDef def = test::world_def(integrator, dt, /*floor=*/false);
  def.tolerance = tolerance;
  def.gravity.setZero();
  BodyDef body = test::box_def(Vec3(1.0, 2.0, 3.0), 3.0, Vec3::Zero());
  body.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 0.5).normalized()));
  body.angular_velocity = Vec3(1.0, 0.7, 1.3);
  def.bodies.push_back(body);
  return def;
}

struct Outcome {
  Quat q;
  long evaluations;
  StepStats stats;
};

Outcome tumble_for(const WorldDef& def, double t) {
  World w(def);
  const long n = std::lround(t / def.dt_s);
  for (long i = 0; i < n; ++i) w.step();
  return {w.bodies()[0].state.q, w.derivative_evaluations(), w.step_stats()};
}

TEST(Adaptive, FreeFallIsExact) {
  // A parabola is a polynomial of degree 2: every stage of a Runge–Kutta method of order >= 2
  // integrates it exactly, so after 2 s only round-off remains (1e-12 m over 20 m of fall).
  WorldDef def = test::world_def(Integrator::Adaptive, 0.05, false);
  def.bodies.push_back(test::particle_def(1.0, Vec3(0, 0, 0)));
  def.bodies[0].velocity = Vec3(1.0, 3.0, 0.0);
  World w(def);
  for (int i = 0; i < 40; ++i) w.step();
  const double t = 2.0;
  EXPECT_NEAR(w.bodies()[0].state.x.y(), 3.0 * t - 0.5 * g * t * t, 1e-12);
  EXPECT_NEAR(w.bodies()[0].state.x.x(), t, 1e-12);
  // The error estimate is zero on a parabola: the controller takes the largest step throughout.
  EXPECT_EQ(w.step_stats().rejected, 0);
  EXPECT_EQ(w.step_stats().largest_step_s, 0.05);
}

TEST(Adaptive, ErrorFollowsTheTolerance) {
  // Torque-free tumble with a largest step of 0.5 s, so the controller, not dt, sets the steps.
  // It holds the local error estimate (that of the embedded 4th-order solution) at the tolerance
  // and propagates the 5th-order one, so the global error at t = 2 s stays below the tolerance
  // and falls with it: monotonically, and by at least 1e4 over six decades (the theoretical
  // rate for an order-5 method with local extrapolation is tol^(5/4) or better).
  const Quat ref = tumble_for(tumbling_def(Integrator::Rk4, 1e-4, 0.0), 2.0).q;
  double previous = INFINITY, first = 0.0;
  for (double tol : {1e-4, 1e-6, 1e-8, 1e-10}) {
    const Outcome o = tumble_for(tumbling_def(Integrator::Adaptive, 0.5, tol), 2.0);
    const double err = test::angle_between(ref, o.q);
    if (first == 0.0) first = err;
    EXPECT_LT(err, tol) << "tolerance " << tol;
    EXPECT_LT(err, previous) << "tolerance " << tol;
    previous = err;
    EXPECT_GT(o.stats.accepted, 4);
    EXPECT_GT(o.stats.smallest_step_s, 0.0);
    EXPECT_LE(o.stats.largest_step_s, 0.5);
  }
  EXPECT_LT(previous, first / 1e4);
}

TEST(Adaptive, BeatsRk4InEvaluationsAtEqualError) {
  // At a tolerance of 1e-8, find the rk4 step that reaches the same orientation error and compare
  // the work: the embedded pair must need fewer derivative evaluations.
  const Quat ref = tumble_for(tumbling_def(Integrator::Rk4, 1e-4, 0.0), 2.0).q;
  const Outcome adaptive = tumble_for(tumbling_def(Integrator::Adaptive, 0.1, 1e-8), 2.0);
  const double target = test::angle_between(ref, adaptive.q);
  long rk4_evaluations = 0;
  for (double dt = 0.1; dt > 1e-4; dt /= 1.25) {
    const double dt_even = 2.0 / std::ceil(2.0 / dt);  // whole steps to t = 2
    const Outcome rk4 = tumble_for(tumbling_def(Integrator::Rk4, dt_even, 0.0), 2.0);
    if (test::angle_between(ref, rk4.q) <= target) {
      rk4_evaluations = rk4.evaluations;
      break;
    }
  }
  ASSERT_GT(rk4_evaluations, 0);
  EXPECT_LT(adaptive.evaluations, rk4_evaluations)
      << "adaptive error " << target << " with " << adaptive.evaluations << " evaluations";
}

TEST(Adaptive, IsDeterministicAndSamplingDoesNotDisturbIt) {
  // Two runs, one of them sampled at every frame time in between: the same bits at the end.
  WorldDef def = tumbling_def(Integrator::Adaptive, 0.05, 1e-9);
  def.gravity = Vec3(0, -g, 0);
  def.floor = FloorDef{};
  def.bodies[0].position = Vec3(0, 3, 0);
  World a(def), b(def);
  Sampler sampler(b);
  for (int k = 0; k <= 180; ++k) sampler.at(k / 60.0);
  while (a.step_count() < b.step_count()) a.step();
  EXPECT_EQ(a.bodies()[0].state.x, b.bodies()[0].state.x);
  EXPECT_EQ(a.bodies()[0].state.q.coeffs(), b.bodies()[0].state.q.coeffs());
  EXPECT_EQ(a.derivative_evaluations(), b.derivative_evaluations());
}

TEST(Adaptive, FirstImpactAtFreeFallTime) {
  // As for the fixed-step integrators: the impact time is located to 1e-12 s, so 0.1 s after the
  // bounce height and speed are those of the exact parabola (largest step 0.05 s).
  WorldDef def = test::world_def(Integrator::Adaptive, 0.05, true);
  BodyDef p = test::particle_def(1.0, Vec3(0, 2.0, 0));
  p.restitution = 0.5;
  def.bodies.push_back(p);
  World w(def);
  const double t_i = std::sqrt(2.0 * 2.0 / g);
  while (w.time() < t_i + 0.1) w.step();
  const double s = w.time() - t_i;
  EXPECT_NEAR(w.bodies()[0].state.x.y(), 0.5 * g * t_i * s - 0.5 * g * s * s, 1e-9);
  EXPECT_NEAR(w.bodies()[0].velocity().y(), 0.5 * g * t_i - g * s, 1e-9);
  ASSERT_EQ(w.contact_stats().events.size(), 1u);
  EXPECT_NEAR(w.contact_stats().events[0].t_s, t_i, 1e-11);
  EXPECT_NEAR(w.contact_stats().events[0].approach_speed_mps, g * t_i, 1e-9);
}

TEST(Adaptive, DefaultDropComesToRestOnAFace) {
  WorldDef def = test::world_def(Integrator::Adaptive, 0.01, true);
  def.tolerance = 1e-8;
  BodyDef b = test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 3, 0));
  b.orientation = Quat(Eigen::AngleAxisd(radians(30.0), Vec3(1, 0, 1).normalized()));
  b.angular_velocity = Vec3(0, 0, 2);
  def.bodies.push_back(b);
  World w(def);
  for (int i = 0; i < 600; ++i) w.step();
  const RigidBody& body = w.bodies()[0];
  EXPECT_TRUE(body.at_rest);
  // Resting on a face: the centre at half the edge, to the touch tolerance (1e-6 of the edge).
  EXPECT_NEAR(body.state.x.y(), 0.5, 1.1e-6);
  EXPECT_TRUE(w.diagnostics().empty());
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

long bounces_of(Integrator integrator, double dt) {
  WorldDef def = test::world_def(integrator, dt, true);
  BodyDef p = test::particle_def(1.0, Vec3(0, 0.5, 0));
  p.restitution = 0.5;
  def.bodies.push_back(p);
  World w(def);
  const long steps = std::lround(3.0 / dt);
  for (long i = 0; i < steps; ++i) w.step();
  long n = 0;
  for (const ImpactEvent& e : w.contact_stats().events)
    n += e.approach_speed_mps >= 1e-2;  // slower ones are inelastic for every integrator
  return n;
}

TEST(Adaptive, BouncesDownLikeAFineRunAtTheSeedsStep) {
  // A particle dropped from 0.5 m (3.1 m/s at impact, e = 0.5) meets the floor until its speed
  // falls below 1 cm/s: 9 impacts. Fixed steps of 1/30 s stop it at the first impact slower than
  // 2 g dt = 0.65 m/s (the 4th, at 0.39 m/s); the adaptive integrator with that largest step
  // keeps the small-dt rest speed and bounces as rk4 at dt = 1e-4 does.
  EXPECT_EQ(bounces_of(Integrator::Rk4, 1e-4), 9);
  EXPECT_EQ(bounces_of(Integrator::Rk4, 1.0 / 30.0), 4);
  EXPECT_EQ(bounces_of(Integrator::Adaptive, 1.0 / 30.0), 9);
}

}  // namespace
}  // namespace tumble
