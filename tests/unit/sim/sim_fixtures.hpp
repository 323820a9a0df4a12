#pragma once
// Small builders for worlds used by the simulation tests.

#include <cmath>

#include "tumble/body.hpp"
#include "tumble/world.hpp"

namespace tumble::test {

inline BodyDef box_def(const Vec3& size, double mass, const Vec3& position) {
  BodyDef b;
  b.name = "box";
  b.mass_kg = mass;
  b.inertia_body = box_inertia(mass, size);
  b.vertices = box_corners(size);
  b.faces = box_faces();
  b.position = position;
  return b;
}

inline BodyDef sphere_def(double radius, double mass, const Vec3& position) {
  BodyDef b;
  b.name = "ball";
  b.shape = ShapeKind::Sphere;
  b.radius_m = radius;
  b.mass_kg = mass;
  b.inertia_body = sphere_inertia(mass, radius);
  b.vertices = {Vec3::Zero()};
  b.length_m = 2.0 * radius;
  b.position = position;
  return b;
}

/// A box that does not move (a wall, a ramp, a table).
inline BodyDef fixed_box_def(const Vec3& size, const Vec3& position,
                             const Quat& orientation = Quat::Identity()) {
  BodyDef b;
  b.name = "wall";
  b.fixed = true;
  b.mass_kg = 1.0;
  b.inertia_body = box_inertia(1.0, size);
  b.vertices = box_corners(size);
  b.faces = box_faces();
  b.position = position;
  b.orientation = orientation;
  return b;
}

inline BodyDef particle_def(double mass, const Vec3& position) {
  BodyDef b;
  b.name = "particle";
  b.particle = true;
  b.shape = ShapeKind::Particle;
  b.mass_kg = mass;
  b.position = position;
  return b;
}

inline WorldDef world_def(Integrator integrator, double dt, bool floor, double restitution = 0.5) {
  WorldDef w;
  w.dt_s = dt;
  w.integrator = integrator;
  if (floor) w.floor = FloorDef{};
  (void)restitution;
  return w;
}

/// Rotation angle between two orientations, radians.
inline double angle_between(const Quat& a, const Quat& b) {
  return 2.0 * std::asin(std::min(1.0, (a.conjugate() * b).vec().norm()));
}

}  // namespace tumble::test
