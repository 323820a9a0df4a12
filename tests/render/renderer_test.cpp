// The renderer on the real EGL + OpenGL stack (llvmpipe here and in CI), at 160×120: where a body
// appears, that nothing is flipped or mirrored, that frames move, that the shadow falls.
#include "tumble/renderer.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "tumble/egl_context.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

constexpr int kW = 160, kH = 120;

// Pixel coordinates (x right, y down) where the camera model puts world point p.
Eigen::Vector2d project(const Scene& s, const Vec3& p) {
  const Eigen::Matrix4d m = perspective(s.camera.fov_deg, double(kW) / kH, 0.1, 100.0) *
                            look_at(s.camera.position, s.camera.target, s.camera.up);
  const Eigen::Vector4d c = m * p.homogeneous();
  const Eigen::Vector2d ndc = c.head<2>() / c.w();
  return {(ndc.x() + 1.0) * 0.5 * kW, (1.0 - ndc.y()) * 0.5 * kH};
}

Scene small_scene() {
  Scene s = parse_scene(R"(
[render]
width = 160
height = 120
msaa = 0
background = "#dfe6ee"
[camera]
position = [0.0, 1.0, 8.0]
target = [0.0, 1.0, 0.0]
[light]
direction = [-1.0, -1.0, 0.0]
[[body]]
name = "red"
shape = "box"
size = [0.6, 0.6, 0.6]
mass = 1.0
position = [2.0, 2.0, 0.0]
color = "#ff0000"
)",
                        "<test>");
  return s;
}

struct Rgb {
  int r, g, b;
};
Rgb at(const Image& img, const Eigen::Vector2d& p) {
  const std::uint8_t* px = img.row(int(p.y())) + 3 * int(p.x());
  return {px[0], px[1], px[2]};
}

Image render(const Scene& s) {
  EglContext gl;
  Renderer r(s);
  const World w(make_world_def(s));
  r.draw(w);
  return r.read_image();
}

TEST(Renderer, BodyAppearsWhereTheCameraModelSaysNotFlippedOrMirrored) {
  const Scene s = small_scene();
  const Image img = render(s);
  ASSERT_EQ(img.width, kW);
  ASSERT_EQ(img.height, kH);
  // The box is up and to the right of the target: it must be drawn in the upper-right quadrant,
  // exactly where the projection puts its centre; the mirror positions show background.
  const Eigen::Vector2d centre = project(s, Vec3(2.0, 2.0, 0.0));
  ASSERT_GT(centre.x(), kW / 2.0);
  ASSERT_LT(centre.y(), kH / 2.0);
  const Rgb c = at(img, centre);
  EXPECT_GT(c.r, 120);  // lit red: red dominant (lighting scales, the hue stays)
  EXPECT_LT(c.g, 40);
  EXPECT_LT(c.b, 40);
  const Rgb mirrored = at(img, {kW - centre.x(), centre.y()});
  const Rgb flipped = at(img, {centre.x(), kH - centre.y()});
  for (const Rgb& bg : {mirrored, flipped}) {  // background #dfe6ee, exactly: no floor here
    EXPECT_EQ(bg.r, 0xdf);
    EXPECT_EQ(bg.g, 0xe6);
    EXPECT_EQ(bg.b, 0xee);
  }
}

TEST(Renderer, FramesChangeAsTheBodyFalls) {
  Scene s = small_scene();
  EglContext gl;
  Renderer r(s);
  World w(make_world_def(s));
  r.draw(w);
  const Image before = r.read_image();
  for (int i = 0; i < 300; ++i) w.step();  // 0.3 s of free fall: 0.44 m
  r.draw(w);
  const Image after = r.read_image();
  long changed = 0;
  for (std::size_t i = 0; i < before.pixels.size(); ++i)
    changed += before.pixels[i] != after.pixels[i];
  EXPECT_GT(changed, 300);  // the box moved by several pixels
  // And the red has moved down in the image to where the projection says.
  const Vec3 fallen = w.bodies()[0].state.x;
  EXPECT_GT(at(after, project(s, fallen)).r, 120);
  EXPECT_LT(at(after, project(s, fallen)).g, 40);
}

TEST(Renderer, ShadowDarkensTheFloorUnderTheBody) {
  // Light along L = (-1, -1, 0): the box centre p = (2, 2, 0) casts its shadow on the floor at
  // p − (p_y / L_y) L = (2, 2, 0) − (2 / −1)·(−1, −1, 0) = (0, 0, 0).
  Scene s = small_scene();
  s.floor = FloorSettings{};
  s.camera.position = Vec3(0.0, 4.0, 8.0);
  const Vec3 shadow_centre = Vec3(2, 2, 0) - (2.0 / -1.0) * Vec3(-1, -1, 0);
  ASSERT_NEAR(shadow_centre.y(), 0.0, 1e-12);
  const Image lit = [&] {
    Scene no_shadow = s;
    no_shadow.light.shadows = false;
    return render(no_shadow);
  }();
  const Image shadowed = render(s);
  const Eigen::Vector2d p = project(s, shadow_centre);
  const Rgb a = at(lit, p), b = at(shadowed, p);
  // The shadow is drawn at 32% black: about 30% darker in sRGB, far beyond any rounding.
  EXPECT_LT(b.r + b.g + b.b, 0.8 * (a.r + a.g + a.b));
  // Away from the shadow the floor is the same.
  const Eigen::Vector2d away = project(s, Vec3(-3.0, 0.0, 2.0));
  EXPECT_EQ(at(lit, away).r, at(shadowed, away).r);
}

TEST(Renderer, MsaaIsClampedToWhatTheDriverOffers) {
  Scene s = small_scene();
  s.render.antialias = Antialias::Msaa;
  s.render.msaa = 16;
  EglContext gl;
  Renderer r(s);
  EXPECT_GE(r.msaa_samples(), 2);
  EXPECT_LE(r.msaa_samples(), 16);
}

TEST(Renderer, FxaaSmoothsTheBodysEdgesAndLeavesTheRestBitExact) {
  Scene s = small_scene();
  s.render.antialias = Antialias::None;
  const Image plain = render(s);
  s.render.antialias = Antialias::Fxaa;
  const Image smooth = render(s);
  const Eigen::Vector2d centre = project(s, Vec3(2.0, 2.0, 0.0));
  long changed = 0, far_changed = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool differs = std::memcmp(plain.row(y) + 3 * x, smooth.row(y) + 3 * x, 3) != 0;
      changed += differs;
      // The box spans about ±12 px around its centre here; FXAA reaches a few more.
      far_changed += differs && (std::abs(x - centre.x()) > 30 || std::abs(y - centre.y()) > 30);
    }
  EXPECT_GT(changed, 10);     // the silhouette's stair steps were blended
  EXPECT_EQ(far_changed, 0);  // nothing else moved
}

TEST(Renderer, AsynchronousReadbackReturnsTheSameFramesInOrder) {
  // The pixel-pack-buffer path that GPUs use, forced on llvmpipe: frames drawn while earlier
  // ones are still being read back come out bit-identical to reading each at once, in order.
  Scene s = small_scene();
  EglContext gl;
  auto frames = [&](Renderer::Readback mode) {
    Renderer r(s, mode);
    World w(make_world_def(s));
    std::vector<std::vector<std::uint8_t>> out(3);
    r.draw(w);
    r.begin_readback();
    for (int k = 1; k < 3; ++k) {
      for (int i = 0; i < 100; ++i) w.step();
      r.draw(w);
      r.begin_readback();
      r.finish_readback(out[k - 1]);
    }
    r.finish_readback(out[2]);
    EXPECT_EQ(r.async_readback(), mode == Renderer::Readback::Async);
    return out;
  };
  const auto sync = frames(Renderer::Readback::Sync);
  const auto async = frames(Renderer::Readback::Async);
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(sync[k].size(), std::size_t(kW) * kH * 4);
    EXPECT_TRUE(sync[k] == async[k]) << "frame " << k;
  }
  EXPECT_FALSE(sync[0] == sync[2]);  // the body moved: the frames are distinct
}

}  // namespace
}  // namespace tumble

namespace tumble {
namespace {

// A sweep draws its jobs one after another with one renderer where their format agrees: after
// reuse_for() it must draw exactly (bit for bit) what a new renderer for that scene draws.
TEST(RendererReuse, AnotherSceneInTheSameFormatDrawsWhatANewRendererDraws) {
  EglContext gl;
  const Scene first = small_scene();
  Scene second = small_scene();
  second.bodies[0].color = Color{0x20, 0x40, 0xff};
  second.bodies[0].position = Vec3(-1.0, 0.8, 0.5);
  second.camera.position = Vec3(3.0, 2.0, 7.0);
  second.light.direction = Vec3(0.5, -1.0, -0.2);
  second.floor = FloorSettings{};
  Renderer reused(first);
  reused.draw(World(make_world_def(first)));
  const Image before = reused.read_image();
  ASSERT_TRUE(reused.reuse_for(second));
  reused.draw(World(make_world_def(second)));
  const Image after = reused.read_image();
  Renderer fresh(second);
  fresh.draw(World(make_world_def(second)));
  const Image expected = fresh.read_image();
  EXPECT_TRUE(after.pixels == expected.pixels) << "a reused renderer draws another picture";
  EXPECT_FALSE(after.pixels == before.pixels);
}

TEST(RendererReuse, TheFirstPictureOfTheNextSceneIsDrawnInFull) {
  // Same camera, same body pose, another sky and floor: only the body's rectangle would be
  // redrawn if the last scene's picture were built on. It must not be.
  EglContext gl;
  const Scene first = small_scene();
  Scene second = small_scene();
  second.render.background = Color{0x30, 0x30, 0x40};
  Renderer reused(first);
  reused.draw(World(make_world_def(first)));
  ASSERT_TRUE(reused.reuse_for(second));
  reused.draw(World(make_world_def(second)));
  EXPECT_EQ(reused.redrawn_share(), 1.0);
  Renderer fresh(second);
  fresh.draw(World(make_world_def(second)));
  EXPECT_TRUE(reused.read_image().pixels == fresh.read_image().pixels);
}

TEST(RendererReuse, AnotherFormatIsRefused) {
  EglContext gl;
  const Scene first = small_scene();
  Renderer r(first);
  Scene bigger = small_scene();
  bigger.render.width = 320;
  EXPECT_FALSE(r.reuse_for(bigger));
  Scene msaa = small_scene();
  msaa.render.antialias = Antialias::Msaa;
  msaa.render.msaa = 4;
  EXPECT_FALSE(r.reuse_for(msaa));
  EXPECT_FALSE(r.reuse_for(first, nullptr, Backdrop::Transparent));
  EXPECT_TRUE(r.reuse_for(first));
}

}  // namespace
}  // namespace tumble
