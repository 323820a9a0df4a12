// Bad input, one test per kind (SPEC.md: Exit codes and errors; docs/scene.md: Errors): exit code
// 2, nothing on stdout, no output written, and one message on stderr,
// `tumble: error: FILE:LINE:COLUMN: message` when it points into a file, else
// `tumble: error: message`.
#include <gtest/gtest.h>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

// Line numbers the tests below rely on:        line
constexpr std::string_view kScene = kDropScene;
//  1 [simulation]   2 duration   3 [floor]   4 [[body]]   5 name   6 shape   7 size   8 mass
//  9 position       10: what a test appends

std::string first_line(const std::string& s) {
  return s.substr(0, s.find('\n'));
}

/// Runs `tumble simulate SCENE_NAME [extra...] --out o` in `dir`.
RunResult simulate(const TestDir& dir, const std::string& scene_name,
                   std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"simulate"};
  if (!scene_name.empty()) args.push_back(scene_name);
  args.insert(args.end(), extra.begin(), extra.end());
  args.push_back("--out");
  args.push_back("o");
  return run_tumble(args, dir.path());
}

/// Exit code 2, stdout empty, no trajectory anywhere under `dir`, and stderr's first line is
/// `tumble: error: ` + `where` + `: ` (`where` = FILE:LINE:COLUMN) followed by a message holding
/// every one of `parts`. With `where` empty, the message must start with `parts[0]`.
void expect_bad_input(const RunResult& r, const TestDir& dir, const std::string& where,
                      const std::vector<std::string>& parts) {
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_EQ(r.out, "") << describe(r);
  const std::string line = first_line(r.err);
  const std::string prefix = "tumble: error: " + (where.empty() ? "" : where + ": ");
  EXPECT_TRUE(line.starts_with(prefix)) << "expected \"" << prefix << "...\", got: " << r.err;
  if (where.empty() && !parts.empty()) {
    EXPECT_TRUE(line.starts_with(prefix + parts.front())) << r.err;
  }
  for (const std::string& part : parts) {
    EXPECT_NE(line.find(part), std::string::npos) << "\"" << part << "\" not in: " << r.err;
  }
  EXPECT_TRUE(find_files_named(dir.path(), "trajectory.csv").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "run.json").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";
}

TEST(BadInput, GoodBaseSceneRuns) {
  // The scene the other tests break, unbroken, runs: their failures are the change they make.
  const TestDir dir;
  write_scene(dir.path(), "scene.toml", kScene);
  const RunResult r = simulate(dir, "scene.toml");
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(read_csv(dir / "o/trajectory.csv").rows.size(), 31u);
}

TEST(BadInput, MissingSceneFile) {
  const TestDir dir;
  const RunResult r = simulate(dir, "missing.toml");
  expect_bad_input(r, dir, "", {"cannot read scene file \"missing.toml\": ", "No such file"});
}

TEST(BadInput, SceneFileIsAFolder) {
  const TestDir dir;
  fs::create_directories(dir / "folder.toml");
  const RunResult r = simulate(dir, "folder.toml");
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(
      first_line(r.err).starts_with("tumble: error: cannot read scene file \"folder.toml\""))
      << r.err;
}

TEST(BadInput, TomlSyntaxError) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml", std::string(kScene) + "restitution = = 0.5\n");
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:10:15", {"TOML syntax error"});
}

TEST(BadInput, UnknownKeySuggestsTheNearestKey) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml", std::string(kScene) + "restitusion = 0.5\n");
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:10:1",
                   {"unknown key \"restitusion\" in [[body]]", "(did you mean \"restitution\"?)"});
}

TEST(BadInput, UnknownTableSuggestsTheNearestTable) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml", replace(std::string(kScene), "[floor]", "[flor]"));
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:3:2",
                   {"unknown table [flor]", "did you mean \"floor\""});
}

TEST(BadInput, ErrorNamesTheSceneFileAsGiven) {
  const TestDir dir;
  write_scene(dir.path(), "scenes/drop.toml", std::string(kScene) + "restitusion = 0.5\n");
  expect_bad_input(simulate(dir, "scenes/drop.toml"), dir, "scenes/drop.toml:10:1",
                   {"restitusion"});
}

TEST(BadInput, StringForMass) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml",
              replace(std::string(kScene), "mass = 1.0", "mass = \"heavy\""));
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:8:8",
                   {"mass", "must be a number", "string"});
}

TEST(BadInput, FloatForIntegerFps) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml", std::string(kScene) + "[render]\nfps = 60.0\n");
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:11:7", {"fps", "integer"});
}

TEST(BadInput, NegativeMass) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml", replace(std::string(kScene), "mass = 1.0", "mass = -1.0"));
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:8:8", {"mass", "> 0", "-1"});
}

TEST(BadInput, RestitutionAboveOne) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml", std::string(kScene) + "restitution = 1.5\n");
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:10:15",
                   {"restitution", "[0, 1]", "1.5"});
}

TEST(BadInput, ZeroDt) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml",
              replace(std::string(kScene), "duration = 0.5", "duration = 0.5\ndt = 0"));
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:3:6", {"dt", "> 0"});
}

TEST(BadInput, NanMass) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml", replace(std::string(kScene), "mass = 1.0", "mass = nan"));
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:8:8", {"mass", "finite"});
}

TEST(BadInput, InfinitePosition) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml",
              replace(std::string(kScene), "[0.0, 3.0, 0.0]", "[0.0, inf, 0.0]"));
  const RunResult r = simulate(dir, "scene.toml");
  // The message points at the vector or at its element: line 9 either way.
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(first_line(r.err).starts_with("tumble: error: scene.toml:9:")) << r.err;
  EXPECT_NE(first_line(r.err).find("finite"), std::string::npos) << r.err;
}

TEST(BadInput, UnknownIntegratorInTheFile) {
  const TestDir dir;
  write_scene(
      dir.path(), "scene.toml",
      replace(std::string(kScene), "duration = 0.5", "duration = 0.5\nintegrator = \"rk5\""));
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:3:14",
                   {"unknown integrator \"rk5\"", "euler, symplectic-euler, midpoint, rk4"});
}

TEST(BadInput, UnknownIntegratorOnTheCommandLine) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--integrator", "rk5"}), dir, "",
                   {"unknown integrator \"rk5\"", "euler, symplectic-euler, midpoint, rk4"});
}

TEST(BadInput, BodyStartsInsideTheFloor) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml",
              replace(std::string(kScene), "[0.0, 3.0, 0.0]", "[0.0, 0.2, 0.0]"));
  // Points at the body's [[body]] header, names the body and says how deep it is.
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:4:1",
                   {"body \"box\"", "inside the floor", "0.3"});
}

TEST(BadInput, MissingMass) {
  const TestDir dir;
  write_scene(dir.path(), "scene.toml", replace(std::string(kScene), "mass = 1.0\n", ""));
  expect_bad_input(simulate(dir, "scene.toml"), dir, "scene.toml:4:1",
                   {"missing key \"mass\" or \"density\" in [[body]]"});
}

TEST(BadInput, ZeroSize) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--size", "0x0"}), dir, "", {"--size", "0x0"});
}

TEST(BadInput, HugeSize) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--size", "100000x100000"}), dir, "",
                   {"--size", "100000x100000", "16384"});
}

TEST(BadInput, MalformedSize) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--size", "1280*720"}), dir, "", {"--size"});
}

TEST(BadInput, ZeroFps) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--fps", "0"}), dir, "", {"--fps"});
}

TEST(BadInput, NegativeDuration) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--duration", "-1"}), dir, "", {"--duration"});
}

TEST(BadInput, NanDuration) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--duration", "nan"}), dir, "", {"--duration"});
}

TEST(BadInput, ZeroDtOnTheCommandLine) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--dt", "0"}), dir, "", {"--dt"});
}

TEST(BadInput, DtLongerThanTheRun) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--duration", "0.5", "--dt", "1"}), dir, "",
                   {"the step dt", "longer than the run"});
}

TEST(BadInput, DtLongerThanAShortRunSaysHowLongTheRunIs) {
  // The message must give the numbers the user typed, not round them away: here it said
  // "the step dt = 0.000001 s is longer than the run (0.000000 s)".
  const TestDir dir;
  const RunResult r = simulate(dir, "", {"--duration", "1e-7", "--dt", "1e-6"});
  expect_bad_input(r, dir, "", {"the step dt"});
  EXPECT_EQ(first_line(r.err).find("0.000000"), std::string::npos)
      << "a run of 1e-7 s is reported as 0 s long: " << r.err;
}

// docs/scene.md's "Errors" examples are what tumble prints: each message there (after its
// FILE:LINE:COLUMN) is the message of a scene made to have that mistake.
TEST(BadInput, SceneDocExamplesAreTheRealMessages) {
  const std::string doc = read_file(source_dir() / "docs/scene.md");
  std::size_t at = doc.find("\n## Errors\n");
  ASSERT_NE(at, std::string::npos);
  at = doc.find("```\n", at) + 4;
  const std::vector<std::string> examples = split(doc.substr(at, doc.find("```", at) - at), '\n');
  const std::vector<std::string> scenes = {
      "[[body]]\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\nrestitusion = 0.5\n",
      "[simulation]\nintegrator = \"rk5\"\n[[body]]\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\n"
      "mass = 1.0\n",
      "[render]\nfps = 0\n[[body]]\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\n",
      "[[body]]\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\n"};
  std::size_t checked = 0;
  for (std::size_t i = 0; i < examples.size(); ++i) {
    if (examples[i].empty()) continue;
    ASSERT_LT(checked, scenes.size()) << "a new example needs its scene here: " << examples[i];
    // "drop.toml:14:1: message" -> "message"
    const std::size_t colon = examples[i].find(": ");
    ASSERT_NE(colon, std::string::npos) << examples[i];
    const TestDir dir;
    write_file(dir / "drop.toml", scenes[checked]);
    const RunResult r = simulate(dir, "drop.toml");
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    const std::string printed = first_line(r.err);
    EXPECT_TRUE(printed.ends_with(": " + examples[i].substr(colon + 2)))
        << "docs/scene.md says: " << examples[i] << "\ntumble prints: " << printed;
    ++checked;
  }
  EXPECT_EQ(checked, scenes.size());
}

TEST(BadInput, ZeroRate) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--rate", "0"}), dir, "", {"--rate"});
}

TEST(BadInput, UnknownOption) {
  const TestDir dir;
  expect_bad_input(simulate(dir, "", {"--bogus"}), dir, "", {});
  // Names the option it did not understand.
  const RunResult r = simulate(dir, "", {"--bogus"});
  EXPECT_NE(first_line(r.err).find("--bogus"), std::string::npos) << r.err;
}

TEST(BadInput, NoSubcommand) {
  const TestDir dir;
  const RunResult r = run_tumble({}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(BadInput, UnknownSubcommand) {
  // Named, with the real ones listed (CLI11 alone says "A subcommand is required").
  const TestDir dir;
  const RunResult r = run_tumble({"frobnicate"}, dir.path());
  expect_bad_input(r, dir, "",
                   {"unknown subcommand \"frobnicate\"; the subcommands are render, simulate, "
                    "study, sweep, info, diff"});
  EXPECT_EQ(r.err.find("A subcommand is required"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
  // A typo gets the subcommand that was probably meant.
  const RunResult typo = run_tumble({"rendr", "--size", "64x48"}, dir.path());
  expect_bad_input(typo, dir, "", {"unknown subcommand \"rendr\" (did you mean \"render\"?)"});
}

// An empty value would read as the option left out (--out "" silently meant out/default/).
TEST(BadInput, EmptyOptionValues) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"simulate", "--out", ""},
                                             {"render", "--no-mp4", "--still", "0", "--out", ""},
                                             {"simulate", "--size", ""},
                                             {"simulate", "--integrator", ""},
                                             {"study", "--integrators", ""},
                                             {"study", "--dts", ""},
                                             {"study", "--tolerances", ""}}) {
    SCOPED_TRACE(args[0] + " " + args[args.size() - 2]);
    const TestDir dir;
    const RunResult r = run_tumble(args, dir.path());
    expect_bad_input(r, dir, "", {args[args.size() - 2], "an empty value"});
    EXPECT_FALSE(fs::exists(dir / "out")) << "ran into the default folder";
  }
}

TEST(BadInput, RateAndEveryStepTogether) {
  const TestDir dir;
  const RunResult r = simulate(dir, "", {"--rate", "30", "--every-step"});
  expect_bad_input(r, dir, "", {"--rate excludes --every-step"});
  const RunResult reversed = simulate(dir, "", {"--every-step", "--rate", "30"});
  expect_bad_input(reversed, dir, "", {"--rate excludes --every-step"});
}

}  // namespace
}  // namespace tumble_e2e
