#include "tumble/world_builder.hpp"

#include <cassert>
#include <cmath>
#include <sstream>

namespace tumble {
namespace {

BodyDef make_body(const BodySpec& spec, double default_restitution) {
  BodyDef b;
  b.name = spec.name;
  b.particle = spec.shape == Shape::Particle;
  b.restitution = spec.restitution.value_or(default_restitution);
  b.position = spec.position;
  b.orientation = spec.orientation;
  b.velocity = spec.velocity;
  b.angular_velocity = spec.angular_velocity;
  if (b.particle) {
    assert(spec.mass);  // the loader rejects a density for a particle
    b.mass_kg = *spec.mass;
    b.length_m = spec.size.maxCoeff();
    return b;
  }
  assert(spec.shape == Shape::Box);  // meshes are rejected by the loader until they land
  const double volume = spec.size.prod();
  b.mass_kg = spec.mass ? *spec.mass : *spec.density * volume;
  b.inertia_body = box_inertia(b.mass_kg, spec.size);
  b.vertices = box_corners(spec.size);
  return b;
}

}  // namespace

WorldDef make_world_def(const Scene& scene) {
  const SimulationSettings& sim = scene.simulation;
  WorldDef def;
  def.dt_s = sim.dt_s;
  def.integrator = sim.integrator;
  def.rotation = sim.rotation;
  def.tolerance = sim.tolerance;
  def.gravity = sim.gravity;
  def.linear_drag = sim.linear_drag;
  def.angular_drag = sim.angular_drag;
  if (scene.floor) def.floor = FloorDef{scene.floor->height, scene.floor->friction};
  const double default_restitution = scene.floor ? scene.floor->restitution : 0.5;
  for (const BodySpec& spec : scene.bodies) {
    def.bodies.push_back(make_body(spec, default_restitution));
    if (!def.floor) continue;
    // A body must start on or above the floor: a start inside it has no physical meaning.
    const RigidBody body(def.bodies.back());
    const double touch =
        ContactTolerances::for_body(body_length(body.vertices(), def.bodies.back().length_m),
                                    def.gravity, def.dt_s)
            .touch_m;
    double lowest = INFINITY;
    for (const Vec3& v : body.vertices()) lowest = std::min(lowest, (body.state.R * v).y());
    const double depth = def.floor->height - (body.state.x.y() + lowest);
    if (depth > touch) {
      std::ostringstream msg;
      msg << "body \"" << spec.name << "\" starts " << depth
          << " m inside the floor (its lowest point is at y = " << body.state.x.y() + lowest
          << ", the floor at y = " << def.floor->height << ")";
      throw Error(ErrorKind::BadInput, msg.str(), spec.where);
    }
  }
  return def;
}

}  // namespace tumble
