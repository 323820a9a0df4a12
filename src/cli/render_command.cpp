// tumble render: simulate, draw every frame at t_k = k/fps through EGL, and write clip.mp4,
// frames/frame_NNNNN.png (--png), still_<T>.png (--still T) and run.json.
//
// Pipeline: this thread samples the world, draws and reads back; an encoder thread behind a
// bounded queue does swscale + H.264 and PNG. On a GPU the encoder is the slow stage and the
// overlap pays; on llvmpipe rendering already uses every core and the queue costs nothing.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <thread>

#include "commands.hpp"
#include "progress.hpp"
#include "tumble/bounded_queue.hpp"
#include "tumble/egl_context.hpp"
#include "tumble/mp4_writer.hpp"
#include "tumble/png.hpp"
#include "tumble/renderer.hpp"
#include "tumble/run_report.hpp"
#include "tumble/sampler.hpp"
#include "tumble/trajectory_writer.hpp"
#include "tumble/world_builder.hpp"

namespace tumble::cli {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void bad(const std::string& message) {
  throw Error(ErrorKind::BadInput, message);
}

std::string frame_name(long k) {
  return frame_stem(k) + ".png";
}

// A frame or a still, in time order.
struct Event {
  double t;
  long frame;  // -1 for a still
  std::size_t still;
};

}  // namespace

void add_render_command(CLI::App& app, RenderOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "render", "Simulate and render: clip.mp4, PNG frames, stills and run.json");
  add_common_options(*cmd, o.common);
  add_strict_option(*cmd, o.common);
  cmd->add_flag("--png", o.png, "Also write every frame as frames/frame_NNNNN.png");
  cmd->add_flag("--no-mp4", o.no_mp4, "Do not write clip.mp4");
  cmd->add_option("--still", o.stills, "Write still_<T>.png of the state at time T (repeatable)");
  cmd->add_option("--crf", o.crf, "H.264 quality, 0 (lossless) to 51 (default 23)");
  cmd->add_option("--antialias", o.antialias, "fxaa (default), msaa or none (overrides the scene)");
  cmd->add_option("--msaa", o.msaa,
                  "Multisample with N samples: 0 (off), 2, 4 (overrides the scene)");
  cmd->add_option("--encoder", o.encoder,
                  "H.264 encoder: auto (hardware where present, else libx264) or a name");
  cmd->add_option("--egl-device", o.egl_device, "Render on EGL device N (see 'tumble info')");
}

int run_render(const RenderOptions& o) {
  const auto start = Clock::now();
  Scene scene = load_scene(o.common);
  if (o.msaa) {
    // As in a scene file: asking for samples asks for multisampling (0 or 1: none).
    if (*o.msaa < 0 || *o.msaa > 16) bad("--msaa must be in [0, 16]");
    scene.render.msaa = *o.msaa;
    scene.render.antialias = *o.msaa > 1 ? Antialias::Msaa : Antialias::None;
  }
  if (!o.antialias.empty()) {
    const auto* it = std::find(kAntialiasNames.begin(), kAntialiasNames.end(), o.antialias);
    if (it == kAntialiasNames.end())
      bad("unknown --antialias \"" + o.antialias + "\" (expected one of: fxaa, msaa, none)");
    scene.render.antialias = static_cast<Antialias>(it - kAntialiasNames.begin());
  }
  if (o.crf < 0 || o.crf > 51) bad("--crf must be in [0, 51]");
  if (o.egl_device && *o.egl_device < 0) bad("--egl-device must be a device number >= 0");
  const int fps = scene.render.fps, width = scene.render.width, height = scene.render.height;
  const double duration = scene.simulation.duration_s;
  const long frames = std::lround(duration * fps);
  const bool want_mp4 = !o.no_mp4;
  if (frames < 1 && (want_mp4 || o.png))
    bad("duration " + format_double(duration) + " s at " + std::to_string(fps) +
        " fps gives no frame");
  for (double t : o.stills)
    if (!std::isfinite(t) || t < 0.0 || t > duration)
      bad("--still " + format_double(t) + " is outside the run [0, " + format_double(duration) +
          "]");
  if (!want_mp4 && !o.png && o.stills.empty())
    bad("nothing to write: --no-mp4 needs --png or --still");
  if (want_mp4 && (width % 2 || height % 2))
    bad("H.264 (yuv420p) needs an even width and height; got " + std::to_string(width) + "x" +
        std::to_string(height) + " (use an even --size, or --no-mp4 with --png)");
  const SceneModels models = load_models(scene);
  const WorldDef def = make_world_def(scene, models);

  const fs::path dir = output_dir(o.common, scene);
  if (o.png) make_output_dir(dir / "frames");
  EglContext gl(o.egl_device.value_or(-1));
  Renderer renderer(scene, Renderer::Readback::Auto, &models);
  std::optional<Mp4Writer> mp4;
  if (want_mp4) mp4.emplace(dir / "clip.mp4", Mp4Settings{width, height, fps, o.crf, o.encoder});

  // The encoder thread: H.264 and PNG frames, fed through a bounded queue of frame buffers that
  // are recycled, so memory is a few frames whatever the clip's length.
  struct Job {
    long frame;
    std::vector<std::uint8_t> rgba;
  };
  BoundedQueue<Job> queue(3);
  BoundedQueue<std::vector<std::uint8_t>> spare(4);
  double encode_s = 0.0, png_s = 0.0;  // the worker's; the main thread keeps still_s
  std::exception_ptr worker_error;
  std::thread worker([&] {
    try {
      while (auto job = queue.pop()) {
        if (mp4) {
          const auto t0 = Clock::now();
          mp4->add_frame(job->rgba.data(), 4, std::ptrdiff_t(width) * 4, /*bottom_up=*/true);
          encode_s += seconds_since(t0);
        }
        if (o.png) {
          const auto t0 = Clock::now();
          write_png(dir / "frames" / frame_name(job->frame),
                    image_from_gl_rgba(job->rgba.data(), width, height));
          png_s += seconds_since(t0);
        }
        spare.push(std::move(job->rgba));
      }
    } catch (...) {
      worker_error = std::current_exception();
      queue.close();  // the producer's next push fails and it stops
      spare.close();  // and it never waits for a buffer that will not come back
    }
  });
  // Whatever happens below, the worker is stopped and joined before anything unwinds past it.
  struct Join {
    BoundedQueue<Job>& q;
    std::thread& t;
    ~Join() {
      q.close();
      if (t.joinable()) t.join();
    }
  } join{queue, worker};

  // Frames k/fps and stills merged in time order on the fly (the sampler only goes forward);
  // nothing here grows with the clip's length. A still at a frame's time comes first.
  std::vector<double> stills = o.stills;
  for (double& t : stills) t += 0.0;  // -0 names the same still as 0
  std::sort(stills.begin(), stills.end());
  stills.erase(std::unique(stills.begin(), stills.end()), stills.end());
  const long frames_to_draw = want_mp4 || o.png ? frames : 0;
  long next_frame = 0;
  std::size_t next_still = 0;
  auto next_event = [&]() -> std::optional<Event> {
    const bool frame_left = next_frame < frames_to_draw, still_left = next_still < stills.size();
    if (!frame_left && !still_left) return std::nullopt;
    const double frame_t = frame_left ? double(next_frame) / fps : INFINITY;
    if (still_left && stills[next_still] <= frame_t)
      return Event{stills[next_still], -1, next_still++};
    return Event{frame_t, next_frame++, 0};
  };

  World world(def);
  Sampler sampler(world);
  double simulate_s = 0.0, render_s = 0.0, readback_s = 0.0, still_s = 0.0;
  std::vector<fs::path> still_paths;
  Progress progress(!o.common.quiet, frames_to_draw, "render", "frames");
  long frames_done = 0;
  // Frame k is read back while frame k+1 is drawn (asynchronous on GPUs): it is collected, in
  // order, after the next frame's readback has begun, or at the end.
  std::optional<long> pending;
  auto collect_pending = [&]() -> bool {
    const auto t0 = Clock::now();
    // A recycled buffer: after the first few frames, no allocation.
    std::vector<std::uint8_t> buffer;
    if (frames_done >= 4) buffer = spare.pop().value_or(std::vector<std::uint8_t>{});
    renderer.finish_readback(buffer);
    readback_s += seconds_since(t0);
    const bool pushed = queue.push(Job{*pending, std::move(buffer)});  // false: the worker failed
    pending.reset();
    progress.update(++frames_done);
    return pushed;
  };
  while (const std::optional<Event> next = next_event()) {
    const Event& e = *next;
    throw_if_interrupted();
    auto t0 = Clock::now();
    const World snapshot = sampler.at(e.t);
    simulate_s += seconds_since(t0);
    t0 = Clock::now();
    renderer.draw(snapshot);
    render_s += seconds_since(t0);
    if (e.frame < 0) {
      t0 = Clock::now();
      const fs::path path = dir / ("still_" + format_double(stills[e.still]) + ".png");
      write_png(path, renderer.read_image());
      still_s += seconds_since(t0);
      still_paths.push_back(path);
      continue;
    }
    t0 = Clock::now();
    renderer.begin_readback();
    readback_s += seconds_since(t0);
    if (pending && !collect_pending()) break;
    pending = e.frame;
  }
  if (pending) collect_pending();
  queue.close();
  worker.join();
  if (worker_error) std::rethrow_exception(worker_error);
  if (mp4) {
    const auto t0 = Clock::now();
    mp4->finish();
    encode_s += seconds_since(t0);
  }

  RunReport report;
  report.command = "render";
  report.scene = &scene;
  report.steps = step_count_for(duration, def.dt_s);  // the last may be taken part-way
  report.samples = frames_to_draw;
  report.sample_rate_hz = fps;
  report.gl_vendor = gl.info().gl_vendor;
  report.gl_renderer =
      gl.info().gl_renderer + " (" + gl.info().gl_version + ", EGL " + gl.info().platform + ")";
  report.encoder = mp4 ? mp4->encoder_name() : "";
  report.antialias_used =
      renderer.antialias() == Antialias::Msaa
          ? "msaa " + std::to_string(renderer.msaa_samples()) + "x"
          : std::string(kAntialiasNames[static_cast<int>(renderer.antialias())]);
  report.times.simulate_s = simulate_s;
  report.times.render_s = render_s;
  report.times.readback_s = readback_s;
  if (mp4) report.times.encode_s = encode_s;
  if (o.png || !still_paths.empty()) report.times.png_s = png_s + still_s;
  report.energy_start_J = World(def).total_energy();
  report.energy_end_J = sampler.at(duration).total_energy();
  report.contact = world.contact_stats();
  if (mp4) report.outputs.push_back(dir / "clip.mp4");
  if (o.png)
    for (long k = 0; k < frames_to_draw; ++k)
      report.outputs.push_back(dir / "frames" / frame_name(k));
  report.outputs.insert(report.outputs.end(), still_paths.begin(), still_paths.end());
  report.world = &world;
  report.models = &models;
  report.times.total_s = seconds_since(start);
  write_run_report(dir / "run.json", report);
  if (!o.common.quiet) {
    const std::string stills_text =
        still_paths.empty() ? "" : " and " + std::to_string(still_paths.size()) + " still(s)";
    std::printf("tumble: rendered %ld frames (%dx%d, %d fps)%s on %s in %.2f s into %s\n",
                frames_to_draw, width, height, fps, stills_text.c_str(),
                gl.info().gl_renderer.c_str(), report.times.total_s, dir.c_str());
  }
  return report_diagnostics(o.common, world.diagnostics());
}

}  // namespace tumble::cli
