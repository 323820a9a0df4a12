#include "tumble/world_builder.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <sstream>

namespace tumble {
namespace {

// A mesh body: mass from density × volume (or as given), principal moments scaled from unit
// density, the hull's vertices as contact points in the principal frame through the centre of
// mass, and the principal axes and centre of mass kept to report and draw the model's own frame.
void make_mesh_body(const BodySpec& spec, const MeshBody& model, BodyDef& b) {
  const MassProperties& mp = model.mass;
  b.mass_kg = spec.mass ? *spec.mass : *spec.density * mp.volume;
  const double density = b.mass_kg / mp.volume;
  b.inertia_body = density * mp.principal_moments;
  const Mat3& axes = mp.principal_axes;  // columns: principal axes in the model frame
  b.principal_axes = Quat(axes).normalized();
  b.com_offset = mp.center_of_mass;
  b.vertices.reserve(model.hull_vertices.size());
  for (const Vec3& v : model.hull_vertices)
    b.vertices.push_back(axes.transpose() * (v - mp.center_of_mass));
  // The hull's faces for meeting other bodies (coplanar triangles merged). Its vertices are
  // the hull's own, in the same (x, y, z) order as hull_vertices.
  const ConvexHull hull = convex_hull(model.hull_vertices);
  std::vector<std::array<int, 3>> triangles;
  for (const auto& t : hull.mesh.triangles)
    triangles.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  b.faces = faces_from_triangles(b.vertices, triangles);
  // The model's size sets the scale of its contact tolerances: its largest extent.
  Vec3 lo = model.mesh.vertices.front(), hi = lo;
  for (const Vec3& v : model.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  b.length_m = (hi - lo).maxCoeff();
}

BodyDef make_body(const BodySpec& spec, double default_restitution, const MeshBody* model) {
  BodyDef b;
  b.name = spec.name;
  b.particle = spec.shape == Shape::Particle;
  b.shape = spec.shape == Shape::Particle ? ShapeKind::Particle
            : spec.shape == Shape::Sphere ? ShapeKind::Sphere
            : spec.shape == Shape::Box    ? ShapeKind::Box
                                          : ShapeKind::Hull;
  b.fixed = spec.fixed;
  b.friction = spec.friction;
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
  if (spec.shape == Shape::Mesh) {
    assert(model);
    make_mesh_body(spec, *model, b);
    return b;
  }
  if (spec.shape == Shape::Sphere) {
    const double volume = 4.0 / 3.0 * kPi * std::pow(spec.radius_m, 3);
    b.mass_kg = spec.mass ? *spec.mass : *spec.density * volume;
    b.radius_m = spec.radius_m;
    b.inertia_body = sphere_inertia(b.mass_kg, spec.radius_m);
    b.vertices = {Vec3::Zero()};
    b.length_m = 2.0 * spec.radius_m;
    return b;
  }
  assert(spec.shape == Shape::Box);
  const double volume = spec.size.prod();
  b.mass_kg = spec.mass ? *spec.mass : *spec.density * volume;
  b.inertia_body = box_inertia(b.mass_kg, spec.size);
  b.vertices = box_corners(spec.size);
  b.faces = box_faces();
  return b;
}

}  // namespace

SceneModels load_models(const Scene& scene) {
  SceneModels models;
  models.bodies.resize(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& spec = scene.bodies[i];
    if (spec.shape != Shape::Mesh) continue;
    MeshLoadOptions options;
    options.scale = spec.scale;
    options.repair = spec.repair;
    try {
      models.bodies[i] = std::make_shared<const MeshBody>(load_mesh_body(spec.mesh, options));
    } catch (const Error& e) {
      // FILE:LINE:COLUMN of the scene's `mesh` key (SPEC's error form), then what is wrong in
      // the model file, with its own path (and line, where the format has one).
      throw Error(e.kind(), "the mesh of body \"" + spec.name + "\": " + e.describe(),
                  spec.mesh_where);
    }
  }
  return models;
}

WorldDef make_world_def(const Scene& scene) {
  return make_world_def(scene, load_models(scene));
}

double adaptive_max_step_s(const SimulationSettings& sim, double sample_interval_s) {
  return sim.max_step_s.value_or(sample_interval_s);
}

WorldDef make_world_def(const Scene& scene, const SceneModels& models,
                        std::optional<double> sample_interval_s) {
  const SimulationSettings& sim = scene.simulation;
  WorldDef def;
  def.dt_s = sim.dt_s;
  if (sim.integrator == Integrator::Adaptive) {
    // The controller chooses the step: from dt as its first trial up to the largest step (the
    // World's step), never beyond; a first trial above the largest is the largest.
    def.dt_s = adaptive_max_step_s(sim, sample_interval_s.value_or(1.0 / scene.render.fps));
    def.first_step_s = std::min(sim.dt_s, def.dt_s);
  }
  def.integrator = sim.integrator;
  def.rotation = sim.rotation;
  def.tolerance = sim.tolerance;
  def.gravity = sim.gravity;
  def.linear_drag = sim.linear_drag;
  def.angular_drag = sim.angular_drag;
  if (scene.floor) def.floor = FloorDef{scene.floor->height, scene.floor->friction};
  def.collisions = sim.collisions;
  for (const PairSpec& p : scene.pairs)
    def.pairs.push_back({p.a, p.b, p.restitution, p.friction, p.collide});
  const double default_restitution = scene.floor ? scene.floor->restitution : 0.5;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& spec = scene.bodies[i];
    def.bodies.push_back(make_body(spec, default_restitution, models.model(i)));
    // A fixed body may sit in the floor: it never meets it.
    if (!def.floor || spec.fixed) continue;
    // A body must start on or above the floor: a start inside it has no physical meaning.
    const RigidBody body(def.bodies.back());
    const double touch =
        ContactTolerances::for_body(length_scale(def.bodies.back()), def.gravity, def.dt_s).touch_m;
    double lowest = INFINITY;
    for (int v = 0; v < static_cast<int>(body.vertices().size()); ++v)
      lowest = std::min(lowest, body.vertex_offset(body.state.R, v).y());
    const double depth = def.floor->height - (body.state.x.y() + lowest);
    if (depth > touch) {
      std::ostringstream msg;
      msg << "body \"" << spec.name << "\" starts " << depth
          << " m inside the floor (its lowest point is at y = " << body.state.x.y() + lowest
          << ", the floor at y = " << def.floor->height << ")";
      throw Error(ErrorKind::BadInput, msg.str(), spec.where);
    }
  }
  // Two bodies that start inside each other have no physical meaning either.
  for (const StartOverlap& o : overlaps_at_start(def)) {
    std::ostringstream msg;
    msg << "bodies \"" << scene.bodies[o.a].name << "\" and \"" << scene.bodies[o.b].name
        << "\" overlap by " << o.depth_m << " m at t = 0";
    throw Error(ErrorKind::BadInput, msg.str(), scene.bodies[o.b].where);
  }
  return def;
}

}  // namespace tumble
