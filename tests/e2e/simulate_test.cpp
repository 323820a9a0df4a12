// tumble simulate end to end: the default scene, the command-line overrides, scene files, and the
// contents of trajectory.csv and run.json (SPEC.md: Commands, Time, Outputs).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <regex>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

const std::regex kSha256Hex("[0-9a-f]{64}");

TEST(Simulate, DefaultSceneWritesTrajectoryAndReport) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  // stderr is not a terminal here: no progress line, and nothing went wrong.
  EXPECT_EQ(r.err, "");

  const fs::path csv_path = dir / "out/default/trajectory.csv";
  const fs::path json_path = dir / "out/default/run.json";
  ASSERT_TRUE(fs::is_regular_file(csv_path));
  ASSERT_TRUE(fs::is_regular_file(json_path));
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";

  const Csv csv = read_csv(csv_path);
  EXPECT_EQ(csv.header, kTrajectoryHeader);
  EXPECT_TRUE(csv.ends_with_newline);
  // 4 s at 60 fps: k = 0 … round(4·60) inclusive, one body.
  ASSERT_EQ(csv.rows.size(), 241u);
  for (std::size_t k = 0; k < csv.rows.size(); ++k) {
    ASSERT_EQ(csv.rows[k].size(), static_cast<std::size_t>(kColumns)) << "row " << k;
    EXPECT_EQ(csv.text(k, BODY), "box");
    EXPECT_EQ(csv.text(k, T), shortest(static_cast<double>(k) / 60.0)) << "row " << k;
  }
  // t = 0: the scene's initial state, the box 3 m up, at rest, with the scene's tilt.
  EXPECT_EQ(csv.text(0, T), "0");
  EXPECT_EQ(csv.text(0, X), "0");
  EXPECT_EQ(csv.text(0, Y), "3");
  EXPECT_EQ(csv.text(0, Z), "0");
  EXPECT_EQ(csv.text(0, VX), "0");
  EXPECT_EQ(csv.text(0, VY), "0");
  EXPECT_EQ(csv.text(0, VZ), "0");
  // 30° about (1, 0, 1)/√2: q = (cos 15°, sin 15°/√2, 0, sin 15°/√2).
  EXPECT_NEAR(csv.value(0, QW), std::cos(std::numbers::pi / 12), 1e-15);
  EXPECT_NEAR(csv.value(0, QX), std::sin(std::numbers::pi / 12) / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(csv.value(0, QY), 0.0, 1e-15);
  EXPECT_NEAR(csv.value(0, QZ), std::sin(std::numbers::pi / 12) / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(csv.value(0, WX), 0.0, 1e-12);
  EXPECT_NEAR(csv.value(0, WY), 0.0, 1e-12);
  EXPECT_NEAR(csv.value(0, WZ), 2.0, 1e-12);
  // m g y + ½ ω·Iω = 9.81·3 + ½·(1/6)·2² for a unit cube of 1 kg.
  EXPECT_NEAR(csv.value(0, ENERGY), 9.81 * 3.0 + 0.5 * (1.0 / 6.0) * 4.0, 1e-12);
  // The final state is in the trajectory, and the box has come to rest on the floor on a face.
  EXPECT_EQ(csv.rows.back()[T], "4");
  EXPECT_NEAR(csv.value(240, Y), 0.5, 1e-6);
  EXPECT_LT(csv.value(240, ENERGY), csv.value(0, ENERGY));

  nlohmann::json j = read_json(json_path);
  const std::string text = read_file(json_path);
  EXPECT_NE(text.find("\"steps\": 4000"), std::string::npos) << text;
  EXPECT_NE(text.find("\"samples\": 241"), std::string::npos) << text;
  EXPECT_EQ(j["tool"]["name"], "tumble");
  EXPECT_EQ(j["command"], "simulate");
  EXPECT_EQ(j["counts"]["steps"], 4000);
  EXPECT_EQ(j["counts"]["samples"], 241);
  EXPECT_EQ(j["counts"]["sample_rate_hz"], 60.0);
  EXPECT_EQ(j["counts"]["every_step"], false);
  EXPECT_EQ(j["settings"]["simulation"]["duration_s"], 4.0);
  EXPECT_EQ(j["settings"]["simulation"]["dt_s"], 0.001);
  EXPECT_EQ(j["settings"]["simulation"]["integrator"], "rk4");
  EXPECT_EQ(j["settings"]["render"]["fps"], 60);
  // The built-in scene is assets/scenes/default.toml, byte for byte.
  const std::string scene_sha = j["scene"]["sha256"].get<std::string>();
  EXPECT_TRUE(std::regex_match(scene_sha, kSha256Hex)) << scene_sha;
  EXPECT_EQ(scene_sha, system_sha256(source_dir() / "assets/scenes/default.toml"));
  // Energies agree with the CSV's first and last rows.
  EXPECT_EQ(j["physics"]["energy_start_J"].get<double>(), csv.value(0, ENERGY));
  EXPECT_EQ(j["physics"]["energy_end_J"].get<double>(), csv.value(240, ENERGY));
  EXPECT_GT(j["physics"]["contacts"].get<long>(), 0);
  // Outputs: the trajectory, with the SHA-256 of its bytes.
  ASSERT_TRUE(j["outputs"].is_array());
  ASSERT_EQ(j["outputs"].size(), 1u);
  EXPECT_EQ(j["outputs"][0]["path"], "out/default/trajectory.csv");
  const std::string csv_sha = j["outputs"][0]["sha256"].get<std::string>();
  EXPECT_TRUE(std::regex_match(csv_sha, kSha256Hex)) << csv_sha;
  EXPECT_EQ(csv_sha, system_sha256(csv_path));
  // The body: 1 kg unit cube, moments 1/6.
  ASSERT_EQ(j["bodies"].size(), 1u);
  EXPECT_EQ(j["bodies"][0]["name"], "box");
  EXPECT_EQ(j["bodies"][0]["mass_kg"], 1.0);
  for (const auto& moment : j["bodies"][0]["principal_moments_kg_m2"])
    EXPECT_NEAR(moment.get<double>(), 1.0 / 6.0, 1e-15);

  // Not quiet: one line on stdout naming both files.
  EXPECT_NE(r.out.find("out/default/trajectory.csv"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("out/default/run.json"), std::string::npos) << r.out;
}

TEST(Simulate, OutOptionChoosesTheFolder) {
  const TestDir dir;
  const RunResult r =
      run_tumble({"simulate", "--out", "results/a b", "--duration", "0.5"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(fs::is_regular_file(dir / "results/a b/trajectory.csv"));
  EXPECT_TRUE(fs::is_regular_file(dir / "results/a b/run.json"));
  EXPECT_FALSE(fs::exists(dir / "out")) << "the default folder was made although --out was given";
  nlohmann::json j = read_json(dir / "results/a b/run.json");
  EXPECT_EQ(j["outputs"][0]["path"], "results/a b/trajectory.csv");
  EXPECT_EQ(j["outputs"][0]["sha256"], system_sha256(dir / "results/a b/trajectory.csv"));
}

TEST(Simulate, RateOptionSetsTheSampleTimes) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate", "--rate", "24", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Csv csv = read_csv(dir / "o/trajectory.csv");
  ASSERT_EQ(csv.rows.size(), 97u);  // round(4·24) + 1
  for (std::size_t k = 0; k < csv.rows.size(); ++k)
    EXPECT_EQ(csv.text(k, T), shortest(static_cast<double>(k) / 24.0)) << "row " << k;
  EXPECT_EQ(csv.rows.back()[T], "4");
  nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["counts"]["samples"], 97);
  EXPECT_EQ(j["counts"]["sample_rate_hz"], 24.0);
  EXPECT_EQ(j["counts"]["steps"], 4000);
  EXPECT_EQ(j["settings"]["render"]["fps"], 60) << "--rate must not change the scene's fps";
}

TEST(Simulate, FpsOptionIsTheDefaultRate) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate", "--fps", "30", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Csv csv = read_csv(dir / "o/trajectory.csv");
  ASSERT_EQ(csv.rows.size(), 121u);  // round(4·30) + 1
  EXPECT_EQ(csv.text(1, T), shortest(1.0 / 30.0));
  nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["settings"]["render"]["fps"], 30);
  EXPECT_EQ(j["counts"]["sample_rate_hz"], 30.0);
}

TEST(Simulate, EveryStepSamplesEveryStepBoundary) {
  const TestDir dir;
  const RunResult r = run_tumble(
      {"simulate", "--every-step", "--duration", "0.5", "--dt", "0.002", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Csv csv = read_csv(dir / "o/trajectory.csv");
  // 0.5 / 0.002 = 250 steps: 251 boundaries, t = 0 and the end included.
  ASSERT_EQ(csv.rows.size(), 251u);
  EXPECT_EQ(csv.text(0, T), "0");
  for (std::size_t k = 0; k + 1 < csv.rows.size(); ++k)
    EXPECT_EQ(csv.text(k, T), shortest(static_cast<double>(k) * 0.002)) << "row " << k;
  EXPECT_EQ(csv.rows.back()[T], "0.5");
  nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["counts"]["steps"], 250);
  EXPECT_EQ(j["counts"]["samples"], 251);
  EXPECT_EQ(j["counts"]["every_step"], true);
  EXPECT_EQ(j["counts"]["sample_rate_hz"], 500.0);
  EXPECT_EQ(j["settings"]["simulation"]["dt_s"], 0.002);
  EXPECT_EQ(j["settings"]["simulation"]["duration_s"], 0.5);
}

TEST(Simulate, EveryStepOnTheDefaultSceneHasStepsPlusOneRows) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate", "--every-step", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Csv csv = read_csv(dir / "o/trajectory.csv");
  ASSERT_EQ(csv.rows.size(), 4001u);
  EXPECT_EQ(csv.rows.back()[T], "4");
  nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["counts"]["steps"], 4000);
  EXPECT_EQ(j["counts"]["samples"], 4001);
}

TEST(Simulate, DurationOptionShortensTheRun) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate", "--duration", "0.5", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Csv csv = read_csv(dir / "o/trajectory.csv");
  ASSERT_EQ(csv.rows.size(), 31u);  // round(0.5·60) + 1
  EXPECT_EQ(csv.rows.back()[T], "0.5");
  nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["settings"]["simulation"]["duration_s"], 0.5);
  EXPECT_EQ(j["counts"]["steps"], 500);
  EXPECT_EQ(j["counts"]["samples"], 31);
}

TEST(Simulate, DtOptionSetsTheStep) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate", "--dt", "0.002", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["settings"]["simulation"]["dt_s"], 0.002);
  EXPECT_EQ(j["counts"]["steps"], 2000);
  EXPECT_EQ(j["counts"]["samples"], 241);  // the sample times do not depend on dt
  EXPECT_EQ(read_csv(dir / "o/trajectory.csv").rows.size(), 241u);
}

TEST(Simulate, IntegratorOptionChangesTheScheme) {
  const TestDir dir;
  const RunResult rk4 = run_tumble({"simulate", "--out", "rk4"}, dir.path());
  const RunResult mid =
      run_tumble({"simulate", "--integrator", "midpoint", "--out", "mid"}, dir.path());
  ASSERT_EQ(rk4.exit_code, 0) << describe(rk4);
  ASSERT_EQ(mid.exit_code, 0) << describe(mid);
  EXPECT_EQ(read_json(dir / "mid/run.json")["settings"]["simulation"]["integrator"], "midpoint");
  EXPECT_EQ(read_json(dir / "rk4/run.json")["settings"]["simulation"]["integrator"], "rk4");
  const Csv a = read_csv(dir / "rk4/trajectory.csv"), b = read_csv(dir / "mid/trajectory.csv");
  ASSERT_EQ(a.rows.size(), b.rows.size());
  EXPECT_NE(a.rows, b.rows) << "--integrator midpoint gave the rk4 trajectory";
  // Both integrate the same physics: the box ends resting on the floor either way.
  EXPECT_NEAR(b.value(b.rows.size() - 1, Y), 0.5, 1e-3);
}

TEST(Simulate, SizeOptionDoesNotChangeTheTrajectory) {
  const TestDir dir;
  const RunResult a = run_tumble({"simulate", "--out", "a"}, dir.path());
  const RunResult b = run_tumble({"simulate", "--size", "64x48", "--out", "b"}, dir.path());
  ASSERT_EQ(a.exit_code, 0) << describe(a);
  ASSERT_EQ(b.exit_code, 0) << describe(b);
  nlohmann::json j = read_json(dir / "b/run.json");
  EXPECT_EQ(j["settings"]["render"]["width"], 64);
  EXPECT_EQ(j["settings"]["render"]["height"], 48);
  EXPECT_EQ(read_file(dir / "a/trajectory.csv"), read_file(dir / "b/trajectory.csv"));
}

TEST(Simulate, SceneFileDefaultsToOutSlashStem) {
  const TestDir dir;
  // A name with a space and a quote: passed as one argument, never through a shell.
  write_scene(dir.path(), "it's a drop.toml",
              "[simulation]\nduration = 0.25\n[[body]]\nshape = \"particle\"\nmass = 1.0\n");
  const RunResult r = run_tumble({"simulate", "it's a drop.toml"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  ASSERT_TRUE(fs::is_regular_file(dir / "out/it's a drop/trajectory.csv"));
  nlohmann::json j = read_json(dir / "out/it's a drop/run.json");
  EXPECT_EQ(j["scene"]["path"], "it's a drop.toml");
  EXPECT_EQ(j["scene"]["sha256"], system_sha256(dir / "it's a drop.toml"));
  const Csv csv = read_csv(dir / "out/it's a drop/trajectory.csv");
  ASSERT_EQ(csv.rows.size(), 16u);        // round(0.25·60) + 1
  EXPECT_EQ(csv.text(0, BODY), "body1");  // an unnamed body is named by its place
}

// Command-line options override the scene file (SPEC.md: "Common options override the scene
// file"), so a scene is valid or not by its settings after the overrides: a file whose duration is
// shorter than the default dt runs when the command line gives a longer duration or a finer dt.
TEST(Simulate, OverridesApplyBeforeTheDtDurationCheck) {
  const TestDir dir;
  write_scene(dir.path(), "short.toml",
              "[simulation]\nduration = 0.0005\n[[body]]\nshape = \"particle\"\nmass = 1.0\n");
  {
    const RunResult r =
        run_tumble({"simulate", "short.toml", "--duration", "0.01", "--out", "a"}, dir.path());
    EXPECT_EQ(r.exit_code, 0) << "effective dt = 0.001 s <= duration = 0.01 s\n" << describe(r);
    EXPECT_EQ(read_csv(dir / "a/trajectory.csv").rows.size(), 2u);  // round(0.01·60) + 1
  }
  {
    const RunResult r =
        run_tumble({"simulate", "short.toml", "--dt", "0.0001", "--out", "b"}, dir.path());
    EXPECT_EQ(r.exit_code, 0) << "effective dt = 1e-4 s <= duration = 5e-4 s\n" << describe(r);
    EXPECT_EQ(read_json(dir / "b/run.json")["counts"]["steps"], 5);
  }
}

// Two bodies, no floor: a particle in free fall and a spinning box. RK4 integrates a constant
// acceleration exactly, so positions match the closed form to rounding; energy is conserved.
TEST(Simulate, TwoBodiesInFreeFallFollowTheClosedForm) {
  const TestDir dir;
  write_scene(dir.path(), "two.toml", R"([simulation]
duration = 1.0

[[body]]
name = "ball"
shape = "particle"
mass = 2.0
position = [1.0, 10.0, -1.0]
velocity = [0.5, 3.0, 0.0]

[[body]]
name = "crate"
shape = "box"
size = [1.0, 2.0, 3.0]
density = 10.0
position = [0.0, 5.0, 0.0]
angular_velocity = [1.0, 0.0, 0.0]
)");
  const RunResult r = run_tumble({"simulate", "two.toml", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Csv csv = read_csv(dir / "o/trajectory.csv");
  ASSERT_EQ(csv.rows.size(), 2u * 61u);  // one row per body per sample, bodies in file order
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    EXPECT_EQ(csv.text(i, BODY), i % 2 == 0 ? "ball" : "crate") << "row " << i;
    EXPECT_EQ(csv.text(i, T), csv.text(i - i % 2, T)) << "row " << i;
  }
  const std::size_t ball_end = csv.rows.size() - 2, crate_end = csv.rows.size() - 1;
  EXPECT_EQ(csv.text(ball_end, T), "1");
  EXPECT_NEAR(csv.value(ball_end, X), 1.5, 1e-12);
  EXPECT_NEAR(csv.value(ball_end, Y), 10.0 + 3.0 - 0.5 * 9.81, 1e-12);
  EXPECT_NEAR(csv.value(ball_end, Z), -1.0, 1e-12);
  EXPECT_NEAR(csv.value(ball_end, VY), 3.0 - 9.81, 1e-12);
  EXPECT_NEAR(csv.value(crate_end, Y), 5.0 - 0.5 * 9.81, 1e-12);
  // Particle energy: m g y + ½ m v² = 2·9.81·10 + ½·2·(0.25 + 9).
  EXPECT_NEAR(csv.value(0, ENERGY), 2.0 * 9.81 * 10.0 + 9.25, 1e-9);
  for (std::size_t i = 2; i < csv.rows.size(); ++i)
    EXPECT_NEAR(csv.value(i, ENERGY), csv.value(i % 2, ENERGY), 1e-9 * csv.value(i % 2, ENERGY))
        << "energy drifts in row " << i;
  // Spin about the x axis (the largest moment) stays about x.
  EXPECT_NEAR(csv.value(crate_end, WX), 1.0, 1e-9);

  nlohmann::json j = read_json(dir / "o/run.json");
  ASSERT_EQ(j["bodies"].size(), 2u);
  EXPECT_EQ(j["bodies"][0]["name"], "ball");
  EXPECT_EQ(j["bodies"][0]["shape"], "particle");
  EXPECT_EQ(j["bodies"][0]["mass_kg"], 2.0);
  EXPECT_EQ(j["bodies"][1]["name"], "crate");
  EXPECT_DOUBLE_EQ(j["bodies"][1]["mass_kg"].get<double>(), 60.0);  // 10 kg/m³ · 6 m³
  // m(b² + c²)/12 etc. for edges 1, 2, 3 and 60 kg: 65, 50, 25.
  const auto& moments = j["bodies"][1]["principal_moments_kg_m2"];
  ASSERT_EQ(moments.size(), 3u);
  EXPECT_NEAR(moments[0].get<double>(), 65.0, 1e-12);
  EXPECT_NEAR(moments[1].get<double>(), 50.0, 1e-12);
  EXPECT_NEAR(moments[2].get<double>(), 25.0, 1e-12);
  EXPECT_EQ(j["settings"]["floor"], nullptr);
  EXPECT_EQ(j["counts"]["samples"], 61);
}

TEST(Simulate, EveryExampleSceneRuns) {
  const TestDir dir;
  const std::vector<fs::path> scenes = example_scenes();
  ASSERT_GE(scenes.size(), 5u);
  for (const fs::path& scene : scenes) {
    SCOPED_TRACE(scene.string());
    const RunResult r = run_tumble({"simulate", scene.string(), "--duration", "0.5"}, dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(r.err, "");
    const fs::path out = dir / "out" / scene.stem();
    const Csv csv = read_csv(out / "trajectory.csv");
    EXPECT_EQ(csv.header, kTrajectoryHeader);
    nlohmann::json j = read_json(out / "run.json");
    const long samples = j["counts"]["samples"].get<long>();
    EXPECT_EQ(samples, std::lround(0.5 * j["settings"]["render"]["fps"].get<double>()) + 1);
    EXPECT_EQ(static_cast<long>(csv.rows.size()), samples * static_cast<long>(j["bodies"].size()));
    EXPECT_EQ(csv.rows.back()[T], "0.5");
    EXPECT_EQ(j["scene"]["sha256"], system_sha256(scene));
    EXPECT_EQ(j["outputs"][0]["sha256"], system_sha256(out / "trajectory.csv"));
    for (const auto& row : csv.rows)
      for (int c = X; c < kColumns; ++c)
        ASSERT_TRUE(std::isfinite(std::strtod(row[static_cast<std::size_t>(c)].c_str(), nullptr)))
            << "non-finite value in column " << c;
  }
}

}  // namespace
}  // namespace tumble_e2e
