// GL-free camera maths: where world points land in the image (top-left origin pixels).
#include "tumble/camera.hpp"

#include <gtest/gtest.h>

#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

Scene scene_with_camera(int width, int height) {
  Scene s = parse_scene(R"([camera]
position = [5.0, 3.0, 6.0]
target = [0.0, 0.5, 0.0]
[[body]]
name = "ball"
shape = "particle"
mass = 1.0
position = [1.0, 2.0, 0.0]
)",
                        "camera.toml");
  s.render.width = width;
  s.render.height = height;
  return s;
}

TEST(Camera, TargetLandsInTheImageCentre) {
  const Scene s = scene_with_camera(1280, 720);
  const Eigen::Matrix4d vp = camera_view_projection(s, s.camera.target);
  const std::optional<Eigen::Vector2d> px = to_pixels(vp, s.camera.target, 1280, 720);
  ASSERT_TRUE(px.has_value());
  EXPECT_NEAR(px->x(), 640.0, 1e-9);
  EXPECT_NEAR(px->y(), 360.0, 1e-9);
}

TEST(Camera, RowsGrowDownwardsAndBehindIsNone) {
  const Scene s = scene_with_camera(640, 480);
  const Eigen::Matrix4d vp = camera_view_projection(s, s.camera.target);
  const Vec3 above = s.camera.target + Vec3(0, 0.5, 0);
  EXPECT_LT(to_pixels(vp, above, 640, 480)->y(), 240.0);
  // Behind the camera: on the far side of the eye from the target.
  const Vec3 behind = s.camera.position + (s.camera.position - s.camera.target);
  EXPECT_FALSE(to_pixels(vp, behind, 640, 480).has_value());
}

TEST(Camera, PixelsScaleWithTheImage) {
  // The same view at twice the size: every point lands at twice the pixel coordinates.
  const Vec3 p(0.7, 1.2, -0.4);
  const Scene small = scene_with_camera(320, 180), large = scene_with_camera(640, 360);
  const Eigen::Vector2d a =
      *to_pixels(camera_view_projection(small, small.camera.target), p, 320, 180);
  const Eigen::Vector2d b =
      *to_pixels(camera_view_projection(large, large.camera.target), p, 640, 360);
  EXPECT_NEAR(b.x(), 2.0 * a.x(), 1e-9);
  EXPECT_NEAR(b.y(), 2.0 * a.y(), 1e-9);
}

TEST(Camera, FollowLooksAtTheBody) {
  Scene s = scene_with_camera(1280, 720);
  s.camera.follow = "ball";
  const World world(make_world_def(s));
  EXPECT_EQ(followed_body(s), std::optional<std::size_t>(0));
  EXPECT_EQ(camera_target(s, world), Vec3(1.0, 2.0, 0.0));
  const std::optional<Eigen::Vector2d> px =
      to_pixels(camera_view_projection(s, world), world.bodies()[0].state.x, 1280, 720);
  EXPECT_NEAR(px->x(), 640.0, 1e-9);
  EXPECT_NEAR(px->y(), 360.0, 1e-9);
}

}  // namespace
}  // namespace tumble
