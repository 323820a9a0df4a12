#include <gtest/gtest.h>

#include <filesystem>

#include "tumble/scene.hpp"

namespace tumble {
namespace {

const std::filesystem::path kDefaultSceneFile =
    std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets/scenes/default.toml";

// Every setting of two scenes, compared exactly (source name, text and stem aside).
void ExpectSameSettings(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.simulation.duration_s, b.simulation.duration_s);
  EXPECT_EQ(a.simulation.dt_s, b.simulation.dt_s);
  EXPECT_EQ(a.simulation.integrator, b.simulation.integrator);
  EXPECT_EQ(a.simulation.rotation, b.simulation.rotation);
  EXPECT_EQ(a.simulation.gravity, b.simulation.gravity);
  EXPECT_EQ(a.simulation.linear_drag, b.simulation.linear_drag);
  EXPECT_EQ(a.simulation.angular_drag, b.simulation.angular_drag);
  ASSERT_EQ(a.floor.has_value(), b.floor.has_value());
  if (a.floor) {
    EXPECT_EQ(a.floor->height, b.floor->height);
    EXPECT_EQ(a.floor->restitution, b.floor->restitution);
    EXPECT_EQ(a.floor->friction, b.floor->friction);
  }
  EXPECT_EQ(a.render.fps, b.render.fps);
  EXPECT_EQ(a.render.width, b.render.width);
  EXPECT_EQ(a.render.height, b.render.height);
  EXPECT_EQ(a.render.msaa, b.render.msaa);
  EXPECT_EQ(a.render.background, b.render.background);
  EXPECT_EQ(a.camera.position, b.camera.position);
  EXPECT_EQ(a.camera.target, b.camera.target);
  EXPECT_EQ(a.camera.up, b.camera.up);
  EXPECT_EQ(a.camera.fov_deg, b.camera.fov_deg);
  EXPECT_EQ(a.camera.follow, b.camera.follow);
  EXPECT_EQ(a.light.direction, b.light.direction);
  EXPECT_EQ(a.light.shadows, b.light.shadows);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const BodySpec& x = a.bodies[i];
    const BodySpec& y = b.bodies[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.shape, y.shape);
    EXPECT_EQ(x.size, y.size);
    EXPECT_EQ(x.mesh, y.mesh);
    EXPECT_EQ(x.scale, y.scale);
    EXPECT_EQ(x.mass, y.mass);
    EXPECT_EQ(x.density, y.density);
    EXPECT_EQ(x.position, y.position);
    EXPECT_EQ(x.orientation.coeffs(), y.orientation.coeffs());
    EXPECT_EQ(x.velocity, y.velocity);
    EXPECT_EQ(x.angular_velocity, y.angular_velocity);
    EXPECT_EQ(x.restitution, y.restitution);
    EXPECT_EQ(x.color, y.color);
  }
}

TEST(DefaultScene, IsTheSeedExperiment) {
  const Scene scene = default_scene();
  EXPECT_EQ(scene.source_name, "<default>");
  EXPECT_EQ(scene.stem, "default");
  EXPECT_EQ(scene.simulation.duration_s, 4.0);
  EXPECT_EQ(scene.simulation.dt_s, 0.001);
  EXPECT_EQ(scene.simulation.integrator, Integrator::Rk4);
  ASSERT_TRUE(scene.floor.has_value());
  EXPECT_EQ(scene.floor->restitution, 0.5);
  ASSERT_EQ(scene.bodies.size(), 1u);
  const BodySpec& box = scene.bodies[0];
  EXPECT_EQ(box.name, "box");
  EXPECT_EQ(box.shape, Shape::Box);
  EXPECT_EQ(box.size, Vec3(1.0, 1.0, 1.0));
  EXPECT_EQ(box.mass, 1.0);
  EXPECT_EQ(box.position, Vec3(0.0, 3.0, 0.0));
  // 30 degrees about (1, 0, 1) / sqrt(2); 1e-12 is round-off on a unit quaternion.
  const Eigen::AngleAxisd tilt(box.orientation);
  EXPECT_NEAR(tilt.angle(), radians(30.0), 1e-12);
  EXPECT_TRUE(tilt.axis().isApprox(Vec3(1.0, 0.0, 1.0).normalized(), 1e-12));
  EXPECT_EQ(box.angular_velocity, Vec3(0.0, 0.0, 2.0));
  EXPECT_EQ(to_string(box.color), "#d9572b");
}

TEST(DefaultScene, MatchesTheAssetFile) {
  const Scene from_file = load_scene_file(kDefaultSceneFile);
  const Scene built_in = default_scene();
  ExpectSameSettings(built_in, from_file);
}

}  // namespace
}  // namespace tumble
