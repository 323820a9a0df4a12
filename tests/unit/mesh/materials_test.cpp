// A model's own materials, textures and vertex colours as the mesh layer reads them, per drawn
// triangle (the models: scripts/make-meshes -> tests/unit/mesh/data/materials/).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "mesh_fixtures.hpp"

namespace tumble::test {
namespace {

const std::filesystem::path kMaterials = kData / "materials";

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// The outward normal of drawn triangle t.
Vec3 normal_of(const MeshBody& body, std::size_t t) {
  const auto& tri = body.mesh.triangles[t];
  const Vec3 &a = body.mesh.vertices[tri[0]], &b = body.mesh.vertices[tri[1]],
             &c = body.mesh.vertices[tri[2]];
  return (b - a).cross(c - a).normalized();
}

// The texture's pixel (x, y), y = 0 the top row, as RGB.
Vec3 texel(const TextureImage& image, int x, int y) {
  const std::size_t i = 4 * (std::size_t(y) * std::size_t(image.width) + std::size_t(x));
  return Vec3(image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]);
}

TEST(MeshMaterials, AModelWithoutMaterialsHasNone) {
  // assimp invents a default material for each of these; none is the file's own.
  for (const char* name : {"cube.obj", "cube.stl", "cube.gltf", "icosphere.glb", "plate.ply",
                           "tetrahedron.off", "die.gltf"})
    EXPECT_FALSE(load(kAssets / name).appearance.has_materials()) << name;
  // `usemtl` without a material library names materials that are not there.
  EXPECT_FALSE(load(kData / "cube_multipart.obj").appearance.has_materials());
}

TEST(MeshMaterials, MtlKdColoursEachTriangleInSrgb) {
  const MeshBody body = load(kMaterials / "two_colours.obj");
  const MeshAppearance& look = body.appearance;
  ASSERT_TRUE(look.has_materials());
  ASSERT_EQ(look.triangle_material.size(), body.mesh.triangles.size());
  ASSERT_EQ(body.mesh.triangles.size(), 12u);
  // Kd 0.8 0.3 0.1 on the faces towards +x, +y, +z; Kd 0.1 0.4 0.7 on the others. MTL colours
  // are sRGB (as the scene's `color`): stored linear.
  const Vec3 warm(srgb_to_linear(0.8), srgb_to_linear(0.3), srgb_to_linear(0.1));
  const Vec3 cool(srgb_to_linear(0.1), srgb_to_linear(0.4), srgb_to_linear(0.7));
  for (std::size_t t = 0; t < body.mesh.triangles.size(); ++t) {
    const MeshMaterial& m = look.materials[look.triangle_material[t]];
    const bool positive = normal_of(body, t).sum() > 0.0;
    EXPECT_EQ(m.name, positive ? "warm" : "cool");
    EXPECT_LT((m.base_color_linear - (positive ? warm : cool)).norm(), 1e-6);
    EXPECT_EQ(m.texture, -1);
    for (const Vec3& c : look.corner_color[t]) EXPECT_EQ(c, Vec3::Ones());
  }
}

TEST(MeshMaterials, GltfBaseColorFactorAloneIsLinear) {
  const MeshBody body = load(kMaterials / "factor.gltf");
  ASSERT_TRUE(body.appearance.has_materials());
  for (const std::uint32_t m : body.appearance.triangle_material) {
    const MeshMaterial& material = body.appearance.materials[m];
    EXPECT_FALSE(material.use_body_color);
    EXPECT_EQ(material.texture, -1);
    // baseColorFactor [0.5, 0.1, 0.02] is linear in glTF: kept as it is (float32 in the file).
    EXPECT_LT((material.base_color_linear - Vec3(0.5, 0.1, 0.02)).norm(), 1e-6);
  }
}

TEST(MeshMaterials, GltfVertexColoursFollowTheirCorners) {
  const MeshBody body = load(kMaterials / "vertex_colours.gltf");
  const MeshAppearance& look = body.appearance;
  ASSERT_TRUE(look.has_materials());
  for (std::size_t t = 0; t < body.mesh.triangles.size(); ++t) {
    // No material of its own: white (glTF's default material), times the vertex colour
    // 0.05 + 0.9 max(0, n), which is linear in glTF.
    const MeshMaterial& m = look.materials[look.triangle_material[t]];
    EXPECT_FALSE(m.use_body_color);
    EXPECT_EQ(m.base_color_linear, Vec3::Ones());
    const Vec3 n = normal_of(body, t);
    const Vec3 expected = Vec3::Constant(0.05) + 0.9 * n.cwiseMax(0.0);
    for (const Vec3& c : look.corner_color[t]) EXPECT_LT((c - expected).norm(), 1e-6) << t;
  }
}

// Every textured cube maps its +z face's corners to u = x + 1/2, v = y + 1/2, and holds the
// texture whose top half is (230, 180, 40) and bottom half (40, 90, 200).
void expect_textured_cube(const std::filesystem::path& file, double tolerance) {
  SCOPED_TRACE(file.filename().string());
  const MeshBody body = load(file);
  const MeshAppearance& look = body.appearance;
  ASSERT_TRUE(look.has_materials());
  ASSERT_EQ(look.textures.size(), 1u);
  const TextureImage& image = look.textures[0];
  ASSERT_EQ(image.width, 16);
  ASSERT_EQ(image.height, 16);
  EXPECT_LT((texel(image, 3, 2) - Vec3(230, 180, 40)).cwiseAbs().maxCoeff(), tolerance);
  EXPECT_LT((texel(image, 12, 13) - Vec3(40, 90, 200)).cwiseAbs().maxCoeff(), tolerance);
  int front = 0;
  for (std::size_t t = 0; t < body.mesh.triangles.size(); ++t) {
    EXPECT_EQ(look.materials[look.triangle_material[t]].texture, 0);
    if (normal_of(body, t).z() < 0.99) continue;
    ++front;
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& p = body.mesh.vertices[body.mesh.triangles[t][k]];
      EXPECT_LT((look.corner_uv[t][k] - Eigen::Vector2d(p.x() + 0.5, p.y() + 0.5)).norm(), 1e-6);
    }
  }
  EXPECT_EQ(front, 2);
}

TEST(MeshMaterials, TexturesFromADataUriABufferViewAFileAndAJpeg) {
  expect_textured_cube(kMaterials / "textured_data_uri.gltf", 0.5);
  expect_textured_cube(kMaterials / "textured_embedded.glb", 0.5);
  expect_textured_cube(kMaterials / "textured_file.gltf", 0.5);
  // The JPEG's flat blocks come back to within the YCbCr rounding: 2 levels.
  expect_textured_cube(kMaterials / "textured_jpeg.obj", 2.5);
}

TEST(MeshMaterials, SeveralMaterialsInOneGltf) {
  const MeshBody body = load(kAssets / "crate.gltf");
  const MeshAppearance& look = body.appearance;
  ASSERT_TRUE(look.has_materials());
  std::set<std::string> names;
  for (std::size_t t = 0; t < body.mesh.triangles.size(); ++t) {
    const MeshMaterial& m = look.materials[look.triangle_material[t]];
    names.insert(m.name);
    EXPECT_EQ(m.name, normal_of(body, t).y() > 0.5 ? "lid" : "planks");
  }
  EXPECT_EQ(names.size(), 2u);
  ASSERT_EQ(look.textures.size(), 1u);
  EXPECT_EQ(look.textures[0].width, 64);
}

TEST(MeshMaterials, AMissingTextureIsAnErrorNamingIt) {
  const std::string error = load_error(kMaterials / "missing_texture.obj");
  EXPECT_CONTAINS(error, "missing_texture.obj");
  EXPECT_CONTAINS(error, "no_such_texture.png");
  EXPECT_CONTAINS(error, "no such file");
}

TEST(MeshMaterials, ATextureThatIsNoImageIsAnError) {
  const std::string error = load_error(kMaterials / "not_an_image.obj");
  EXPECT_CONTAINS(error, "two_colours.mtl");
  EXPECT_CONTAINS(error, "neither a PNG nor a JPEG");
}

TEST(MeshMaterials, TexturesHaveThePixelLimit) {
  MeshLoadOptions options;
  options.max_texture_pixels = 255;  // the 16 x 16 texture has 256
  const std::string error = load_error(kMaterials / "textured_file.gltf", options);
  EXPECT_CONTAINS(error, "two_colours.png");
  EXPECT_CONTAINS(error, "16 x 16 pixels, above the limit of 255");
}

TEST(MeshMaterials, TexturesHaveTheFileSizeLimit) {
  MeshLoadOptions options;
  // Enough for the OBJ and its MTL, not for the PNG beside them.
  options.max_file_bytes = std::filesystem::file_size(kMaterials / "large_texture.obj");
  ASSERT_GT(std::filesystem::file_size(kMaterials / "noise.png"), options.max_file_bytes);
  const std::string error = load_error(kMaterials / "large_texture.obj", options);
  EXPECT_CONTAINS(error, "noise.png");
  EXPECT_CONTAINS(error, "above the limit of");
}

TEST(MeshMaterials, HullRepairDropsTheMaterials) {
  EXPECT_FALSE(load(kMaterials / "two_colours.obj", MeshRepair::Hull).appearance.has_materials());
}

}  // namespace
}  // namespace tumble::test
