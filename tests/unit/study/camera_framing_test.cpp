// Framing a run: the camera fitted to the points the bodies occupy sees every one of them inside
// the image with the stated margin, at the smallest such distance (or ortho height), from the
// stated direction; a stated camera is left alone. Projected with the renderer's own camera
// maths (camera.hpp), so a point inside here is a point inside the picture.
#include "tumble/camera_framing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "tumble/camera.hpp"
#include "tumble/sampler.hpp"
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

// camera.follow without a position: a 0.5 m box thrown at 12 m/s (7.2 across, 9.6 up), seen at
// 480x270. Framing the whole 29 m throw would leave it 6 px tall; the following camera keeps it
// at least a sixth of the image's height (45 px) in every frame, and inside the image.
TEST(CameraFraming, AFollowedBodyFillsAShareOfThePictureInEveryFrame) {
  for (const char* projection : {"perspective", "orthographic"}) {
    SCOPED_TRACE(projection);
    Scene s = parse_scene(std::string(R"([simulation]
duration = 4.0
[floor]
[render]
width = 480
height = 270
[camera]
follow = "box"
projection = ")") + projection +
                              R"("
[[body]]
name = "box"
shape = "box"
size = [0.5, 0.5, 0.5]
mass = 1.0
position = [0.0, 1.0, 0.0]
velocity = [7.2, 9.6, 0.0]
angular_velocity = [1.0, 2.0, 3.0]
)",
                          "s.toml");
    const WorldDef def = make_world_def(s, load_models(s));
    s.camera = frame_camera(s, def);
    EXPECT_TRUE(s.camera.framed);
    EXPECT_TRUE(camera_moves_with_target(s.camera));
    World world(def);
    Sampler sampler(world);
    double smallest_px = INFINITY, largest_ndc = 0.0, farthest_m = 0.0;
    for (int k = 0; k < 240; ++k) {
      const World& at = sampler.at(k / 60.0);
      const Eigen::Matrix4d vp = camera_view_projection(s, at);
      std::vector<Vec3> corners;
      body_points(s, at, corners);
      double top = INFINITY, bottom = -INFINITY;
      for (const Vec3& c : corners) {
        const std::optional<Eigen::Vector2d> px = to_pixels(vp, c, 480, 270);
        ASSERT_TRUE(px) << "a corner behind the camera at frame " << k;
        top = std::min(top, px->y());
        bottom = std::max(bottom, px->y());
        largest_ndc = std::max(
            {largest_ndc, std::abs(px->x() / 240.0 - 1.0), std::abs(px->y() / 135.0 - 1.0)});
      }
      smallest_px = std::min(smallest_px, bottom - top);
      farthest_m = std::max(farthest_m, (at.bodies()[0].state.x - Vec3(0.0, 1.0, 0.0)).norm());
    }
    EXPECT_GT(farthest_m, 20.0) << "the throw goes far";
    EXPECT_GE(smallest_px, 270.0 / 6.0);
    // The bounding sphere spans 40 % of the height: the corners stay well inside.
    EXPECT_LT(largest_ndc, 0.5);
    std::printf("[ %s ] followed 0.5 m box: at least %.1f px of 270\n", projection, smallest_px);
  }
}

TEST(CameraFraming, AFollowedBodyWithAStatedPositionKeepsIt) {
  Scene s = parse_scene(R"([camera]
position = [1.0, 2.0, 9.0]
follow = "box"
[[body]]
name = "box"
shape = "box"
size = [0.5, 0.5, 0.5]
mass = 1.0
position = [0.0, 3.0, 0.0]
velocity = [7.2, 9.6, 0.0]
)",
                        "s.toml");
  const WorldDef def = make_world_def(s, load_models(s));
  s.camera = frame_camera(s, def);
  EXPECT_FALSE(s.camera.framed);
  EXPECT_FALSE(camera_moves_with_target(s.camera));
  World world(def);
  Sampler sampler(world);
  EXPECT_EQ(camera_eye(s, sampler.at(1.0)), Vec3(1.0, 2.0, 9.0)) << "it turns, it does not move";
}

TEST(CameraFraming, FollowCameraSizesEveryShape) {
  // A sphere of radius 0.2 m (diameter 0.4 m) spans exactly kFollowShare of a 16:9 image's
  // height at the fitted distance; a portrait image fits it to the width instead.
  const double tan_y = std::tan(0.5 * radians(45.0));
  CameraSettings cam;
  const CameraSettings wide = follow_camera(cam, Vec3(1.0, 2.0, 3.0), 0.2, 16.0 / 9.0, true);
  EXPECT_EQ(wide.target, Vec3(1.0, 2.0, 3.0));
  EXPECT_NEAR((wide.position - wide.target).norm(), 0.2 / (kFollowShare * tan_y), 1e-12);
  EXPECT_NEAR((wide.position - wide.target).normalized().dot(kFramingDirection.normalized()), 1.0,
              1e-12);
  const CameraSettings tall = follow_camera(cam, Vec3::Zero(), 0.2, 0.5, true);
  EXPECT_NEAR(tall.position.norm(), 0.2 / (kFollowShare * 0.5 * tan_y), 1e-12);
  cam.projection = Projection::Orthographic;
  EXPECT_NEAR(follow_camera(cam, Vec3::Zero(), 0.2, 16.0 / 9.0, true).ortho_height_m,
              0.4 / kFollowShare, 1e-12);
  EXPECT_EQ(follow_camera(cam, Vec3::Zero(), 0.2, 16.0 / 9.0, false).ortho_height_m, 4.0);
  // A field of view near 180 degrees: still two radii away, never inside the body.
  cam.projection = Projection::Perspective;
  cam.fov_deg = 179.0;
  EXPECT_NEAR(follow_camera(cam, Vec3::Zero(), 0.2, 1.0, true).position.norm(), 0.4, 1e-12);

  const Scene s = parse_scene(R"([[body]]
name = "ball"
shape = "sphere"
radius = 0.2
mass = 1.0
[[body]]
name = "crate"
shape = "box"
size = [0.6, 0.8, 2.4]
mass = 1.0
position = [3.0, 0.0, 0.0]
)",
                              "s.toml");
  const World world(make_world_def(s, load_models(s)));
  EXPECT_NEAR(bounding_radius(s, world, 0), 0.2, 1e-12);
  EXPECT_NEAR(bounding_radius(s, world, 1), 0.5 * std::sqrt(0.36 + 0.64 + 5.76), 1e-12);
}

}  // namespace
}  // namespace tumble
