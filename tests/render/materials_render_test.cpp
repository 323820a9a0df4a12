// Models drawn in their own materials, on the real EGL + OpenGL stack: each colour where the
// file puts it, within 5/255 of what the lighting makes of it on a face lit head-on; a scene
// `color` overriding them; the partial redraw and shadows unchanged by them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "tumble/egl_context.hpp"
#include "tumble/renderer.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {
namespace {

const std::filesystem::path kMaterials =
    std::filesystem::path(TUMBLE_SOURCE_DIR) / "tests" / "unit" / "mesh" / "data" / "materials";
constexpr int kW = 200, kH = 100;

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double linear_to_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// What shade() in shaders/common.glsl makes of a linear albedo on a face whose normal points
// at the light and at the (orthographic) viewer, both along +z: full diffuse, the hemisphere
// ambient halfway (n.y = 0), and the whole specular term (n = h), as 8-bit sRGB.
Vec3 lit_head_on(const Vec3& albedo_linear) {
  const Vec3 ambient = 0.5 * (Vec3(0.20, 0.19, 0.18) + Vec3(0.38, 0.42, 0.48));
  Vec3 out;
  for (int i = 0; i < 3; ++i)
    out[i] = 255.0 * linear_to_srgb(albedo_linear[i] * (ambient[i] + 0.85) + 0.25);
  return out;
}
Vec3 lit_head_on_srgb(const Vec3& albedo_srgb) {
  return lit_head_on(Vec3(srgb_to_linear(albedo_srgb.x()), srgb_to_linear(albedo_srgb.y()),
                          srgb_to_linear(albedo_srgb.z())));
}

// Two unit-cube models side by side at x = -1 and x = +1, the right one turned 180° about y
// (its -z face towards the camera), seen head-on along -z through an orthographic camera 2 m
// high, lit along -z; no floor, no gravity. `extra` goes into both bodies.
Scene two_models(const std::string& file, const std::string& extra = "") {
  const std::string mesh = (kMaterials / file).string();
  return parse_scene(R"(
[simulation]
gravity = [0.0, 0.0, 0.0]
[render]
width = 200
height = 100
background = "#000000"
[camera]
projection = "orthographic"
ortho_height = 2.0
position = [0.0, 0.0, 10.0]
target = [0.0, 0.0, 0.0]
[light]
direction = [0.0, 0.0, -1.0]
[[body]]
name = "front"
shape = "mesh"
mesh = ")" + mesh + R"("
mass = 1.0
position = [-1.0, 0.0, 0.0]
)" + extra + R"(
[[body]]
name = "back"
shape = "mesh"
mesh = ")" + mesh + R"("
mass = 1.0
position = [1.0, 0.0, 0.0]
orientation = { axis = [0.0, 1.0, 0.0], degrees = 180.0 }
)" + extra,
                     "<materials test>");
}

Image render(const Scene& s) {
  EglContext gl;
  const SceneModels models = load_models(s);
  Renderer r(s, Renderer::Readback::Auto, &models);
  const World w(make_world_def(s, models));
  r.draw(w);
  return r.read_image();
}

// The colour at world point (x, y) on the z = 0.5 plane (the faces towards the camera).
Vec3 at(const Image& img, double x, double y) {
  const int px = int(std::lround((x / 2.0 + 0.5 * kW / double(kH)) * kH - 0.5));
  const int py = int(std::lround((0.5 - y / 2.0) * kH - 0.5));
  const std::uint8_t* p = img.row(py) + 3 * px;
  return Vec3(p[0], p[1], p[2]);
}

double off_by(const Vec3& got, const Vec3& expected) {
  return (got - expected).cwiseAbs().maxCoeff();
}

TEST(MaterialsRender, TwoMtlColoursEachWithinFiveOfTheirLitValue) {
  const Image img = render(two_models("two_colours.obj"));
  // The front cube shows its +z face (Kd 0.8 0.3 0.1), the turned one its -z face (0.1 0.4 0.7).
  const Vec3 warm = lit_head_on_srgb(Vec3(0.8, 0.3, 0.1));
  const Vec3 cool = lit_head_on_srgb(Vec3(0.1, 0.4, 0.7));
  for (const double dx : {-0.3, 0.0, 0.3})
    for (const double dy : {-0.3, 0.0, 0.3}) {
      EXPECT_LE(off_by(at(img, -1.0 + dx, dy), warm), 5.0)
          << at(img, -1.0 + dx, dy).transpose() << " vs " << warm.transpose();
      EXPECT_LE(off_by(at(img, 1.0 + dx, dy), cool), 5.0)
          << at(img, 1.0 + dx, dy).transpose() << " vs " << cool.transpose();
    }
}

// The texture's top half (230, 180, 40) on the upper half of the face, its bottom half
// (40, 90, 200) on the lower half, where u = x + 1/2, v = y + 1/2 put them (the turned cube's
// -z face has the same mapping seen from behind: the same halves up and down).
void expect_two_texel_colours(const Image& img) {
  const Vec3 top = lit_head_on_srgb(Vec3(230, 180, 40) / 255.0);
  const Vec3 bottom = lit_head_on_srgb(Vec3(40, 90, 200) / 255.0);
  for (const double cx : {-1.0, 1.0})
    for (const double dx : {-0.3, 0.0, 0.3}) {
      EXPECT_LE(off_by(at(img, cx + dx, 0.25), top), 5.0)
          << cx + dx << ": " << at(img, cx + dx, 0.25).transpose() << " vs " << top.transpose();
      EXPECT_LE(off_by(at(img, cx + dx, -0.25), bottom), 5.0)
          << cx + dx << ": " << at(img, cx + dx, -0.25).transpose() << " vs "
          << bottom.transpose();
    }
}

TEST(MaterialsRender, GltfTextureShowsBothTexelColoursWhereTheUvsPutThem) {
  expect_two_texel_colours(render(two_models("textured_data_uri.gltf")));
  expect_two_texel_colours(render(two_models("textured_embedded.glb")));
  expect_two_texel_colours(render(two_models("textured_file.gltf")));
}

TEST(MaterialsRender, JpegTextureThroughMapKd) {
  expect_two_texel_colours(render(two_models("textured_jpeg.obj")));
}

TEST(MaterialsRender, BaseColorFactorAlone) {
  const Image img = render(two_models("factor.gltf"));
  const Vec3 expected = lit_head_on(Vec3(0.5, 0.1, 0.02));  // linear, as glTF defines it
  EXPECT_LE(off_by(at(img, -1.0, 0.0), expected), 5.0) << at(img, -1.0, 0.0).transpose();
  EXPECT_LE(off_by(at(img, 1.0, 0.0), expected), 5.0) << at(img, 1.0, 0.0).transpose();
}

TEST(MaterialsRender, PerVertexColours) {
  const Image img = render(two_models("vertex_colours.gltf"));
  // COLOR_0 is 0.05 + 0.9 max(0, n) (linear): the +z face blue, the -z face a dark grey.
  const Vec3 front = lit_head_on(Vec3(0.05, 0.05, 0.95));
  const Vec3 back = lit_head_on(Vec3(0.05, 0.05, 0.05));
  EXPECT_LE(off_by(at(img, -1.0, 0.0), front), 5.0) << at(img, -1.0, 0.0).transpose();
  EXPECT_LE(off_by(at(img, 1.0, 0.0), back), 5.0) << at(img, 1.0, 0.0).transpose();
}

TEST(MaterialsRender, ASceneColourOverridesTheModelsMaterials) {
  const Image img = render(two_models("two_colours.obj", "color = \"#2b7bd9\""));
  const Vec3 expected = lit_head_on_srgb(Vec3(0x2b, 0x7b, 0xd9) / 255.0);
  EXPECT_LE(off_by(at(img, -1.0, 0.0), expected), 5.0) << at(img, -1.0, 0.0).transpose();
  EXPECT_LE(off_by(at(img, 1.0, 0.0), expected), 5.0) << at(img, 1.0, 0.0).transpose();
  // The same as a box of that colour would be: the model's materials are gone.
  const Image textured = render(two_models("textured_file.gltf", "color = \"#2b7bd9\""));
  EXPECT_LE(off_by(at(textured, -1.0, 0.3), expected), 5.0);
  EXPECT_LE(off_by(at(textured, -1.0, -0.3), expected), 5.0);
}

// A textured model thrown over a floor, with shadows: every frame of the partial redraw is the
// very bytes of drawing it all, for each antialiasing mode, and over a transparent backdrop.
TEST(MaterialsRender, PartialRedrawOfATexturedModelIsTheFullPicture) {
  for (const char* antialias : {"fxaa", "msaa", "none", "transparent"}) {
    SCOPED_TRACE(antialias);
    const bool transparent = std::string(antialias) == "transparent";
    if (transparent) antialias = "fxaa";
    const Backdrop backdrop = transparent ? Backdrop::Transparent : Backdrop::Sky;
    const Scene s = parse_scene(std::string(R"(
[render]
width = 160
height = 120
antialias = ")") + antialias + R"("
[floor]
[camera]
position = [0.0, 2.0, 7.0]
target = [0.0, 1.0, 0.0]
[[body]]
name = "crate"
shape = "mesh"
mesh = ")" + (std::filesystem::path(TUMBLE_SOURCE_DIR) / "assets" / "meshes" / "crate.gltf").string() +
                                     R"("
mass = 1.0
scale = 0.6
position = [-2.0, 1.5, 0.0]
velocity = [4.0, 2.0, 0.0]
angular_velocity = [1.0, 2.0, 3.0]
)",
                                "<materials test>");
    EglContext gl;
    const SceneModels models = load_models(s);
    Renderer partial(s, Renderer::Readback::Auto, &models, backdrop);
    Renderer full(s, Renderer::Readback::Auto, &models, backdrop);
    full.redraw_in_full(true);
    World w(make_world_def(s, models));
    double drawn = 0.0;
    for (int k = 0; k < 8; ++k) {
      for (int i = 0; i < 66 && k > 0; ++i) w.step();  // 1/15 s at dt = 0.001
      partial.draw(w);
      full.draw(w);
      if (k > 0) drawn += partial.redrawn_share();
      const Image a = partial.read_image(), b = full.read_image();
      ASSERT_EQ(a.pixels, b.pixels) << "frame " << k;
      // Transparent: RGBA (straight alpha), as every PNG output then is.
      if (transparent) {
        EXPECT_EQ(a.channels, 4);
      }
    }
    EXPECT_LT(drawn / 7.0, 0.8);  // it did redraw only part of the frame
  }
}

}  // namespace
}  // namespace tumble
