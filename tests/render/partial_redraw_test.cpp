// A picture is drawn again only inside the rectangles where it can differ from the last one
// (the bodies and shadows of both) while the camera and floor stay put. The claim is that the
// result is the very bytes of drawing everything: checked here frame by frame against
// redraw_in_full(), for every antialiasing mode and backdrop, for bodies that leave the screen,
// for many bodies, for a following camera, and with strobe pictures drawn in between.
#include <gtest/gtest.h>

#include <functional>

#include "tumble/egl_context.hpp"
#include "tumble/renderer.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

// Two boxes thrown across the view and a particle, over a floor; 12 frames 1/15 s apart.
std::string moving_scene(const std::string& extra = "") {
  return R"(
[simulation]
dt = 0.002
[render]
width = 160
height = 120
[camera]
position = [0.0, 2.0, 9.0]
target = [0.0, 1.0, 0.0]
[[body]]
name = "thrown"
shape = "box"
size = [0.6, 0.4, 0.5]
mass = 1.0
position = [-3.0, 2.5, 0.0]
velocity = [7.0, 1.0, 0.0]
angular_velocity = [1.0, 3.0, 0.5]
[[body]]
name = "spinner"
shape = "box"
size = [0.5, 0.5, 0.5]
mass = 1.0
position = [1.0, 0.25, 1.0]
angular_velocity = [0.0, 4.0, 0.0]
[[body]]
name = "dot"
shape = "particle"
mass = 0.1
position = [0.5, 3.0, -1.0]
)" + extra;
}

struct Frames {
  std::vector<std::vector<std::uint8_t>> rgba;
  std::vector<double> share;  // redrawn_share() after each draw
};

// Draws `count` frames of the scene with `in_full`, calling `between` (a picture drawn in
// between, say) before frame k where it returns true.
Frames draw_frames(const Scene& s, bool in_full, int count, Backdrop backdrop = Backdrop::Sky,
                   const std::function<void(Renderer&, const World&, int)>& between = {}) {
  Renderer r(s, Renderer::Readback::Sync, nullptr, backdrop);
  r.redraw_in_full(in_full);
  World w(make_world_def(s));
  Frames out;
  for (int k = 0; k < count; ++k) {
    if (between) between(r, w, k);
    r.draw(w);
    out.share.push_back(r.redrawn_share());
    out.rgba.emplace_back();
    r.read_rgba(out.rgba.back());
    for (int i = 0; i < 33; ++i) w.step();
  }
  return out;
}

void expect_same_frames(const Frames& partial, const Frames& full) {
  ASSERT_EQ(partial.rgba.size(), full.rgba.size());
  for (std::size_t k = 0; k < full.rgba.size(); ++k) {
    EXPECT_TRUE(partial.rgba[k] == full.rgba[k]) << "frame " << k << " differs from a full redraw";
    EXPECT_EQ(full.share[k], 1.0);
  }
  EXPECT_FALSE(full.rgba.front() == full.rgba.back());  // the bodies did move
}

TEST(PartialRedraw, SameBytesAsAFullRedrawInEveryAntialiasingMode) {
  EglContext gl;
  for (const char* aa : {"fxaa", "none", "msaa"}) {
    SCOPED_TRACE(aa);
    Scene t = parse_scene(moving_scene(), "<test>");
    t.render.antialias = std::string(aa) == "fxaa"   ? Antialias::Fxaa
                         : std::string(aa) == "none" ? Antialias::None
                                                     : Antialias::Msaa;
    t.render.msaa = std::string(aa) == "msaa" ? 4 : 0;
    const Frames partial = draw_frames(t, false, 12), full = draw_frames(t, true, 12);
    expect_same_frames(partial, full);
    // The first frame is drawn whole; later ones only around the bodies (the thrown box
    // crosses the view, so some frames redraw a good part of it, never all of it).
    EXPECT_EQ(partial.share.front(), 1.0);
    double least = 1.0;
    for (std::size_t k = 1; k < partial.share.size(); ++k) {
      EXPECT_LT(partial.share[k], 1.0) << "frame " << k;
      least = std::min(least, partial.share[k]);
    }
    EXPECT_LT(least, 0.6);
  }
}

TEST(PartialRedraw, TransparentBackdropToo) {
  EglContext gl;
  const Scene s = parse_scene(moving_scene(), "<test>");
  expect_same_frames(draw_frames(s, false, 12, Backdrop::Transparent),
                     draw_frames(s, true, 12, Backdrop::Transparent));
}

TEST(PartialRedraw, PicturesDrawnInBetweenAreCleanedUp) {
  // A strobe of three earlier poses drawn between frames (as the frame pipeline does for
  // stills and strobes) leaves ghosts and shadows where the next frame has none.
  EglContext gl;
  const Scene s = parse_scene(moving_scene(), "<test>");
  std::vector<World> poses;
  auto strobe = [&](Renderer& r, const World& w, int k) {
    poses.push_back(w);
    if (k % 4 != 3) return;
    std::vector<Exposure> e;
    for (std::size_t i = 0; i < poses.size(); ++i) e.push_back({&poses[i], 0.3 + 0.1 * double(i)});
    r.draw(e);
  };
  const Frames partial = draw_frames(s, false, 12, Backdrop::Sky, strobe);
  poses.clear();
  const Frames full = draw_frames(s, true, 12, Backdrop::Sky, strobe);
  expect_same_frames(partial, full);
}

TEST(PartialRedraw, ABodyThatLeavesTheViewLeavesNothingBehind) {
  // Thrown at 30 m/s the box is off the screen within a few frames: the rectangle where it
  // was must still be redrawn although it now has none.
  EglContext gl;
  Scene s = parse_scene(moving_scene(), "<test>");
  s.bodies[0].velocity = Vec3(30.0, 0.0, 0.0);
  const Frames partial = draw_frames(s, false, 12), full = draw_frames(s, true, 12);
  expect_same_frames(partial, full);
}

TEST(PartialRedraw, ManyBodiesAndAFollowingCamera) {
  EglContext gl;
  std::string many;
  for (int i = 0; i < 14; ++i)
    many += "[[body]]\nshape = \"box\"\nsize = [0.2, 0.2, 0.2]\nmass = 1.0\nposition = [" +
            std::to_string(-3.5 + 0.5 * i) + ", " + std::to_string(0.5 + 0.2 * (i % 5)) +
            ", 0.5]\nvelocity = [0.0, 2.0, 0.0]\nangular_velocity = [1.0, 2.0, 3.0]\n";
  const Scene crowd = parse_scene(moving_scene(many), "<test>");
  expect_same_frames(draw_frames(crowd, false, 10), draw_frames(crowd, true, 10));
  // More rectangles than are merged pairwise (two per body and picture): their bounding box.
  std::string swarm;
  for (int i = 0; i < 40; ++i)
    swarm += "[[body]]\nshape = \"particle\"\nmass = 0.1\nposition = [" +
             std::to_string(-4.0 + 0.2 * i) + ", " + std::to_string(0.5 + 0.3 * (i % 7)) +
             ", 0.0]\nvelocity = [0.0, 3.0, 0.0]\n";
  const Scene crowded = parse_scene(moving_scene(swarm), "<test>");
  expect_same_frames(draw_frames(crowded, false, 6), draw_frames(crowded, true, 6));

  Scene followed = parse_scene(moving_scene(), "<test>");
  followed.camera.follow = "thrown";
  const Frames partial = draw_frames(followed, false, 10), full = draw_frames(followed, true, 10);
  expect_same_frames(partial, full);
  for (double share : partial.share) EXPECT_EQ(share, 1.0);  // the camera moves every frame
}

}  // namespace
}  // namespace tumble
