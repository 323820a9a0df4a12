// The exact reference against the World itself: where the scene has one, fine rk4 must agree with
// it to round-off (rk4 is exact on parabolas, impacts are located to 1e-12 s), bounce for bounce.
#include "../../../src/study/analytic_reference.hpp"

#include <gtest/gtest.h>

#include "../../../src/study/run_comparison.hpp"

namespace tumble::study {
namespace {

// A particle thrown sideways onto a floor with e = 0.5: about 10 bounces, then it slides on the
// frictionless floor (the rest speed, 1 cm/s·√ℓ = 4.5 mm/s for its 0.2 m, ends the bouncing at
// t ≈ 1.35 s, well inside the run).
constexpr const char* kParticle = R"([simulation]
duration = 2.0
[floor]
restitution = 0.5
[[body]]
name = "ball"
shape = "particle"
size = [0.2, 0.2, 0.2]
mass = 0.1
position = [-1.0, 1.0, 0.0]
velocity = [1.0, 0.0, 0.0]
)";

// A unit box dropped flat, e = 0.5: it bounces on its face, then rests (and is put to sleep) at
// t ≈ 1.9 s.
constexpr const char* kFlatBox = R"([simulation]
duration = 2.5
[floor]
restitution = 0.5
[[body]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 2.5, 0.0]
)";

RunRecord fine_rk4(const StudySetup& setup) {
  // dt = 1e-4: its rest speed max(1 cm/s·√ℓ, 2 g dt) is the small-dt limit the reference uses.
  return record_world(setup, setup.def_for(Integrator::Rk4, 1e-4, std::nullopt), {});
}

// The samples before time t.
RunRecord before(RunRecord r, double t) {
  while (!r.times.empty() && r.times.back() >= t) r.times.pop_back(), r.samples.pop_back();
  return r;
}

TEST(AnalyticReference, ParticleBouncesLikeFineRk4) {
  const Scene scene = parse_scene(kParticle, "particle.toml");
  const StudySetup setup(scene);
  ASSERT_FALSE(analytic_obstacle(setup).has_value());
  const AnalyticReference exact = analytic_reference(setup);
  const RunRecord rk4 = fine_rk4(setup);
  // While it bounces: each impact time is located to 1e-12 s and each bounce speed follows from
  // it; after ten bounces at up to 4.4 m/s, 1e-9 m is a hundred times the round-off seen.
  const double rest_time = exact.record.events.back().t_s;
  EXPECT_LT(
      compare_runs(before(rk4, rest_time), before(exact.record, rest_time), 1.0 / 60.0).position_m,
      1e-9);
  // Then it stops anywhere within its touch tolerance (1e-6 ℓ = 2e-7 m) above the floor.
  EXPECT_EQ(exact.uncertainty_m, 1e-6 * 0.2);
  const RunErrors e = compare_runs(rk4, exact.record, 1.0 / 60.0);
  EXPECT_LE(e.position_m, exact.uncertainty_m);
  EXPECT_GE(e.bounces, 9);
  EXPECT_EQ(e.missed, 0);
  EXPECT_EQ(e.extra, 0);
  ASSERT_TRUE(e.impact_time_s.has_value());
  EXPECT_LT(*e.impact_time_s, 1e-9);
  // The last impact stops it: the particle ends on the floor, sliding at its 1 m/s.
  const BodySample& end = exact.record.samples.back()[0];
  EXPECT_NEAR(end.points[0].y(), 0.0, 1e-12);
  EXPECT_NEAR(end.points[0].x(), -1.0 + 2.0, 1e-12);
  EXPECT_TRUE(end.touching);
}

TEST(AnalyticReference, RoundOffAloneWhileNothingRests) {
  // The same throw for 0.5 s: one bounce, never at rest.
  std::string text = kParticle;
  text.replace(text.find("duration = 2.0"), 14, "duration = 0.5");
  const Scene scene = parse_scene(text, "particle.toml");
  EXPECT_EQ(analytic_reference(StudySetup(scene)).uncertainty_m, 1e-9 * 0.2);
}

TEST(AnalyticReference, FlatBoxBouncesAndRestsLikeFineRk4) {
  const Scene scene = parse_scene(kFlatBox, "flat.toml");
  const StudySetup setup(scene);
  ASSERT_FALSE(analytic_obstacle(setup).has_value());
  const AnalyticReference exact = analytic_reference(setup);
  const RunRecord rk4 = fine_rk4(setup);
  // Until the box comes to rest, as for the particle (its 8 corners move with its centre).
  const double rest_time = exact.record.events.back().t_s;
  const RunRecord exact_flight = before(exact.record, rest_time);
  const RunRecord rk4_flight = before(rk4, rest_time);
  const RunErrors flight = compare_runs(rk4_flight, exact_flight, 1.0 / 60.0);
  EXPECT_LT(flight.position_m, 1e-9);
  EXPECT_LT(flight.orientation_rad, 1e-12);
  // The whole run: a slow box stops anywhere within its touch tolerance (1e-6 m) above the
  // floor, where the steps fall; the reference says so in its uncertainty.
  EXPECT_EQ(exact.uncertainty_m, 1e-6);
  const RunErrors e = compare_runs(rk4, exact.record, 1.0 / 60.0);
  EXPECT_LE(e.position_m, exact.uncertainty_m);
  EXPECT_EQ(e.missed, 0);
  EXPECT_EQ(e.extra, 0);
  EXPECT_GE(e.bounces, 9);
  ASSERT_TRUE(e.impact_time_s.has_value());
  EXPECT_LT(*e.impact_time_s, 1e-9);
  // At rest on its face: the bottom corners on the floor.
  EXPECT_NEAR(exact.record.samples.back()[0].points[0].y(), 0.0, 1e-12);
}

TEST(AnalyticReference, FirstImpactAtFreeFallTime) {
  // Dropped from h = 1 m (the particle's centre): t = sqrt(2h/g), speed sqrt(2 g h).
  const Scene scene = parse_scene(kParticle, "particle.toml");
  const RunRecord exact = analytic_reference(StudySetup(scene)).record;
  ASSERT_FALSE(exact.events.empty());
  EXPECT_NEAR(exact.events[0].t_s, std::sqrt(2.0 / 9.81), 1e-15);
  EXPECT_NEAR(exact.events[0].approach_speed_mps, std::sqrt(2.0 * 9.81), 1e-14);
  EXPECT_NEAR(exact.events[1].t_s - exact.events[0].t_s, 2.0 * 0.5 * std::sqrt(2.0 / 9.81), 1e-14);
}

std::string box_scene(const std::string& extra_simulation, const std::string& extra_body) {
  return "[simulation]\nduration = 1.0\n" + extra_simulation +
         "[floor]\n[[body]]\nname = \"box\"\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1.0\n"
         "position = [0, 2, 0]\n" +
         extra_body;
}

TEST(AnalyticObstacle, NamesWhatRulesTheExactSolutionOut) {
  auto obstacle = [](const std::string& text) {
    const Scene scene = parse_scene(text, "s.toml");
    return analytic_obstacle(StudySetup(scene)).value_or("");
  };
  EXPECT_EQ(obstacle(box_scene("", "")), "");
  EXPECT_EQ(obstacle(box_scene("", "angular_velocity = [0, 0, 1]\n")), "body \"box\" spins");
  EXPECT_EQ(obstacle(box_scene("linear_drag = 0.1\n", "")), "the scene models drag");
  EXPECT_EQ(obstacle(box_scene("", "orientation = { axis = [1, 0, 0], degrees = 30 }\n")),
            "body \"box\" does not land on a flat face");
  // A quarter turn about x puts another face down: flat again.
  EXPECT_EQ(obstacle(box_scene("", "orientation = { axis = [1, 0, 0], degrees = 90 }\n")), "");
  EXPECT_EQ(obstacle(box_scene("gravity = [1, -9.81, 0]\n", "")),
            "gravity is not perpendicular to the floor");
}

}  // namespace
}  // namespace tumble::study
