// tumble study: every integrator × step (and adaptive × tolerance) measured against a reference;
// study.csv, study.md and study.svg. The option lists are checked here, where their names are
// known; the study itself is the library's (src/study).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <thread>

#include "commands.hpp"
#include "progress.hpp"
#include "tumble/camera_framing.hpp"
#include "tumble/study.hpp"
#include "tumble/trajectory_writer.hpp"
#include "tumble/world_builder.hpp"

namespace tumble::cli {
namespace {

constexpr int kMaxJobs = 1024;

// The comma-separated items of `list`, spaces around them dropped; an empty item is an error.
std::vector<std::string> split(const std::string& list, const char* option) {
  std::vector<std::string> items;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t end = std::min(list.find(',', begin), list.size());
    std::string item = list.substr(begin, end - begin);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (item.empty())
      bad(std::string(option) + " has an empty item in \"" + list +
          "\"; give a comma-separated list");
    items.push_back(item);
    if (end == list.size()) return items;
    begin = end + 1;
  }
}

double parse_number(const std::string& text, const char* option) {
  double value = 0.0;
  const auto [end, err] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (err != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    bad(std::string(option) + ": \"" + text + "\" is not a number");
  return value;
}

std::vector<Integrator> parse_integrators(const std::string& list) {
  if (list.empty())
    return {Integrator::Euler, Integrator::SymplecticEuler, Integrator::Midpoint, Integrator::Rk4,
            Integrator::Adaptive};
  std::vector<Integrator> out;
  for (const std::string& name : split(list, "--integrators")) {
    const std::optional<Integrator> i = parse_integrator(name);
    if (!i)
      bad("--integrators: unknown integrator \"" + name +
          "\" (expected a comma-separated list of: euler, symplectic-euler, midpoint, rk4, "
          "adaptive)");
    if (std::find(out.begin(), out.end(), *i) != out.end())
      bad("--integrators lists \"" + name + "\" twice");
    out.push_back(*i);
  }
  return out;
}

// The values of a list option; `what` checks one and returns an error message, empty when fine.
template <class Check>
std::vector<double> parse_values(const std::string& list, const char* option, Check check) {
  std::vector<double> out;
  for (const std::string& item : split(list, option)) {
    const double v = parse_number(item, option);
    if (const std::string problem = check(v); !problem.empty())
      bad(std::string(option) + ": " + item + " " + problem);
    if (std::find(out.begin(), out.end(), v) != out.end())
      bad(std::string(option) + " lists " + item + " twice");
    out.push_back(v);
  }
  return out;
}

study::StudyPlan make_plan(const StudyOptions& o, const Scene& scene) {
  study::StudyPlan plan;
  plan.integrators = parse_integrators(o.integrators);
  const bool adaptive = std::find(plan.integrators.begin(), plan.integrators.end(),
                                  Integrator::Adaptive) != plan.integrators.end();
  const bool fixed = plan.integrators.size() > (adaptive ? 1u : 0u);
  const double duration = scene.simulation.duration_s;
  auto step_problem = [&](double dt) -> std::string {
    if (dt <= 0.0) return "is not a positive step in seconds";
    if (dt > duration)
      return "is longer than the run (" + format_double(duration) + " s; see --duration)";
    if (duration / dt > kMaxSteps) return "asks for more than 1e9 steps; is it in seconds?";
    return "";
  };
  if (!o.dts.empty()) {
    if (!fixed) bad("--dts applies to the fixed-step integrators, and --integrators lists none");
    plan.dts_s = parse_values(o.dts, "--dts", step_problem);
  } else if (fixed) {
    plan.dts_s = study::default_dts(scene.simulation.dt_s);
    for (const double dt : plan.dts_s)
      if (const std::string problem = step_problem(dt); !problem.empty())
        bad("the default steps are the scene's dt × 4, 2, 1, 1/2, 1/4, and " + format_double(dt) +
            " s " + problem + "; give --dts");
  }
  if (!o.tolerances.empty()) {
    if (!adaptive) bad("--tolerances applies to adaptive, and --integrators leaves it out");
    plan.tolerances = parse_values(o.tolerances, "--tolerances", [](double t) -> std::string {
      if (!(t >= study::kMinTolerance && t <= study::kMaxTolerance))
        return "is outside [1e-14, 0.1] (a local error tolerance)";
      return "";
    });
  } else if (adaptive) {
    plan.tolerances.assign(study::kDefaultTolerances.begin(), study::kDefaultTolerances.end());
  }
  if (o.target_error_m) {
    if (!std::isfinite(*o.target_error_m) || *o.target_error_m <= 0.0)
      bad("--target-error must be a positive distance in metres");
    plan.target_error_m = o.target_error_m;
  }
  if (o.jobs) {
    if (*o.jobs < 1 || *o.jobs > kMaxJobs)
      bad("--jobs must be an integer in [1, " + std::to_string(kMaxJobs) + "]");
    plan.jobs = *o.jobs;
  } else {
    plan.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }
  return plan;
}

}  // namespace

void add_study_command(CLI::App& app, StudyOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "study",
      "Speed vs accuracy: every integrator x step against a reference; study.csv, study.md and "
      "study.svg in the output folder");
  add_common_options(*cmd, o.common);
  // Kept so that its use gets a message saying what to use instead, not CLI11's bare refusal.
  cmd->get_option("--integrator")
      ->description("Not for study, which runs every integrator: use --integrators LIST");
  cmd->add_option("--integrators", o.integrators,
                  "Comma-separated integrators (default: euler,symplectic-euler,midpoint,rk4,"
                  "adaptive)")
      ->check(non_empty());
  cmd->add_option(
         "--dts", o.dts,
         "Comma-separated fixed steps in seconds (default: the scene's dt x 4,2,1,1/2,1/4)")
      ->check(non_empty());
  cmd->add_option("--tolerances", o.tolerances,
                  "Comma-separated adaptive tolerances (default: 1e-4,1e-6,1e-8,1e-10)")
      ->check(non_empty());
  cmd->add_option("--target-error", o.target_error_m,
                  "Also name the cheapest setting whose error is at most this many metres");
  cmd->add_option("--jobs,-j", o.jobs, "Runs in parallel (default: the hardware's threads)");
}

int run_study(const StudyOptions& o) {
  if (!o.common.integrator.empty())
    bad("--integrator does not apply to study, which runs every integrator it lists; choose "
        "them with --integrators LIST");
  Scene scene = load_scene(o.common);
  // Pixels are those of the clip `tumble render` would draw: the same framed camera.
  scene.camera = frame_camera(scene, make_world_def(scene, load_models(scene)));
  const study::StudyPlan plan = make_plan(o, scene);
  const std::filesystem::path dir = output_dir(o.common, scene);

  std::optional<Progress> progress;
  study::StudyHooks hooks;
  hooks.stop_requested = [] { return interrupted(); };
  hooks.progress = [&](int done, int total) {
    if (!progress) progress.emplace(!o.common.quiet, total, "study", "runs");
    progress->update(done);
  };
  study::StudyResult result;
  try {
    result = study::run_study(scene, plan, hooks);
  } catch (const study::Cancelled&) {
    throw_if_interrupted();
    throw Interrupted{2};  // stop_requested() is interrupted(): not reached
  }
  throw_if_interrupted();
  const std::vector<std::filesystem::path> written = study::write_study(dir, result);
  if (!o.common.quiet) {
    std::fputs(study::study_summary(result).c_str(), stdout);
    std::printf("tumble: wrote %s, %s and %s\n", written[0].c_str(), written[1].c_str(),
                written[2].c_str());
    std::fflush(stdout);
    for (const std::string& w : result.warnings)
      std::fprintf(stderr, "tumble: warning: %s\n", w.c_str());
  }
  return 0;
}

}  // namespace tumble::cli
