// A job's effective scene: the base scene with the parameters set, standalone, deterministic;
// and the scene loader's objections mapped back to the plan.
#include "tumble/job_scene.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "../test_dir.hpp"
#include "tumble/scene.hpp"
#include "tumble/world_builder.hpp"

namespace tumble::sweep {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kScene = R"(# a comment the effective scene drops
[simulation]
duration = 0.5
dt = 0.001
[floor]
[[body]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 3.0, 0.0]
)";

struct Fixture {
  fs::path dir;
  Plan plan;
};

Fixture fixture(std::string_view plan_text, const std::string& test) {
  const fs::path dir = test::fresh_dir("job_scene", test);
  std::ofstream(dir / "drop.toml") << kScene;
  return {dir, parse_plan(plan_text, (dir / "plan.toml").string())};
}

// What the sweep command checks: the scene loader and the world builder.
const SceneCheck kLoad = [](const std::string& text, const std::string& name) {
  const Scene scene = parse_scene(text, name);
  make_world_def(scene);
};

std::string job_error(const Fixture& f, std::size_t job) {
  try {
    check_job_scene(f.plan, make_job(f.plan, job), kLoad);
  } catch (const Error& e) {
    const std::string d = e.describe();
    return d.substr(d.find("plan.toml:") + 10);
  }
  return "no error";
}

TEST(JobScene, SetsTheParametersAndParsesAsAScene) {
  const Fixture f = fixture(R"(scene = "drop.toml"
args = ["--no-mp4", "--still", "0.25"]
[grid]
"floor.restitution" = [0.25]
"body.box.orientation" = [{ axis = [1.0, 0.0, 0.0], degrees = 30.0 }]
"simulation.gravity" = [[0.0, -1.62, 0.0]]
)",
                            "sets");
  const std::string text = job_scene_text(f.plan, make_job(f.plan, 0));
  EXPECT_EQ(text, R"(# tumble sweep, job_00000: tumble render --no-mp4 --still 0.25
# floor.restitution = 0.25
# body.box.orientation = { axis = [1.0, 0.0, 0.0], degrees = 30.0 }
# simulation.gravity = [0.0, -1.62, 0.0]

[simulation]
dt = 0.001
duration = 0.5
gravity = [0.0, -1.62, 0.0]

[floor]
restitution = 0.25

[[body]]
mass = 1.0
name = "box"
orientation = { axis = [1.0, 0.0, 0.0], degrees = 30.0 }
position = [0.0, 3.0, 0.0]
shape = "box"
size = [1.0, 1.0, 1.0]
)");
  const Scene scene = parse_scene(text, "scene.toml");
  ASSERT_TRUE(scene.floor);
  EXPECT_EQ(scene.floor->restitution, 0.25);
  EXPECT_EQ(scene.simulation.gravity.y(), -1.62);
  EXPECT_NO_THROW(check_job_scene(f.plan, make_job(f.plan, 0), kLoad));
}

TEST(JobScene, NumbersReadBackBitExact) {
  const Fixture f = fixture(R"(scene = "drop.toml"
[random]
count = 50
seed = 11
"body.box.position" = { uniform = [[-1e-7, 2.0, -1e3], [1e-7, 4.0, 1e3]] }
)",
                            "exact");
  for (std::size_t i = 0; i < 50; ++i) {
    const Job job = make_job(f.plan, i);
    const Scene scene = parse_scene(job_scene_text(f.plan, job), "scene.toml");
    const std::string written = job.parameters[0].value;
    char expected[128];
    std::snprintf(expected, sizeof expected, "%.17g", scene.bodies[0].position.x());
    // Parsing the written text gives back exactly the drawn double.
    EXPECT_EQ(std::stod(written.substr(1)), std::stod(expected)) << written;
  }
}

TEST(JobScene, RelativeMeshPathsBecomeAbsolute) {
  const fs::path dir = test::fresh_dir("job_scene", "mesh");
  fs::create_directories(dir / "scenes");
  std::ofstream(dir / "scenes/m.toml") << R"([[body]]
name = "m"
shape = "mesh"
mesh = "../meshes/cube.obj"
mass = 1.0
)";
  const Plan plan = parse_plan("scene = \"scenes/m.toml\"\n[grid]\n\"body.m.mass\" = [2.0]\n",
                               (dir / "plan.toml").string());
  const std::string text = job_scene_text(plan, make_job(plan, 0));
  const std::string mesh = (fs::absolute(dir) / "meshes/cube.obj").lexically_normal().string();
  EXPECT_NE(text.find("mesh = \"" + mesh + "\""), std::string::npos) << text;
}

TEST(JobScene, TheSceneLoadersErrorsPointIntoThePlan) {
  const Fixture f = fixture(R"(scene = "drop.toml"
[grid]
"floor.restitution" = [0.5, 1.5]
"floor.restitutoin" = [0.5]
"body.box.position" = [[0.0, 3.0, 0.0], [0.0, -2.0, 0.0]]
)",
                            "errors");
  // Job 0 (0.5, 0.5, above): the unknown key, at the key path, with the loader's suggestion.
  EXPECT_EQ(job_error(f, 0),
            "4:1: job 0 (floor.restitution = 0.5, floor.restitutoin = 0.5, body.box.position = "
            "[0.0, 3.0, 0.0]): unknown key \"restitutoin\" in [floor] (did you mean "
            "\"restitution\"?) (key path \"floor.restitutoin\")");
}

TEST(JobScene, ABadValueIsBlamedOnItsGridValue) {
  const Fixture f = fixture(R"(scene = "drop.toml"
[grid]
"floor.restitution" = [0.5, 1.5]
)",
                            "value");
  EXPECT_EQ(job_error(f, 0), "no error");
  EXPECT_EQ(job_error(f, 1),
            "3:29: job 1 (floor.restitution = 1.5): restitution in [floor] must be in [0, 1], "
            "got 1.5");
}

TEST(JobScene, ADrawTheSceneRejectsIsBlamedOnItsDistribution) {
  const Fixture f = fixture(R"(scene = "drop.toml"
[random]
count = 4
seed = 3
"simulation.dt" = { normal = [0.0, 1.0] }
)",
                            "draw");
  // Some of four standard normal draws are negative (the fixed stream decides which).
  bool some_failed = false;
  for (std::size_t i = 0; i < 4; ++i) {
    const std::string e = job_error(f, i);
    if (e == "no error") continue;
    some_failed = true;
    EXPECT_TRUE(e.starts_with("5:19: job " + std::to_string(i) + " (simulation.dt = ")) << e;
  }
  EXPECT_TRUE(some_failed);
}

TEST(JobScene, ABodyPlacedInsideTheFloorIsBlamedOnTheKey) {
  const Fixture f = fixture(R"(scene = "drop.toml"
[grid]
"body.box.position" = [[0.0, 3.0, 0.0], [0.0, 0.2, 0.0]]
)",
                            "floor");
  EXPECT_EQ(job_error(f, 0), "no error");
  const std::string e = job_error(f, 1);
  EXPECT_TRUE(e.starts_with("3:1: job 1 (body.box.position = [0.0, 0.2, 0.0]): ")) << e;
}

TEST(JobScene, AMissingMeshIsBlamedWhereTheLoaderSaysOnce) {
  const fs::path dir = test::fresh_dir("job_scene", "missing_mesh");
  std::ofstream(dir / "m.toml") << "[[body]]\nname = \"m\"\nshape = \"mesh\"\nmesh = "
                                   "\"gone.obj\"\nmass = 1.0\n";
  const Plan plan = parse_plan("scene = \"m.toml\"\n[grid]\n\"body.m.mass\" = [2.0]\n",
                               (dir / "plan.toml").string());
  const SceneCheck load = [](const std::string& text, const std::string& name) {
    const Scene scene = parse_scene(text, name);
    make_world_def(scene, load_models(scene));
  };
  try {
    check_job_scene(plan, make_job(plan, 0), load);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string d = e.describe();
    EXPECT_NE(d.find("job 0 (body.m.mass = 2.0): "), std::string::npos) << d;
    // The location is given once, in front.
    EXPECT_EQ(d.find(": job 0"), d.find(": "));
  }
}

TEST(JobScene, ALineBreakInAnArgumentStaysInTheComment) {
  const Fixture f = fixture(
      "scene = \"drop.toml\"\nargs = [\"--out\\nx = 1\"]\n[grid]\n"
      "\"floor.height\" = [0.0]\n",
      "line_break");
  const std::string text = job_scene_text(f.plan, make_job(f.plan, 0));
  EXPECT_NO_THROW(parse_scene(text, "scene.toml")) << text;
  EXPECT_TRUE(text.starts_with("# tumble sweep, job_00000: tumble render --out x = 1\n")) << text;
}

TEST(JobScene, APathThroughAValueIsAnError) {
  const Fixture f = fixture(R"(scene = "drop.toml"
[grid]
"body.box.mass.kg" = [1.0]
)",
                            "through");
  try {
    job_scene_text(f.plan, make_job(f.plan, 0));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where().line, 3);
    EXPECT_NE(std::string(e.what()).find("mass is not a table"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tumble::sweep
