// tumble study end to end (SPEC.md: study, Outputs): the three outputs and their shape, results
// independent of --jobs, the target answer, diverged runs as rows, and bad options. Runs are kept
// short (1 s of the built-in scene at a small size: about 0.1 s per study).
#include <gtest/gtest.h>

#include <regex>
#include <sstream>

#include "run_tumble.hpp"

namespace tumble_e2e {
namespace {

constexpr const char* kSpecHeader =
    "integrator,dt,tolerance,steps,evaluations,wall_s,error,pixel_error,energy_drift";

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<std::string> cells(const std::string& line, char sep = ',') {
  std::vector<std::string> out;
  std::size_t begin = 0;
  for (std::size_t at; (at = line.find(sep, begin)) != std::string::npos; begin = at + 1)
    out.push_back(line.substr(begin, at - begin));
  out.push_back(line.substr(begin));
  return out;
}

// study.csv without its wall_s column (the one thing allowed to differ between runs).
std::string csv_without_wall(const std::string& csv) {
  std::string out;
  for (const std::string& line : lines(csv)) {
    std::vector<std::string> c = cells(line);
    c.erase(c.begin() + 5);
    for (std::size_t i = 0; i < c.size(); ++i) out += (i ? "," : "") + c[i];
    out += '\n';
  }
  return out;
}

// study.md with every wall time masked: the runs table's wall column and the "took … s/ms" text.
std::string markdown_without_wall(const std::string& md) {
  std::string out;
  for (std::string line : lines(md)) {
    if (line.rfind("| ", 0) == 0 && cells(line, '|').size() == 15) {
      std::vector<std::string> c = cells(line, '|');
      c[6] = " wall ";
      line.clear();
      for (std::size_t i = 0; i < c.size(); ++i) line += (i ? "|" : "") + c[i];
    }
    out += line + '\n';
  }
  out = std::regex_replace(out, std::regex(R"(took [0-9.e+-]+ s)"), "took X s");
  return std::regex_replace(out, std::regex(R"([0-9.e+-]+ ms)"), "X ms");
}

// A small well-formedness check of XML: every tag closed in order, attributes quoted.
bool well_formed_xml(const std::string& text, std::string& why) {
  std::vector<std::string> open;
  std::size_t at = 0;
  while ((at = text.find('<', at)) != std::string::npos) {
    if (text.compare(at, 4, "<!--") == 0) {
      at = text.find("-->", at);
      if (at == std::string::npos) return why = "unclosed comment", false;
      continue;
    }
    const std::size_t end = text.find('>', at);
    if (end == std::string::npos) return why = "unclosed tag", false;
    std::string tag = text.substr(at + 1, end - at - 1);
    at = end + 1;
    if (tag.front() == '?' || tag.front() == '!') continue;
    if (std::count(tag.begin(), tag.end(), '"') % 2 != 0) return why = "quote in <" + tag, false;
    if (tag.front() == '/') {
      const std::string name = tag.substr(1);
      if (open.empty() || open.back() != name)
        return why = "</" + name + "> closes <" + (open.empty() ? "" : open.back()) + ">", false;
      open.pop_back();
    } else if (tag.back() != '/') {
      open.push_back(tag.substr(0, tag.find_first_of(" \n\t")));
    }
  }
  if (!open.empty()) return why = "<" + open.back() + "> never closed", false;
  return true;
}

const std::vector<std::string> kShort = {"study", "--duration", "1", "--size", "320x180"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(Study, WritesCsvMarkdownAndSvgWithOneRowPerSetting) {
  const TestDir dir;
  const RunResult r = run_tumble(kShort, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const fs::path out = dir / "out/default";
  for (const char* name : {"study.csv", "study.md", "study.svg"})
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";

  const std::vector<std::string> csv = lines(read_file(out / "study.csv"));
  ASSERT_FALSE(csv.empty());
  EXPECT_EQ(csv[0].rfind(std::string(kSpecHeader) + ",", 0), 0u) << csv[0];
  // 4 fixed-step integrators × 5 steps + adaptive × 4 tolerances.
  ASSERT_EQ(csv.size(), 1u + 4u * 5u + 4u);
  const std::size_t columns = cells(csv[0]).size();
  for (std::size_t i = 1; i < csv.size(); ++i) {
    const std::vector<std::string> c = cells(csv[i]);
    ASSERT_EQ(c.size(), columns) << csv[i];
    const bool adaptive = c[0] == "adaptive";
    EXPECT_EQ(c[0], i <= 5    ? "euler"
                    : i <= 10 ? "symplectic-euler"
                    : i <= 15 ? "midpoint"
                    : i <= 20 ? "rk4"
                              : "adaptive");
    // dt: the scene's 0.001 × 4, 2, 1, 1/2, 1/4 (adaptive: its largest step, by default the
    // frame interval 1/60 s; the scene's dt is its first trial step).
    const char* dts[] = {"0.004", "0.002", "0.001", "5e-04", "0.00025"};
    if (adaptive)
      EXPECT_EQ(std::stod(c[1]), 1.0 / 60.0) << csv[i];
    else
      EXPECT_EQ(c[1], dts[(i - 1) % 5]) << csv[i];
    EXPECT_EQ(c[2].empty(), !adaptive) << csv[i];
    EXPECT_FALSE(c[6].empty()) << "no error in " << csv[i];
  }
  EXPECT_EQ(cells(csv[24])[2], "1e-10");

  const std::string md = read_file(out / "study.md");
  for (const char* part : {"## Reference", "## Runs", "## Fitted convergence order",
                           "## Recommendation", "uncertainty"})
    EXPECT_NE(md.find(part), std::string::npos) << part;
  // stdout: the table, the fitted orders and the recommendation.
  EXPECT_NE(r.out.find("fitted order: euler"), std::string::npos) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("recommended: [a-z4-]+ (dt|tol)="))) << r.out;
}

TEST(Study, SvgIsAWellFormedTwoPanelPlot) {
  const TestDir dir;
  ASSERT_EQ(run_tumble(with(kShort, {"--quiet"}), dir.path()).exit_code, 0);
  const std::string svg = read_file(dir / "out/default/study.svg");
  ASSERT_EQ(svg.rfind("<svg", 0), 0u) << svg.substr(0, 80);
  std::string why;
  EXPECT_TRUE(well_formed_xml(svg, why)) << why;
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  for (const char* text : {"derivative evaluations", "wall time", "Pareto front", "rk4", "adaptive",
                           "reference uncertainty"})
    EXPECT_NE(svg.find(text), std::string::npos) << text;
}

TEST(Study, JobsChangeNothingButWallTimes) {
  const TestDir dir;
  ASSERT_EQ(run_tumble(with(kShort, {"--jobs", "1", "--out", "one", "-q"}), dir.path()).exit_code,
            0);
  ASSERT_EQ(run_tumble(with(kShort, {"--jobs", "2", "--out", "two", "-q"}), dir.path()).exit_code,
            0);
  const std::string a = read_file(dir / "one/study.csv"), b = read_file(dir / "two/study.csv");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(csv_without_wall(a), csv_without_wall(b));
  EXPECT_EQ(markdown_without_wall(read_file(dir / "one/study.md")),
            markdown_without_wall(read_file(dir / "two/study.md")));
}

TEST(Study, TargetErrorNamesTheCheapestSettingReachingIt) {
  const TestDir dir;
  const RunResult r = run_tumble(with(kShort, {"--target-error", "1e-3"}), dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(target 0\.001 m: [a-z4-]+ (dt|tol)=)")))
      << r.out;
  EXPECT_NE(read_file(dir / "out/default/study.md").find("Target error 0.001 m"),
            std::string::npos);
}

TEST(Study, ListsAndQuiet) {
  const TestDir dir;
  const RunResult r = run_tumble(with(kShort, {"--integrators", "rk4,adaptive", "--dts",
                                               "0.002, 0.001", "--tolerances", "1e-6", "--quiet"}),
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");
  const std::vector<std::string> csv = lines(read_file(dir / "out/default/study.csv"));
  ASSERT_EQ(csv.size(), 4u);
  EXPECT_EQ(csv[1].rfind("rk4,0.002,,", 0), 0u) << csv[1];
  EXPECT_EQ(csv[2].rfind("rk4,0.001,,", 0), 0u) << csv[2];
  // adaptive's dt column: its largest step, the frame interval 1/60 s.
  EXPECT_EQ(csv[3].rfind("adaptive,0.016666666666666666,1e-06,", 0), 0u) << csv[3];
}

TEST(Study, ADivergedRunIsARowNotAFailure) {
  // Stiff drag: explicit Euler at dt = 0.01 multiplies the velocity by -99 per step.
  const TestDir dir;
  const fs::path scene = write_scene(dir.path(), "stiff.toml", R"([simulation]
duration = 2.0
linear_drag = 10000.0
[[body]]
name = "ball"
shape = "particle"
mass = 1.0
velocity = [1.0, 0.0, 0.0]
)");
  const RunResult r = run_tumble(
      {"study", scene.string(), "--integrators", "euler", "--dts", "0.01,1e-4"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const std::vector<std::string> csv = lines(read_file(dir / "out/stiff/study.csv"));
  ASSERT_EQ(csv.size(), 3u);
  const std::vector<std::string> header = cells(csv[0]);
  const std::size_t status = std::find(header.begin(), header.end(), "status") - header.begin();
  ASSERT_LT(status, header.size());
  EXPECT_EQ(cells(csv[1])[status], "diverged") << csv[1];
  EXPECT_EQ(cells(csv[1])[6], "") << "a diverged run has no error";
  EXPECT_EQ(cells(csv[2])[status], "ok") << csv[2];
  EXPECT_NE(r.out.find("diverged"), std::string::npos) << r.out;
}

struct BadOption {
  std::vector<std::string> args;
  std::string message;  // part of the error
};

class StudyBadOption : public ::testing::TestWithParam<BadOption> {};

TEST_P(StudyBadOption, ExitsTwoWithAMessage) {
  const TestDir dir;
  const RunResult r = run_tumble(with(kShort, GetParam().args), dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_EQ(r.err.rfind("tumble: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out/default/study.csv"));
}

INSTANTIATE_TEST_SUITE_P(
    Options, StudyBadOption,
    ::testing::Values(BadOption{{"--integrators", "rk5"}, "unknown integrator \"rk5\""},
                      BadOption{{"--integrators", "rk4,,euler"}, "empty item"},
                      BadOption{{"--integrators", "rk4,rk4"}, "twice"},
                      BadOption{{"--integrator", "rk4"}, "--integrators"},
                      BadOption{{"--dts", "0"}, "not a positive step"},
                      BadOption{{"--dts", "-0.001"}, "not a positive step"},
                      BadOption{{"--dts", "1e-3,abc"}, "\"abc\" is not a number"},
                      BadOption{{"--dts", "2"}, "longer than the run"},
                      BadOption{{"--dts", "1e-12"}, "more than 1e9 steps"},
                      BadOption{{"--tolerances", "1"}, "outside [1e-14, 0.1]"},
                      BadOption{{"--tolerances", "1e-15"}, "outside [1e-14, 0.1]"},
                      BadOption{{"--integrators", "euler", "--tolerances", "1e-6"}, "adaptive"},
                      BadOption{{"--integrators", "adaptive", "--dts", "0.001"}, "fixed-step"},
                      BadOption{{"--target-error", "-1"}, "--target-error"},
                      BadOption{{"--jobs", "0"}, "--jobs"},
                      BadOption{{"--dt", "0.4"}, "default steps"}));

}  // namespace
}  // namespace tumble_e2e
