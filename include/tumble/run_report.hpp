#pragma once
/// run.json: what ran, on what, how long each stage took, what the physics did, and every output
/// with its SHA-256. Plain facts in; the JSON layout lives in run_report.cpp.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tumble/scene.hpp"
#include "tumble/world.hpp"
#include "tumble/world_builder.hpp"

namespace tumble {

/// Wall time per stage, seconds. Stages a command does not run stay absent from run.json.
struct StageTimes {
  std::optional<double> simulate_s, render_s, readback_s, encode_s, png_s;
  double total_s = 0.0;
};

struct RunReport {
  std::string command;  ///< "simulate", "render"
  const Scene* scene = nullptr;
  long steps = 0;
  long samples = 0;  ///< trajectory samples or frames
  double sample_rate_hz = 0.0;
  bool every_step = false;
  std::string gl_vendor, gl_renderer, encoder;  ///< empty when nothing was rendered/encoded
  std::string antialias_used;                   ///< what the renderer did ("fxaa", "msaa 4x", …)
  StageTimes times;
  double energy_start_J = 0.0, energy_end_J = 0.0;
  ContactStats contact;
  std::vector<std::filesystem::path> outputs;  ///< hashed when the report is written
  const World* world = nullptr;                ///< for per-body mass properties
  const SceneModels* models = nullptr;         ///< mesh bodies: volume, axes, hull, repairs
};

/// Writes run.json atomically at `path`.
void write_run_report(const std::filesystem::path& path, const RunReport& report);

}  // namespace tumble
