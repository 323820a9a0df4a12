#include "framing_pass.hpp"

#include <algorithm>
#include <cmath>

#include "tumble/camera.hpp"
#include "tumble/camera_framing.hpp"
#include "tumble/error.hpp"
#include "tumble/sampler.hpp"

namespace tumble::cli {
namespace {

// Every time the pass samples: the frame times k / fps, the times to keep, and the end.
std::vector<double> sample_times(const Scene& scene, const std::vector<double>& keep_times_s) {
  const int fps = scene.render.fps;
  const double duration = scene.simulation.duration_s;
  const long frames = std::lround(duration * fps);
  std::vector<double> times = keep_times_s;
  for (long k = 0; k < frames; ++k) times.push_back(static_cast<double>(k) / fps);
  times.push_back(duration);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

}  // namespace

std::optional<World> KeptRun::take(double t) {
  while (next_ < times_s.size() && times_s[next_] < t) worlds[next_++].reset();
  if (next_ < times_s.size() && times_s[next_] == t && worlds[next_]) return *worlds[next_];
  return std::nullopt;
}

std::size_t world_bytes(const World& world) {
  std::size_t bytes = sizeof(World);
  for (const RigidBody& b : world.bodies()) {
    // The body and the world's per-body records (tolerances, controller, flight state, ...);
    // its shape (corners, faces) is shared with the world it was copied from.
    bytes += sizeof(RigidBody) + sizeof(ContactTolerances) + 2 * sizeof(BodyState) + 128;
    bytes += b.name().capacity();
  }
  const ContactStats& stats = world.contact_stats();
  bytes += stats.events.capacity() * sizeof(ImpactEvent) +
           stats.pairs.capacity() * sizeof(PairContactStats);
  for (const Diagnostic& d : world.diagnostics().list())
    bytes +=
        sizeof(Diagnostic) + d.code.size() + d.message.size() + d.fix.size() + d.severity.size();
  return bytes;
}

long framing_samples(const Scene& scene, const std::vector<double>& keep_times_s) {
  return static_cast<long>(sample_times(scene, keep_times_s).size());
}

FramingPass framing_pass(const Scene& scene, const WorldDef& def,
                         const std::vector<double>& keep_times_s, std::size_t budget_bytes,
                         Progress& progress) {
  const auto start = Clock::now();
  FramingPass out;
  const std::vector<double> times = sample_times(scene, keep_times_s);
  const int fps = scene.render.fps;
  const double duration = scene.simulation.duration_s;
  const long frames = std::lround(duration * fps);
  KeptRun& kept = out.kept;
  World world(def);
  Sampler sampler(world);
  std::vector<Vec3> points;
  // A budget of 0 keeps nothing and hands on nothing: the drawing pass simulates afresh, as a
  // render did before the pass kept anything (the reference the tests compare with).
  bool keeping = budget_bytes > 0;
  // The next kept world's size, guessed from the last one (the first: the world at the start):
  // a world that would not fit is not sampled for keeping, so the stepping world can still be
  // handed on from just before it.
  std::size_t next_bytes = world_bytes(world);
  long next_frame = 0;
  try {
    for (std::size_t i = 0; i < times.size(); ++i) {
      const double t = times[i];
      const bool keep = std::binary_search(keep_times_s.begin(), keep_times_s.end(), t);
      if (keeping && keep && kept.bytes + next_bytes > budget_bytes) {
        keeping = false;
        kept.resume = world;
      }
      World snapshot = sampler.at(t);
      // The points frame_camera() takes: each frame's, then the end's.
      const bool frame = next_frame < frames && t == static_cast<double>(next_frame) / fps;
      if (frame) ++next_frame;
      if (frame || t == duration) body_points(scene, snapshot, points);
      if (keeping && keep) {
        next_bytes = world_bytes(snapshot);
        kept.bytes += next_bytes;
        kept.times_s.push_back(t);
        kept.worlds.push_back(std::move(snapshot));
      }
      progress.update(static_cast<long>(i) + 1);
    }
    if (keeping) {
      kept.resume = world;
      kept.complete = true;
    }
  } catch (const Error&) {
    // The run stops being finite: framed on what came before (t = 0 at least), as
    // frame_camera() does; the drawing pass simulates afresh and meets the same error.
    if (points.empty()) throw;
    kept = KeptRun{};
  }
  const double aspect = double(scene.render.width) / scene.render.height;
  const CameraSettings& stated = scene.camera;
  // A followed body is framed alone and the camera moves with it (frame_camera() decides that
  // from t = 0 without the run); the kept worlds serve the drawing all the same.
  out.camera = followed_body(scene) ? frame_camera(scene, def)
                                    : fit_camera(stated, points, aspect, !stated.target_given,
                                                 !stated.ortho_height_given);
  out.seconds = seconds_since(start);
  return out;
}

}  // namespace tumble::cli
