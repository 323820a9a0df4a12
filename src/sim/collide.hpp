#pragma once
// The narrow phase: pure functions of two shapes and two poses (Box2D's b2Collide* in spirit).
// A pair's separation is signed (negative: they overlap by that much), and its contact manifold
// is the normal and the points where they touch, each with the feature it comes from.
//
//   sphere / sphere, sphere / particle: the line of centres.
//   sphere or particle / box or hull: the closest point of the polyhedron (its deepest face when
//     the centre is inside).
//   box or hull / box or hull: the separating-axis test over both bodies' face normals and the
//     cross products of their edge directions; a face axis gives the incident face clipped
//     against the reference face's sides (the support polygon of the touching region), an edge
//     axis the closest points of the two edges.
//   the floor (the plane y = h) / any shape: the points of the shape below h + margin.
// A particle never meets another particle; the world never asks.

#include <cstdint>

#include "tumble/body.hpp"

namespace tumble {

/// Where a body is: its centre of mass and orientation.
struct Pose {
  Vec3 x = Vec3::Zero();
  Mat3 R = Mat3::Identity();
};

inline Pose pose_of(const BodyState& s) {
  return {s.x, s.R};
}

struct ManifoldPoint {
  Vec3 on_a = Vec3::Zero();  ///< the contact point on body a (world)
  Vec3 on_b = Vec3::Zero();  ///< and on body b; (on_b − on_a)·normal = separation
  double separation = 0.0;   ///< signed, m; negative = overlap
  std::uint32_t feature = 0;  ///< which features touch (stable while the contact persists)
};

/// A pair's contact: the unit normal from a towards b and up to kMaxPoints points.
struct Manifold {
  static constexpr int kMaxPoints = 8;
  Vec3 normal = Vec3::UnitY();
  /// The normal is b's (its reference face, or the polyhedron a round a touches): it turns
  /// with b. Otherwise it is a's, or (round against round) the line of centres.
  bool normal_of_b = false;
  /// An edge of a against an edge of b (one point): the normal is their cross product, and
  /// turns with both. `edge_a`, `edge_b`: their world directions.
  bool edges = false;
  Vec3 edge_a = Vec3::Zero(), edge_b = Vec3::Zero();
  int count = 0;
  ManifoldPoint points[kMaxPoints];
};

/// Signed separation of bodies a and b at these poses: positive = the gap (a lower bound of the
/// distance for two polyhedra, exact for spheres and at contact), negative = the overlap depth
/// along the best separating axis. Continuous in the poses: the gap function of impacts.
/// `axis`, where given, receives that axis (unit, from a towards b): the two bodies' projections
/// on it are `separation` apart, so while neither moves along it by the rest, they do not meet.
double separation(const RigidBody& a, const Pose& pa, const RigidBody& b, const Pose& pb,
                  Vec3* axis = nullptr);

/// The manifold of a and b: the points whose separation is at most `margin` (none when the
/// pair is farther apart).
Manifold collide(const RigidBody& a, const Pose& pa, const RigidBody& b, const Pose& pb,
                 double margin);

/// The lowest point of body b above the plane y = height (signed, as `separation`).
double plane_separation(double height, const RigidBody& b, const Pose& pb);

/// The plane y = height as body a (normal +y) against body b: the points of b at most `margin`
/// above it, a face's many reduced to the corners of their support polygon.
Manifold collide_plane(double height, const RigidBody& b, const Pose& pb, double margin);

}  // namespace tumble
