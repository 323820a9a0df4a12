#include "run_record.hpp"

#include <algorithm>
#include <cmath>

#include "tumble/camera.hpp"
#include "tumble/sampler.hpp"
#include "tumble/study.hpp"
#include "tumble/world_builder.hpp"

namespace tumble::study {
namespace {

// Standard gravity: the energy scale of a body when the scene has no gravity (as the World's own
// free-flight check does).
constexpr double kStandardGravity = 9.81;

}  // namespace

std::vector<double> sample_times(double duration_s, int fps) {
  const long frames = std::lround(duration_s * fps);
  std::vector<double> times;
  times.reserve(static_cast<std::size_t>(frames) + 1);
  for (long k = 0; k < frames; ++k) times.push_back(static_cast<double>(k) / fps);
  // round(duration·fps) frames end at most half a frame before the end, so the end is later.
  if (times.empty() || times.back() < duration_s) times.push_back(duration_s);
  return times;
}

StudySetup::StudySetup(const Scene& s) : scene(&s), def(make_world_def(s)) {
  times = sample_times(s.simulation.duration_s, s.render.fps);
  const World world(def);
  const double g = def.gravity.norm() > 0.0 ? def.gravity.norm() : kStandardGravity;
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    bodies.push_back(world.bodies()[i]);
    tolerances.push_back(world.tolerances(i));
    energy_scale_J.push_back(bodies.back().mass() * g * tolerances.back().length_m);
  }
}

WorldDef StudySetup::def_for(Integrator integrator, double dt_s,
                             std::optional<double> tolerance) const {
  WorldDef d = def;
  d.integrator = integrator;
  d.dt_s = dt_s;
  // adaptive: dt_s is its largest step, and the scene's dt its first trial step.
  d.first_step_s =
      integrator == Integrator::Adaptive ? std::min(scene->simulation.dt_s, dt_s) : 0.0;
  if (tolerance) d.tolerance = *tolerance;
  return d;
}

BodySample sample_body(const StudySetup& setup, std::size_t body, const BodyState& s,
                       const Eigen::Matrix4d& view_projection) {
  RigidBody b = setup.bodies[body];
  b.state = s;
  BodySample out;
  out.q = s.q;
  out.energy_J = b.energy(setup.def.gravity);
  out.kinetic_J = b.energy(Vec3::Zero());
  const int width = setup.scene->render.width, height = setup.scene->render.height;
  for (const Vec3& v : b.vertices()) {
    const Vec3 p = s.x + s.R * v;
    out.points.push_back(p);
    out.pixels.push_back(to_pixels(view_projection, p, width, height));
    if (setup.def.floor && p.y() - setup.def.floor->height <= setup.tolerances[body].touch_m)
      out.touching = true;
  }
  return out;
}

RunRecord record_world(const StudySetup& setup, const WorldDef& def,
                       const std::function<bool()>& stop) {
  World world(def);
  Sampler sampler(world);
  RunRecord record;
  record.times = setup.times;
  record.samples.reserve(setup.times.size());
  World snapshot = world;
  for (const double t : setup.times) {
    if (stop && stop()) throw Cancelled{};
    snapshot = sampler.at(t);
    const Eigen::Matrix4d vp = camera_view_projection(*setup.scene, snapshot);
    std::vector<BodySample>& row = record.samples.emplace_back();
    for (std::size_t i = 0; i < snapshot.bodies().size(); ++i)
      row.push_back(sample_body(setup, i, snapshot.bodies()[i].state, vp));
  }
  // The last sample (the end of the run) holds every impact and diagnostic, those of a final
  // part-step included; the cost is the main world's: the steps a clip of this run takes.
  record.events = snapshot.contact_stats().events;
  for (const Diagnostic& d : snapshot.diagnostics().list()) record.diagnostics.push_back(d.code);
  for (std::size_t i = 0; i < world.bodies().size(); ++i)
    record.rest_speed_mps.push_back(world.tolerances(i).rest_speed_mps);
  record.evaluations = world.derivative_evaluations();
  if (def.integrator == Integrator::Adaptive) {
    record.steps = world.step_stats().accepted;
    record.rejected_steps = world.step_stats().rejected;
  } else {
    record.steps = world.step_count();
  }
  return record;
}

}  // namespace tumble::study
