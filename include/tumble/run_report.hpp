#pragma once
/// run.json: what ran, on what, how long each stage took, what the physics did, and every output
/// with its SHA-256. Plain facts in; the JSON layout lives in run_report.cpp.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tumble/output_folder.hpp"
#include "tumble/scene.hpp"
#include "tumble/world.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {

/// Wall time per stage, seconds. Stages a command does not run stay absent from run.json.
struct StageTimes {
  std::optional<double> framing_s;  ///< render of a framed scene: the framing pass
  std::optional<double> simulate_s, render_s, readback_s, encode_s, png_s, gif_s, webp_s;
  double total_s = 0.0;
};

/// What `render --strobe / --transparent / --gif / --webp` made, as run.json's "figures".
struct FigureFacts {
  bool transparent = false;              ///< PNG, GIF and WebP outputs carry alpha
  std::vector<double> strobe_times_s;    ///< the strobe's poses (empty: no strobe)
  std::vector<double> strobe_opacities;  ///< each pose's opacity, the last 1
  /// An animation: its frames and the rate the format could carry.
  struct Animation {
    long frames = 0;          ///< frames written (GIF: every frame_step-th of the clip)
    int frame_step = 1;       ///< clip frames per animation frame
    double rate_hz = 0.0;     ///< frames per second, on average
    std::vector<int> delays;  ///< distinct frame durations used (GIF: cs, WebP: ms)
    bool exact = false;       ///< every duration is exactly frame_step / fps
    double duration_s = 0.0;  ///< how long one loop lasts
  };
  std::optional<Animation> gif, webp;
};

struct RunReport {
  std::string command;  ///< "simulate", "render"
  const Scene* scene = nullptr;
  long steps = 0;
  long samples = 0;            ///< trajectory samples or frames
  std::optional<long> frames;  ///< render: the clip's frame count N = round(duration · fps)
  /// render: clip frames not drawn again because nothing in them moved (the previous image).
  std::optional<long> frames_reused;
  double sample_rate_hz = 0.0;
  bool every_step = false;
  std::string gl_vendor, gl_renderer, encoder;  ///< empty when nothing was rendered/encoded
  std::string antialias_used;                   ///< what the renderer did ("fxaa", "msaa 4x", …)
  StageTimes times;
  double energy_start_J = 0.0, energy_end_J = 0.0;
  ContactStats contact;
  /// This run's outputs, exactly (run.json is the manifest), by their final names; hashed
  /// when the report is written.
  std::vector<std::filesystem::path> outputs;
  /// Where the outputs are still staged (the report is written before they are committed):
  /// their digests are taken there. Null: the outputs are in place.
  const OutputFolder* staged_in = nullptr;
  const World* world = nullptr;         ///< for per-body mass properties
  const SceneModels* models = nullptr;  ///< mesh bodies: volume, axes, hull, repairs
  std::optional<FigureFacts> figures;   ///< render only
};

/// Writes run.json atomically at `path`.
void write_run_report(const std::filesystem::path& path, const RunReport& report);

}  // namespace tumble
