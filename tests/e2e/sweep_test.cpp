// tumble sweep end to end: the job list, grid order, random determinism, shards (flag and the
// schedulers' variables), idempotent reruns, interrupted and failed jobs, --collect, plan errors
// at file:line:column, SIGTERM.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <regex>
#include <set>
#include <sstream>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

// `tumble sweep ARGS` with the schedulers' variables removed (so the test means the same inside
// a Slurm or Kubernetes job) and `env` (NAME=VALUE) added.
RunResult sweep(std::vector<std::string> args, const fs::path& cwd,
                const std::vector<std::string>& env = {}, const RunOptions& options = {}) {
  std::vector<std::string> command = {"-u", "SLURM_ARRAY_TASK_ID",  "-u", "SLURM_ARRAY_TASK_COUNT",
                                      "-u", "SLURM_ARRAY_TASK_MIN", "-u", "SLURM_ARRAY_TASK_STEP",
                                      "-u", "JOB_COMPLETION_INDEX"};
  command.insert(command.end(), env.begin(), env.end());
  command.push_back(tumble_binary().string());
  command.push_back("sweep");
  command.insert(command.end(), args.begin(), args.end());
  return run_program("env", command, cwd, options);
}

// A plan of 6 simulate jobs (3 restitutions x 2 spins) on kDropScene: fast, no GL.
constexpr std::string_view kGridPlan = R"(scene = "drop.toml"
command = "simulate"
args = ["--rate", "20"]
[grid]
"floor.restitution" = [0.2, 0.5, 0.8]
"body.box.angular_velocity" = [[0.0, 0.0, 1.0], [0.0, 0.0, 4.0]]
)";

void write_plan(const TestDir& dir, std::string_view plan, const std::string& name = "plan.toml") {
  write_scene(dir.path(), "drop.toml", kDropScene);
  write_file(dir / name, plan);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

fs::path job(const TestDir& dir, int index, const std::string& out = "out/plan") {
  char name[32];
  std::snprintf(name, sizeof name, "job_%05d", index);
  return dir / out / name;
}

// sweep.csv read by RFC 4180 (quoted fields may hold commas, quotes doubled).
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name) const {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw std::runtime_error("no column " + name);
    return static_cast<std::size_t>(it - header.begin());
  }
};
CsvTable read_sweep_csv(const fs::path& path) {
  const std::string text = read_file(path);
  std::vector<std::vector<std::string>> records(1, std::vector<std::string>(1));
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        records.back().back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        records.back().back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      records.back().emplace_back();
    } else if (c == '\n') {
      records.emplace_back(1);
    } else {
      records.back().back() += c;
    }
  }
  if (records.back().size() == 1 && records.back()[0].empty()) records.pop_back();
  CsvTable table;
  table.header = records.front();
  table.rows.assign(records.begin() + 1, records.end());
  for (const auto& row : table.rows)
    if (row.size() != table.header.size()) throw std::runtime_error("ragged sweep.csv");
  return table;
}

// A file's modification time in nanoseconds: unchanged means not rewritten.
long long mtime_ns(const fs::path& p) {
  struct stat st {};
  if (stat(p.c_str(), &st) != 0) return -1;
  return static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
}

TEST(Sweep, ListPrintsTheJobsInGridOrderAndRunsNothing) {
  const TestDir dir;
  write_plan(dir, kGridPlan);
  const RunResult r = sweep({"plan.toml", "--list"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  // The first key varies slowest.
  EXPECT_EQ(lines(r.out),
            (std::vector<std::string>{"index,floor.restitution,body.box.angular_velocity",
                                      "0,0.2,\"[0.0, 0.0, 1.0]\"", "1,0.2,\"[0.0, 0.0, 4.0]\"",
                                      "2,0.5,\"[0.0, 0.0, 1.0]\"", "3,0.5,\"[0.0, 0.0, 4.0]\"",
                                      "4,0.8,\"[0.0, 0.0, 1.0]\"", "5,0.8,\"[0.0, 0.0, 4.0]\""}));
  EXPECT_FALSE(fs::exists(dir / "out"));
  // A shard lists its own jobs.
  const RunResult s = sweep({"plan.toml", "--list", "--shard", "1/4"}, dir.path());
  ASSERT_EQ(s.exit_code, 0) << describe(s);
  EXPECT_EQ(lines(s.out).size(), 3u);  // header, jobs 1 and 5
  EXPECT_TRUE(lines(s.out)[2].starts_with("5,0.8,")) << s.out;
}

TEST(Sweep, RandomJobsAreTheSameEveryRunWithADocumentedDraw) {
  const TestDir dir;
  write_plan(dir, R"(scene = "drop.toml"
command = "simulate"
[random]
count = 3
seed = 7
"body.box.orientation.degrees" = { uniform = [0.0, 90.0] }
"body.box.orientation.axis" = { choice = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]] }
)");
  const RunResult list = sweep({"plan.toml", "--list"}, dir.path());
  ASSERT_EQ(list.exit_code, 0) << describe(list);
  // docs/sweeps.md's example draw: seed 7, job 0, key 0, uniform on [0, 90] (exact: no libm).
  ASSERT_GE(lines(list.out).size(), 2u);
  EXPECT_TRUE(lines(list.out)[1].starts_with("0,15.456347869706617,")) << list.out;
  for (const char* out : {"a", "b"}) {
    const RunResult r = sweep({"plan.toml", "--out", out, "--quiet"}, dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
  }
  for (int i = 0; i < 3; ++i) {
    const std::string a = read_file(job(dir, i, "a") / "scene.toml");
    ASSERT_FALSE(a.empty());
    EXPECT_EQ(a, read_file(job(dir, i, "b") / "scene.toml")) << "job " << i;
    EXPECT_EQ(read_file(job(dir, i, "a") / "trajectory.csv"),
              read_file(job(dir, i, "b") / "trajectory.csv"));
  }
  EXPECT_NE(read_file(job(dir, 0, "a") / "scene.toml").find("degrees = 15.456347869706617"),
            std::string::npos);
}

TEST(Sweep, EveryJobWritesItsFolderAndTheRunReportsTheSceneHash) {
  const TestDir dir;
  write_plan(dir, kGridPlan);
  const RunResult r = sweep({"plan.toml", "--quiet"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.out, "");
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(names_in(job(dir, i)),
              (std::vector<std::string>{"run.json", "scene.toml", "trajectory.csv"}));
    const auto report = read_json(job(dir, i) / "run.json");
    EXPECT_EQ(report["scene"]["sha256"], system_sha256(job(dir, i) / "scene.toml"));
  }
  // The effective scene is a standalone scene: tumble runs it alone to the same bytes.
  const RunResult alone = run_tumble({"simulate", (job(dir, 3) / "scene.toml").string(), "--rate",
                                      "20", "--out", "alone", "--quiet"},
                                     dir.path());
  ASSERT_EQ(alone.exit_code, 0) << describe(alone);
  EXPECT_EQ(read_file(dir / "alone/trajectory.csv"), read_file(job(dir, 3) / "trajectory.csv"));
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";
}

TEST(Sweep, RenderJobsShareOneContextAndMatchALoneRender) {
  const TestDir dir;
  write_plan(dir, R"(scene = "drop.toml"
args = ["--size", "160x120", "--duration", "0.25", "--still", "0.2"]
[grid]
"body.box.orientation" = [{ axis = [1.0, 0.0, 0.0], degrees = 20.0 }, { axis = [0.0, 0.0, 1.0], degrees = 50.0 }]
)");
  const RunResult r = sweep({"plan.toml"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  for (int i = 0; i < 2; ++i) {
    const RunResult alone =
        run_tumble({"render", (job(dir, i) / "scene.toml").string(), "--size", "160x120",
                    "--duration", "0.25", "--still", "0.2", "--out", "alone", "--quiet"},
                   dir.path());
    ASSERT_EQ(alone.exit_code, 0) << describe(alone);
    // Byte-identical: the second job ran in the first one's EGL context.
    EXPECT_EQ(read_file(dir / "alone/clip.mp4"), read_file(job(dir, i) / "clip.mp4")) << i;
    EXPECT_EQ(read_file(dir / "alone/still_0.2.png"), read_file(job(dir, i) / "still_0.2.png"));
  }
  EXPECT_NE(read_file(job(dir, 0) / "clip.mp4"), read_file(job(dir, 1) / "clip.mp4"));
}

TEST(Sweep, ShardsSplitTheJobsAndCoverEachOnce) {
  const TestDir dir;
  write_plan(dir, kGridPlan);
  std::multiset<int> ran;
  for (int i = 0; i < 4; ++i) {
    const RunResult r = sweep({"plan.toml", "--shard", std::to_string(i) + "/4"}, dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    for (int j = 0; j < 6; ++j)
      if (r.out.find("job " + std::to_string(j) + " done") != std::string::npos) ran.insert(j);
  }
  EXPECT_EQ(ran, (std::multiset<int>{0, 1, 2, 3, 4, 5}));
  for (int j = 0; j < 6; ++j) EXPECT_TRUE(fs::exists(job(dir, j) / "run.json")) << j;
}

TEST(Sweep, SlurmArrayTasksAndIndexedJobsPickTheirShard) {
  const TestDir dir;
  write_plan(dir, kGridPlan);
  // Array --array=10-12: task 11 is shard 1 of 3, jobs 1 and 4.
  const RunResult slurm =
      sweep({"plan.toml", "--out", "slurm"}, dir.path(),
            {"SLURM_ARRAY_TASK_ID=11", "SLURM_ARRAY_TASK_MIN=10", "SLURM_ARRAY_TASK_COUNT=3"});
  ASSERT_EQ(slurm.exit_code, 0) << describe(slurm);
  EXPECT_EQ(names_in(dir / "slurm"), (std::vector<std::string>{"job_00001", "job_00004"}));
  // An Indexed Job's pod 0 of 2: jobs 0, 2, 4.
  const RunResult k8s =
      sweep({"plan.toml", "--out", "k8s", "--shards", "2"}, dir.path(), {"JOB_COMPLETION_INDEX=0"});
  ASSERT_EQ(k8s.exit_code, 0) << describe(k8s);
  EXPECT_EQ(names_in(dir / "k8s"),
            (std::vector<std::string>{"job_00000", "job_00002", "job_00004"}));
  // Out of range: bad input before any job runs.
  const RunResult bad =
      sweep({"plan.toml", "--out", "bad", "--shards", "2"}, dir.path(), {"JOB_COMPLETION_INDEX=2"});
  EXPECT_EQ(bad.exit_code, 2) << describe(bad);
  EXPECT_NE(bad.err.find("out of range"), std::string::npos) << bad.err;
  EXPECT_EQ(sweep({"plan.toml", "--shard", "3/3"}, dir.path()).exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "bad"));
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(Sweep, ARerunSkipsFinishedJobsAndRunsInterruptedOrChangedOnes) {
  const TestDir dir;
  write_plan(dir, kGridPlan);
  ASSERT_EQ(sweep({"plan.toml", "--quiet"}, dir.path()).exit_code, 0);
  std::vector<long long> before;
  for (int i = 0; i < 6; ++i) before.push_back(mtime_ns(job(dir, i) / "run.json"));
  const std::string report3 = read_file(job(dir, 3) / "run.json");

  const RunResult again = sweep({"plan.toml"}, dir.path());
  ASSERT_EQ(again.exit_code, 0) << describe(again);
  EXPECT_NE(again.out.find("0 ran, 6 skipped"), std::string::npos) << again.out;
  for (int i = 0; i < 6; ++i) EXPECT_EQ(mtime_ns(job(dir, i) / "run.json"), before[i]) << i;

  // An interrupted job has no run.json (it is written last): only that job runs again.
  fs::remove(job(dir, 2) / "run.json");
  fs::remove(job(dir, 2) / "trajectory.csv");
  const RunResult resumed = sweep({"plan.toml"}, dir.path());
  ASSERT_EQ(resumed.exit_code, 0) << describe(resumed);
  EXPECT_NE(resumed.out.find("1 ran, 5 skipped"), std::string::npos) << resumed.out;
  EXPECT_NE(resumed.out.find("job 2 done"), std::string::npos) << resumed.out;
  EXPECT_TRUE(fs::exists(job(dir, 2) / "run.json"));
  EXPECT_EQ(read_file(job(dir, 3) / "run.json"), report3);

  // A changed plan changes the scenes of the jobs it touches: those run again, the rest not.
  write_file(dir / "plan.toml", replace(std::string(kGridPlan), "0.8]", "0.9]"));
  const RunResult changed = sweep({"plan.toml"}, dir.path());
  ASSERT_EQ(changed.exit_code, 0) << describe(changed);
  EXPECT_NE(changed.out.find("2 ran, 4 skipped"), std::string::npos) << changed.out;
  EXPECT_EQ(read_file(job(dir, 3) / "run.json"), report3);
  // So do the job options: the effective scene names them.
  write_file(dir / "plan.toml", replace(std::string(kGridPlan), "\"20\"", "\"25\""));
  const RunResult options = sweep({"plan.toml"}, dir.path());
  EXPECT_NE(options.out.find("6 ran, 0 skipped"), std::string::npos) << options.out;
}

// Job 1 asks for a still beyond its shorter run: the scene is valid, the run is not.
constexpr std::string_view kFailingPlan = R"(scene = "drop.toml"
args = ["--no-mp4", "--still", "0.4", "--size", "64x48"]
[grid]
"simulation.duration" = [0.5, 0.3, 0.5]
)";

TEST(Sweep, AFailedJobIsWorseThanAFlaggedOne) {
  // --strict, euler at dt = 0.02 s with a fast spin: job 0 completes flagged (exit 4, outputs
  // written); job 1 asks for a still beyond its shorter run (exit 2, nothing written). The
  // shard exits 2: exit 4 would say every job's outputs exist.
  const TestDir dir;
  write_plan(dir, R"(scene = "drop.toml"
args = ["--strict", "--integrator", "euler", "--dt", "0.02", "--no-mp4", "--still", "0.4",
        "--size", "64x48"]
[grid]
"simulation.duration" = [0.5, 0.3]
"body.box.angular_velocity" = [[0.0, 20.0, 0.0]]
)");
  const RunResult r = sweep({"plan.toml", "--quiet"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(read_file(job(dir, 0) / "error.txt").starts_with("exit 4\n"));
  EXPECT_TRUE(fs::exists(job(dir, 0) / "run.json"));
  EXPECT_TRUE(read_file(job(dir, 1) / "error.txt").starts_with("exit 2\n"));
  EXPECT_FALSE(fs::exists(job(dir, 1) / "run.json"));
  // Rerun: job 0 counts as done (skipped, still flagged), job 1 fails again; still 2.
  EXPECT_EQ(sweep({"plan.toml", "--quiet"}, dir.path()).exit_code, 2);
}

TEST(Sweep, AFailedJobLeavesErrorTxtAndTheShardGoesOn) {
  const TestDir dir;
  write_plan(dir, kFailingPlan);
  const RunResult r = sweep({"plan.toml", "--quiet"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_NE(r.err.find("job 1 failed (exit 2)"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(job(dir, 0) / "run.json"));
  EXPECT_TRUE(fs::exists(job(dir, 2) / "run.json")) << "the shard stopped at the failure";
  EXPECT_FALSE(fs::exists(job(dir, 1) / "run.json"));
  const std::string error = read_file(job(dir, 1) / "error.txt");
  EXPECT_TRUE(error.starts_with("exit 2\n")) << error;
  EXPECT_NE(error.find("--still 0.4 is outside the run"), std::string::npos) << error;

  // --collect: sweep.csv with every job, exit 1 naming the failed one.
  const RunResult c = sweep({"plan.toml", "--collect"}, dir.path());
  EXPECT_EQ(c.exit_code, 1) << describe(c);
  EXPECT_NE(c.err.find("failed jobs (see their error.txt): 1\n"), std::string::npos) << c.err;
  const CsvTable csv = read_sweep_csv(dir / "out/plan/sweep.csv");
  ASSERT_EQ(csv.rows.size(), 3u);
  const std::size_t status = csv.column("status");
  EXPECT_EQ(csv.rows[0][status], "finished");
  EXPECT_EQ(csv.rows[1][status], "failed");
  EXPECT_EQ(csv.rows[1][csv.column("exit_code")], "2");
}

TEST(Sweep, CollectNamesMissingJobsAndReportsKeyFigures) {
  const TestDir dir;
  write_plan(dir, kGridPlan);
  ASSERT_EQ(sweep({"plan.toml", "--shard", "0/2", "--quiet"}, dir.path()).exit_code, 0);
  const RunResult c = sweep({"plan.toml", "--collect"}, dir.path());
  EXPECT_EQ(c.exit_code, 1) << describe(c);
  EXPECT_NE(c.err.find("missing jobs (not run, interrupted or stale): 1, 3, 5\n"),
            std::string::npos)
      << c.err;
  ASSERT_EQ(sweep({"plan.toml", "--shard", "1/2", "--quiet"}, dir.path()).exit_code, 0);
  const RunResult all = sweep({"plan.toml", "--collect"}, dir.path());
  EXPECT_EQ(all.exit_code, 0) << describe(all);
  EXPECT_EQ(all.err, "");
  const CsvTable csv = read_sweep_csv(dir / "out/plan/sweep.csv");
  ASSERT_EQ(csv.rows.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    const auto report = read_json(job(dir, static_cast<int>(i)) / "run.json");
    EXPECT_EQ(csv.rows[i][csv.column("index")], std::to_string(i));
    EXPECT_EQ(csv.rows[i][csv.column("status")], "finished");
    EXPECT_EQ(std::stod(csv.rows[i][csv.column("energy_start_J")]),
              report["physics"]["energy_start_J"].get<double>());
    EXPECT_EQ(csv.rows[i][csv.column("contacts")],
              std::to_string(report["physics"]["contacts"].get<long>()));
    EXPECT_EQ(csv.rows[i][csv.column("outputs")],
              "trajectory.csv=" + system_sha256(job(dir, static_cast<int>(i)) / "trajectory.csv"));
  }
  EXPECT_EQ(csv.rows[4][csv.column("floor.restitution")], "0.8");
}

TEST(Sweep, PlanErrorsPointIntoThePlanBeforeAnyJobRuns) {
  const TestDir dir;
  const std::string head = "scene = \"drop.toml\"\ncommand = \"simulate\"\n";
  struct Case {
    std::string plan, error;
  };
  const std::vector<Case> cases = {
      {head + "[grid]\n\"floor.restitutoin\" = [0.5]\n",
       "plan.toml:4:1: job 0 (floor.restitutoin = 0.5): unknown key \"restitutoin\" in [floor] "
       "(did you mean \"restitution\"?) (key path \"floor.restitutoin\")"},
      // Job 0 is fine; job 1's value is out of range: nothing runs, not even job 0.
      {head + "[grid]\n\"floor.restitution\" = [0.5, 1.5]\n",
       "plan.toml:4:29: job 1 (floor.restitution = 1.5): restitution in [floor] must be in [0, "
       "1], got 1.5"},
      {head + "[random]\ncount = 2\nseed = 1\n\"floor.friction\" = { gauss = [0, 1] }\n",
       "plan.toml:6:22: unknown distribution \"gauss\" in [random] \"floor.friction\" (expected "
       "one of: uniform, normal, integer, choice)"},
      {head + "args = [\"--rate\", \"fast\"]\n[grid]\n\"floor.height\" = [0.0]\n",
       "plan.toml:3:8: args: Could not convert: --rate = fast (options of tumble simulate)"},
      {head + "args = [\"--duration\", \"0.0005\", \"--dt\", \"0.001\"]\n[grid]\n"
              "\"floor.height\" = [0.0]\n",
       "plan.toml:3:8: job 0 (floor.height = 0.0): the step dt = 0.001 s is longer than the run "
       "(5e-04 s)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.plan);
    write_plan(dir, c.plan);
    const RunResult r = sweep({"plan.toml"}, dir.path());
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_EQ(r.err, "tumble: error: " + c.error + "\n");
    EXPECT_FALSE(fs::exists(dir / "out")) << "a job ran despite the plan error";
  }
}

// Ten million random jobs: listed and checked lazily, one job at a time.
constexpr std::string_view kHugePlan = R"(scene = "drop.toml"
command = "simulate"
[random]
count = 10000000
seed = 7
"floor.restitution" = { uniform = [0.1, 0.9] }
)";

TEST(Sweep, ListOfTenMillionJobsStartsAtOnceInBoundedMemory) {
  // Checking and listing every job before the first line took 380 s and 3.7 GB. Now the header
  // and the first rows come at once: killed after 3 s (the first line is due within a second;
  // the rest is room for a loaded machine), under a 1 GiB address-space limit that 10^7 jobs
  // held at once would break.
  const TestDir dir;
  write_plan(dir, kHugePlan);
  RunOptions quick;
  quick.timeout = std::chrono::seconds(3);
  const RunResult r = run_program(
      "sh",
      {"-c", "ulimit -v 1048576 && exec \"$0\" sweep plan.toml --list", tumble_binary().string()},
      dir.path(), quick);
  EXPECT_TRUE(r.timed_out) << "listed all 10^7 jobs in 3 s? " << describe(r);
  const std::vector<std::string> rows = lines(r.out);
  ASSERT_GE(rows.size(), 3u) << describe(r);
  EXPECT_EQ(rows[0], "index,floor.restitution");
  EXPECT_TRUE(rows[1].starts_with("0,0.")) << rows[1];
  EXPECT_TRUE(rows[2].starts_with("1,0.")) << rows[2];
  EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
}

TEST(Sweep, AShardListsAndChecksOnlyItsOwnJobs) {
  // --shard 0/1000 of the ten million: jobs 0, 1000, 2000, ... and nothing else.
  const TestDir dir;
  write_plan(dir, kHugePlan);
  RunOptions quick;
  quick.timeout = std::chrono::seconds(3);
  const RunResult r = sweep({"plan.toml", "--list", "--shard", "7/1000"}, dir.path(), {}, quick);
  const std::vector<std::string> rows = lines(r.out);
  ASSERT_GE(rows.size(), 3u) << describe(r);
  EXPECT_TRUE(rows[1].starts_with("7,")) << rows[1];
  EXPECT_TRUE(rows[2].starts_with("1007,")) << rows[2];

  // Draws from a normal distribution reach any value: job by job, some restitutions fall
  // outside [0, 1]. A shard of valid jobs lists them; one holding a bad job fails naming it.
  write_plan(dir, R"(scene = "drop.toml"
command = "simulate"
[random]
count = 12
seed = 3
"floor.restitution" = { normal = [0.5, 0.4] }
)");
  const RunResult all = sweep({"plan.toml", "--list"}, dir.path());
  ASSERT_EQ(all.exit_code, 2) << "no draw of 12 fell outside [0, 1]? " << describe(all);
  int listed = 0, failed = 0;
  for (int i = 0; i < 12; ++i) {
    const std::string shard = std::to_string(i) + "/12";
    const RunResult one = sweep({"plan.toml", "--list", "--shard", shard}, dir.path());
    if (one.exit_code == 0) {
      ++listed;
      const std::vector<std::string> shard_rows = lines(one.out);
      ASSERT_EQ(shard_rows.size(), 2u) << describe(one);
      EXPECT_TRUE(shard_rows[1].starts_with(std::to_string(i) + ",")) << shard_rows[1];
    } else {
      ++failed;
      EXPECT_EQ(one.exit_code, 2) << describe(one);
      EXPECT_NE(one.err.find("job " + std::to_string(i) + " (floor.restitution = "),
                std::string::npos)
          << one.err;
    }
  }
  EXPECT_GT(listed, 0);
  EXPECT_GT(failed, 0);
}

TEST(Sweep, APlanErrorOutsideTheShardIsStillReported) {
  // Job 1's restitution is out of range; shard 0/2 holds only job 0, yet the plan's own check
  // (every grid value, the ends of every uniform range) reports it before anything runs.
  const TestDir dir;
  const std::string head = "scene = \"drop.toml\"\ncommand = \"simulate\"\n";
  write_plan(dir, head + "[grid]\n\"floor.restitution\" = [0.5, 1.5]\n");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"plan.toml", "--shard", "0/2"},
        std::vector<std::string>{"plan.toml", "--shard", "0/2", "--list"}}) {
    const RunResult r = sweep(args, dir.path());
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_EQ(r.err,
              "tumble: error: plan.toml:4:29: job 1 (floor.restitution = 1.5): restitution in "
              "[floor] must be in [0, 1], got 1.5\n");
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
  // A uniform range whose upper end is out of range: reported at the distribution.
  write_plan(dir, head +
                      "[random]\ncount = 1000\nseed = 1\n"
                      "\"floor.restitution\" = { uniform = [0.5, 1.2] }\n");
  const RunResult u = sweep({"plan.toml", "--shard", "3/1000", "--list"}, dir.path());
  EXPECT_EQ(u.exit_code, 2) << describe(u);
  EXPECT_NE(u.err.find("plan.toml:6:"), std::string::npos) << u.err;
  EXPECT_NE(u.err.find("at the end of its range (1.2)"), std::string::npos) << u.err;
  EXPECT_NE(u.err.find("must be in [0, 1], got 1.2"), std::string::npos) << u.err;
}

TEST(Sweep, SigtermEndsTheCurrentJobCleanly) {
  const TestDir dir;
  // Job 0 is short; job 1 takes far longer than the 3 s before SIGTERM.
  write_plan(dir, R"(scene = "drop.toml"
args = ["--size", "160x120", "--quiet"]
[grid]
"simulation.duration" = [0.2, 10000.0]
)");
  RunOptions options;
  options.signal = SIGTERM;
  options.signal_after = std::chrono::milliseconds(3000);
  const RunResult r = sweep({"plan.toml"}, dir.path(), {}, options);
  EXPECT_EQ(r.exit_code, 143) << describe(r);
  EXPECT_FALSE(r.timed_out);
  EXPECT_TRUE(fs::exists(job(dir, 0) / "run.json")) << "job 0 did not finish in 3 s";
  EXPECT_TRUE(fs::exists(job(dir, 1) / "scene.toml"));
  EXPECT_FALSE(fs::exists(job(dir, 1) / "run.json"));
  EXPECT_FALSE(fs::exists(job(dir, 1) / "clip.mp4"));
  EXPECT_FALSE(fs::exists(job(dir, 1) / "error.txt")) << "an interruption is no failure";
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";
  // --collect counts it missing.
  const RunResult c = sweep({"plan.toml", "--collect"}, dir.path());
  EXPECT_EQ(c.exit_code, 1);
  EXPECT_NE(c.err.find("missing jobs (not run, interrupted or stale): 1\n"), std::string::npos)
      << c.err;
}

}  // namespace
}  // namespace tumble_e2e
