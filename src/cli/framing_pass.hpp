#pragma once
// The framing pass of `tumble render`: a scene without a camera position is simulated once to
// place the camera (camera_framing.hpp). The pass samples the run at every frame time anyway, so
// it keeps what the drawing pass will need (the world at each clip frame and each picture's
// exposure times) while the copies fit in a byte budget; the drawing pass then takes those and
// simulates only past them, from the world as the framing pass left it. The budget bounds memory
// by an estimate of each kept world's bytes; past it the pass keeps nothing more, and the rest
// is simulated again as before. Same worlds, same bits: the output does not depend on the budget.

#include <cstddef>
#include <optional>
#include <vector>

#include "progress.hpp"
#include "tumble/scene.hpp"
#include "tumble/world.hpp"

namespace tumble::cli {

/// Bytes of kept worlds the framing pass may hold: 256 MiB, about 110 000 samples of one box
/// (2.3 kB each: a half-hour clip at 60 fps), or about 75 frames of 2 000 boxes.
inline constexpr std::size_t kFramingKeepBytes = std::size_t{256} << 20;

/// Worlds sampled by the framing pass for the drawing pass, in time order.
struct KeptRun {
  std::vector<double> times_s;               ///< increasing
  std::vector<std::optional<World>> worlds;  ///< the world at each time (reset once handed out)
  /// The stepping world as the pass left it after the last kept time: the drawing pass goes on
  /// from here (every later time is simulated from it, bit for bit as from the start).
  std::optional<World> resume;
  /// Whether every time asked for was kept (then nothing is simulated again).
  bool complete = false;
  std::size_t bytes = 0;  ///< the estimate of what is kept

  /// The world at `t` when it was kept (a copy; earlier worlds are freed, so calls come in
  /// non-decreasing t), else nullopt: t lies past the kept times.
  std::optional<World> take(double t);

 private:
  std::size_t next_ = 0;
};

struct FramingPass {
  CameraSettings camera;  ///< as frame_camera() would place it
  KeptRun kept;           ///< empty when the run stopped being finite (the drawing pass meets it)
  double seconds = 0.0;   ///< wall time of the pass
};

/// An estimate of the bytes a copy of `world` holds (the object, its bodies with their hulls,
/// contact records and diagnostics).
std::size_t world_bytes(const World& world);

/// Simulates `def` once, sampling every frame time k / fps and the end: frames the camera on
/// them exactly as frame_camera() does, and keeps the world at each of `keep_times_s` (sorted;
/// frame times, exposure times, the end) while the kept copies fit in `budget_bytes` (0: keeps
/// nothing and hands on no resume world: the drawing pass simulates afresh).
/// `progress` counts the samples.
FramingPass framing_pass(const Scene& scene, const WorldDef& def,
                         const std::vector<double>& keep_times_s, std::size_t budget_bytes,
                         Progress& progress);

/// The number of samples framing_pass() takes for `scene` with `keep_times_s`.
long framing_samples(const Scene& scene, const std::vector<double>& keep_times_s);

}  // namespace tumble::cli
