// Convex hulls through Qhull: exact corner sets for simple solids, interior and coplanar points
// dropped, flat input refused with a clear message, the result independent of input order.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "mesh_fixtures.hpp"

namespace tumble {
namespace {

TEST(ConvexHull, CubeHasEightVerticesAndSixFaces) {
  const TriangleMesh cube = test::box_mesh(Vec3::Ones());
  const ConvexHull hull = convex_hull(cube.vertices);
  EXPECT_EQ(hull.mesh.vertices.size(), 8u);
  EXPECT_EQ(hull.faces, 6u);
  EXPECT_EQ(hull.mesh.triangles.size(), 12u);
  EXPECT_NEAR(mass_properties(hull.mesh).volume, 1.0, 1e-12);  // closed and outward
  // Sorted by (x, y, z).
  EXPECT_TRUE(std::is_sorted(hull.mesh.vertices.begin(), hull.mesh.vertices.end(),
                             [](const Vec3& a, const Vec3& b) {
                               return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
                             }));
}

TEST(ConvexHull, GridPointsOnFacesAndInsideAreNotVertices) {
  // A 5 x 5 x 5 grid of a cube: 125 points, 8 corners.
  std::vector<Vec3> points;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k) points.emplace_back(0.25 * i, 0.25 * j, 0.25 * k);
  const ConvexHull hull = convex_hull(points);
  EXPECT_EQ(hull.mesh.vertices.size(), 8u);
  EXPECT_EQ(hull.faces, 6u);
}

TEST(ConvexHull, SameHullWhateverTheInputOrder) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::vector<Vec3> points;
  for (int i = 0; i < 500; ++i) points.emplace_back(normal(rng), normal(rng), normal(rng));
  const std::vector<Vec3> a = convex_hull_vertices(points);
  std::shuffle(points.begin(), points.end(), rng);
  const std::vector<Vec3> b = convex_hull_vertices(points);
  EXPECT_EQ(a, b);
  // Every point lies inside the hull (within round-off of its planes).
  const ConvexHull hull = convex_hull(points);
  for (const auto& t : hull.mesh.triangles) {
    const Vec3& p0 = hull.mesh.vertices[t[0]];
    const Vec3 n = (hull.mesh.vertices[t[1]] - p0).cross(hull.mesh.vertices[t[2]] - p0);
    for (const Vec3& p : points) EXPECT_LE(n.dot(p - p0), 1e-12 * n.norm() * 10.0);
  }
}

TEST(ConvexHull, FlatInputIsRefusedClearly) {
  const std::vector<Vec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  try {
    convex_hull(square);
    FAIL() << "a flat hull was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_CONTAINS(std::string(e.what()), "flat: the points lie in one plane or on one line");
  }
  EXPECT_THROW(convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), Error);  // three points
}

TEST(ConvexHull, ThinSlabIsNotFlat) {
  // 1 mm over 1 km: aspect 1e-6, still a solid to Qhull.
  const TriangleMesh slab = test::box_mesh(Vec3(1000.0, 0.001, 1000.0));
  const ConvexHull hull = convex_hull(slab.vertices);
  EXPECT_EQ(hull.mesh.vertices.size(), 8u);
  EXPECT_NEAR(mass_properties(hull.mesh).volume, 1000.0, 1e-6);
}

}  // namespace
}  // namespace tumble
