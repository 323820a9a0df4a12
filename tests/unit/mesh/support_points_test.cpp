// Support-point reduction: a flat face's contact candidates become the corners of its support
// polygon, most extreme first, at most max_points of them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mesh_fixtures.hpp"

namespace tumble {
namespace {

// Points in (x, y, z) order, to compare sets.
std::vector<Vec3> sorted(std::vector<Vec3> v) {
  std::sort(v.begin(), v.end(), [](const Vec3& a, const Vec3& b) {
    return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
  });
  return v;
}

std::vector<Vec3> pick(const std::vector<Vec3>& points, const std::vector<int>& indices) {
  std::vector<Vec3> out;
  for (int i : indices) out.push_back(points[static_cast<std::size_t>(i)]);
  return out;
}

TEST(SupportPoints, GridFaceReducesToItsFourCorners) {
  // A 5 x 5 grid on the floor minus its centre: 24 points, the support polygon a square.
  std::vector<Vec3> face;
  for (int i = 0; i < 5; ++i)
    for (int k = 0; k < 5; ++k)
      if (i != 2 || k != 2) face.emplace_back(0.25 * i - 0.5, 0.0, 0.25 * k - 0.5);
  ASSERT_EQ(face.size(), 24u);
  const std::vector<int> chosen = reduce_support_points(face, Vec3::UnitY(), 8);
  ASSERT_EQ(chosen.size(), 4u);
  EXPECT_EQ(sorted(pick(face, chosen)),
            sorted({{-0.5, 0, -0.5}, {0.5, 0, -0.5}, {-0.5, 0, 0.5}, {0.5, 0, 0.5}}));
}

TEST(SupportPoints, OctagonWithEdgePointsKeepsItsEightCorners) {
  // 8 corners and two points on every edge: 24 points; the 2-D hull is the octagon.
  std::vector<Vec3> corners, face;
  for (int k = 0; k < 8; ++k) {
    const double a = 2.0 * kPi * k / 8.0 + 0.1;
    corners.emplace_back(std::cos(a), 0.3, std::sin(a));
  }
  for (int k = 0; k < 8; ++k) {
    const Vec3& p = corners[static_cast<std::size_t>(k)];
    const Vec3& q = corners[static_cast<std::size_t>((k + 1) % 8)];
    face.push_back(p);
    face.push_back(p + (q - p) / 3.0);
    face.push_back(p + 2.0 * (q - p) / 3.0);
  }
  ASSERT_EQ(face.size(), 24u);
  const std::vector<int> chosen = reduce_support_points(face, Vec3(0, -2, 0), 8);
  EXPECT_EQ(chosen.size(), 8u);
  EXPECT_EQ(sorted(pick(face, chosen)), sorted(corners));
}

TEST(SupportPoints, MostExtremeFirstWhenCornersExceedTheLimit) {
  // A 24-gon: every point is a corner. With 4 allowed, the first two are (nearly) opposite,
  // and the four span most of the polygon.
  std::vector<Vec3> circle;
  for (int k = 0; k < 24; ++k) {
    const double a = 2.0 * kPi * k / 24.0;
    circle.emplace_back(std::cos(a), std::sin(a), 2.0);
  }
  const std::vector<int> chosen = reduce_support_points(circle, Vec3::UnitZ(), 4);
  ASSERT_EQ(chosen.size(), 4u);
  const std::vector<Vec3> p = pick(circle, chosen);
  EXPECT_NEAR((p[0] - p[1]).norm(), 2.0, 1e-12);  // a diameter
  // The other two on either side of it, a quarter turn away: the inscribed square.
  EXPECT_NEAR((p[2] - p[3]).norm(), 2.0, 1e-12);
  EXPECT_NEAR(std::abs((p[0] - p[1]).dot(p[2] - p[3])), 0.0, 1e-12);
}

TEST(SupportPoints, DeterministicAndTiesToTheLowerIndex) {
  // Duplicates of every corner: the lower index is the one kept.
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1},
                                    {0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  const std::vector<int> a = reduce_support_points(points, Vec3::UnitY(), 8);
  EXPECT_EQ(a, reduce_support_points(points, Vec3::UnitY(), 8));
  ASSERT_EQ(a.size(), 4u);
  for (int i : a) EXPECT_LT(i, 4);
}

TEST(SupportPoints, FewPointsAndLimits) {
  const std::vector<Vec3> two = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(reduce_support_points(two, Vec3::UnitY(), 8).size(), 2u);
  const std::vector<Vec3> line = {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}};
  const std::vector<int> ends = reduce_support_points(line, Vec3::UnitY(), 8);
  EXPECT_EQ(sorted(pick(line, ends)), sorted({{0, 0, 0}, {1, 0, 0}}));
  EXPECT_TRUE(reduce_support_points(line, Vec3::UnitY(), 0).empty());
  EXPECT_TRUE(reduce_support_points({}, Vec3::UnitY(), 4).empty());
  EXPECT_EQ(reduce_support_points(line, Vec3::UnitY(), 1).size(), 1u);
}

TEST(SupportPoints, DieFaceOnTheFloor) {
  // The die's bottom face has 4 hull vertices in the plane y = -1/2, plus the bevel ring
  // slightly above: the caller passes the ones within its contact tolerance.
  const MeshBody die = test::load(test::kAssets / "die.obj");
  std::vector<Vec3> bottom;
  for (const Vec3& v : die.hull_vertices)
    if (v.y() < -0.5 + 1e-9) bottom.push_back(v);
  ASSERT_EQ(bottom.size(), 4u);
  EXPECT_EQ(reduce_support_points(bottom, Vec3::UnitY(), 8).size(), 4u);
}

}  // namespace
}  // namespace tumble
