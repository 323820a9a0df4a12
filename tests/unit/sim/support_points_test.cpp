// Bodies with many contact vertices (a mesh hull): a flat face or an edge on the floor puts many
// of them there at once; they are reduced to the corners of their support polygon, so such a
// body moves exactly like the box with only its 8 corners.
#include <gtest/gtest.h>

#include <cmath>

#include "../../../src/sim/floor_contact.hpp"
#include "sim_fixtures.hpp"
#include "tumble/world.hpp"

namespace tumble {
namespace {

// A unit box's surface sampled on an n×n grid per face (corners, edge and face points): what a
// finely tessellated cube's hull vertices would be.
std::vector<Vec3> gridded_cube(int n) {
  std::vector<Vec3> v;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const bool surface = i == 0 || j == 0 || k == 0 || i == n - 1 || j == n - 1 || k == n - 1;
        if (surface)
          v.emplace_back(-0.5 + i / double(n - 1), -0.5 + j / double(n - 1),
                         -0.5 + k / double(n - 1));
      }
  return v;
}

WorldDef tilted_spinning_drop(const std::vector<Vec3>& vertices) {
  WorldDef def = test::world_def(Integrator::Rk4, 0.001, true);
  BodyDef b = test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 3, 0));
  b.vertices = vertices;
  b.orientation = Quat(Eigen::AngleAxisd(radians(30.0), Vec3(1, 0, 1).normalized()));
  b.angular_velocity = Vec3(0, 0, 2);
  def.bodies.push_back(b);
  return def;
}

TEST(SupportPoints, GriddedCubeMovesLikeTheEightCornerBox) {
  // 5×5 points per face (98 vertices): flight, corner and edge impacts, rocking on edges (5
  // collinear points) and faces (25 coplanar points), rest. The reduced contact sets are the
  // same corners, in another order, so the paths agree to round-off amplified by the chaotic
  // rocking phase: measured 4.6e-9 m over 4 s; tolerance 1e-8 m.
  World box(tilted_spinning_drop(box_corners(Vec3(1, 1, 1))));
  World grid(tilted_spinning_drop(gridded_cube(5)));
  double worst = 0.0;
  for (int i = 0; i < 4000; ++i) {
    box.step();
    grid.step();
    worst = std::max(worst, (box.bodies()[0].state.x - grid.bodies()[0].state.x).norm());
  }
  EXPECT_LT(worst, 1e-8);
  EXPECT_TRUE(grid.bodies()[0].at_rest);
  EXPECT_NEAR(grid.bodies()[0].state.x.y(), 0.5, 1.1e-6);
}

TEST(SupportPoints, FlatFaceReducesToItsCorners) {
  // A 7×7 grid face flat on the floor: 49 touching points, reduced to the 4 corners.
  BodyDef def = test::box_def(Vec3(1, 1, 1), 1.0, Vec3(0, 0.5, 0));
  def.vertices = gridded_cube(7);
  const RigidBody body(def);
  const ContactSet c = touching_vertices(body, 0.0, 1e-6, INFINITY);
  ASSERT_EQ(c.count, 4);
  for (int i : c.indices()) {
    const Vec3& v = body.vertices()[i];
    EXPECT_EQ(std::abs(v.x()), 0.5);
    EXPECT_EQ(std::abs(v.z()), 0.5);
    EXPECT_EQ(v.y(), -0.5);
  }
}

TEST(SupportPoints, RoundFaceKeepsAtMostEightExtremePoints) {
  // A 32-gon flat on the floor (a cylinder's hull): more corners than the LCP takes; the 8 kept
  // are the extremes in 8 directions, so the support polygon is the inscribed octagon.
  BodyDef def = test::box_def(Vec3(2, 1, 2), 1.0, Vec3(0, 0.5, 0));
  def.vertices.clear();
  for (int k = 0; k < 32; ++k) {
    const double a = 2.0 * kPi * k / 32.0;
    def.vertices.emplace_back(std::cos(a), -0.5, std::sin(a));
    def.vertices.emplace_back(std::cos(a), 0.5, std::sin(a));
  }
  const RigidBody body(def);
  const ContactSet c = touching_vertices(body, 0.0, 1e-6, INFINITY);
  EXPECT_EQ(c.count, 8);
  for (int i : c.indices()) {
    const double a = std::atan2(body.vertices()[i].z(), body.vertices()[i].x());
    const double eighths = a / (kPi / 4.0);
    EXPECT_NEAR(eighths, std::round(eighths), 1e-12) << "not an extreme point: angle " << a;
  }
  EXPECT_TRUE(can_rest(body, c, Vec3(0, -9.81, 0), 1e-3));
}

}  // namespace
}  // namespace tumble
