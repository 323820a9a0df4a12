// Every way a model can be refused: each error names the file first, says what is wrong with
// counts, and where (coordinates in file units).
#include <gtest/gtest.h>

#include <fstream>

#include "../test_dir.hpp"
#include "mesh_fixtures.hpp"

namespace tumble {
namespace {

using test::kAssets;
using test::kData;
using test::load_error;

MeshLoadOptions with_repair(MeshRepair repair) {
  MeshLoadOptions options;
  options.repair = repair;
  return options;
}

TEST(MeshErrors, MissingFile) {
  const auto file = kData / "does_not_exist.obj";
  EXPECT_EQ(load_error(file), file.string() + ": no such mesh file");
}

TEST(MeshErrors, UnknownFormatListsTheKnownOnes) {
  const auto file = kData / "unknown.xyz";
  EXPECT_EQ(load_error(file), file.string() +
                                  ": unsupported mesh format \".xyz\": tumble reads .obj, .stl, "
                                  ".ply, .off, .gltf, .glb, .fbx, .dae, .3ds");
}

TEST(MeshErrors, UnparseableFileGivesAssimpsText) {
  const std::string e = load_error(kData / "garbage.obj");
  EXPECT_EQ(e.rfind((kData / "garbage.obj").string() + ": cannot read it as .obj: ", 0), 0u) << e;
  EXPECT_FALSE(e.empty());
}

TEST(MeshErrors, TruncatedBinaryStl) {
  const auto dir = test::fresh_dir("MeshErrors", "TruncatedBinaryStl");
  std::ifstream in(kAssets / "cube.stl", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::ofstream(dir / "cut.stl", std::ios::binary) << bytes.substr(0, 300);
  EXPECT_CONTAINS(load_error(dir / "cut.stl"), "cut.stl: cannot read it as .stl: ");
}

TEST(MeshErrors, FileTooLarge) {
  MeshLoadOptions options;
  options.max_file_bytes = 100;
  EXPECT_CONTAINS(load_error(kAssets / "cube.obj", options),
                  "cube.obj: file too large: 482 bytes, above the limit of 100");
}

TEST(MeshErrors, TooManyTriangles) {
  MeshLoadOptions options;
  options.max_triangles = 11;
  EXPECT_CONTAINS(load_error(kAssets / "cube.obj", options),
                  "cube.obj: too many triangles: 12, above the limit of 11");
}

TEST(MeshErrors, ScaleMustBePositive) {
  MeshLoadOptions options;
  options.scale = Vec3(1.0, 0.0, 1.0);
  EXPECT_CONTAINS(load_error(kAssets / "cube.obj", options),
                  "scale must be finite and positive on every axis, got (1, 0, 1)");
}

TEST(MeshErrors, OpenBoxNamesItsOpenEdges) {
  const auto file = kData / "open_box.obj";
  EXPECT_EQ(load_error(file),
            file.string() +
                ": not closed: 4 open edges (used by one triangle only), e.g. "
                "(-0.5, 0.5, -0.5)\u2013(-0.5, 0.5, 0.5), (-0.5, 0.5, -0.5)\u2013(0.5, 0.5, -0.5), "
                "(-0.5, 0.5, 0.5)\u2013(0.5, 0.5, 0.5) (repair = \"hull\" would use its convex "
                "hull instead)");
}

TEST(MeshErrors, ExampleCoordinatesAreInFileUnits) {
  MeshLoadOptions options;
  options.scale = Vec3::Constant(0.001);  // a model in millimetres
  EXPECT_CONTAINS(load_error(kData / "open_box.obj", options),
                  "e.g. (-0.5, 0.5, -0.5)\u2013(-0.5, 0.5, 0.5)");
}

TEST(MeshErrors, NonManifoldEdge) {
  EXPECT_CONTAINS(load_error(kData / "non_manifold.obj"),
                  "non_manifold.obj: non-manifold: 1 edge is shared by more than two "
                  "triangles, e.g. (1, 1, 0)\u2013(1, 1, 1)");
  // Orient cannot fix it; hull can.
  EXPECT_CONTAINS(load_error(kData / "non_manifold.obj", with_repair(MeshRepair::Orient)),
                  "non-manifold");
  EXPECT_EQ(load_error(kData / "non_manifold.obj", with_repair(MeshRepair::Hull)), "");
}

TEST(MeshErrors, InconsistentWinding) {
  EXPECT_CONTAINS(load_error(kData / "inconsistent_winding.obj"),
                  "inconsistent_winding.obj: inconsistent winding: 3 edges are used twice "
                  "in the same direction (neighbouring triangles face opposite ways), e.g. ");
  EXPECT_CONTAINS(load_error(kData / "inconsistent_winding.obj"),
                  "(repair = \"orient\" makes the winding consistent)");
}

TEST(MeshErrors, InsideOutWithoutRepair) {
  EXPECT_CONTAINS(load_error(kData / "inside_out_cube.obj"),
                  "inside_out_cube.obj: inside-out: its 12 triangles face inward (signed "
                  "volume -1 m^3); repair = \"orient\" flips them");
}

TEST(MeshErrors, CavityFacingOutward) {
  EXPECT_CONTAINS(load_error(kData / "hollow_cube_wrong.obj"),
                  "inside-out: 1 of 2 shells face the wrong way");
}

TEST(MeshErrors, FlatSurfaceHasZeroVolume) {
  EXPECT_CONTAINS(load_error(kData / "flat.obj"),
                  "flat.obj: zero volume: the surface encloses no volume");
  EXPECT_CONTAINS(load_error(kData / "flat.obj", with_repair(MeshRepair::Hull)),
                  "flat.obj: repair = \"hull\": flat: the points lie in one plane");
}

TEST(MeshErrors, DegenerateTriangles) {
  EXPECT_CONTAINS(load_error(kData / "degenerate.obj"),
                  "degenerate.obj: degenerate: 4 of 4 triangles have zero area");
}

TEST(MeshErrors, OverlappingShellsIntersect) {
  EXPECT_CONTAINS(load_error(kData / "overlapping_cubes.obj"),
                  "overlapping_cubes.obj: self-intersecting: the shell of 12 triangles");
}

TEST(MeshErrors, ReferencedFileOutsideTheModelsFolderIsRefused) {
  // escape.gltf's buffer is "../cube_buffer.bin": assimp may read only the model's folder.
  EXPECT_CONTAINS(load_error(kData / "confined" / "escape.gltf"), "outside the model's folder");
}

TEST(MeshErrors, NotOrientableSurface) {
  // A Klein bottle: a 4 x 4 grid glued to a torus, but with one pair of sides glued reversed.
  // Closed and manifold, yet no winding makes every edge run once each way.
  const int n = 4;
  auto vertex = [&](int i, int j) {
    i = ((i % n) + n) % n;
    if (j == n) {  // the twisted seam: (i, n) is (n - i, 0)
      j = 0;
      i = (n - i) % n;
    }
    return 1 + i * n + j;
  };
  std::string obj;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      obj += "v " + std::to_string(i) + " " + std::to_string(j) + " " +
             std::to_string((i * 7 + j * 3) % 5) + "\n";
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                d = vertex(i, j + 1);
      obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n";
      obj += "f " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
    }
  const auto dir = test::fresh_dir("MeshErrors", "NotOrientableSurface");
  std::ofstream(dir / "klein.obj") << obj;
  EXPECT_CONTAINS(load_error(dir / "klein.obj"), "inconsistent winding");
  EXPECT_CONTAINS(load_error(dir / "klein.obj", with_repair(MeshRepair::Orient)), "not orientable");
}

TEST(MeshErrors, ADirectoryIsNoMesh) {
  const auto dir = test::fresh_dir("MeshErrors", "ADirectoryIsNoMesh") / "folder.obj";
  std::filesystem::create_directories(dir);
  EXPECT_CONTAINS(load_error(dir), "folder.obj: not a regular file");
}

}  // namespace
}  // namespace tumble
