#include <charconv>
#include <cmath>
#include <cstdio>

#include "commands.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/output_folder.hpp"
#include "tumble/trajectory_writer.hpp"

namespace tumble::cli {

CLI::Validator non_empty() {
  return CLI::Validator(
      [](const std::string& value) {
        return value.empty() ? std::string("an empty value; give one or leave the option out")
                             : std::string();
      },
      "", "NON_EMPTY");
}

void add_common_options(CLI::App& cmd, CommonOptions& o) {
  cmd.add_option("scene", o.scene_path, "Scene file (TOML); omitted: the built-in default scene");
  cmd.add_option("--out", o.out_dir, "Output folder (default: out/<scene-stem>/)")
      ->check(non_empty());
  cmd.add_option("--duration", o.duration_s, "Simulated seconds (overrides the scene)");
  cmd.add_option("--dt", o.dt_s, "Fixed physics step in seconds (overrides the scene)");
  cmd.add_option("--fps", o.fps, "Frames per second (overrides the scene)");
  cmd.add_option("--size", o.size, "Image size WxH, e.g. 1280x720 (overrides the scene)")
      ->check(non_empty());
  cmd.add_option("--integrator", o.integrator,
                 "euler | symplectic-euler | midpoint | rk4 | adaptive (overrides the scene)")
      ->check(non_empty());
  cmd.add_flag("--quiet,-q", o.quiet, "Print nothing but errors");
}

Scene load_scene(const CommonOptions& o) {
  Scene scene = o.scene_path.empty() ? default_scene()
                                     : load_scene_file(o.scene_path, {o.duration_s, o.dt_s});
  apply_overrides(scene, o);
  return scene;
}

void apply_overrides(Scene& scene, const CommonOptions& o) {
  SimulationSettings& sim = scene.simulation;
  if (o.duration_s) {
    if (!std::isfinite(*o.duration_s) || *o.duration_s <= 0.0 || *o.duration_s > 1e6)
      bad("--duration must be a number of seconds in (0, 1e6]");
    sim.duration_s = *o.duration_s;
  }
  if (o.dt_s) {
    if (!std::isfinite(*o.dt_s) || *o.dt_s <= 0.0) bad("--dt must be a positive number of seconds");
    sim.dt_s = *o.dt_s;
  }
  if (sim.dt_s > sim.duration_s)
    bad("the step dt = " + format_double(sim.dt_s) + " s is longer than the run (" +
        format_double(sim.duration_s) + " s)");
  if (sim.duration_s / sim.dt_s > kMaxSteps)
    bad("duration / dt asks for more than 1e9 steps; is dt in seconds?");
  if (!o.integrator.empty()) {
    const auto integrator = parse_integrator(o.integrator);
    if (!integrator)
      bad("unknown integrator \"" + o.integrator +
          "\" (expected one of: euler, symplectic-euler, midpoint, rk4, adaptive)");
    sim.integrator = *integrator;
  }
  if (o.fps) {
    if (*o.fps < 1 || *o.fps > 1000) bad("--fps must be an integer in [1, 1000]");
    scene.render.fps = *o.fps;
  }
  if (!o.size.empty()) {
    // "WxH": two decimal integers around one 'x'.
    long w = 0, h = 0;
    const std::string& z = o.size;
    const std::size_t x = z.find('x');
    const auto [end_w, err_w] = std::from_chars(z.data(), z.data() + (x == z.npos ? 0 : x), w);
    const auto [end_h, err_h] = x == z.npos
                                    ? std::from_chars_result{nullptr, std::errc::invalid_argument}
                                    : std::from_chars(z.data() + x + 1, z.data() + z.size(), h);
    if (x == z.npos || x == 0 || err_w != std::errc() || end_w != z.data() + x ||
        err_h != std::errc() || end_h != z.data() + z.size())
      bad("--size must look like 1280x720, not \"" + z + "\"");
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
      bad("--size " + o.size + " is out of range: width and height must be in [1, 16384]");
    scene.render.width = static_cast<int>(w);
    scene.render.height = static_cast<int>(h);
  }
}

void add_strict_option(CLI::App& cmd, CommonOptions& o) {
  cmd.add_flag("--strict", o.strict,
               "A diagnostic warning ends the run with exit 4 (outputs are still written)");
}

int report_diagnostics(const CommonOptions& o, const Diagnostics& diagnostics) {
  if (!o.quiet)
    for (const Diagnostic& d : diagnostics.list())
      std::fprintf(stderr, "tumble: warning: %s (%s)\n", d.message.c_str(), d.fix.c_str());
  return o.strict && !diagnostics.empty() ? 4 : 0;
}

namespace {

std::filesystem::path output_path(const CommonOptions& o, const Scene& scene) {
  return o.out_dir.empty() ? std::filesystem::path("out") / scene.stem
                           : std::filesystem::path(o.out_dir);
}

}  // namespace

std::filesystem::path output_dir(const CommonOptions& o, const Scene& scene) {
  const std::filesystem::path dir = output_path(o, scene);
  make_output_dir(dir);
  return dir;
}

std::unique_ptr<OutputFolder> open_output_folder(const CommonOptions& o, const Scene& scene) {
  return std::make_unique<OutputFolder>(output_path(o, scene));
}

}  // namespace tumble::cli
