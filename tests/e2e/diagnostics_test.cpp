// Diagnostics end to end (SPEC.md: run.json `diagnostics`, `--strict`, exit 4, a state that stops
// being finite), and the adaptive integrator from a scene file and the command line.
#include <gtest/gtest.h>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

// Explicit Euler at dt = 0.02 s on a box spinning at 20 rad/s: 0.4 rad per step, past what the
// method follows (0.1): run.json and stderr must say so.
constexpr std::string_view kCoarseSpin = R"([simulation]
duration = 1.0
dt = 0.02
integrator = "euler"
gravity = [0.0, 0.0, 0.0]
[[body]]
name = "spinner"
shape = "box"
size = [1.0, 2.0, 3.0]
mass = 1.0
angular_velocity = [1.0, 20.0, 1.0]
)";

TEST(Diagnostics, CoarseStepIsReportedInRunJsonAndOnStderr) {
  const TestDir dir;
  write_scene(dir.path(), "spin.toml", kCoarseSpin);
  const RunResult r = run_tumble({"simulate", "spin.toml", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_NE(r.err.find("tumble: warning: body \"spinner\" turns 0.4"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(use dt <= "), std::string::npos) << r.err;
  const nlohmann::json j = read_json(dir / "o/run.json");
  ASSERT_TRUE(j["diagnostics"].is_array());
  ASSERT_FALSE(j["diagnostics"].empty());
  bool spin = false;
  for (const auto& d : j["diagnostics"]) {
    for (const char* key : {"code", "severity", "message", "t_s", "fix"})
      EXPECT_TRUE(d.contains(key)) << key;
    spin = spin || d["code"] == "step_too_large_for_spin";
    // Each diagnostic is printed once, however often it recurred.
    const std::string line = "tumble: warning: " + d["message"].get<std::string>();
    const std::size_t first = r.err.find(line);
    EXPECT_NE(first, std::string::npos);
    EXPECT_EQ(r.err.find(line, first + 1), std::string::npos);
  }
  EXPECT_TRUE(spin);
  EXPECT_TRUE(fs::is_regular_file(dir / "o/trajectory.csv"));
}

TEST(Diagnostics, QuietSilencesTheWarningsButNotRunJson) {
  const TestDir dir;
  write_scene(dir.path(), "spin.toml", kCoarseSpin);
  const RunResult r = run_tumble({"simulate", "spin.toml", "--out", "o", "-q"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.err, "");
  EXPECT_FALSE(read_json(dir / "o/run.json")["diagnostics"].empty());
}

TEST(Diagnostics, StrictTurnsAWarningIntoExit4WithOutputsKept) {
  const TestDir dir;
  write_scene(dir.path(), "spin.toml", kCoarseSpin);
  const RunResult sim = run_tumble({"simulate", "spin.toml", "--out", "s", "--strict"}, dir.path());
  EXPECT_EQ(sim.exit_code, 4) << describe(sim);
  EXPECT_TRUE(fs::is_regular_file(dir / "s/trajectory.csv"));
  EXPECT_TRUE(fs::is_regular_file(dir / "s/run.json"));
  const RunResult ren = run_tumble(
      {"render", "spin.toml", "--out", "r", "--strict", "--size", "64x48", "--fps", "10"},
      dir.path());
  EXPECT_EQ(ren.exit_code, 4) << describe(ren);
  EXPECT_TRUE(fs::is_regular_file(dir / "r/clip.mp4"));
  EXPECT_FALSE(read_json(dir / "r/run.json")["diagnostics"].empty());
}

TEST(Diagnostics, TrustworthyRunIsCleanAndStrictPasses) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate", "--out", "o", "--strict"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.err, "");
  const nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_TRUE(j["diagnostics"].is_array());
  EXPECT_TRUE(j["diagnostics"].empty());
  // rk4: 4 evaluations a step while the box moves (it rests from about 2.45 s of the 4 s) plus
  // the impact searches.
  EXPECT_GT(j["counts"]["derivative_evaluations"].get<long>(), 4 * 2400);
}

TEST(Diagnostics, AStateWhoseEnergyOverflowsIsRefusedBeforeAnythingIsWritten) {
  // Every field is finite and in range, but ½ m v² at 1e155 m/s is not: no inf or nan may reach
  // trajectory.csv or run.json, so the run ends with exit 2 (render too).
  const TestDir dir;
  write_scene(dir.path(), "fast.toml", R"([simulation]
duration = 0.1
[[body]]
name = "fast"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 3.0, 0.0]
velocity = [1e155, 0.0, 0.0]
)");
  for (const char* command : {"simulate", "render"}) {
    const RunResult r =
        run_tumble({command, "fast.toml", "--out", "o", "--size", "64x48"}, dir.path());
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_NE(r.err.find("tumble: error: the starting state of body \"fast\" is beyond double "
                         "precision"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "o/run.json"));
    EXPECT_FALSE(fs::exists(dir / "o/trajectory.csv"));
  }
}

TEST(Diagnostics, ANonFiniteStateEndsTheRunWithExit2AndNoOutputs) {
  // Stiff drag (c dt / m = 1000) under explicit Euler: the speed grows 999-fold each step.
  const TestDir dir;
  write_scene(dir.path(), "stiff.toml", R"([simulation]
duration = 1.0
integrator = "euler"
linear_drag = 1000000.0
[[body]]
name = "p"
shape = "particle"
size = [0.1, 0.1, 0.1]
mass = 1.0
velocity = [1.0, 0.0, 0.0]
)");
  const RunResult r = run_tumble({"simulate", "stiff.toml", "--out", "o"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_NE(r.err.find("tumble: error: the state of body \"p\" stopped being finite near t = "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("smaller dt"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "o/trajectory.csv"));
  EXPECT_FALSE(fs::exists(dir / "o/run.json"));
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";
  // The adaptive integrator finds the stable step and runs the same scene to the end.
  const RunResult a =
      run_tumble({"simulate", "stiff.toml", "--out", "a", "--integrator", "adaptive"}, dir.path());
  EXPECT_EQ(a.exit_code, 0) << describe(a);
}

TEST(Adaptive, SceneToleranceAndStepStatisticsInRunJson) {
  const TestDir dir;
  write_scene(dir.path(), "drop.toml",
              replace(std::string(kDropScene), "duration = 0.5",
                      "duration = 1.0\ndt = 0.01\nmax_step = 0.05\nintegrator = \"adaptive\"\n"
                      "tolerance = 1e-9"));
  const RunResult r = run_tumble({"simulate", "drop.toml", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["settings"]["simulation"]["integrator"], "adaptive");
  EXPECT_EQ(j["settings"]["simulation"]["tolerance"], 1e-9);
  EXPECT_EQ(j["settings"]["simulation"]["dt_s"], 0.01);
  EXPECT_EQ(j["settings"]["simulation"]["max_step_s"], 0.05);
  const nlohmann::json& a = j["adaptive"];
  EXPECT_EQ(a["tolerance"], 1e-9);
  EXPECT_EQ(a["first_step_s"], 0.01);
  EXPECT_EQ(a["largest_step_s"], 0.05);
  EXPECT_GT(a["accepted_steps"].get<long>(), 0);
  EXPECT_GE(a["rejected_steps"].get<long>(), 0);
  EXPECT_GT(a["smallest_step_taken_s"].get<double>(), 0.0);
  EXPECT_LE(a["largest_step_taken_s"].get<double>(), 0.05);
  // The first impact of the box (bottom face from 2.5 m) is where the fixed-step rk4 puts it.
  const Csv csv = read_csv(dir / "o/trajectory.csv");
  EXPECT_EQ(csv.rows.size(), 61u);
}

TEST(Adaptive, LargestStepDefaultsToTheSampleInterval) {
  // No max_step: simulate's sample interval (1/rate) is the largest step, so every sample is a
  // step boundary; dt (0.001) is only the first trial step.
  const TestDir dir;
  write_scene(dir.path(), "drop.toml",
              replace(std::string(kDropScene), "duration = 0.5",
                      "duration = 1.0\nintegrator = \"adaptive\""));
  for (const char* rate : {"20", "50"}) {
    const std::string out = std::string("o") + rate;
    const RunResult r =
        run_tumble({"simulate", "drop.toml", "--rate", rate, "--out", out}, dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const nlohmann::json j = read_json(dir / out / "run.json");
    EXPECT_EQ(j["adaptive"]["largest_step_s"], 1.0 / std::stod(rate));
    EXPECT_EQ(j["settings"]["simulation"]["max_step_s"], 1.0 / std::stod(rate));
    EXPECT_EQ(j["adaptive"]["first_step_s"], 0.001);
    EXPECT_EQ(j["counts"]["steps"], std::stol(rate));  // one world step per sample interval
  }
}

TEST(Adaptive, MaxStepIsCheckedAndIgnoredByFixedStepIntegrators) {
  const TestDir dir;
  // Checked like every number, whatever the integrator: FILE:LINE:COLUMN of the value.
  for (const char* bad : {"max_step = 0.0", "max_step = -0.01", "max_step = \"big\""}) {
    write_scene(
        dir.path(), "bad.toml",
        replace(std::string(kDropScene), "duration = 0.5", "duration = 0.5\n" + std::string(bad)));
    const RunResult r = run_tumble({"simulate", "bad.toml", "--out", "o"}, dir.path());
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << describe(r);
    EXPECT_NE(r.err.find("bad.toml:3:12: max_step in [simulation]"), std::string::npos)
        << bad << ": " << r.err;
  }
  // A typo names the key meant.
  write_scene(dir.path(), "typo.toml",
              replace(std::string(kDropScene), "duration = 0.5", "duration = 0.5\nmax_stp = 0.1"));
  const RunResult typo = run_tumble({"simulate", "typo.toml", "--out", "o"}, dir.path());
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.err.find("max_step"), std::string::npos) << typo.err;
  // With rk4 it is read and ignored (as tolerance is), so --integrator can switch methods: the
  // trajectory is that of the scene without it, and run.json says max_step_s null.
  write_scene(dir.path(), "rk4.toml",
              replace(std::string(kDropScene), "duration = 0.5", "duration = 0.5\nmax_step = 0.1"));
  write_scene(dir.path(), "plain.toml", kDropScene);
  ASSERT_EQ(run_tumble({"simulate", "rk4.toml", "--out", "a"}, dir.path()).exit_code, 0);
  ASSERT_EQ(run_tumble({"simulate", "plain.toml", "--out", "b"}, dir.path()).exit_code, 0);
  EXPECT_TRUE(read_file(dir / "a/trajectory.csv") == read_file(dir / "b/trajectory.csv"));
  const nlohmann::json j = read_json(dir / "a/run.json");
  EXPECT_TRUE(j["settings"]["simulation"]["max_step_s"].is_null());
  EXPECT_FALSE(j.contains("adaptive") && !j["adaptive"].is_null());
  const RunResult adaptive =
      run_tumble({"simulate", "rk4.toml", "--integrator", "adaptive", "--out", "c"}, dir.path());
  ASSERT_EQ(adaptive.exit_code, 0) << describe(adaptive);
  EXPECT_EQ(read_json(dir / "c/run.json")["adaptive"]["largest_step_s"], 0.1);
}

TEST(Adaptive, ToleranceOutOfRangeIsAnError) {
  const TestDir dir;
  write_scene(
      dir.path(), "drop.toml",
      replace(std::string(kDropScene), "duration = 0.5", "duration = 0.5\ntolerance = 0.5"));
  const RunResult r = run_tumble({"simulate", "drop.toml", "--out", "o"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_NE(r.err.find("drop.toml:3:13: tolerance in [simulation] must be in [1e-14, 0.1]"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace tumble_e2e
