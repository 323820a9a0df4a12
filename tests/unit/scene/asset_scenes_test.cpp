#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "tumble/sampler.hpp"
#include "tumble/scene.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

const std::filesystem::path kSceneDir = std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets/scenes";

Scene load(std::string_view name) {
  return load_scene_file(kSceneDir / name);
}

TEST(AssetScenes, EveryOneLoads) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(kSceneDir))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 5u);
  for (const auto& file : files) {
    try {
      const Scene scene = load_scene_file(file);
      EXPECT_EQ(scene.stem, file.stem().string());
      EXPECT_FALSE(scene.bodies.empty());
    } catch (const Error& e) {
      ADD_FAILURE() << e.describe();
    }
  }
}

TEST(AssetScenes, SeedDropUsesTheSeedsSettings) {
  const Scene scene = load("seed_drop.toml");
  EXPECT_NEAR(scene.simulation.dt_s, 1.0 / 30.0, 1e-15);  // written to 15 decimals
  EXPECT_EQ(scene.simulation.integrator, Integrator::Midpoint);
  EXPECT_EQ(scene.simulation.rotation, RotationRep::Matrix);
  EXPECT_EQ(scene.simulation.duration_s, 6.0);
  ASSERT_TRUE(scene.floor.has_value());
  EXPECT_EQ(scene.floor->restitution, 0.5);
  EXPECT_EQ(scene.bodies.at(0).position.y(), 3.0);
  EXPECT_NE(scene.bodies[0].angular_velocity, Vec3::Zero());
}

TEST(AssetScenes, FlatDropStartsWithItsBottomFaceAtTwoMetres) {
  const Scene scene = load("flat_drop.toml");
  const BodySpec& box = scene.bodies.at(0);
  EXPECT_EQ(box.position.y() - box.size.y() / 2.0, 2.0);
  EXPECT_EQ(box.orientation.coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(box.angular_velocity, Vec3::Zero());
  EXPECT_EQ(box.restitution, 0.8);
  EXPECT_EQ(scene.simulation.duration_s, 5.0);
  EXPECT_TRUE(scene.floor.has_value());
}

TEST(AssetScenes, IntermediateAxisSpinIsMostlyAboutY) {
  const Scene scene = load("tumble_intermediate_axis.toml");
  EXPECT_FALSE(scene.floor.has_value());
  EXPECT_EQ(scene.simulation.gravity, Vec3::Zero());
  const BodySpec& box = scene.bodies.at(0);
  // Moments of a box go as the sum of squares of the other two edges: y's is in the middle.
  const Vec3 s = box.size.cwiseProduct(box.size);
  const Vec3 moments(s.y() + s.z(), s.x() + s.z(), s.x() + s.y());
  EXPECT_GT(moments.x(), moments.y());
  EXPECT_GT(moments.y(), moments.z());
  const Vec3 w = box.angular_velocity;
  EXPECT_GT(std::abs(w.y()), 20.0 * std::abs(w.x()));
  EXPECT_GT(std::abs(w.y()), 20.0 * std::abs(w.z()));
  EXPECT_NE(w.x(), 0.0);  // the perturbation that makes the flip happen
}

TEST(AssetScenes, ParticleIsThrownOntoABouncyFloor) {
  const Scene scene = load("particle.toml");
  const BodySpec& p = scene.bodies.at(0);
  EXPECT_EQ(p.shape, Shape::Particle);
  EXPECT_EQ(p.mass, 0.1);
  EXPECT_EQ(p.position, Vec3(-2.0, 1.0, 0.0));
  EXPECT_EQ(p.velocity, Vec3(1.0, 4.0, 0.0));
  ASSERT_TRUE(scene.floor.has_value());
  EXPECT_EQ(scene.floor->restitution, 0.7);
  EXPECT_EQ(scene.simulation.duration_s, 3.0);
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

// Under the sanitizers (a -O1 debug build, Eigen's checks on) the physics runs some 18x slower:
// there each scene runs its first half second, which reaches every example's impacts and held
// contacts; the optimised build runs each whole. (dominoes.toml's whole 1.5 s is 6 min there.)
#if defined(__SANITIZE_ADDRESS__)
constexpr double kLongestRun = 0.5;
#else
constexpr double kLongestRun = INFINITY;
#endif

TEST(AssetScenes, EveryOneAndTheDefaultRunWithoutDiagnostics) {
  // No false alarms: the scenes users start from must not warn. Each runs its whole duration
  // (under the sanitizers its first kLongestRun seconds).
  std::vector<Scene> scenes{default_scene()};
  for (const auto& entry : std::filesystem::directory_iterator(kSceneDir))
    if (entry.path().extension() == ".toml") scenes.push_back(load_scene_file(entry.path()));
  for (const Scene& scene : scenes) {
    World world(make_world_def(scene));
    const double duration = std::min(scene.simulation.duration_s, kLongestRun);
    const long steps = step_count_for(duration, scene.simulation.dt_s);
    for (long i = 0; i < steps; ++i) world.step();
    for (const Diagnostic& d : world.diagnostics().list())
      ADD_FAILURE() << scene.source_name << ": " << d.code << ": " << d.message;
  }
}

}  // namespace
}  // namespace tumble
