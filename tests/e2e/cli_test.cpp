// The command line's own surface: --help, --version, --quiet.
#include <gtest/gtest.h>

#include <regex>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

TEST(Cli, HelpListsSimulate) {
  const TestDir dir;
  const RunResult r = run_tumble({"--help"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_NE(r.out.find("simulate"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--version"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(Cli, SimulateHelpListsItsOptions) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate", "--help"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  for (const char* option : {"--out", "--duration", "--fps", "--size", "--dt", "--integrator",
                             "--quiet", "--rate", "--every-step"})
    EXPECT_NE(r.out.find(option), std::string::npos) << option << " missing from:\n" << r.out;
  EXPECT_FALSE(fs::exists(dir / "out")) << "--help ran a simulation";
}

TEST(Cli, VersionPrintsNameAndSemver) {
  const TestDir dir;
  const RunResult r = run_tumble({"--version"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(std::regex_match(r.out, std::regex(R"(tumble \d+\.\d+\.\d+\n)"))) << r.out;
  EXPECT_EQ(r.out, "tumble 0.1.0\n");
  EXPECT_EQ(r.err, "");
  // The version run.json reports is the same.
  ASSERT_EQ(run_tumble({"simulate", "--duration", "0.5", "--quiet"}, dir.path()).exit_code, 0);
  const std::string reported =
      read_json(dir / "out/default/run.json")["tool"]["version"].get<std::string>();
  EXPECT_EQ("tumble " + reported + "\n", r.out);
}

TEST(Cli, QuietPrintsNothingOnSuccess) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate", "--quiet"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(read_csv(dir / "out/default/trajectory.csv").rows.size(), 241u);
  // -q is the same flag.
  const RunResult q = run_tumble({"simulate", "-q", "--every-step", "--out", "q"}, dir.path());
  EXPECT_EQ(q.exit_code, 0) << describe(q);
  EXPECT_EQ(q.out, "");
  EXPECT_EQ(q.err, "");
}

TEST(Cli, QuietStillReportsErrors) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate", "--quiet", "missing.toml"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
}

}  // namespace
}  // namespace tumble_e2e
