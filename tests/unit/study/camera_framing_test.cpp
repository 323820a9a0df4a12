// Framing a run: the camera fitted to the points the bodies occupy sees every one of them inside
// the image with the stated margin, at the smallest such distance (or ortho height), from the
// stated direction; a stated camera is left alone. Projected with the renderer's own camera
// maths (camera.hpp), so a point inside here is a point inside the picture.
#include "tumble/camera_framing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tumble/camera.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

// A spread of points, not symmetric about anything.
std::vector<Vec3> some_points() {
  return {{-1.0, 0.0, 0.5}, {2.0, 3.5, -1.0}, {0.3, 0.2, 2.0}, {4.0, 0.5, 0.0}, {-0.5, 1.0, -2.5}};
}

Scene scene_of(const CameraSettings& camera, int width, int height) {
  Scene s =
      parse_scene("[[body]]\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\n", "s.toml");
  s.camera = camera;
  s.render.width = width;
  s.render.height = height;
  return s;
}

// The largest |NDC x| or |NDC y| of the points (1: on the image edge), and whether every point
// is in front of the camera.
double largest_ndc(const Scene& s, const std::vector<Vec3>& points, bool& all_in_front) {
  const Eigen::Matrix4d vp = camera_view_projection(s, s.camera.target);
  double largest = 0.0;
  all_in_front = true;
  for (const Vec3& p : points) {
    const Eigen::Vector4d clip = vp * p.homogeneous();
    all_in_front &= clip.w() > 0.0 && std::abs(clip.z() / clip.w()) < 1.0;
    largest = std::max({largest, std::abs(clip.x() / clip.w()), std::abs(clip.y() / clip.w())});
  }
  return largest;
}

TEST(CameraFraming, PerspectiveFitsEveryPointWithTheMarginAndNoMore) {
  const std::vector<Vec3> points = some_points();
  for (const double aspect : {16.0 / 9.0, 4.0 / 3.0, 0.5}) {
    SCOPED_TRACE(aspect);
    const CameraSettings c = fit_camera(CameraSettings{}, points, aspect, true, true);
    EXPECT_TRUE(c.framed);
    const Scene s = scene_of(c, int(std::lround(720 * aspect)), 720);
    bool in_front = false;
    // Tight: the nearest point to an edge sits exactly at 1 - margin (round-off 1e-9: the
    // distance comes from a closed form, the projection from 4x4 products).
    EXPECT_NEAR(largest_ndc(s, points, in_front), 1.0 - kFramingMargin, 1e-9);
    EXPECT_LE(largest_ndc(s, points, in_front), 1.0 - kFramingMargin + 1e-9);
    EXPECT_TRUE(in_front);
    // Looking from the framing direction.
    const Vec3 d = (c.position - c.target).normalized();
    EXPECT_NEAR(d.dot(kFramingDirection.normalized()), 1.0, 1e-12);
  }
}

TEST(CameraFraming, OrthographicFitsTheHeightToo) {
  const std::vector<Vec3> points = some_points();
  CameraSettings ortho;
  ortho.projection = Projection::Orthographic;
  const CameraSettings c = fit_camera(ortho, points, 16.0 / 9.0, true, true);
  const Scene s = scene_of(c, 1280, 720);
  bool in_front = false;
  EXPECT_NEAR(largest_ndc(s, points, in_front), 1.0 - kFramingMargin, 1e-9);
  EXPECT_TRUE(in_front);
  // A stated ortho height is kept (the points may then not fit: the user chose the scale).
  ortho.ortho_height_m = 2.5;
  EXPECT_EQ(fit_camera(ortho, points, 16.0 / 9.0, true, false).ortho_height_m, 2.5);
}

TEST(CameraFraming, TargetCanBeKept) {
  const std::vector<Vec3> points = some_points();
  CameraSettings stated;
  stated.target = Vec3(0.0, 1.0, 0.0);
  const CameraSettings c = fit_camera(stated, points, 16.0 / 9.0, false, true);
  EXPECT_EQ(c.target, stated.target);
  const Scene s = scene_of(c, 1280, 720);
  bool in_front = false;
  EXPECT_LE(largest_ndc(s, points, in_front), 1.0 - kFramingMargin + 1e-9);
  EXPECT_TRUE(in_front);
}

TEST(CameraFraming, AStatedPositionIsNotFramed) {
  Scene s = parse_scene(R"([camera]
position = [1.0, 2.0, 9.0]
[[body]]
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 30.0, 0.0]
)",
                        "s.toml");
  const CameraSettings c = frame_camera(s, make_world_def(s, load_models(s)));
  EXPECT_FALSE(c.framed);
  EXPECT_EQ(c.position, Vec3(1.0, 2.0, 9.0));
  EXPECT_EQ(c.target, Vec3(0.0, 0.5, 0.0));
}

TEST(CameraFraming, ADropIsInsideAtEveryFrame) {
  // A box dropped from 3 m with a sideways push: every corner at every frame inside the image.
  Scene s = parse_scene(R"([simulation]
duration = 2.0
[floor]
[[body]]
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 3.0, 0.0]
velocity = [1.5, 0.0, 0.0]
angular_velocity = [0.0, 1.0, 2.0]
)",
                        "s.toml");
  const WorldDef def = make_world_def(s, load_models(s));
  s.camera = frame_camera(s, def);
  ASSERT_TRUE(s.camera.framed);
  World world(def);
  for (int k = 0; k < 120; ++k) {
    world.step();
    while (world.time() < (k + 1) / 60.0 - 1e-12) world.step();
    std::vector<Vec3> corners;
    body_points(s, world, corners);
    ASSERT_EQ(corners.size(), 8u);
    bool in_front = false;
    EXPECT_LE(largest_ndc(s, corners, in_front), 1.0 - kFramingMargin + 0.02)
        << "t = " << world.time();  // steps, not frame times: within a step's motion
    EXPECT_TRUE(in_front);
  }
}

}  // namespace
}  // namespace tumble
