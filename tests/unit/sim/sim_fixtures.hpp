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
  b.position = position;
  return b;
}

inline BodyDef particle_def(double mass, const Vec3& position) {
  BodyDef b;
  b.name = "particle";
  b.particle = true;
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
