// tumble render: simulate, draw through EGL, and write what was asked for: clip.mp4,
// frames/frame_NNNNN.png (--png), still_<T>.png (--still T), strobe.png (--strobe N), clip.gif
// (--gif), clip.webp (--webp), all with a transparent background where they can carry one
// (--transparent), and run.json. This file checks the options and chooses the sinks; the frame
// pipeline (frame_pipeline.hpp) draws and feeds them, each sink writes its own output.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "commands.hpp"
#include "frame_pipeline.hpp"
#include "frame_sinks.hpp"
#include "framing_pass.hpp"
#include "progress.hpp"
#include "tumble/camera_framing.hpp"
#include "tumble/egl_context.hpp"
#include "tumble/output_folder.hpp"
#include "tumble/renderer.hpp"
#include "tumble/run_report.hpp"
#include "tumble/trajectory_writer.hpp"
#include "tumble/webp_writer.hpp"
#include "tumble/world_builder.hpp"

namespace tumble::cli {
namespace {

namespace fs = std::filesystem;

// More poses than this cannot be told apart in one picture; a typo is likelier.
constexpr int kMaxStrobePoses = 1000;

// The span "A:B" of --strobe-span, checked against the run.
std::pair<double, double> parse_span(const std::string& text, double duration) {
  const std::size_t colon = text.find(':');
  double a = 0.0, b = 0.0;
  const char* end = text.data() + text.size();
  bool ok = colon != std::string::npos && colon > 0 && colon + 1 < text.size();
  if (ok) {
    const auto ra = std::from_chars(text.data(), text.data() + colon, a);
    const auto rb = std::from_chars(text.data() + colon + 1, end, b);
    ok = ra.ec == std::errc() && ra.ptr == text.data() + colon && rb.ec == std::errc() &&
         rb.ptr == end && std::isfinite(a) && std::isfinite(b);
  }
  if (!ok) bad("--strobe-span must look like 0.5:2.5 (seconds from:to), not \"" + text + "\"");
  if (!(a < b)) bad("--strobe-span " + text + " must run forwards: its start below its end");
  if (a < 0.0 || b > duration)
    bad("--strobe-span " + text + " is outside the run [0, " + format_double(duration) + "]");
  return {a + 0.0, b};  // -0 starts at 0
}

}  // namespace

void add_render_command(CLI::App& app, RenderOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "render", "Simulate and render: clip.mp4, PNG frames, stills, figures and run.json");
  add_common_options(*cmd, o.common);
  add_strict_option(*cmd, o.common);
  cmd->add_flag("--png", o.png, "Also write every frame as frames/frame_NNNNN.png");
  cmd->add_flag("--no-mp4", o.no_mp4, "Do not write clip.mp4");
  // One time per --still (repeatable), so a scene path after it is not taken for a time.
  cmd->add_option("--still", o.stills, "Write still_<T>.png of the state at time T (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--crf", o.crf, "H.264 quality, 0 (lossless) to 51 (default 23)");
  cmd->add_option("--antialias", o.antialias, "fxaa (default), msaa or none (overrides the scene)");
  cmd->add_option("--msaa", o.msaa,
                  "Multisample with N samples: 0 (off), 2, 4 (overrides the scene)");
  cmd->add_option("--encoder", o.encoder,
                  "H.264 encoder: auto (hardware where present, else libx264) or a name");
  cmd->add_option("--egl-device", o.egl_device, "Render on EGL device N (see 'tumble info')");
  cmd->add_option("--strobe", o.strobe,
                  "Write strobe.png: every body at N (>= 2) evenly spaced times in one image, "
                  "earlier poses fainter");
  cmd->add_option("--strobe-span", o.strobe_span,
                  "The strobe's time span A:B in seconds (default: the whole run)");
  cmd->add_flag("--transparent", o.transparent,
                "PNG frames, stills, strobe, GIF and WebP with a transparent background (the "
                "MP4 keeps the sky)");
  cmd->add_flag("--gif", o.gif, "Also write clip.gif (looping, one palette for the clip)");
  cmd->add_flag("--webp", o.webp, "Also write clip.webp (animated WebP, looping)");
  // Hidden (no group): the reference the tests compare skipping of unchanged frames against.
  cmd->add_flag("--draw-every-frame", o.draw_every_frame,
                "Draw every clip frame in full, even where nothing moved (the same output, slower)")
      ->group("");
  // Hidden: the framing pass's budget for the worlds it keeps for drawing (tests compare a
  // render that keeps none, or some, with one that keeps them all).
  cmd->add_option("--framing-keep-bytes", o.framing_keep_bytes,
                  "Bytes of worlds the framing pass keeps for drawing (default 256 MiB)")
      ->group("");
}

int run_render(const RenderOptions& o, RenderSession* session) {
  const auto start = Clock::now();
  Scene scene = load_scene(o.common);
  if (o.msaa) {
    // On the command line, asking for samples asks for multisampling (0 or 1: none), unless
    // --antialias (below) says otherwise; in a scene file msaa is only the sample count.
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
  const bool want_clip = want_mp4 || o.png || o.gif || o.webp;  // outputs of every frame
  if (frames < 1 && want_clip)
    bad("duration " + format_double(duration) + " s at " + std::to_string(fps) +
        " fps gives no frame");
  for (double t : o.stills)
    if (!std::isfinite(t) || t < 0.0 || t > duration)
      bad("--still " + format_double(t) + " is outside the run [0, " + format_double(duration) +
          "]");
  if (o.strobe && (*o.strobe < 2 || *o.strobe > kMaxStrobePoses))
    bad("--strobe " + std::to_string(*o.strobe) + ": a strobe needs 2 to " +
        std::to_string(kMaxStrobePoses) + " poses");
  if (!o.strobe_span.empty() && !o.strobe) bad("--strobe-span needs --strobe N");
  const auto [strobe_from, strobe_to] =
      o.strobe_span.empty() ? std::pair(0.0, duration) : parse_span(o.strobe_span, duration);
  if (!want_clip && o.stills.empty() && !o.strobe)
    bad("nothing to write: --no-mp4 needs --png, --still, --strobe, --gif or --webp");
  if (o.transparent && !o.png && o.stills.empty() && !o.strobe && !o.gif && !o.webp)
    bad("--transparent applies to PNG outputs (--png, --still, --strobe), --gif and --webp; "
        "an MP4 has no alpha");
  if (want_mp4 && (width % 2 || height % 2))
    bad("H.264 (yuv420p) needs an even width and height; got " + std::to_string(width) + "x" +
        std::to_string(height) + " (use an even --size, or --no-mp4 with --png)");
  if (o.webp && (width > WebpWriter::kMaxSide || height > WebpWriter::kMaxSide))
    bad("--webp: a WebP is at most " + std::to_string(WebpWriter::kMaxSide) +
        " pixels a side; got " + std::to_string(width) + "x" + std::to_string(height));
  const SceneModels models = load_models(scene);
  WorldDef def = make_world_def(scene, models);
  def.poll = throw_if_interrupted;  // a long step stops at a signal too
  std::vector<double> stills = o.stills;
  for (double& t : stills) t += 0.0;  // -0 names the same still as 0
  std::sort(stills.begin(), stills.end());
  stills.erase(std::unique(stills.begin(), stills.end()), stills.end());
  const std::optional<Picture> strobe_times =
      o.strobe ? std::optional(strobe_picture(*o.strobe, strobe_from, strobe_to, nullptr))
               : std::nullopt;
  // No camera position in the scene: simulate once to frame the whole run; run.json then
  // records the camera used, so the view can be pinned. That pass keeps the worlds the drawing
  // needs (clip frames, exposures) within a budget, so the run is not simulated twice.
  std::optional<KeptRun> kept;
  std::optional<double> framing_s;
  if (!scene.camera.position_given) {
    std::vector<double> keep_times = stills;
    if (strobe_times)
      keep_times.insert(keep_times.end(), strobe_times->times_s.begin(),
                        strobe_times->times_s.end());
    if (want_clip)
      for (long k = 0; k < frames; ++k) keep_times.push_back(static_cast<double>(k) / fps);
    std::sort(keep_times.begin(), keep_times.end());
    keep_times.erase(std::unique(keep_times.begin(), keep_times.end()), keep_times.end());
    Progress framing_progress(!o.common.quiet, framing_samples(scene, keep_times), "framing",
                              "samples");
    FramingPass pass = framing_pass(
        scene, def, keep_times, o.framing_keep_bytes.value_or(kFramingKeepBytes), framing_progress);
    scene.camera = pass.camera;
    kept = std::move(pass.kept);
    framing_s = pass.seconds;
  }

  // Locked for this run; every output is staged and committed together, run.json last, so a
  // run that fails or is stopped leaves the folder exactly as it was.
  const std::unique_ptr<OutputFolder> outputs = open_output_folder(o.common, scene);
  const fs::path dir = outputs->dir();
  try {
    // A sweep renders all its jobs in one context; a lone render makes its own.
    std::unique_ptr<EglContext> own_gl;
    std::unique_ptr<EglContext>& gl_slot = session ? session->gl : own_gl;
    if (!gl_slot) gl_slot = std::make_unique<EglContext>(o.egl_device.value_or(-1));
    const EglContext& gl = *gl_slot;
    // A sweep's next job in the same format reuses the last one's renderer.
    const Backdrop backdrop = o.transparent ? Backdrop::Transparent : Backdrop::Sky;
    std::unique_ptr<Renderer> own_renderer;
    std::unique_ptr<Renderer>& renderer_slot = session ? session->renderer : own_renderer;
    if (!renderer_slot || !renderer_slot->reuse_for(scene, &models, backdrop)) {
      renderer_slot.reset();  // its GL objects go before the new ones are made
      renderer_slot =
          std::make_unique<Renderer>(scene, Renderer::Readback::Auto, &models, backdrop);
    }
    Renderer& renderer = *renderer_slot;
    renderer.redraw_in_full(o.draw_every_frame);  // the reference: nothing reused

    // The sinks: every clip frame to the clip sinks; each still and the strobe is a picture.
    const long clip_frames = want_clip ? frames : 0;
    FramePipeline pipeline(def, renderer, fps, clip_frames, kept ? &*kept : nullptr);
    pipeline.draw_every_frame(o.draw_every_frame);
    if (want_mp4)
      pipeline.add_clip_sink(make_mp4_sink(outputs->file("clip.mp4"),
                                           {width, height, fps, o.crf, o.encoder},
                                           scene.render.background));
    if (o.png)
      pipeline.add_clip_sink(make_png_frames_sink(outputs->folder("frames", is_frame_file_name)));
    if (o.gif)
      pipeline.add_clip_sink(
          make_gif_sink(outputs->file("clip.gif"), width, height, fps, clip_frames, o.transparent));
    if (o.webp)
      pipeline.add_clip_sink(make_webp_sink(outputs->file("clip.webp"), width, height, fps,
                                            clip_frames, o.transparent));
    for (const double t : stills)
      pipeline.add_picture(still_picture(
          t, make_png_image_sink(outputs->file("still_" + format_double(t) + ".png"))));
    FigureFacts figures;
    figures.transparent = o.transparent;
    if (o.strobe) {
      // A figure written once: the smaller PNG is worth its ~20 ms.
      Picture strobe = strobe_picture(
          *o.strobe, strobe_from, strobe_to,
          make_png_image_sink(outputs->file("strobe.png"), PngOptions::Packing::Small));
      figures.strobe_times_s = strobe.times_s;
      figures.strobe_opacities = strobe.opacities;
      pipeline.add_picture(std::move(strobe));
    }

    Progress progress(!o.common.quiet, clip_frames, "render", "frames");
    pipeline.run(progress);

    RunReport report;
    report.command = "render";
    report.scene = &scene;
    report.steps = step_count_for(duration, def.dt_s);  // the last may be taken part-way
    report.samples = clip_frames;
    report.frames = clip_frames;
    report.sample_rate_hz = fps;
    report.gl_vendor = gl.info().gl_vendor;
    report.gl_renderer =
        gl.info().gl_renderer + " (" + gl.info().gl_version + ", EGL " + gl.info().platform + ")";
    report.antialias_used =
        renderer.antialias() == Antialias::Msaa
            ? "msaa " + std::to_string(renderer.msaa_samples()) + "x"
            : std::string(kAntialiasNames[static_cast<int>(renderer.antialias())]);
    if (o.transparent || o.strobe || o.gif || o.webp) report.figures = figures;
    pipeline.report(report);
    report.times.framing_s = framing_s;
    report.energy_start_J = World(def).total_energy();
    report.energy_end_J = pipeline.sampler().at(duration).total_energy();
    report.contact = pipeline.world().contact_stats();
    report.world = &pipeline.world();
    report.models = &models;
    report.times.total_s = seconds_since(start);
    report.staged_in = outputs.get();
    write_run_report(outputs->file("run.json").staged, report);
    outputs->commit();
    if (!o.common.quiet) {
      // What was drawn: the clip's frames, stills, a strobe (a strobe alone is not "0 frames").
      std::vector<std::string> drawn;
      if (clip_frames > 0)
        drawn.push_back(std::to_string(clip_frames) + " frames (" + std::to_string(width) + "x" +
                        std::to_string(height) + ", " + std::to_string(fps) + " fps)");
      if (!stills.empty())
        drawn.push_back(std::to_string(stills.size()) +
                        (stills.size() == 1 ? " still" : " stills"));
      if (o.strobe) drawn.push_back("strobe.png (" + std::to_string(*o.strobe) + " poses)");
      std::string what;
      for (std::size_t i = 0; i < drawn.size(); ++i)
        what += (i == 0 ? "" : i + 1 == drawn.size() ? " and " : ", ") + drawn[i];
      if (clip_frames == 0) what += " at " + std::to_string(width) + "x" + std::to_string(height);
      std::printf("tumble: rendered %s on %s in %.2f s into %s\n", what.c_str(),
                  gl.info().gl_renderer.c_str(), report.times.total_s, dir.c_str());
    }
    return report_diagnostics(o.common, pipeline.world().diagnostics());
  } catch (const Error& e) {
    throw outputs->in_final_names(e);
  }
}

}  // namespace tumble::cli
