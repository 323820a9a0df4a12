// tumble sweep PLAN: every job of a plan (or one shard of them), each in OUT/job_NNNNN/ with its
// effective scene.toml, the command's outputs and run.json last; --list, --collect. The plan,
// its jobs, the job folders and the CSV tables are the sweep layer's (tumble/sweep.hpp); this
// file parses the job options with the subcommand's own definitions, checks the plan's values
// and then every job's scene of this shard (made one at a time, never all at once) before any
// runs, and runs the jobs one after another in this process (one EGL context).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "commands.hpp"
#include "progress.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/egl_context.hpp"
#include "tumble/job_folder.hpp"
#include "tumble/job_scene.hpp"
#include "tumble/renderer.hpp"  // RenderSession keeps one
#include "tumble/sha256.hpp"
#include "tumble/shard.hpp"
#include "tumble/sweep.hpp"
#include "tumble/sweep_csv.hpp"
#include "tumble/trajectory_writer.hpp"
#include "tumble/world_builder.hpp"

namespace tumble::cli {
namespace {

// The worse of two job exit codes: a failure (3, the environment, over 2, bad input) over a run
// that completed but was flagged (4, its outputs written) over success, so that a shard exiting
// 4 means every job's outputs exist.
int worse(int a, int b) {
  auto rank = [](int code) { return code == 0 ? 0 : code == 4 ? 1 : code == 2 ? 2 : 3; };
  return rank(b) > rank(a) ? b : a;
}

namespace fs = std::filesystem;
using sweep::Job;
using sweep::JobRecord;
using sweep::JobState;
using sweep::Plan;

// The options every job runs with, parsed by the real subcommand's definitions, so an option
// a plan's args misspell is an error here exactly as on the command line.
struct JobOptions {
  RenderOptions render;
  SimulateOptions simulate;
  CommonOptions& common(const Plan& plan) {
    return plan.command == "render" ? render.common : simulate.common;
  }
};

JobOptions parse_job_options(const Plan& plan) {
  JobOptions o;
  CLI::App app{"", "tumble"};
  if (plan.command == "render")
    add_render_command(app, o.render);
  else
    add_simulate_command(app, o.simulate);
  // CLI11 takes the arguments in reverse order.
  std::vector<std::string> args = {plan.command};
  args.insert(args.end(), plan.args.begin(), plan.args.end());
  std::reverse(args.begin(), args.end());
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    throw Error(ErrorKind::BadInput,
                "args: " + std::string(e.what()) + " (options of tumble " + plan.command + ")",
                plan.args_at);
  }
  const CommonOptions& c = o.common(plan);
  if (!c.scene_path.empty())
    throw Error(ErrorKind::BadInput,
                "args name a scene (\"" + c.scene_path +
                    "\"): a sweep's jobs run the plan's scene with its parameters",
                plan.args_at);
  if (!c.out_dir.empty())
    throw Error(ErrorKind::BadInput,
                "args give --out: each job writes to OUT/job_NNNNN/ (tumble sweep --out OUT)",
                plan.args_at);
  return o;
}

// The key of the models a scene loads: its mesh bodies' files, scales and repairs.
std::string models_key(const Scene& scene) {
  std::string key;
  for (const BodySpec& b : scene.bodies)
    if (b.shape == Shape::Mesh)
      key += b.mesh + "|" + format_double(b.scale.x()) + "," + format_double(b.scale.y()) + "," +
             format_double(b.scale.z()) + "|" +
             std::string(kMeshRepairNames[static_cast<int>(b.repair)]) + "\n";
  return key;
}

// Checks job scenes the way each job will load them (scene loader, overrides, world builder).
// Models are loaded once per distinct set of mesh files.
class JobChecker {
 public:
  JobChecker(const Plan& plan, const CommonOptions& common) : plan_(plan) {
    check_ = [this, &common](const std::string& text, const std::string& name) {
      Scene scene = parse_scene(text, name, {common.duration_s, common.dt_s});
      apply_overrides(scene, common);
      const std::string key = models_key(scene);
      auto it = models_.find(key);
      if (it == models_.end()) it = models_.emplace(key, load_models(scene)).first;
      make_world_def(scene, it->second);
    };
  }
  /// The plan itself, cheaply (check_plan_values): what any shard must hear about.
  void plan_values() const { sweep::check_plan_values(plan_, check_); }
  void job(const Job& job) const { sweep::check_job_scene(plan_, job, check_); }

 private:
  const Plan& plan_;
  mutable std::map<std::string, SceneModels> models_;
  sweep::SceneCheck check_;
};

// Calls f(job) for every job of the shard, in order, each made when it is reached: memory does
// not grow with the plan's job count.
template <class F>
void for_each_job(const Plan& plan, const sweep::Shard& shard, F&& f) {
  const std::size_t count = plan.job_count();
  for (std::size_t j = shard.index; j < count; j += shard.count) {
    throw_if_interrupted();  // a long list or check stops at a signal like a run
    f(sweep::make_job(plan, j));
  }
}

sweep::Shard choose_shard(const SweepOptions& o) {
  if (!o.shard.empty()) {
    if (o.shards) throw Error(ErrorKind::BadInput, "give --shard I/N or --shards N, not both");
    return sweep::parse_shard(o.shard);
  }
  const sweep::Environment env = [](const char* name) -> std::optional<std::string> {
    const char* value = std::getenv(name);
    return value ? std::optional<std::string>(value) : std::nullopt;
  };
  return sweep::shard_from_environment(env, o.shards).value_or(sweep::Shard{});
}

// "3, 5, 8 and 12 more": job numbers for a message, not a wall of them.
std::string job_numbers(const std::vector<std::size_t>& jobs) {
  constexpr std::size_t kShown = 20;
  std::string s;
  for (std::size_t i = 0; i < jobs.size() && i < kShown; ++i)
    s += (i ? ", " : "") + std::to_string(jobs[i]);
  if (jobs.size() > kShown) s += " and " + std::to_string(jobs.size() - kShown) + " more";
  return s;
}

int collect(const Plan& plan, const std::vector<Job>& jobs, const fs::path& out, bool quiet) {
  std::vector<JobRecord> records;
  std::vector<std::size_t> missing, failed;
  for (const Job& job : jobs) {
    const std::string sha = sha256_hex(sweep::job_scene_text(plan, job));
    records.push_back(
        sweep::read_job_folder(out / sweep::job_folder_name(job.index), sha, TUMBLE_VERSION));
    if (records.back().state == JobState::Failed) failed.push_back(job.index);
    if (records.back().state == JobState::Missing || records.back().state == JobState::Stale)
      missing.push_back(job.index);
  }
  make_output_dir(out);
  write_file_atomically(out / "sweep.csv", sweep::sweep_csv(plan, jobs, records));
  const std::size_t finished = jobs.size() - missing.size() - failed.size();
  if (!quiet)
    std::printf("tumble: wrote %s: %zu jobs, %zu finished, %zu missing, %zu failed\n",
                (out / "sweep.csv").c_str(), jobs.size(), finished, missing.size(), failed.size());
  if (!missing.empty())
    std::fprintf(stderr, "tumble: error: missing jobs (not run, interrupted or stale): %s\n",
                 job_numbers(missing).c_str());
  if (!failed.empty())
    std::fprintf(stderr, "tumble: error: failed jobs (see their error.txt): %s\n",
                 job_numbers(failed).c_str());
  return missing.empty() && failed.empty() ? 0 : 1;
}

}  // namespace

void add_sweep_command(CLI::App& app, SweepOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Run many scenes from one plan (a grid and/or random draws), locally or sharded");
  cmd->add_option("plan", o.plan_path, "Sweep plan (TOML): scene, command, args, [grid], [random]")
      ->required();
  cmd->add_option("--out", o.out_dir, "Output folder (default: out/<plan-stem>/)")
      ->check(non_empty());
  cmd->add_flag("--list", o.list, "Print the jobs as CSV (index and parameters); run nothing");
  cmd->add_flag("--collect", o.collect,
                "Write OUT/sweep.csv; exit 1 naming the jobs that are missing or failed");
  cmd->add_option("--shard", o.shard, "Run only the jobs j with j mod N = I (I/N)");
  cmd->add_option("--shards", o.shards,
                  "In a Kubernetes Indexed Job: N shards, this one JOB_COMPLETION_INDEX");
  cmd->add_flag("--quiet,-q", o.quiet, "Print nothing but errors");
}

int run_sweep(const SweepOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (o.list && o.collect) throw Error(ErrorKind::BadInput, "give --list or --collect, not both");
  const Plan plan = sweep::load_plan(o.plan_path);
  JobOptions options = parse_job_options(plan);
  CommonOptions& common = options.common(plan);
  if (o.quiet) common.quiet = true;
  // The plan's own values first, then only the jobs this process lists or runs, each when it
  // is reached: a shard of a huge plan checks its share, and --list starts at once.
  const JobChecker checker(plan, common);
  checker.plan_values();
  const sweep::Shard shard = o.collect ? sweep::Shard{} : choose_shard(o);

  if (o.list) {
    // Streamed: each row as soon as its job is checked (a later job's error ends the list).
    std::fputs((sweep::job_list_header(plan) + "\n").c_str(), stdout);
    std::fflush(stdout);
    for_each_job(plan, shard, [&](const Job& job) {
      checker.job(job);
      std::fputs((sweep::job_list_row(job) + "\n").c_str(), stdout);
      std::fflush(stdout);
    });
    return 0;
  }
  const fs::path out = o.out_dir.empty() ? fs::path("out") / plan.stem : fs::path(o.out_dir);
  if (o.collect) {
    std::vector<Job> jobs;
    jobs.reserve(plan.job_count());
    for_each_job(plan, shard, [&](const Job& job) {
      checker.job(job);
      jobs.push_back(job);
    });
    return collect(plan, jobs, out, o.quiet);
  }
  // Every job of the shard is checked before any runs.
  std::size_t in_shard = 0;
  for_each_job(plan, shard, [&](const Job& job) {
    checker.job(job);
    ++in_shard;
  });

  RenderSession session;
  int worst = 0;
  std::size_t ran = 0, skipped = 0, failed = 0;
  std::size_t done = 0;
  for_each_job(plan, shard, [&](const Job& job) {
    throw_if_interrupted();
    ++done;
    const fs::path dir = out / sweep::job_folder_name(job.index);
    const std::string scene = sweep::job_scene_text(plan, job);
    const JobRecord before = sweep::read_job_folder(dir, sha256_hex(scene), TUMBLE_VERSION);
    if (before.complete) {
      // Finished for this very scene and version: its outputs would come out the same.
      ++skipped;
      if (before.state == JobState::Failed) worst = worse(worst, before.exit_code);
      return;
    }
    const auto job_start = std::chrono::steady_clock::now();
    make_output_dir(dir);
    sweep::clear_job_results(dir);
    write_file_atomically(dir / "scene.toml", scene);
    CommonOptions& c = options.common(plan);
    c.scene_path = (dir / "scene.toml").string();
    c.out_dir = dir.string();
    int code = 0;
    std::string message;
    try {
      code = plan.command == "render" ? run_render(options.render, &session)
                                      : run_simulate(options.simulate);
      if (code != 0) message = "--strict: a diagnostic flagged the run (see run.json)";
    } catch (const Error& e) {
      // Interrupted is no Error: it ends the sweep (main exits 128 + signal), leaving this job
      // without run.json so that it runs again.
      code = e.exit_code();
      message = e.describe();
    } catch (const std::exception& e) {
      // Anything else (allocation, the file system) is the environment's failure, as in main.
      code = static_cast<int>(ErrorKind::Environment);
      message = e.what();
    }
    ++ran;
    if (code != 0) {
      ++failed;
      worst = worse(worst, code);
      sweep::write_error_file(dir, code, message);
      std::fprintf(stderr, "tumble: error: job %zu failed (exit %d): %s\n", job.index, code,
                   message.c_str());
    } else if (!o.quiet) {
      std::printf("tumble: sweep: job %zu done in %.2f s (%zu/%zu of shard %s)\n", job.index,
                  seconds_since(job_start), done, in_shard, shard.describe().c_str());
    }
  });
  if (!o.quiet)
    std::printf(
        "tumble: sweep: shard %s: %zu jobs, %zu ran, %zu skipped (finished before), %zu "
        "failed, in %.2f s into %s\n",
        shard.describe().c_str(), in_shard, ran, skipped, failed, seconds_since(start),
        out.c_str());
  return worst;
}

}  // namespace tumble::cli
