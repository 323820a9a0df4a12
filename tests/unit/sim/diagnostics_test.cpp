// Diagnostics: every suspect regime is reported once with a fix, a run that stops being finite
// ends with an error naming the time, and a trustworthy run stays silent.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_fixtures.hpp"
#include "tumble/error.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

World spinning_box(Integrator integrator, double dt, const Vec3& omega) {
  WorldDef def = test::world_def(integrator, dt, /*floor=*/false);
  def.gravity.setZero();
  BodyDef body = test::box_def(Vec3(1.0, 2.0, 3.0), 3.0, Vec3::Zero());
  body.angular_velocity = omega;
  def.bodies.push_back(body);
  return World(def);
}

const Diagnostic* find(const World& w, const std::string& code) {
  for (const Diagnostic& d : w.diagnostics().list())
    if (d.code == code) return &d;
  return nullptr;
}

TEST(Diagnostics, ExplicitEulerAtACoarseStepIsFlagged) {
  // dt·|ω| = 0.02 · 20 = 0.4 rad per step: four times what explicit Euler follows (0.1). It also
  // pumps energy into the tumble (each step's rotation is too large) and its quaternion leaves
  // unit length by (dt|ω|)²/8 = 2 % per step: three diagnostics, each naming a fix.
  World w = spinning_box(Integrator::Euler, 0.02, Vec3(1.0, 20.0, 1.0));
  for (int i = 0; i < 100; ++i) w.step();
  const Diagnostic* spin = find(w, "step_too_large_for_spin");
  ASSERT_NE(spin, nullptr);
  EXPECT_EQ(spin->severity, "warning");
  EXPECT_EQ(spin->t_s, 0.0);  // from the first step
  EXPECT_NE(spin->fix.find("dt <="), std::string::npos) << spin->fix;
  EXPECT_GE(spin->occurrences, 100);
  EXPECT_NE(find(w, "free_flight_energy_gain"), nullptr);
  EXPECT_NE(find(w, "rotation_drift"), nullptr);
}

TEST(Diagnostics, Rk4AtAFineStepIsSilent) {
  World w = spinning_box(Integrator::Rk4, 0.001, Vec3(1.0, 20.0, 1.0));
  for (int i = 0; i < 2000; ++i) w.step();
  EXPECT_TRUE(w.diagnostics().empty());
}

TEST(Diagnostics, EachCodeIsKeptOnceWithItsFirstTime) {
  Diagnostics d;
  d.warn("a", 0.5, "first", "fix a");
  d.warn("b", 0.7, "other", "fix b");
  d.warn("a", 0.9, "again", "fix a");
  ASSERT_EQ(d.list().size(), 2u);
  EXPECT_EQ(d.list()[0].t_s, 0.5);
  EXPECT_EQ(d.list()[0].message, "first");
  EXPECT_EQ(d.list()[0].occurrences, 2);
  EXPECT_TRUE(d.has("b"));
  EXPECT_FALSE(d.has("c"));
}

TEST(Diagnostics, AStateThatStopsBeingFiniteEndsTheRunNamingTheTime) {
  // Linear drag c = 1e6 N·s/m on 1 kg: explicit Euler multiplies v by (1 − c dt/m) = −999 every
  // step, so the speed overflows to infinity within ~100 steps. The world throws before any
  // non-finite state can be sampled.
  WorldDef def = test::world_def(Integrator::Euler, 0.001, false);
  def.linear_drag = 1e6;
  BodyDef p = test::particle_def(1.0, Vec3(0, 1, 0));
  p.velocity = Vec3(1, 0, 0);
  def.bodies.push_back(p);
  World w(def);
  try {
    for (int i = 0; i < 1000; ++i) {
      w.step();
      ASSERT_TRUE(w.bodies()[0].state.x.allFinite());
    }
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    const std::string what = e.what();
    EXPECT_NE(what.find("stopped being finite near t = "), std::string::npos) << what;
    EXPECT_NE(what.find("smaller dt"), std::string::npos) << what;
  }
}

TEST(Diagnostics, AdaptiveHandlesTheStiffDragThatBreaksEuler) {
  // The same stiff drag under the adaptive integrator: the controller finds the stable step
  // (about 3/λ = 3e-6 s), the speed decays as e^(−c t/m) and nothing is flagged.
  WorldDef def = test::world_def(Integrator::Adaptive, 0.001, false);
  def.linear_drag = 1e6;
  def.gravity.setZero();
  def.tolerance = 1e-8;
  BodyDef p = test::particle_def(1.0, Vec3(0, 1, 0));
  p.velocity = Vec3(1, 0, 0);
  def.bodies.push_back(p);
  World w(def);
  for (int i = 0; i < 10; ++i) w.step();
  // Terminal displacement: v0 m / c = 1e-6 m; the motion has died out after 10 ms.
  EXPECT_NEAR(w.bodies()[0].state.x.x(), 1e-6, 1e-12);
  EXPECT_TRUE(w.diagnostics().empty());
  EXPECT_GT(w.step_stats().rejected, 0);
}

TEST(Diagnostics, AdaptiveStepPinnedAtItsMinimumIsFlagged) {
  // Drag c = 1e11 N·s/m on 1 kg needs steps below ~3e-11 s to be stable; the controller's floor
  // is 1e-6 dt = 1e-9 s, so it is pinned there, says so, and the run then diverges.
  WorldDef def = test::world_def(Integrator::Adaptive, 0.001, false);
  def.linear_drag = 1e11;
  def.gravity.setZero();
  BodyDef p = test::particle_def(1.0, Vec3(0, 1, 0));
  p.velocity = Vec3(1, 0, 0);
  def.bodies.push_back(p);
  World w(def);
  EXPECT_THROW(
      {
        for (int i = 0; i < 100; ++i) w.step();
      },
      Error);
  EXPECT_TRUE(w.diagnostics().has("adaptive_step_pinned"));
}

}  // namespace
}  // namespace tumble
