// Mesh bodies end to end (SPEC.md: [[body]] with mesh, scale, repair; run.json per-body mass
// properties; exit 2 for a bad mesh): the example scene simulates and renders, paths are taken
// relative to the scene file, and a broken model is an error naming it and the body.
#include <gtest/gtest.h>

#include <cmath>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

std::string mesh_scene(const std::string& mesh_line, const std::string& extra = "") {
  return "[floor]\n[[body]]\nname = \"m\"\nshape = \"mesh\"\n" + mesh_line +
         "\ndensity = 1000.0\nposition = [0.0, 2.0, 0.0]\n" + extra;
}

TEST(Meshes, ExampleSceneSimulatesWithMassPropertiesInRunJson) {
  const TestDir dir;
  const RunResult r =
      run_tumble({"simulate", (source_dir() / "assets/scenes/meshes.toml").string(), "--out", "o"},
                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.err, "");  // no diagnostics: the example runs clean
  const nlohmann::json j = read_json(dir / "o/run.json");
  ASSERT_EQ(j["bodies"].size(), 3u);
  const nlohmann::json& l = j["bodies"][0];
  EXPECT_EQ(l["name"], "lshape");
  EXPECT_EQ(l["shape"], "mesh");
  // 0.375 m³ at 700 kg/m³; centre of mass (5/12, 5/12, 1/4) in the file.
  EXPECT_NEAR(l["mass_kg"].get<double>(), 262.5, 1e-9);
  EXPECT_NEAR(l["mesh"]["volume_m3"].get<double>(), 0.375, 1e-12);
  EXPECT_NEAR(l["com_offset_m"][0].get<double>(), 5.0 / 12.0, 1e-12);
  EXPECT_NEAR(l["com_offset_m"][2].get<double>(), 0.25, 1e-12);
  EXPECT_EQ(l["mesh"]["hull_vertices"], 10);
  EXPECT_EQ(l["mesh"]["repair"], "none");
  EXPECT_EQ(l["mesh"]["principal_axes"].size(), 3u);
  // The die is scaled by 0.8: its volume is 0.8³ of the file's.
  EXPECT_EQ(j["bodies"][1]["shape"], "mesh");
  EXPECT_GT(j["bodies"][2]["principal_moments_kg_m2"][0].get<double>(), 0.0);
}

TEST(Meshes, PathIsRelativeToTheSceneFileNotTheWorkingFolder) {
  const TestDir dir;
  fs::create_directories(dir / "scenes/models");
  fs::copy_file(source_dir() / "assets/meshes/cube.stl", dir / "scenes/models/cube.stl");
  write_scene(dir / "scenes", "s.toml", mesh_scene("mesh = \"models/cube.stl\""));
  const RunResult r =
      run_tumble({"simulate", "scenes/s.toml", "--out", "o", "--duration", "0.5"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_NEAR(read_json(dir / "o/run.json")["bodies"][0]["mass_kg"].get<double>(), 1000.0, 1e-9);
}

TEST(Meshes, ScalePerAxisScalesTheVolume) {
  const TestDir dir;
  write_scene(dir.path(), "s.toml",
              mesh_scene("mesh = \"" + (source_dir() / "assets/meshes/cube.obj").string() + "\"",
                         "scale = [0.1, 0.2, 0.5]\n"));
  const RunResult r =
      run_tumble({"simulate", "s.toml", "--out", "o", "--duration", "0.5"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_NEAR(j["bodies"][0]["mesh"]["volume_m3"].get<double>(), 0.01, 1e-15);
  EXPECT_NEAR(j["bodies"][0]["mass_kg"].get<double>(), 10.0, 1e-12);
}

TEST(Meshes, RendersTheModel) {
  const TestDir dir;
  const RunResult r = run_tumble({"render", (source_dir() / "assets/scenes/meshes.toml").string(),
                                  "--out", "o", "--no-mp4", "--size", "160x120", "--still", "1"},
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(fs::is_regular_file(dir / "o/still_1.png"));
}

TEST(Meshes, MissingOrBrokenModelIsExit2NamingTheFileAndTheBody) {
  const TestDir dir;
  write_scene(dir.path(), "missing.toml", mesh_scene("mesh = \"nowhere.obj\""));
  const RunResult missing = run_tumble({"simulate", "missing.toml", "--out", "a"}, dir.path());
  EXPECT_EQ(missing.exit_code, 2) << describe(missing);
  // SPEC's form: FILE:LINE:COLUMN of the scene's mesh key, then the body and the model file.
  EXPECT_TRUE(missing.err.starts_with(
      "tumble: error: missing.toml:5:8: the mesh of body \"m\": nowhere.obj: no such mesh file"))
      << missing.err;
  EXPECT_FALSE(fs::exists(dir / "a/run.json"));

  write_scene(dir.path(), "open.toml",
              mesh_scene("mesh = \"" +
                         (source_dir() / "tests/unit/mesh/data/open_box.obj").string() + "\""));
  const RunResult open = run_tumble({"simulate", "open.toml", "--out", "b"}, dir.path());
  EXPECT_EQ(open.exit_code, 2) << describe(open);
  EXPECT_NE(open.err.find("not closed: 4 open edges"), std::string::npos) << open.err;
  // repair = "hull" makes the same model a body: its convex hull.
  write_scene(
      dir.path(), "hull.toml",
      mesh_scene("mesh = \"" + (source_dir() / "tests/unit/mesh/data/open_box.obj").string() + "\"",
                 "repair = \"hull\"\n"));
  const RunResult hull =
      run_tumble({"simulate", "hull.toml", "--out", "c", "--duration", "0.5"}, dir.path());
  EXPECT_EQ(hull.exit_code, 0) << describe(hull);
  const nlohmann::json j = read_json(dir / "c/run.json");
  EXPECT_EQ(j["bodies"][0]["mesh"]["repair"], "hull");
  EXPECT_NE(j["bodies"][0]["mesh"]["repair_note"], "");
}

}  // namespace
}  // namespace tumble_e2e

namespace tumble_e2e {
namespace {

// Issue 23: a model's texture that is missing is a clear error (exit 2) naming the texture, the
// model and the body, for render and simulate alike (the model is loaded the same way).
TEST(MeshMaterials, AMissingTextureIsExitTwoNamingIt) {
  const TestDir dir;
  const fs::path data = source_dir() / "tests/unit/mesh/data/materials";
  for (const char* name : {"missing_texture.obj", "missing_texture.mtl"})
    fs::copy_file(data / name, dir / name);
  write_scene(dir.path(), "s.toml", mesh_scene("mesh = \"missing_texture.obj\""));
  {
    const RunResult r = run_tumble({"render", "s.toml", "--out", "o", "--duration", "0.1",
                                    "--size", "64x48", "--no-mp4", "--still", "0"},
                                   dir.path());
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_NE(r.err.find("no_such_texture.png"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("missing_texture.obj"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("body \"m\""), std::string::npos) << r.err;
    // Missing, not "outside the model's folder": a model named relative to the working folder
    // confines its textures to that folder.
    EXPECT_NE(r.err.find("no_such_texture.png\": no such file"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o/still_0.png"));
  }
  const RunResult s =
      run_tumble({"simulate", "s.toml", "--out", "o", "--duration", "0.1"}, dir.path());
  EXPECT_EQ(s.exit_code, 2) << describe(s);
  EXPECT_NE(s.err.find("no_such_texture.png"), std::string::npos) << s.err;
}

// The example scene of a model in its own materials renders (its texture beside it is found).
TEST(MeshMaterials, TheCrateExampleRenders) {
  const TestDir dir;
  const RunResult r = run_tumble({"render", (source_dir() / "assets/scenes/crate.toml").string(),
                                  "--out", "o", "--no-mp4", "--still", "1", "--size", "160x90"},
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(fs::exists(dir / "o/still_1.png"));
}

}  // namespace
}  // namespace tumble_e2e
