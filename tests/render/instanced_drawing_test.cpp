// Bodies that share a model (boxes, spheres, particles) are drawn many per draw call, each
// instance with its own transform and colour, in the lit and the shadow pass. The claim is the
// very bytes of drawing each body with its own uniforms and call: checked here against
// draw_each_body() with redraw_in_full() (the reference of both claims), frame by frame, for a
// crowd of 50 moving bodies of every shape beside mesh bodies (drawn on their own), in every
// antialiasing mode and backdrop, and for strobe pictures (translucent poses, one by one, over
// opaque ones and the shadows of both).
#include <gtest/gtest.h>

#include "tumble/egl_context.hpp"
#include "tumble/renderer.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

// 40 boxes, 5 spheres and 5 particles thrown up and spinning from a grid over a floor, passing
// through each other, and two mesh bodies (one in its file's materials, one in a scene colour),
// 160x120.
std::string crowd_scene() {
  std::string s = R"(
[simulation]
dt = 0.002
collisions = "floor"
[floor]
[render]
width = 160
height = 120
[camera]
position = [0.0, 3.0, 9.0]
target = [0.0, 1.0, 0.0]
[[body]]
name = "die"
shape = "mesh"
mesh = ")" + std::string(TUMBLE_SOURCE_DIR) +
                  R"(/assets/meshes/die.gltf"
scale = 0.4
mass = 1.0
position = [-1.5, 3.4, 1.5]
angular_velocity = [1.0, 2.0, 0.0]
[[body]]
name = "ico"
shape = "mesh"
mesh = ")" + std::string(TUMBLE_SOURCE_DIR) +
                  R"(/assets/meshes/icosphere.obj"
scale = 0.3
mass = 1.0
color = "#3a7bd5"
position = [1.5, 3.4, 1.5]
velocity = [0.0, 1.0, 0.0]
)";
  for (int k = 0; k < 50; ++k) {
    const char* shape = k % 10 == 3 ? "sphere" : k % 10 == 7 && k > 20 ? "particle" : "box";
    const double x = -3.0 + 0.6 * (k % 10), y = 0.6 + 0.5 * (k / 10), z = -0.5 * (k % 3);
    s += "[[body]]\nshape = \"" + std::string(shape) + "\"\nmass = 1.0\n";
    if (std::string(shape) == "box")
      s += "size = [0.3, 0.2, 0.25]\n";
    else if (std::string(shape) == "sphere")
      s += "radius = 0.15\n";
    s += "position = [" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) +
         "]\nvelocity = [" + std::to_string(0.3 * (k % 4) - 0.5) + ", 2.0, 0.0]\n";
    if (std::string(shape) != "particle")  // a particle does not turn
      s += "angular_velocity = [" + std::to_string(1.0 + k % 3) + ", 2.0, " +
           std::to_string(0.5 * (k % 5)) + "]\n";
    if (k % 4 == 0) s += "color = \"#" + std::string(k % 8 == 0 ? "2bd957" : "d9572b") + "\"\n";
  }
  return s;
}

// Frames 1/15 s apart, drawn instanced with partial redraw, or each body on its own and every
// picture in full; a strobe of the last three poses is drawn (and read) before every third.
std::vector<std::vector<std::uint8_t>> draw_frames(const Scene& s, const SceneModels& models,
                                                   bool reference, Backdrop backdrop) {
  Renderer r(s, Renderer::Readback::Sync, &models, backdrop);
  r.redraw_in_full(reference);
  r.draw_each_body(reference);
  World w(make_world_def(s, models));
  std::vector<World> poses;
  std::vector<std::vector<std::uint8_t>> out;
  for (int k = 0; k < 8; ++k) {
    poses.push_back(w);
    if (k % 3 == 2) {
      std::vector<Exposure> e;
      for (std::size_t i = poses.size() - 3; i < poses.size(); ++i)
        e.push_back({&poses[i], i + 1 == poses.size() ? 1.0 : 0.3 + 0.2 * double(i % 3)});
      r.draw(e);
      out.emplace_back();
      r.read_rgba(out.back());
    }
    r.draw(w);
    out.emplace_back();
    r.read_rgba(out.back());
    for (int i = 0; i < 33; ++i) w.step();
  }
  return out;
}

void expect_same_pictures(const Scene& s, Backdrop backdrop = Backdrop::Sky) {
  const SceneModels models = load_models(s);
  const auto instanced = draw_frames(s, models, false, backdrop);
  const auto reference = draw_frames(s, models, true, backdrop);
  ASSERT_EQ(instanced.size(), reference.size());
  for (std::size_t k = 0; k < reference.size(); ++k)
    EXPECT_TRUE(instanced[k] == reference[k]) << "picture " << k << " differs from the reference";
  EXPECT_FALSE(reference.front() == reference.back());  // the bodies did move
}

TEST(InstancedDrawing, SameBytesAsEachBodyOnItsOwnInEveryAntialiasingMode) {
  EglContext gl;
  for (const Antialias aa : {Antialias::Fxaa, Antialias::None, Antialias::Msaa}) {
    SCOPED_TRACE(int(aa));
    Scene s = parse_scene(crowd_scene(), "<test>");
    s.render.antialias = aa;
    s.render.msaa = aa == Antialias::Msaa ? 4 : 0;
    expect_same_pictures(s);
  }
}

TEST(InstancedDrawing, TransparentBackdropAndNoShadowsToo) {
  EglContext gl;
  Scene s = parse_scene(crowd_scene(), "<test>");
  expect_same_pictures(s, Backdrop::Transparent);
  s.light.shadows = false;
  expect_same_pictures(s);
}

}  // namespace
}  // namespace tumble
