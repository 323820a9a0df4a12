// The floor checker scales with the moving bodies: a power of ten near their size, never set by
// fixed bodies or particles, coarser where the camera could not draw it without moiré; and it
// fades to an even grey where a pixel spans several squares.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tumble/camera_framing.hpp"
#include "tumble/egl_context.hpp"
#include "tumble/renderer.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

Scene box_scene(double edge_m, const std::string& extra = "", double z_m = 0.0) {
  const std::string e = std::to_string(edge_m);
  const bool sized = extra.find("[render]") != std::string::npos;
  return parse_scene(std::string(sized ? "" : "[render]\nwidth = 320\nheight = 180\n") + R"(
[floor]
[[body]]
name = "box"
shape = "box"
size = [)" + e + ", " + e + ", " + e + R"(]
mass = 1.0
position = [0.0, )" + std::to_string(0.5 * edge_m) + ", " + std::to_string(z_m) + R"(]
)" + extra,
                     "<checker test>");
}

TEST(FloorChecker, APowerOfTenNearTheMovingBodysSize) {
  EXPECT_DOUBLE_EQ(checker_tile_m(box_scene(0.01)), 0.01);
  EXPECT_DOUBLE_EQ(checker_tile_m(box_scene(100.0)), 100.0);
  // Nearest in log scale: 0.3 m rounds to 0.1 m, 0.35 m to 1 m, 2.5 m to 1 m, 4 m to 10 m.
  EXPECT_DOUBLE_EQ(checker_tile_m(box_scene(0.3)), 0.1);
  EXPECT_DOUBLE_EQ(checker_tile_m(box_scene(0.35)), 1.0);
  EXPECT_DOUBLE_EQ(checker_tile_m(box_scene(2.5)), 1.0);
  EXPECT_DOUBLE_EQ(checker_tile_m(box_scene(4.0)), 10.0);
  // The default scene's 1 m box keeps its 1 m squares.
  EXPECT_DOUBLE_EQ(checker_tile_m(default_scene()), 1.0);
}

TEST(FloorChecker, FixedBodiesAndParticlesDoNotSetIt) {
  // A 40 m fixed ramp under a 1 cm box: the box sets it.
  EXPECT_DOUBLE_EQ(checker_tile_m(box_scene(0.01, R"(
[[body]]
name = "ramp"
shape = "box"
size = [40.0, 1.0, 40.0]
fixed = true
position = [0.0, -5.0, 0.0]
)")),
                   0.01);
  // A particle's drawn size is a marker: a scene of particles keeps 1 m squares.
  EXPECT_DOUBLE_EQ(checker_tile_m(parse_scene(R"(
[[body]]
name = "p"
shape = "particle"
size = [0.02, 0.02, 0.02]
mass = 1.0
position = [0.0, 1.0, 0.0]
)",
                                              "<checker test>")),
                   1.0);
  // The largest moving body decides: a 5 cm sphere beside a 2 m box.
  EXPECT_DOUBLE_EQ(checker_tile_m(box_scene(2.0, R"(
[[body]]
name = "ball"
shape = "sphere"
radius = 0.025
mass = 0.1
position = [3.0, 0.5, 0.0]
)")),
                   1.0);
}

TEST(FloorChecker, CoarserWhereTheCameraCannotResolveIt) {
  // The side view: a 0.24 m ball (0.1 m squares by size) seen 8° above the floor through an
  // orthographic camera, where a 0.1 m square is 2 px deep at 960x400: drawn as 1 m squares.
  Scene side = parse_scene(R"(
[render]
width = 960
height = 400
[floor]
[camera]
projection = "orthographic"
ortho_height = 2.7
position = [0.5, 5.17, 30.0]
target = [0.5, 0.95, 0.0]
[[body]]
name = "ball"
shape = "sphere"
radius = 0.12
mass = 0.2
position = [0.0, 1.0, 0.0]
)",
                           "<checker test>");
  EXPECT_DOUBLE_EQ(checker_tile_m(side), 0.1);
  EXPECT_DOUBLE_EQ(floor_tile_m(side), 1.0);
  // A framed camera sees a box's own squares at its own scale.
  for (const double edge : {0.01, 1.0, 100.0}) {
    Scene s = box_scene(edge);
    s.camera = frame_camera(s, make_world_def(s));
    EXPECT_DOUBLE_EQ(floor_tile_m(s), edge) << edge;
  }
}

// Light/dark transitions along image row y (top-down) and the row's contrast.
struct RowChecker {
  int transitions = 0;
  int contrast = 0;
  int largest_step = 0;  // between neighbouring pixels: a square's edge, not the fade's gradient
};
RowChecker row_checker(const Image& img, int y, int x0 = 0, int x1 = -1) {
  std::vector<int> luma;
  for (int x = x0; x < (x1 < 0 ? img.width : x1); ++x) {
    const std::uint8_t* p = img.row(y) + 3 * x;
    luma.push_back((299 * p[0] + 587 * p[1] + 114 * p[2]) / 1000);
  }
  const auto [lo, hi] = std::minmax_element(luma.begin(), luma.end());
  RowChecker r;
  r.contrast = *hi - *lo;
  const int mid = (*hi + *lo) / 2;
  for (std::size_t x = 1; x < luma.size(); ++x) {
    if ((luma[x - 1] < mid) != (luma[x] < mid)) ++r.transitions;
    r.largest_step = std::max(r.largest_step, std::abs(luma[x] - luma[x - 1]));
  }
  return r;
}

Image render(Scene s) {
  s.camera = frame_camera(s, make_world_def(s));
  EglContext gl;
  Renderer r(s);
  const World w(make_world_def(s));
  r.draw(w);
  return r.read_image();
}

TEST(FloorChecker, ASquareNearTheBodyIsTensOfPixelsFromOneCentimetreToOneHundredMetres) {
  for (const double edge : {0.01, 1.0, 100.0}) {
    SCOPED_TRACE(edge);
    const Image img = render(box_scene(edge));
    // The floor just in front of the body (the framed box reaches down to row ~168 of 180):
    // the bottom row, about a box size from it.
    const RowChecker row = row_checker(img, img.height - 1);
    EXPECT_GE(row.contrast, 15);  // light and dark squares, not an even grey
    ASSERT_GT(row.transitions, 0);
    const double square_px = double(img.width) / row.transitions;
    std::printf("box %g m: %d transitions across 320 px (a square ~%.0f px), contrast %d\n", edge,
                row.transitions, square_px, row.contrast);
    EXPECT_GE(square_px, 8.0);
    EXPECT_LE(square_px, 80.0);
  }
}

TEST(FloorChecker, AnEvenGreyWhereAPixelSpansSeveralSquares) {
  // A camera 3 m over 1 m squares at 160x90 (45° over 90 rows: 8.7 mrad a pixel): 39 m away
  // a pixel row spans 39² · 0.0087 / 3 = 4.4 m of floor in depth. The box is behind the camera (out of
  // the picture, and its shadow too).
  Scene s = box_scene(1.0, R"(
[render]
width = 160
height = 90
[camera]
position = [0.0, 3.0, 8.0]
target = [0.0, 0.5, 0.0]
)",
                      20.0);
  EglContext gl;
  Renderer r(s);
  const World w(make_world_def(s));
  r.draw(w);
  const Image img = r.read_image();
  const Eigen::Matrix4d vp = camera_view_projection(s, w);
  ASSERT_FALSE(to_pixels(vp, Vec3(0.0, 0.5, 20.0), img.width, img.height));
  const auto row_at = [&](double z) {
    return int((*to_pixels(vp, Vec3(0.0, 0.0, z), img.width, img.height)).y());
  };
  // Near: squares with sharp (pixel-filtered) edges. Far: no edge left, only the fade's gentle
  // gradient towards the sky along the row.
  const RowChecker near = row_checker(img, row_at(2.0));
  EXPECT_GE(near.largest_step, 5);
  ASSERT_DOUBLE_EQ(floor_tile_m(s), 1.0);
  for (const double z : {-31.0, -33.0}) {
    const RowChecker far = row_checker(img, row_at(z));
    std::printf("z = %g m: largest step between neighbours %d\n", z, far.largest_step);
    EXPECT_LE(far.largest_step, 1) << z;
  }
}

}  // namespace
}  // namespace tumble
