#pragma once
// A run as the study sees it: every body's points (world and screen), orientation and energy at
// the sample times, its impacts, and its cost. Made from a World stepped and sampled as `render`
// would (record_world) or from exact states (the analytic reference), so both are measured alike.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tumble/scene.hpp"
#include "tumble/world.hpp"

namespace tumble::study {

/// The study's sample times: the frame times k/fps, k = 0 … N-1 with N = round(duration·fps),
/// then the end of the run (as `render` takes frames, plus the final state).
std::vector<double> sample_times(double duration_s, int fps);

/// One body at one sample time.
struct BodySample {
  std::vector<Vec3> points;  ///< contact vertices (particle: centre), world
  std::vector<std::optional<Eigen::Vector2d>>
      pixels;  ///< the same on screen; none behind the camera
  Quat q = Quat::Identity();
  double energy_J = 0.0;   ///< kinetic + gravitational
  double kinetic_J = 0.0;  ///< kinetic alone
  bool touching = false;   ///< a vertex within the body's touch tolerance of the floor
};

struct RunRecord {
  std::vector<double> times;
  std::vector<std::vector<BodySample>> samples;  ///< [sample][body]
  std::vector<ImpactEvent> events;               ///< every impact, in time order
  std::vector<double> rest_speed_mps;            ///< per body: slower impacts are not bounces
  long steps = 0, rejected_steps = 0, evaluations = 0;
  std::vector<std::string> diagnostics;  ///< World diagnostic codes, in order of first occurrence
};

/// What every run of one study shares: the scene, its WorldDef (integrator, dt and tolerance are
/// replaced per run), the sample times and each body's fixed properties.
struct StudySetup {
  const Scene* scene = nullptr;
  WorldDef def;
  std::vector<double> times;
  std::vector<RigidBody> bodies;              ///< initial states; geometry and mass
  std::vector<ContactTolerances> tolerances;  ///< at the scene's dt (touch and lengths)
  std::vector<double> energy_scale_J;         ///< per body m·g·ℓ: see energy_drift()

  explicit StudySetup(const Scene& scene);
  /// The scene's WorldDef with this setting's integrator, dt and tolerance.
  WorldDef def_for(Integrator integrator, double dt_s, std::optional<double> tolerance) const;
};

/// One body's sample from its state `s` seen through `view_projection`.
BodySample sample_body(const StudySetup& setup, std::size_t body, const BodyState& s,
                       const Eigen::Matrix4d& view_projection);

/// Runs a World of `def` over the study's times and records it. A non-finite state throws
/// tumble::Error (as the World does); `stop` (may be empty) is polled once per sample and makes
/// it throw Cancelled.
RunRecord record_world(const StudySetup& setup, const WorldDef& def,
                       const std::function<bool()>& stop);

}  // namespace tumble::study
