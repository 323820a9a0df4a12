// The framing pass keeps the worlds the drawing pass needs within its byte budget, and hands on
// the stepping world so that the drawing pass goes on bit for bit as if it had simulated from
// the start: whatever the budget, the same worlds at every time, the same camera.
#include "framing_pass.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tumble/camera_framing.hpp"
#include "tumble/sampler.hpp"
#include "tumble/world_builder.hpp"

namespace tumble::cli {
namespace {

// A tilted, spinning box dropped onto a floor (impacts, then rest): no camera, so it is framed.
constexpr const char* kScene = R"(
[simulation]
duration = 1.0
[floor]
restitution = 0.6
[render]
fps = 30
width = 160
height = 120
[[body]]
name = "box"
shape = "box"
size = [0.4, 0.3, 0.2]
mass = 1.0
position = [0.0, 1.0, 0.0]
orientation = { axis = [1.0, 0.0, 1.0], degrees = 30.0 }
angular_velocity = [0.0, 1.0, 3.0]
)";

struct DropRun {
  Scene scene = parse_scene(kScene, "drop.toml", {});
  WorldDef def = make_world_def(scene);
  std::vector<double> times;  // clip frames and two exposures between them
  DropRun() {
    for (long k = 0; k < 30; ++k) times.push_back(static_cast<double>(k) / 30.0);
    times.push_back(0.123);
    times.push_back(0.77);
    std::sort(times.begin(), times.end());
  }
  FramingPass pass(std::size_t budget) const {
    Progress quiet(
        Progress::Style::Off, 0, "", "", [] { return 0.0; }, [](const std::string&) {});
    return framing_pass(scene, def, times, budget, quiet);
  }
};

bool same_state(const World& a, const World& b) {
  return same_poses(a, b) && a.bodies()[0].state.P == b.bodies()[0].state.P &&
         a.bodies()[0].state.L == b.bodies()[0].state.L;
}

// The drawing pass as FramePipeline does it: the kept world where there is one, else sampled
// from the resume world. Compared with a run simulated from the start at every time, and at
// the end: step count, evaluations and impacts.
void expect_same_run_as_from_the_start(const DropRun& run, FramingPass pass) {
  World fresh(run.def);
  Sampler reference(fresh);
  ASSERT_TRUE(pass.kept.resume.has_value());
  World resumed = std::move(*pass.kept.resume);
  Sampler sampler(resumed);
  for (const double t : run.times) {
    const World expected = reference.at(t);
    std::optional<World> got = pass.kept.take(t);
    if (!got) got = sampler.at(t);
    EXPECT_TRUE(same_state(*got, expected)) << "t = " << t;
  }
  const double end = run.scene.simulation.duration_s;
  EXPECT_TRUE(same_state(sampler.at(end), reference.at(end)));
  EXPECT_EQ(resumed.step_count(), fresh.step_count());
  EXPECT_EQ(resumed.derivative_evaluations(), fresh.derivative_evaluations());
  EXPECT_EQ(resumed.contact_stats().impacts, fresh.contact_stats().impacts);
  EXPECT_GT(fresh.contact_stats().impacts, 0);
}

TEST(FramingPass, PlacesTheCameraAsFrameCameraDoes) {
  const DropRun run;
  const CameraSettings expected = frame_camera(run.scene, run.def);
  for (const std::size_t budget : {std::size_t{0}, std::size_t{20000}, kFramingKeepBytes}) {
    const FramingPass pass = run.pass(budget);
    EXPECT_EQ(pass.camera.position, expected.position) << budget;
    EXPECT_EQ(pass.camera.target, expected.target) << budget;
    EXPECT_TRUE(pass.camera.framed);
    EXPECT_GE(pass.seconds, 0.0);
  }
}

TEST(FramingPass, KeepsEveryWorldWithinTheDefaultBudget) {
  const DropRun run;
  FramingPass pass = run.pass(kFramingKeepBytes);
  EXPECT_TRUE(pass.kept.complete);
  EXPECT_EQ(pass.kept.times_s, run.times);
  EXPECT_GT(pass.kept.bytes, 0u);
  EXPECT_LE(pass.kept.bytes, kFramingKeepBytes);
  expect_same_run_as_from_the_start(run, std::move(pass));
}

TEST(FramingPass, ZeroBudgetKeepsNothing) {
  // The reference: nothing kept, nothing handed on; the drawing pass simulates afresh.
  const DropRun run;
  const FramingPass pass = run.pass(0);
  EXPECT_FALSE(pass.kept.complete);
  EXPECT_TRUE(pass.kept.times_s.empty());
  EXPECT_FALSE(pass.kept.resume.has_value());
}

TEST(FramingPass, ABudgetTooSmallForOneWorldResumesFromWhereKeepingStopped) {
  // One byte: the first time to keep does not fit, so the stepping world is handed on from just
  // before it (here the start: the first clip frame is t = 0).
  const DropRun run;
  FramingPass pass = run.pass(1);
  EXPECT_TRUE(pass.kept.times_s.empty());
  ASSERT_TRUE(pass.kept.resume.has_value());
  EXPECT_EQ(pass.kept.resume->step_count(), 0);
  expect_same_run_as_from_the_start(run, std::move(pass));
}

TEST(FramingPass, PartBudgetKeepsTheFirstTimesAndResumesAfterThem) {
  // Room for about ten worlds of one box: the first ten or so times kept, the rest simulated
  // again from where the pass stopped keeping.
  const DropRun run;
  const std::size_t one = world_bytes(World(run.def));
  FramingPass pass = run.pass(10 * one + one / 2);
  EXPECT_FALSE(pass.kept.complete);
  EXPECT_GE(pass.kept.times_s.size(), 5u);
  EXPECT_LT(pass.kept.times_s.size(), run.times.size());
  ASSERT_TRUE(pass.kept.resume.has_value());
  EXPECT_GT(pass.kept.resume->step_count(), 0);
  // The budget bounds what is kept, give or take the last world (its size is guessed before).
  EXPECT_LE(pass.kept.bytes, 10 * one + one / 2 + one);
  expect_same_run_as_from_the_start(run, std::move(pass));
}

TEST(FramingPass, WorldBytesGrowWithBodiesAndRecords) {
  DropRun run;
  const std::size_t one = world_bytes(World(run.def));
  run.def.bodies.push_back(run.def.bodies[0]);
  run.def.bodies.back().position = Vec3(2.0, 1.0, 0.0);
  EXPECT_GT(world_bytes(World(run.def)), one + sizeof(RigidBody));
}

}  // namespace
}  // namespace tumble::cli
