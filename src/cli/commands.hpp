#pragma once
// The subcommands, each a thin client of the library. Options shared by every command that runs
// a scene live in CommonOptions; apply_overrides() checks them as strictly as the scene loader.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tumble/diagnostics.hpp"
#include "tumble/error.hpp"
#include "tumble/scene.hpp"

namespace tumble {
class EglContext;
class OutputFolder;
class Renderer;
}  // namespace tumble

namespace tumble::cli {

/// A run stopped by SIGINT, SIGTERM, SIGHUP or SIGQUIT; main() exits with 128 + the signal, like
/// a shell.
struct Interrupted {
  int signal;
};
void install_interrupt_handlers();
bool interrupted();
/// Throws Interrupted once a signal arrived; the loops call it once per frame or sample.
void throw_if_interrupted();

/// A user's mistake on the command line: tumble::Error (BadInput, exit 2).
[[noreturn]] inline void bad(const std::string& message) {
  throw Error(ErrorKind::BadInput, message);
}

/// More steps than this is a typo (dt in ms?), not a run anyone waits for (--dt, study's --dts).
inline constexpr double kMaxSteps = 1e9;

struct CommonOptions {
  std::string scene_path;  // empty: the built-in default scene
  std::string out_dir;     // empty: out/<scene-stem>/
  std::optional<double> duration_s, dt_s;
  std::optional<int> fps;
  std::string size;  // "WxH"
  std::string integrator;
  bool quiet = false;
  bool strict = false;  // render/simulate: a diagnostic warning ends the run with exit 4
};

/// Refuses an empty option value (`--out ""`, `--integrators ''`): empty would otherwise read
/// as the option left out. Exit 2 through CLI11's parse errors.
CLI::Validator non_empty();
/// Registers the common options on a subcommand.
void add_common_options(CLI::App& cmd, CommonOptions& o);
/// Loads the scene (or the default) and applies the command-line overrides; throws
/// tumble::Error (BadInput) for a bad value.
Scene load_scene(const CommonOptions& o);
/// Applies the command-line overrides to a scene parsed with TimeOverrides{o.duration_s,
/// o.dt_s} (what load_scene does after loading); throws tumble::Error (BadInput).
void apply_overrides(Scene& scene, const CommonOptions& o);
/// The output folder, created. Throws tumble::Error (Environment) when it cannot be.
std::filesystem::path output_dir(const CommonOptions& o, const Scene& scene);
/// The output folder of a run that writes its outputs as one set (render, simulate): created,
/// locked against a second run and staged (tumble/output_folder.hpp). Throws tumble::Error
/// (Environment).
std::unique_ptr<OutputFolder> open_output_folder(const CommonOptions& o, const Scene& scene);
/// Registers --strict (render and simulate).
void add_strict_option(CLI::App& cmd, CommonOptions& o);
/// Prints each diagnostic once as `tumble: warning: message (fix)` unless quiet; returns the
/// command's exit code: 4 when --strict and there was a warning, else 0.
int report_diagnostics(const CommonOptions& o, const Diagnostics& diagnostics);

struct SimulateOptions {
  CommonOptions common;
  std::optional<double> rate_hz;
  bool every_step = false;
  bool plot = false;  // also trajectory.svg: height and energy over time, impacts marked
};
void add_simulate_command(CLI::App& app, SimulateOptions& o);
int run_simulate(const SimulateOptions& o);

struct RenderOptions {
  CommonOptions common;
  bool png = false;
  bool no_mp4 = false;
  std::vector<double> stills;
  int crf = 23;
  std::optional<int> msaa;
  std::string antialias;  // empty: the scene's
  std::string encoder = "auto";
  std::optional<int> egl_device;
  // Documentation figures.
  std::optional<int> strobe;      // strobe.png with N poses
  std::string strobe_span;        // "A:B"; empty: the whole run
  bool transparent = false;       // PNG, GIF and WebP outputs with a transparent background
  bool gif = false;               // clip.gif
  bool webp = false;              // clip.webp
  bool draw_every_frame = false;  // hidden: no reuse of unchanged frames (tests compare)
  // hidden: the framing pass's budget for kept worlds (tests: 0 keeps none, as before)
  std::optional<std::size_t> framing_keep_bytes;
};
void add_render_command(CLI::App& app, RenderOptions& o);
/// What the renders of one process share (tumble sweep): the EGL context the first one makes,
/// current for every later one, so a job does not pay for a context (and the process loads the
/// GL driver once), and the last Renderer, reused (shaders, framebuffers) by a job drawn in the
/// same format (Renderer::reuse_for). The renderer goes before the context it was made in.
struct RenderSession {
  std::unique_ptr<EglContext> gl;
  std::unique_ptr<Renderer> renderer;
};
/// `session`: null for a lone render (its own context), else shared with the other renders.
int run_render(const RenderOptions& o, RenderSession* session = nullptr);

struct SweepOptions {
  std::string plan_path;
  std::string out_dir;   // empty: out/<plan-stem>/
  bool list = false;     // print the jobs as CSV, run nothing
  bool collect = false;  // write sweep.csv, exit 1 naming missing or failed jobs
  std::string shard;     // "I/N"; empty: from the scheduler's environment, else every job
  std::optional<std::size_t> shards;  // a Kubernetes Indexed Job's completions
  bool quiet = false;
};
void add_sweep_command(CLI::App& app, SweepOptions& o);
/// Throws tumble::Error (BadInput) for a plan error, before any job runs; returns the worst
/// job's exit code, or (--collect) 1 when a job is missing or failed.
int run_sweep(const SweepOptions& o);

void add_info_command(CLI::App& app);
int run_info();

struct DiffOptions {
  std::string expected, actual;  // two PNGs, two folders of PNGs or two videos
  int max_delta = 0;
  double max_fraction = 0.0;
  std::optional<double> min_psnr_db;
  std::string diff_out;  // empty: no diff images
  std::string report;    // --report DIR; empty: none
  std::string junit;     // --junit FILE; empty: none
};
void add_diff_command(CLI::App& app, DiffOptions& o);
/// 0 within tolerance, 1 beyond it; throws tumble::Error (BadInput) for a missing or undecodable
/// input or a bad option, (Environment) when a diff image cannot be written.
int run_diff(const DiffOptions& o);

struct StudyOptions {
  CommonOptions common;     // --integrator is refused: a study runs every integrator it lists
  std::string integrators;  // comma-separated; empty: all five
  std::string dts;          // comma-separated seconds; empty: the scene's dt × 4, 2, 1, 1/2, 1/4
  std::string tolerances;   // comma-separated; empty: 1e-4, 1e-6, 1e-8, 1e-10
  std::optional<double> target_error_m;
  std::optional<int> jobs;  // empty: the hardware's threads
};
void add_study_command(CLI::App& app, StudyOptions& o);
/// Throws tumble::Error (BadInput) for a bad option or a reference run that fails.
int run_study(const StudyOptions& o);

}  // namespace tumble::cli
