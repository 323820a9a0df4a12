// Where outputs go and what a failure leaves behind (SPEC.md: Exit codes and errors, "Nothing is
// ever half-written"): an output folder that cannot be made is exit 3 with the path named; a
// failed run leaves no trajectory under its final name and never replaces a previous good one.
#include <gtest/gtest.h>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

constexpr std::string_view kGoodScene = kDropScene;

TEST(Environment, OutUnderARegularFileIsExit3) {
  const TestDir dir;
  write_file(dir / "blocker", "not a folder\n");
  const RunResult r =
      run_tumble({"simulate", "--out", "blocker/sub", "--duration", "0.5"}, dir.path());
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
  EXPECT_NE(r.err.find("blocker/sub"), std::string::npos) << "the path is not named: " << r.err;
  EXPECT_TRUE(find_files_named(dir.path(), "trajectory.csv").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "run.json").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "").empty());
  EXPECT_EQ(read_file(dir / "blocker"), "not a folder\n");
}

TEST(Environment, OutIsARegularFileIsExit3) {
  const TestDir dir;
  write_file(dir / "blocker", "x");
  const RunResult r = run_tumble({"simulate", "--out", "blocker", "--duration", "0.5"}, dir.path());
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_NE(r.err.find("blocker"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(dir / "blocker"), "x");
}

TEST(Environment, UnwritableLocationIsExit3) {
  const TestDir dir;
  const RunResult r =
      run_tumble({"simulate", "--out", "/proc/tumble-x", "--duration", "0.5"}, dir.path());
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
  EXPECT_NE(r.err.find("/proc/tumble-x"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists("/proc/tumble-x"));
}

TEST(Environment, TrajectoryPathTakenByAFolderIsExit3) {
  // The final rename cannot replace a folder: exit 3, and the temporary is cleaned up.
  const TestDir dir;
  fs::create_directories(dir / "o/trajectory.csv");
  const RunResult r = run_tumble({"simulate", "--out", "o", "--duration", "0.5"}, dir.path());
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_NE(r.err.find("trajectory.csv"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_directory(dir / "o/trajectory.csv"));
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";
  EXPECT_FALSE(fs::exists(dir / "o/run.json"));
}

TEST(NothingHalfWritten, FailedRunWritesNoTrajectory) {
  const TestDir dir;
  write_scene(dir.path(), "bad.toml",
              replace(std::string(kGoodScene), "mass = 1.0", "mass = -1.0"));
  fs::create_directories(dir / "o");
  const RunResult r = run_tumble({"simulate", "bad.toml", "--out", "o"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(fs::is_empty(dir / "o")) << "the failed run left files in its output folder";
  EXPECT_TRUE(find_files_named(dir.path(), "trajectory.csv").empty());
  // Without --out: the default folder gets no trajectory either.
  const RunResult r2 = run_tumble({"simulate", "bad.toml"}, dir.path());
  EXPECT_EQ(r2.exit_code, 2) << describe(r2);
  EXPECT_FALSE(fs::exists(dir / "out/bad/trajectory.csv"));
  EXPECT_TRUE(find_files_named(dir.path(), "").empty());
}

TEST(NothingHalfWritten, FailedRunKeepsThePreviousGoodOutput) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml", kGoodScene);
  const RunResult good = run_tumble({"simulate", "scene.toml", "--out", "o"}, dir.path());
  ASSERT_EQ(good.exit_code, 0) << describe(good);
  const std::string csv = read_file(dir / "o/trajectory.csv");
  const std::string json = read_file(dir / "o/run.json");
  ASSERT_EQ(read_csv(dir / "o/trajectory.csv").rows.size(), 31u);

  // The same scene, now broken in several ways, and bad command lines, into the same folder.
  const std::vector<std::pair<std::string, std::vector<std::string>>> failures = {
      {replace(std::string(kGoodScene), "mass = 1.0", "mass = -1.0"), {}},
      {std::string(kGoodScene) + "restitusion = 0.5\n", {}},
      {replace(std::string(kGoodScene), "[0.0, 3.0, 0.0]", "[0.0, 0.2, 0.0]"), {}},
      {std::string(kGoodScene) + "oops = = 1\n", {}},
      {std::string(kGoodScene), {"--rate", "0"}},
      {std::string(kGoodScene), {"--fps", "0"}},
      {std::string(kGoodScene), {"--integrator", "rk5"}},
  };
  for (const auto& [text, extra] : failures) {
    SCOPED_TRACE(text + (extra.empty() ? "" : " with " + extra[0] + " " + extra[1]));
    write_scene(dir.path(), "scene.toml", text);
    std::vector<std::string> args = {"simulate", "scene.toml", "--out", "o"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult bad = run_tumble(args, dir.path());
    EXPECT_EQ(bad.exit_code, 2) << describe(bad);
    EXPECT_TRUE(read_file(dir / "o/trajectory.csv") == csv) << "trajectory.csv was changed";
    EXPECT_TRUE(read_file(dir / "o/run.json") == json) << "run.json was changed";
    EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";
  }
}

// A run stopped part-way (Ctrl-C, a CI timeout) leaves no trajectory under the final name and the
// previous good files untouched.
TEST(NothingHalfWritten, InterruptedRunKeepsThePreviousGoodOutput) {
  const TestDir dir;
  const std::string scene = (source_dir() / "assets/scenes/tumble_intermediate_axis.toml").string();
  const RunResult good =
      run_tumble({"simulate", scene, "--out", "o", "--duration", "1", "--quiet"}, dir.path());
  ASSERT_EQ(good.exit_code, 0) << describe(good);
  const std::string csv = read_file(dir / "o/trajectory.csv");
  const std::string json = read_file(dir / "o/run.json");
  for (const int signal : {SIGINT, SIGTERM}) {
    SCOPED_TRACE("signal " + std::to_string(signal));
    RunOptions options;
    options.signal = signal;
    options.signal_after = std::chrono::milliseconds(300);
    // A free tumble for 10^5 s takes minutes; it is stopped after 0.3 s.
    const RunResult stopped = run_tumble(
        {"simulate", scene, "--out", "o", "--duration", "100000", "--rate", "100", "--quiet"},
        dir.path(), options);
    EXPECT_NE(stopped.exit_code, 0) << describe(stopped);
    EXPECT_FALSE(stopped.timed_out);
    EXPECT_TRUE(read_file(dir / "o/trajectory.csv") == csv) << "trajectory.csv was changed";
    EXPECT_TRUE(read_file(dir / "o/run.json") == json) << "run.json was changed";
  }
}

TEST(NothingHalfWritten, SuccessfulRunReplacesThePreviousOutput) {
  // The other side of the contract: a good run does replace what was there, atomically.
  const TestDir dir;
  write_file(dir / "o/trajectory.csv", "stale\n");
  write_file(dir / "o/run.json", "{}\n");
  const RunResult r = run_tumble({"simulate", "--out", "o", "--duration", "0.5"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(read_csv(dir / "o/trajectory.csv").header, kTrajectoryHeader);
  EXPECT_EQ(read_json(dir / "o/run.json")["counts"]["samples"], 31);
  EXPECT_TRUE(find_files_named(dir.path(), "").empty());
}

}  // namespace
}  // namespace tumble_e2e
