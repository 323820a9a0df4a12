// The renderer's figure features on the real EGL + OpenGL stack (llvmpipe here and in CI), at
// 160×120: several exposures in one picture (strobe), the transparent backdrop, and the
// orthographic camera (its maths, its shadows, its FXAA rectangles).
#include <gtest/gtest.h>

#include <cstring>

#include "tumble/camera.hpp"
#include "tumble/egl_context.hpp"
#include "tumble/premultiplied.hpp"
#include "tumble/renderer.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

constexpr int kW = 160, kH = 120;

// A red box in the sky at `x`, seen from +z; optionally a floor and shadows, orthographic.
Scene scene_with_box_at(double x, bool floor = false, bool ortho = false,
                        const char* antialias = "none") {
  std::string text = std::string(R"([simulation]
gravity = [0.0, 0.0, 0.0]
[render]
width = 160
height = 120
antialias = ")") + antialias +
                     R"("
background = "#dfe6ee"
[camera]
position = [0.0, 1.5, 8.0]
target = [0.0, 1.0, 0.0]
)" + (ortho ? "projection = \"orthographic\"\northo_height = 5.0\n" : "") +
                     R"([light]
direction = [-1.0, -1.0, 0.0]
[[body]]
name = "red"
shape = "box"
size = [0.6, 0.6, 0.6]
mass = 1.0
color = "#ff0000"
position = [)" + std::to_string(x) +
                     ", 2.0, 0.0]\n";
  Scene s = parse_scene(text + (floor ? "[floor]\n" : ""), "<test>");
  return s;
}

// Pixel (x right, y down) of world point p in the scene's camera.
Eigen::Vector2d pixel_of(const Scene& s, const World& w, const Vec3& p) {
  return *to_pixels(camera_view_projection(s, w), p, kW, kH);
}

// RGBA at (x, y) (top-down) of bottom-up rows.
const std::uint8_t* at(const std::vector<std::uint8_t>& rgba, const Eigen::Vector2d& p) {
  const int x = int(p.x()), y = kH - 1 - int(p.y());
  return rgba.data() + (std::size_t(y) * kW + x) * 4;
}

// ---- several exposures ----

// A translucent pose and an opaque one in one picture: the opaque pose is drawn exactly as a
// single frame draws it, the ghost is the body's colour blended over the sky at its opacity.
TEST(Strobe, GhostIsBlendedAtItsOpacityAndTheLastPoseIsAsAFrame) {
  const Scene left = scene_with_box_at(-2.0), right = scene_with_box_at(2.0);
  EglContext gl;
  Renderer r(right);
  const World ghost(make_world_def(left)), last(make_world_def(right));
  const Exposure exposures[] = {{&ghost, 0.5}, {&last, 1.0}};
  r.draw(exposures);
  std::vector<std::uint8_t> strobe;
  r.read_rgba(strobe);
  r.draw(last);
  std::vector<std::uint8_t> single;
  r.read_rgba(single);

  const Eigen::Vector2d at_last = pixel_of(right, last, Vec3(2.0, 2.0, 0.0));
  const Eigen::Vector2d at_ghost = pixel_of(right, last, Vec3(-2.0, 2.0, 0.0));
  EXPECT_EQ(std::memcmp(at(strobe, at_last), at(single, at_last), 4), 0)
      << "the opaque pose is the frame's";
  // The ghost: the lit red over the sky #dfe6ee at half opacity, so red stays high and green and
  // blue fall to about half the sky's (230 → ~115), far from both the sky and the solid body.
  const std::uint8_t* g = at(strobe, at_ghost);
  const std::uint8_t* solid = at(single, at_last);
  EXPECT_GT(g[0], 150);
  EXPECT_GT(g[1], 80);
  EXPECT_LT(g[1], 150);
  EXPECT_GT(g[1], solid[1] + 60) << "fainter than the opaque body";
  EXPECT_EQ(g[3], 255) << "over the sky backdrop the picture stays opaque";
  // Where the ghost is, the single frame shows sky.
  const std::uint8_t* sky = at(single, at_ghost);
  EXPECT_EQ(sky[0], 0xdf);
  EXPECT_EQ(sky[1], 0xe6);
}

// Each pose's shadow darkens the floor; where shadows overlap the darkest wins instead of
// compounding, so a pile of faint poses never blackens the floor.
TEST(Strobe, EveryPoseCastsItsShadowAndOverlapsDoNotCompound) {
  const Scene s = scene_with_box_at(0.0, /*floor=*/true);
  EglContext gl;
  Renderer r(s);
  const World w(make_world_def(s));
  r.draw(w);
  std::vector<std::uint8_t> one;
  r.read_rgba(one);
  const Exposure same_place_twice[] = {{&w, 1.0}, {&w, 0.4}, {&w, 0.7}};
  r.draw(same_place_twice);
  std::vector<std::uint8_t> three;
  r.read_rgba(three);
  // The box centre (0, 2, 0) casts along L = (-1, -1, 0) onto y = 0 at (-2, 0, 0).
  const Eigen::Vector2d shadow = pixel_of(s, w, Vec3(-2.0, 0.0, 0.0));
  EXPECT_EQ(std::memcmp(at(one, shadow), at(three, shadow), 4), 0);
}

// ---- transparent backdrop ----

TEST(Transparent, BackgroundIsAlphaZeroFloorAndBodyOpaque) {
  const Scene s = scene_with_box_at(1.0, /*floor=*/true);
  EglContext gl;
  Renderer sky(s), clear(s, Renderer::Readback::Auto, nullptr, Backdrop::Transparent);
  EXPECT_EQ(clear.backdrop(), Backdrop::Transparent);
  const World w(make_world_def(s));
  std::vector<std::uint8_t> a, b;
  sky.draw(w);
  sky.read_rgba(a);
  clear.draw(w);
  clear.read_rgba(b);
  const std::uint8_t* top = b.data() + (std::size_t(kH - 1) * kW) * 4;  // top-left pixel
  EXPECT_EQ(top[0] + top[1] + top[2] + top[3], 0) << "premultiplied (0, 0, 0, 0)";
  const Eigen::Vector2d floor = {kW / 2.0, kH - 3.0};
  EXPECT_EQ(at(b, floor)[3], 255) << "the floor in front is opaque";
  EXPECT_EQ(std::memcmp(at(a, floor), at(b, floor), 3), 0) << "and the same colour";
  const Eigen::Vector2d body = pixel_of(s, w, Vec3(1.0, 2.0, 0.0));
  EXPECT_EQ(at(b, body)[3], 255);
  EXPECT_EQ(std::memcmp(at(a, body), at(b, body), 3), 0);
  // read_image() gives straight-alpha RGBA.
  const Image image = clear.read_image();
  EXPECT_EQ(image.channels, 4);
}

// FXAA with a transparent backdrop smooths the silhouette in alpha too: coverage between 0 and
// 1 around the box; without anti-aliasing alpha is 0 or 255 only.
TEST(Transparent, FxaaSmoothsTheSilhouetteAgainstTransparency) {
  EglContext gl;
  auto partial = [&](const char* antialias) {
    const Scene s = scene_with_box_at(0.0, false, false, antialias);
    Renderer r(s, Renderer::Readback::Auto, nullptr, Backdrop::Transparent);
    r.draw(World(make_world_def(s)));
    std::vector<std::uint8_t> rgba;
    r.read_rgba(rgba);
    long n = 0, opaque = 0;
    for (std::size_t i = 3; i < rgba.size(); i += 4) {
      n += rgba[i] > 0 && rgba[i] < 255;
      opaque += rgba[i] == 255;
    }
    EXPECT_GT(opaque, 100) << antialias;
    return n;
  };
  EXPECT_EQ(partial("none"), 0);
  EXPECT_GT(partial("fxaa"), 10);
  EXPECT_GT(partial("msaa"), 10);
}

// ---- orthographic camera ----

TEST(Orthographic, HeightsReadTrueAtAnyDepth) {
  Scene s = scene_with_box_at(0.0, false, /*ortho=*/true);
  s.camera.position = Vec3(0.0, 1.0, 8.0);  // level: the image's vertical is the world's
  const World w(make_world_def(s));
  const Eigen::Matrix4d vp = camera_view_projection(s, w);
  // ortho_height 5 m over 120 px: the target's row ± 2.5 m reach the top and bottom edges.
  EXPECT_NEAR(to_pixels(vp, Vec3(0.0, 1.0 + 2.5, 0.0), kW, kH)->y(), 0.0, 1e-9);
  EXPECT_NEAR(to_pixels(vp, Vec3(0.0, 1.0 - 2.5, 0.0), kW, kH)->y(), kH, 1e-9);
  EXPECT_NEAR(to_pixels(vp, Vec3(2.5 * kW / kH, 1.0, 0.0), kW, kH)->x(), kW, 1e-9);
  for (const double z : {-20.0, -3.0, 0.0, 4.0}) {
    const Eigen::Vector2d p = *to_pixels(vp, Vec3(0.7, 2.2, z), kW, kH);
    EXPECT_NEAR(p.y(), (1.0 - (2.2 - 1.0) / 2.5) * kH / 2.0, 1e-9) << "z = " << z;
    EXPECT_NEAR(p.x(), (1.0 + 0.7 / (2.5 * kW / kH)) * kW / 2.0, 1e-9) << "z = " << z;
  }
}

TEST(Orthographic, ShadowFallsWhereTheLightPutsItAndFxaaStaysNearTheBody) {
  Scene s = scene_with_box_at(0.0, /*floor=*/true, /*ortho=*/true, "fxaa");
  s.camera.position = Vec3(0.0, 6.0, 8.0);  // 32° down: the shadow on the floor is seen open
  Scene no_shadow = s;
  no_shadow.light.shadows = false;
  Scene plain = s;
  plain.render.antialias = Antialias::None;
  EglContext gl;
  auto draw = [&](const Scene& scene) {
    Renderer r(scene);
    r.draw(World(make_world_def(scene)));
    return r.read_image();
  };
  const Image shadowed = draw(s), lit = draw(no_shadow), hard = draw(plain);
  const World w(make_world_def(s));
  const Eigen::Vector2d p = pixel_of(s, w, Vec3(-2.0, 0.0, 0.0));
  const std::uint8_t* a = lit.row(int(p.y())) + 3 * int(p.x());
  const std::uint8_t* b = shadowed.row(int(p.y())) + 3 * int(p.x());
  EXPECT_LT(b[0] + b[1] + b[2], 0.8 * (a[0] + a[1] + a[2])) << "the shadow darkens the floor";
  // FXAA changes pixels only inside the rectangle around the body and its shadow (the box's
  // and its flattened corners, as the renderer bounds them, plus its reach): its rectangles
  // work in ortho.
  Eigen::Array2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? 0.3 : -0.3, 2.0 + ((c & 2) ? 0.3 : -0.3), (c & 4) ? 0.3 : -0.3);
    const Vec3 flat = corner - (corner.y() / -1.0) * Vec3(-1.0, -1.0, 0.0);
    for (const Vec3& q : {corner, flat}) {
      const Eigen::Array2d px = pixel_of(s, w, q).array();
      lo = lo.min(px);
      hi = hi.max(px);
    }
  }
  long changed = 0, far = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool differs = std::memcmp(hard.row(y) + 3 * x, shadowed.row(y) + 3 * x, 3) != 0;
      changed += differs;
      far += differs && (x < lo.x() - 12 || x > hi.x() + 12 || y < lo.y() - 12 || y > hi.y() + 12);
    }
  EXPECT_GT(changed, 10);
  EXPECT_EQ(far, 0);
}

}  // namespace
}  // namespace tumble
