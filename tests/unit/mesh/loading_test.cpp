// Loading real files: the same cube in every format gives the same body; meshes split over
// objects, mirrored node transforms, cavities; every asset in assets/meshes loads clean.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "../test_dir.hpp"
#include "mesh_fixtures.hpp"

namespace tumble {
namespace {

using test::kAssets;
using test::kData;
using test::load;

void expect_same_body(const MeshBody& a, const MeshBody& b, double tolerance) {
  EXPECT_NEAR(a.mass.volume, b.mass.volume, tolerance);
  EXPECT_LT((a.mass.center_of_mass - b.mass.center_of_mass).norm(), tolerance);
  EXPECT_LT((a.mass.inertia_com - b.mass.inertia_com).norm(), tolerance);
  EXPECT_LT((a.mass.principal_moments - b.mass.principal_moments).norm(), tolerance);
  EXPECT_LT((a.mass.principal_axes - b.mass.principal_axes).norm(), tolerance);
  ASSERT_EQ(a.hull_vertices.size(), b.hull_vertices.size());
  for (std::size_t i = 0; i < a.hull_vertices.size(); ++i)
    EXPECT_LT((a.hull_vertices[i] - b.hull_vertices[i]).norm(), tolerance) << i;
  EXPECT_EQ(a.hull_faces, b.hull_faces);
}

TEST(MeshLoading, CubeIsTheSameInObjStlGltfAndAsciiStl) {
  const MeshBody obj = load(kAssets / "cube.obj");
  EXPECT_EQ(obj.source_triangles, 12u);
  EXPECT_EQ(obj.welded_vertices, 8u);
  EXPECT_EQ(obj.mesh.vertices.size(), 8u);
  EXPECT_EQ(obj.hull_vertices.size(), 8u);
  EXPECT_EQ(obj.hull_faces, 6u);
  EXPECT_EQ(obj.repair_note, "");
  // Summation order may differ between formats: round-off only.
  for (const char* name : {"cube.stl", "cube.gltf"}) {
    SCOPED_TRACE(name);
    const MeshBody other = load(kAssets / name);
    EXPECT_EQ(other.welded_vertices, 8u);  // STL and glTF store 36 unshared corners
    expect_same_body(obj, other, 1e-12);
  }
  expect_same_body(obj, load(kData / "cube_ascii.stl"), 1e-12);
}

TEST(MeshLoading, OneBodyFromSeveralMeshesWelds) {
  // Two objects with two materials: assimp gives two aiMeshes; the body is one cube.
  const MeshBody split = load(kData / "cube_multipart.obj");
  EXPECT_EQ(split.welded_vertices, 8u);
  expect_same_body(load(kAssets / "cube.obj"), split, 1e-12);
}

TEST(MeshLoading, MirroringNodeTransformKeepsTheWindingOutward) {
  // The node maps x -> -2x + 3 (determinant -2): without reversing the winding, the cube would
  // come out inside-out.
  const MeshBody body = load(kData / "mirrored_cube.gltf");
  EXPECT_EQ(body.repair_note, "");
  EXPECT_NEAR(body.mass.volume, 2.0, 1e-12);
  EXPECT_LT((body.mass.center_of_mass - Vec3(3.0, 0.0, 0.0)).norm(), 1e-12);
  EXPECT_GT(mass_properties(body.mesh).volume, 0.0);
}

TEST(MeshLoading, ColladaUnitAndUpAxisAreApplied) {
  // A 100 cm cube declared in centimetres: 1 m^3 (to float32, in which assimp scales).
  const MeshBody cube = load(kData / "cube_centimetres_z_up.dae");
  EXPECT_NEAR(cube.mass.volume, 1.0, 1e-6);
  // Z up becomes y up: (x, y, z) -> (x, z, -y), a rotation, so the winding stays outward.
  const MeshBody l = load(kData / "lshape_z_up.dae");
  EXPECT_NEAR(l.mass.volume, 0.375, 1e-12);
  EXPECT_LT((l.mass.center_of_mass - Vec3(5.0 / 12.0, 0.25, -5.0 / 12.0)).norm(), 1e-12);
}

TEST(MeshLoading, CavityFacingInwardIsSubtracted) {
  const MeshBody body = load(kData / "hollow_cube.obj");
  EXPECT_NEAR(body.mass.volume, 7.0, 1e-12);
  // Still isotropic: the 2 m cube's V (a² + a²)/12 = 16/3 less the cavity's 1/6, about any axis.
  EXPECT_LT((body.mass.inertia_com - Mat3::Identity() * 31.0 / 6.0).norm(), 1e-12);
  EXPECT_EQ(body.hull_vertices.size(), 8u);  // the contact hull is the outer cube only
}

TEST(MeshLoading, OrientFlipsAnOutwardCavity) {
  const MeshBody body = load(kData / "hollow_cube_wrong.obj", MeshRepair::Orient);
  EXPECT_NEAR(body.mass.volume, 7.0, 1e-12);
  EXPECT_EQ(body.repair_note, "flipped 12 triangles in 1 inside-out shell");
}

TEST(MeshLoading, EveryAssetLoadsCleanAsAClosedSolid) {
  std::vector<std::filesystem::path> files;
  // The models, not the files they reference (a texture beside its glTF).
  const auto& models = mesh_file_extensions();
  for (const auto& entry : std::filesystem::directory_iterator(kAssets)) {
    const std::string ext = entry.path().extension().string();
    if (!ext.empty() && std::find(models.begin(), models.end(), ext.substr(1)) != models.end())
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 14u);
  for (const auto& file : files) {
    SCOPED_TRACE(file.filename().string());
    try {
      const MeshBody body = load(file);
      EXPECT_EQ(body.repair_note, "");
      EXPECT_EQ(body.degenerate_triangles, 0u);
      EXPECT_GT(body.mass.volume, 0.0);
      // Every hull vertex is a mesh vertex; the mesh is closed and outward.
      EXPECT_NEAR(mass_properties(body.mesh).volume, body.mass.volume, 1e-12);
      for (const Vec3& h : body.hull_vertices)
        EXPECT_TRUE(std::find(body.mesh.vertices.begin(), body.mesh.vertices.end(), h) !=
                    body.mesh.vertices.end());
    } catch (const Error& e) {
      ADD_FAILURE() << e.describe();
    }
  }
}

TEST(MeshLoading, SameModelInTwoFormatsIsOneBody) {
  for (const auto& [a, b] :
       std::vector<std::pair<const char*, const char*>>{{"tetrahedron.obj", "tetrahedron.off"},
                                                        {"icosphere.obj", "icosphere.glb"},
                                                        {"lshape.obj", "lshape.stl"},
                                                        {"plate.obj", "plate.ply"},
                                                        {"die.obj", "die.gltf"}}) {
    SCOPED_TRACE(a);
    // OBJ text and binary float32 may round the same decimal differently by an ulp.
    expect_same_body(load(kAssets / a), load(kAssets / b), 1e-6);
  }
}

TEST(MeshLoading, DieHullHasAllTwentyFourCorners) {
  const MeshBody die = load(kAssets / "die.obj");
  EXPECT_EQ(die.hull_vertices.size(), 24u);
  EXPECT_EQ(die.hull_faces, 26u);  // 6 faces, 12 edge bevels, 8 corner bevels
  EXPECT_TRUE(die.mass.principal_axes.isIdentity(0.0));
}

TEST(MeshLoading, ThinPlateKeepsItsThickness) {
  const MeshBody plate = load(kAssets / "plate.obj");
  EXPECT_NEAR(plate.mass.volume, 1.0 * 0.03125 * 0.75, 1e-15);
  EXPECT_EQ(plate.hull_vertices.size(), 8u);
}

TEST(MeshLoading, NearlyCoincidentVerticesWeld) {
  // One corner of a cube written twice, one float32 ulp (6e-8) apart, as exporters do:
  // within the weld tolerance (1e-7 of the diagonal), so the cube is closed.
  const auto dir = test::fresh_dir("MeshLoading", "NearlyCoincidentVerticesWeld");
  std::ofstream(dir / "jitter.obj") << "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv -0.5 0.5 -0.5\n"
                                       "v 0.5 0.5 -0.5\nv -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\n"
                                       "v -0.5 0.5 0.5\nv 0.5 0.5 0.5\nv 0.50000006 0.5 0.5\n"
                                       "f 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\nf 1 2 6\nf 1 6 5\n"
                                       "f 3 7 9\nf 3 8 4\nf 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\n";
  const MeshBody body = load(dir / "jitter.obj");
  EXPECT_EQ(body.welded_vertices, 8u);
  EXPECT_NEAR(body.mass.volume, 1.0, 1e-6);
}

TEST(MeshLoading, ConvexHullRepairWorksOnAnOpenBox) {
  const MeshBody body = load(kData / "open_box.obj", MeshRepair::Hull);
  EXPECT_NEAR(body.mass.volume, 1.0, 1e-12);
  EXPECT_EQ(body.hull_vertices.size(), 8u);
  EXPECT_EQ(body.mesh.vertices.size(), 8u);
  EXPECT_EQ(body.repair_note,
            "replaced by its convex hull (8 vertices, 6 faces) in place of the 10 source "
            "triangles, which were not closed (4 open edges)");
}

TEST(MeshLoading, ConvexHullRepairOfANonConvexBodyFillsIt) {
  const MeshBody body = load(kAssets / "lshape.obj", MeshRepair::Hull);
  EXPECT_NEAR(body.mass.volume, 0.375 + 0.5 * 0.5 * 0.5 * 0.5, 1e-12);  // + the notch's half
}

TEST(MeshLoading, OrientRewindsAStrayTriangle) {
  const MeshBody body = load(kData / "inconsistent_winding.obj", MeshRepair::Orient);
  EXPECT_NEAR(body.mass.volume, 1.0, 1e-12);
  EXPECT_EQ(body.repair_note, "re-wound 1 triangle to match their neighbours");
}

TEST(MeshLoading, OrientFlipsAnInsideOutMesh) {
  const MeshBody body = load(kData / "inside_out_cube.obj", MeshRepair::Orient);
  EXPECT_NEAR(body.mass.volume, 1.0, 1e-12);
  EXPECT_EQ(body.repair_note, "flipped 12 triangles (the mesh was inside-out)");
  const MeshBody hull = load(kData / "inside_out_cube.obj", MeshRepair::Hull);
  EXPECT_NEAR(hull.mass.volume, 1.0, 1e-12);
}

}  // namespace
}  // namespace tumble
