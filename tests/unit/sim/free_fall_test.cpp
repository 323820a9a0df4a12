// Free fall under constant gravity: x(t) = x0 + v0 t + ½ g t², exact for every integrator of
// order >= 2; the Euler variants are off by exactly ∓½ g t dt (their local error is ½ g dt² per
// step, all of one sign).
#include <gtest/gtest.h>

#include "sim_fixtures.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

using test::box_def;
using test::particle_def;

struct FallCase {
  Integrator integrator;
  bool particle;
};

Vec3 fall_error(Integrator integrator, bool particle, double dt, int steps) {
  WorldDef def = test::world_def(integrator, dt, /*floor=*/false);
  const Vec3 x0(0.3, 10.0, -0.2), v0(1.0, 2.0, -0.5);
  BodyDef body = particle ? particle_def(2.0, x0) : box_def(Vec3(1, 2, 3), 2.0, x0);
  body.velocity = v0;
  def.bodies.push_back(body);
  World world(def);
  for (int i = 0; i < steps; ++i) world.step();
  const double t = world.time();
  const Vec3 exact = x0 + v0 * t + 0.5 * def.gravity * t * t;
  return world.bodies()[0].state.x - exact;
}

class ExactOnParabola : public ::testing::TestWithParam<FallCase> {};

TEST_P(ExactOnParabola, PositionMatchesClosedForm) {
  // 400 steps of a few-metre state: round-off bound ~ 400 · 2e-16 · 20 m ≈ 2e-12 m.
  const Vec3 err = fall_error(GetParam().integrator, GetParam().particle, 0.005, 400);
  EXPECT_LT(err.cwiseAbs().maxCoeff(), 1e-11);
}

INSTANTIATE_TEST_SUITE_P(FreeFall, ExactOnParabola,
                         ::testing::Values(FallCase{Integrator::Rk4, true},
                                           FallCase{Integrator::Rk4, false},
                                           FallCase{Integrator::Midpoint, true},
                                           FallCase{Integrator::Midpoint, false}));

TEST(FreeFall, ExplicitEulerLagsByHalfGTdt) {
  const double dt = 0.01;
  const int steps = 200;
  const double t = dt * steps;
  const Vec3 err = fall_error(Integrator::Euler, true, dt, steps);
  // x_n = x0 + v0 t + ½ g t² − ½ g t dt: the body is higher than exact when g points down.
  EXPECT_NEAR(err.y(), -0.5 * -9.81 * t * dt, 1e-11);
  EXPECT_NEAR(err.x(), 0.0, 1e-12);
}

TEST(FreeFall, SymplecticEulerLeadsByHalfGTdt) {
  const double dt = 0.01;
  const int steps = 200;
  const double t = dt * steps;
  const Vec3 err = fall_error(Integrator::SymplecticEuler, false, dt, steps);
  EXPECT_NEAR(err.y(), 0.5 * -9.81 * t * dt, 1e-11);
  EXPECT_NEAR(err.z(), 0.0, 1e-12);
}

}  // namespace
}  // namespace tumble
