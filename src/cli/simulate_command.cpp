// tumble simulate: the trajectory, sampled at k/rate (or every step), and run.json. No GL.
#include <cmath>
#include <cstdio>

#include "commands.hpp"
#include "progress.hpp"
#include "trajectory_plot.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/output_folder.hpp"
#include "tumble/run_report.hpp"
#include "tumble/sampler.hpp"
#include "tumble/trajectory_writer.hpp"
#include "tumble/world_builder.hpp"

namespace tumble::cli {
namespace {

// The run itself, its outputs staged in `outputs` and committed at the end (run.json last).
int simulate_into(const SimulateOptions& o, const Scene& scene, const SceneModels& models,
                  const WorldDef& def, OutputFolder& outputs, Clock::time_point start) {
  const double rate = o.rate_hz.value_or(scene.render.fps);
  const double duration = scene.simulation.duration_s, dt = def.dt_s;
  const long steps = step_count_for(duration, dt);
  const long samples = o.every_step ? steps + 1 : sample_count(duration, rate);
  const StagedOutput csv_out = outputs.file("trajectory.csv");
  const std::optional<StagedOutput> svg_out =
      o.plot ? std::optional(outputs.file("trajectory.svg")) : std::nullopt;

  World world(def);
  Sampler sampler(world);
  TrajectoryWriter csv(csv_out.staged);
  Progress progress(!o.common.quiet, samples, "simulate", "samples");
  TrajectoryPlot plot(scene.stem, duration, samples);
  double energy_start = 0.0, energy_end = 0.0;
  for (long k = 0; k < samples; ++k) {
    // Every step boundary n·dt, or k/rate; the last sample is the end of the run exactly, so
    // the final state is always in the trajectory even when duration·rate is not whole.
    const double t = k == samples - 1 ? duration
                     : o.every_step   ? static_cast<double>(k) * dt
                                      : static_cast<double>(k) / rate;
    throw_if_interrupted();
    const World snapshot = sampler.at(t);
    csv.write(t, snapshot);
    if (o.plot) plot.add(k, t, snapshot);
    if (k == 0) energy_start = snapshot.total_energy();
    if (k == samples - 1) energy_end = snapshot.total_energy();
    progress.update(k + 1);
  }
  csv.commit();
  const double simulate_s = seconds_since(start);
  if (svg_out) write_file_atomically(svg_out->staged, plot.svg(world.contact_stats().events));

  RunReport report;
  report.command = "simulate";
  report.scene = &scene;
  report.steps = steps;  // the last may have been taken part-way, on a copy
  report.samples = samples;
  report.sample_rate_hz = o.every_step ? 1.0 / dt : rate;
  report.every_step = o.every_step;
  report.times.simulate_s = simulate_s;
  report.times.total_s = seconds_since(start);
  report.energy_start_J = energy_start;
  report.energy_end_J = energy_end;
  report.contact = world.contact_stats();
  report.outputs = {csv_out.final};
  if (svg_out) report.outputs.push_back(svg_out->final);
  report.world = &world;
  report.models = &models;
  report.staged_in = &outputs;
  write_run_report(outputs.file("run.json").staged, report);
  outputs.commit();
  if (!o.common.quiet)
    std::printf("tumble: wrote %s (%ld rows)%s and %s\n", csv_out.final.c_str(), csv.rows(),
                svg_out ? (", " + svg_out->final.string()).c_str() : "",
                (outputs.dir() / "run.json").c_str());
  return report_diagnostics(o.common, world.diagnostics());
}

}  // namespace

void add_simulate_command(CLI::App& app, SimulateOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Simulate only (no GL): trajectory.csv and run.json in the output folder");
  add_common_options(*cmd, o.common);
  add_strict_option(*cmd, o.common);
  CLI::Option* rate =
      cmd->add_option("--rate", o.rate_hz, "Sample rate in Hz (default: the scene's fps)");
  // Either a rate or every step: both would leave one of them silently unused.
  cmd->add_flag("--every-step", o.every_step, "Sample at every step boundary instead")
      ->excludes(rate);
  cmd->add_flag("--plot", o.plot,
                "Also write trajectory.svg: height and energy of each body over time, impacts "
                "marked");
}

int run_simulate(const SimulateOptions& o) {
  const auto start = Clock::now();
  const Scene scene = load_scene(o.common);
  const double rate = o.rate_hz.value_or(scene.render.fps);
  if (!std::isfinite(rate) || rate <= 0.0 || rate > 1e6)
    throw Error(ErrorKind::BadInput, "--rate must be a positive number of Hz, at most 1e6");
  const SceneModels models = load_models(scene);
  // adaptive: its largest step defaults to the sample interval, so sampling never re-steps.
  WorldDef def = make_world_def(scene, models, 1.0 / rate);
  def.poll = throw_if_interrupted;  // a long step stops at a signal too
  const double duration = scene.simulation.duration_s, dt = def.dt_s;
  const long steps = step_count_for(duration, dt);
  const long samples = o.every_step ? steps + 1 : sample_count(duration, rate);
  if (samples > 100'000'000)
    throw Error(ErrorKind::BadInput, "that run would write " + std::to_string(samples) +
                                         " samples; lower --rate or drop --every-step");
  // Locked for this run; every output is staged and committed together, run.json last.
  const std::unique_ptr<OutputFolder> outputs = open_output_folder(o.common, scene);
  try {
    return simulate_into(o, scene, models, def, *outputs, start);
  } catch (const Error& e) {
    throw outputs->in_final_names(e);
  }
}

}  // namespace tumble::cli
