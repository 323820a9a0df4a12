// Plans: their keys and jobs (grid order, random draws, both), and every plan error at its
// file:line:column.
#include <gtest/gtest.h>

#include <charconv>
#include <fstream>

#include "../test_dir.hpp"
#include "tumble/split_mix.hpp"
#include "tumble/sweep.hpp"
#include "tumble/sweep_csv.hpp"

namespace tumble::sweep {
namespace {

namespace fs = std::filesystem;

// How a drawn number is written (docs/sweeps.md): its shortest round-trip digits, as a float.
std::string toml_number_for_test(double x) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
  std::string s(buffer, end);
  return s.find_first_of(".e") == std::string::npos ? s + ".0" : s;
}

constexpr std::string_view kScene = R"([simulation]
duration = 0.5
[floor]
[[body]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 3.0, 0.0]
)";

// A plan in a fresh folder beside the scene above (drop.toml).
Plan plan_of(std::string_view text, const std::string& test) {
  const fs::path dir = test::fresh_dir("sweep_plan", test);
  std::ofstream(dir / "drop.toml") << kScene;
  return parse_plan(text, (dir / "plan.toml").string());
}

// The error a plan gives: "line:column: message" (the file name left out).
std::string plan_error(std::string_view text, const std::string& test) {
  try {
    plan_of(text, test);
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    const std::string d = e.describe();
    return d.substr(d.find("plan.toml:") + 10);
  }
  return "no error";
}

TEST(SweepPlan, GridVariesItsFirstKeySlowest) {
  const Plan plan = plan_of(R"(scene = "drop.toml"
[grid]
"floor.restitution" = [0.2, 0.5, 0.8]
"body.box.angular_velocity" = [[0.0, 0.0, 1.0], [0.0, 0.0, 4.0]]
)",
                            "grid");
  ASSERT_EQ(plan.job_count(), 6u);
  EXPECT_EQ(plan.command, "render");
  std::vector<std::string> seen;
  for (std::size_t i = 0; i < 6; ++i) {
    const Job job = make_job(plan, i);
    ASSERT_EQ(job.parameters.size(), 2u);
    seen.push_back(job.parameters[0].value + " " + job.parameters[1].value);
  }
  EXPECT_EQ(seen, (std::vector<std::string>{"0.2 [0.0, 0.0, 1.0]", "0.2 [0.0, 0.0, 4.0]",
                                            "0.5 [0.0, 0.0, 1.0]", "0.5 [0.0, 0.0, 4.0]",
                                            "0.8 [0.0, 0.0, 1.0]", "0.8 [0.0, 0.0, 4.0]"}));
  // Each value remembers its place in the plan: 0.5 is on line 3, column 27.
  EXPECT_EQ(make_job(plan, 2).parameters[0].from.line, 3);
  EXPECT_EQ(make_job(plan, 2).parameters[0].from.column, 29);
}

TEST(SweepPlan, DottedKeysWithoutQuotesAreKeyPathsToo) {
  const Plan plan = plan_of(R"(scene = "drop.toml"
[grid]
floor.restitution = [0.2, 0.5]
body.box.orientation.degrees = [10, 20, 30]
)",
                            "dotted");
  ASSERT_EQ(plan.keys().size(), 2u);
  EXPECT_EQ(plan.keys()[0]->path, "floor.restitution");
  EXPECT_EQ(plan.keys()[1]->path, "body.box.orientation.degrees");
  EXPECT_EQ(plan.job_count(), 6u);
}

TEST(SweepPlan, RandomDrawsComeFromTheJobsStreams) {
  const Plan plan = plan_of(R"(scene = "drop.toml"
command = "simulate"
[random]
count = 3
seed = 7
"body.box.orientation.degrees" = { uniform = [0.0, 90.0] }
"body.box.velocity" = { normal = [[0.0, 0.0, 0.0], [1.0, 0.0, 2.0]] }
"floor.friction" = { integer = [0, 2] }
"render.antialias" = { choice = ["fxaa", "none"] }
)",
                            "random");
  ASSERT_EQ(plan.job_count(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const Job job = make_job(plan, i);
    SplitMix64 degrees = SplitMix64::stream(7, i, 0);
    EXPECT_EQ(job.parameters[0].value, toml_number_for_test(degrees.uniform(0.0, 90.0)));
    SplitMix64 velocity = SplitMix64::stream(7, i, 1);
    const double x = velocity.normal(0.0, 1.0), y = velocity.normal(0.0, 0.0),
                 z = velocity.normal(0.0, 2.0);
    std::string vector = "[";  // appended piece by piece: GCC 12 warns falsely on "[" + s
    vector.append(toml_number_for_test(x)).append(", ").append(toml_number_for_test(y));
    vector.append(", ").append(toml_number_for_test(z)).append("]");
    EXPECT_EQ(job.parameters[1].value, vector);
    SplitMix64 friction = SplitMix64::stream(7, i, 2);
    EXPECT_EQ(job.parameters[2].value, std::to_string(friction.integer(0, 2)));
    EXPECT_TRUE(job.parameters[3].value == "\"fxaa\"" || job.parameters[3].value == "\"none\"");
  }
  // The fixed draw of docs/sweeps.md (computed independently, see split_mix_test.cpp).
  EXPECT_EQ(make_job(plan, 0).parameters[0].value, "15.456347869706617");
  // The same plan, the same jobs.
  EXPECT_EQ(make_job(plan, 2).parameters[1].value, make_job(plan, 2).parameters[1].value);
}

TEST(SweepPlan, EveryGridPointGetsCountDraws) {
  const Plan plan = plan_of(R"(scene = "drop.toml"
[grid]
"floor.restitution" = [0.2, 0.8]
[random]
count = 3
seed = 1
"body.box.orientation.degrees" = { uniform = [0, 90] }
)",
                            "both");
  ASSERT_EQ(plan.job_count(), 6u);
  for (std::size_t i = 0; i < 6; ++i)
    EXPECT_EQ(make_job(plan, i).parameters[0].value, i < 3 ? "0.2" : "0.8") << i;
  const std::string csv = job_list_csv(plan, {make_job(plan, 0)});
  EXPECT_TRUE(csv.starts_with("index,floor.restitution,body.box.orientation.degrees\n0,0.2,")) << csv;
}

TEST(SweepPlan, JobFolderNames) {
  EXPECT_EQ(job_folder_name(0), "job_00000");
  EXPECT_EQ(job_folder_name(42), "job_00042");
  EXPECT_EQ(job_folder_name(123456), "job_123456");
}

TEST(SweepPlanErrors, PointIntoThePlan) {
  const std::string head = "scene = \"drop.toml\"\n";
  EXPECT_EQ(plan_error(head + "[grid]\n\"flor.restitution\" = [0.2]\n", "t1"),
            "3:1: unknown key path \"flor.restitution\": a scene has no table \"flor\" (did you "
            "mean \"floor\"?) (a key path is table.key or body.<name>.key)");
  EXPECT_EQ(plan_error(head + "[grid]\n\"body.bxo.mass\" = [1.0]\n", "t2"),
            "3:1: unknown key path \"body.bxo.mass\": the scene has no body named \"bxo\" (did "
            "you mean \"box\"?)");
  EXPECT_EQ(plan_error(head + "[grid]\n\"floor.restitution\" = []\n", "t3"),
            "3:23: [grid] \"floor.restitution\" has no values");
  EXPECT_EQ(plan_error(head + "[random]\ncount = 2\nseed = 1\n\"floor.friction\" = { unifrom = "
                              "[0, 1] }\n",
                       "t4"),
            "5:22: unknown distribution \"unifrom\" in [random] \"floor.friction\" (did you mean "
            "\"uniform\"?) (expected one of: uniform, normal, integer, choice)");
  EXPECT_EQ(plan_error(head + "[random]\ncount = 2\nseed = 1\n\"floor.friction\" = { uniform = "
                              "[1, 0] }\n",
                       "t5"),
            "5:32: [random] \"floor.friction\" uniform must run upwards: [a, b] with a <= b");
  EXPECT_EQ(plan_error(head + "[random]\ncount = 2\nseed = 1\n\"floor.friction\" = { normal = "
                              "[0, -1] }\n",
                       "t6"),
            "5:31: [random] \"floor.friction\" normal's standard deviation must be >= 0");
  EXPECT_EQ(plan_error(head + "[random]\ncount = 0\nseed = 1\n", "t7"),
            "3:9: count in [random] must be an integer >= 1, got 0");
  EXPECT_EQ(plan_error(head + "[random]\ncount = 2\n", "t8"),
            "2:1: [random] needs seed, an integer >= 0 (the same seed, the same jobs)");
  EXPECT_EQ(plan_error(head + "comand = \"render\"\n[grid]\n\"floor.height\" = [0]\n", "t9"),
            "2:1: unknown key \"comand\" in a sweep plan (did you mean \"command\"?) (a plan has "
            "scene, command, args, [grid] and [random])");
  EXPECT_EQ(plan_error(head + "command = \"study\"\n[grid]\n\"floor.height\" = [0]\n", "t10"),
            "2:11: command must be \"render\" or \"simulate\", got \"study\"");
  EXPECT_EQ(plan_error(head + "args = [\"--size\", 320]\n[grid]\n\"floor.height\" = [0]\n", "t11"),
            "2:19: args must be an array of strings; got 320 (write numbers in quotes: \"1.0\")");
  EXPECT_EQ(plan_error(head, "t12"),
            "1:1: a plan needs a [grid] of values or a [random] block (or both)");
  EXPECT_EQ(
      plan_error("scene = \"nope.toml\"\n[grid]\n\"floor.height\" = [0]\n", "t13").substr(0, 29),
      "1:9: cannot read scene file \"");
  EXPECT_EQ(plan_error(head + "[grid]\n\"floor.height\" = [0]\n[random]\ncount = 1\nseed = 1\n"
                              "\"floor.height\" = { uniform = [0, 1] }\n",
                       "t14"),
            "7:1: key path \"floor.height\" is set twice in the plan (first at 3:1)");
}

}  // namespace
}  // namespace tumble::sweep
