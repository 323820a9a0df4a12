// The narrow phase: separations and manifolds of every pair of shapes, against geometry done
// by hand. Tolerances are round-off (1e-12 m on 1 m shapes) unless stated.
#include <gtest/gtest.h>

#include <cmath>

#include "../../../src/sim/collide.hpp"
#include "sim_fixtures.hpp"

namespace tumble {
namespace {

RigidBody sphere(double r, const Vec3& x) {
  BodyDef d = test::sphere_def(r, 1.0, x);
  return RigidBody(d);
}
RigidBody box(const Vec3& size, const Vec3& x, const Quat& q = Quat::Identity()) {
  BodyDef d = test::box_def(size, 1.0, x);
  d.orientation = q;
  return RigidBody(d);
}

TEST(NarrowPhase, SpheresAlongTheLineOfCentres) {
  const RigidBody a = sphere(0.5, Vec3(0, 0, 0)), b = sphere(0.25, Vec3(1, 0, 0));
  EXPECT_NEAR(separation(a, pose_of(a.state), b, pose_of(b.state)), 0.25, 1e-15);
  const Manifold m = collide(a, pose_of(a.state), b, pose_of(b.state), 0.3);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR((m.normal - Vec3::UnitX()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((m.points[0].on_a - Vec3(0.5, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((m.points[0].on_b - Vec3(0.75, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_EQ(collide(a, pose_of(a.state), b, pose_of(b.state), 0.2).count, 0);  // beyond margin
}

TEST(NarrowPhase, SphereAgainstABoxFaceEdgeAndInside) {
  const RigidBody b = box(Vec3(2, 2, 2), Vec3::Zero());
  // Above the top face: the gap is the height above it.
  const RigidBody over = sphere(0.5, Vec3(0.3, 1.7, -0.2));
  EXPECT_NEAR(separation(over, pose_of(over.state), b, pose_of(b.state)), 0.2, 1e-15);
  const Manifold m = collide(over, pose_of(over.state), b, pose_of(b.state), 1.0);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR((m.normal + Vec3::UnitY()).norm(), 0.0, 1e-15);  // from the sphere to the box
  EXPECT_TRUE(m.normal_of_b);
  // Beyond an edge: the distance to the edge line, minus the radius.
  const RigidBody edge = sphere(0.1, Vec3(1.3, 1.4, 0.0));
  EXPECT_NEAR(separation(edge, pose_of(edge.state), b, pose_of(b.state)), 0.5 - 0.1, 1e-15);
  // Centre inside: the depth is to the nearest face, plus the radius.
  const RigidBody inside = sphere(0.1, Vec3(0.0, 0.9, 0.0));
  EXPECT_NEAR(separation(inside, pose_of(inside.state), b, pose_of(b.state)), -0.2, 1e-15);
}

TEST(NarrowPhase, BoxOnABoxFaceToFaceGivesItsFourCorners) {
  const RigidBody lower = box(Vec3(2, 1, 2), Vec3::Zero());
  const RigidBody upper = box(Vec3(1, 1, 1), Vec3(0.2, 1.0 + 1e-9, 0.1));
  EXPECT_NEAR(separation(lower, pose_of(lower.state), upper, pose_of(upper.state)), 1e-9, 1e-15);
  const Manifold m = collide(lower, pose_of(lower.state), upper, pose_of(upper.state), 1e-6);
  ASSERT_EQ(m.count, 4);
  EXPECT_NEAR((m.normal - Vec3::UnitY()).norm(), 0.0, 1e-15);
  for (int i = 0; i < m.count; ++i) {
    EXPECT_NEAR(m.points[i].separation, 1e-9, 1e-15);
    EXPECT_NEAR(m.points[i].on_b.y(), 0.5 + 1e-9, 1e-15);
    EXPECT_NEAR(std::abs(m.points[i].on_b.x() - 0.2), 0.5, 1e-15);
    EXPECT_NEAR(std::abs(m.points[i].on_b.z() - 0.1), 0.5, 1e-15);
  }
}

TEST(NarrowPhase, BoxTurnedOnAnEqualBoxGivesTheOctagon) {
  // Two unit squares, one turned 45° about the normal: they overlap in a regular octagon.
  const RigidBody lower = box(Vec3::Ones(), Vec3::Zero());
  const Quat turn(Eigen::AngleAxisd(kPi / 4, Vec3::UnitY()));
  const RigidBody upper = box(Vec3::Ones(), Vec3(0, 1.0, 0), turn);
  const Manifold m = collide(lower, pose_of(lower.state), upper, pose_of(upper.state), 1e-6);
  ASSERT_EQ(m.count, 8);
  const double apothem = 0.5;  // the octagon's corners lie on the unit square's and the turned one's edges
  for (int i = 0; i < m.count; ++i) {
    const Vec3& p = m.points[i].on_b;
    EXPECT_NEAR(std::max(std::abs(p.x()), std::abs(p.z())), apothem, 1e-12);
    EXPECT_NEAR(std::abs(m.points[i].separation), 0.0, 1e-12);
  }
}

TEST(NarrowPhase, CrossedEdgesMeetAtOnePoint) {
  // A box balanced on an edge across another box's top edge, turned 90°: an edge–edge contact.
  const Quat on_edge(Eigen::AngleAxisd(kPi / 4, Vec3::UnitZ()));
  const Quat b_edge = Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY())) * on_edge;
  const RigidBody a = box(Vec3::Ones(), Vec3::Zero(), on_edge);
  const double h = std::sqrt(0.5);  // half a diagonal
  const RigidBody b = box(Vec3::Ones(), Vec3(0, 2 * h + 0.01, 0), b_edge);
  EXPECT_NEAR(separation(a, pose_of(a.state), b, pose_of(b.state)), 0.01, 1e-12);
  const Manifold m = collide(a, pose_of(a.state), b, pose_of(b.state), 0.1);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR((m.normal - Vec3::UnitY()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((m.points[0].on_a - Vec3(0, h, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((m.points[0].on_b - Vec3(0, h + 0.01, 0)).norm(), 0.0, 1e-12);
}

TEST(NarrowPhase, PlaneHoldsABoxCornersAndASphere) {
  const RigidBody b = box(Vec3::Ones(), Vec3(0, 0.5, 0));
  EXPECT_NEAR(plane_separation(0.0, b, pose_of(b.state)), 0.0, 1e-15);
  EXPECT_EQ(collide_plane(0.0, b, pose_of(b.state), 1e-6).count, 4);
  const RigidBody s = sphere(0.3, Vec3(1, 0.4, 2));
  EXPECT_NEAR(plane_separation(0.0, s, pose_of(s.state)), 0.1, 1e-15);
  const Manifold m = collide_plane(0.0, s, pose_of(s.state), 0.2);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR((m.points[0].on_b - Vec3(1, 0.1, 2)).norm(), 0.0, 1e-15);
}

TEST(NarrowPhase, SeparationIsSymmetric) {
  const RigidBody a = box(Vec3(1, 0.5, 2), Vec3(0.1, 0.2, 0.3),
                          Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())));
  const RigidBody b = box(Vec3(0.4, 1.5, 0.8), Vec3(0.9, 0.8, 0.5),
                          Quat(Eigen::AngleAxisd(-1.1, Vec3(3, 1, -2).normalized())));
  EXPECT_NEAR(separation(a, pose_of(a.state), b, pose_of(b.state)),
              separation(b, pose_of(b.state), a, pose_of(a.state)), 1e-12);
}

}  // namespace
}  // namespace tumble
