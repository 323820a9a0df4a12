// The command line's own surface: --help, --version, --quiet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <regex>
#include <sstream>
#include <vector>

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
  const std::string first_line = r.out.substr(0, r.out.find('\n'));
  EXPECT_TRUE(std::regex_match(first_line, std::regex(R"(tumble \d+\.\d+\.\d+)"))) << r.out;
  EXPECT_EQ(r.err, "");
  // The version run.json reports is the same.
  ASSERT_EQ(run_tumble({"simulate", "--duration", "0.5", "--quiet"}, dir.path()).exit_code, 0);
  const std::string reported =
      read_json(dir / "out/default/run.json")["tool"]["version"].get<std::string>();
  EXPECT_EQ("tumble " + reported, first_line);
}

TEST(Cli, VersionNamesEveryLibraryItRunsWith) {
  const TestDir dir;
  const RunResult r = run_tumble({"--version"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  // One "NAME VERSION" line per library after the first line, the version starting with a digit.
  std::vector<std::string> lines;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  for (const std::string library :
       {"libavcodec", "libavformat", "libavfilter", "libswscale", "libavutil", "libpng", "assimp",
        "Qhull", "Eigen", "toml++", "OpenSSL", "nlohmann_json", "CLI11"}) {
    const auto named = [&](const std::string& line) {
      return line.size() > library.size() + 1 && line.starts_with(library + " ") &&
             std::isdigit(static_cast<unsigned char>(line[library.size() + 1]));
    };
    EXPECT_EQ(std::count_if(lines.begin() + 1, lines.end(), named), 1)
        << library << " not named once in:\n" << r.out;
  }
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
