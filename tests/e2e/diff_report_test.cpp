// tumble diff --report DIR and --junit FILE (SPEC.md: diff): written whatever the verdict, exit
// codes unchanged, atomic, the same bytes for the same inputs, bad paths refused before anything
// is compared; a video's report shows its frames with index and time.
//
// The report in a browser and the JUnit file through an XML parser are checked by
// diff_report_check.py (python3 and Debian's chromium), run from here; the browser check is
// skipped, with its reason, only where chromium is not installed.
#include <gtest/gtest.h>

#include <algorithm>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

bool contains(const std::string& text, std::string_view part) {
  return text.find(part) != std::string::npos;
}

// A solid-colour 8x6 RGB PNG, drawn by the ffmpeg tool (scripts/setup --tests installs it).
void solid_png(const fs::path& file, const std::string& colour) {
  fs::create_directories(file.parent_path());
  const RunResult r =
      run_program("ffmpeg",
                  {"-v", "error", "-y", "-f", "lavfi", "-i", "color=c=" + colour + ":s=8x6",
                   "-frames:v", "1", "-pix_fmt", "rgb24", file.string()},
                  "/");
  ASSERT_EQ(r.exit_code, 0) << describe(r);
}

// golden/ and actual/: same.png equal, changed.png another colour, missing.png and extra.png
// on one side each.
void folder_pair(const TestDir& dir) {
  solid_png(dir / "golden/same.png", "gray");
  solid_png(dir / "actual/same.png", "gray");
  solid_png(dir / "golden/changed.png", "gray");
  solid_png(dir / "actual/changed.png", "red");
  solid_png(dir / "golden/missing.png", "blue");
  solid_png(dir / "actual/extra.png", "green");
}

RunResult run_script(const TestDir& dir, const std::string& mode) {
  RunOptions options;
  options.timeout = std::chrono::seconds(90);
  return run_program("python3",
                     {(source_dir() / "tests/e2e/diff_report_check.py").string(),
                      tumble_binary().string(), (dir / "work").string(), mode},
                     dir.path(), options);
}

TEST(DiffReport, OpensInChromiumWithNoErrorsNoRequestsAndAWorkingCompare) {
  const TestDir dir;
  const RunResult r = run_script(dir, "browser");
  if (r.exit_code == 77) GTEST_SKIP() << r.out;
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  std::printf("%s", r.out.c_str());  // the report's size and the time taken
}

TEST(DiffReport, JunitFileParsesWithTheCountsNamesAndFailureMessages) {
  const TestDir dir;
  const RunResult r = run_script(dir, "junit");
  EXPECT_EQ(r.exit_code, 0) << describe(r);
}

TEST(DiffReport, WrittenWhateverTheVerdictWithTheExitCodeUnchanged) {
  const TestDir dir;
  folder_pair(dir);
  RunResult r = run_tumble(
      {"diff", "golden", "actual", "--report", "report", "--junit", "junit.xml"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(contains(r.out, "tumble diff: 3 of 4 files differ beyond tolerance")) << r.out;
  EXPECT_TRUE(fs::exists(dir / "report/index.html"));
  EXPECT_TRUE(contains(read_file(dir / "junit.xml"), "tests=\"4\" failures=\"3\""));
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left";
  EXPECT_FALSE(fs::exists(dir / ".report.partial"));

  // Within tolerance: exit 0, and both written all the same.
  r = run_tumble(
      {"diff", "golden/same.png", "actual/same.png", "--report", "ok", "--junit", "ok.xml"},
      dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  const std::string page = read_file(dir / "ok/index.html");
  EXPECT_TRUE(contains(page, "1 pair, 0 failed, worst delta 0")) << page;
  EXPECT_TRUE(contains(page, "src=\"images/001-same.png\"")) << "identical: one picture";
  EXPECT_TRUE(contains(read_file(dir / "ok.xml"), "tests=\"1\" failures=\"0\""));
}

TEST(DiffReport, SameInputsGiveTheSameReportBytes) {
  const TestDir dir;
  folder_pair(dir);
  std::vector<std::string> digests;
  for (int run = 0; run < 2; ++run) {
    const RunResult r = run_tumble({"diff", "golden", "actual", "--report", "report"}, dir.path());
    ASSERT_EQ(r.exit_code, 1) << describe(r);
    std::string all;
    for (const std::string& name : names_in(dir / "report/images"))
      all += name + " " + system_sha256(dir / "report/images" / name) + "\n";
    digests.push_back(system_sha256(dir / "report/index.html") + "\n" + all);
  }
  EXPECT_EQ(digests[0], digests[1]);
}

TEST(DiffReport, AnErrorWritesNeitherAndKeepsAnEarlierReport) {
  const TestDir dir;
  folder_pair(dir);
  ASSERT_EQ(run_tumble({"diff", "golden", "actual", "--report", "report"}, dir.path()).exit_code,
            1);
  const std::string earlier = read_file(dir / "report/index.html");
  write_file(dir / "actual/same.png", "not a PNG");  // exit 2: undecodable input
  const RunResult r = run_tumble(
      {"diff", "golden", "actual", "--report", "report", "--junit", "junit.xml"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_EQ(read_file(dir / "report/index.html"), earlier);
  EXPECT_FALSE(fs::exists(dir / "junit.xml"));
  EXPECT_FALSE(fs::exists(dir / ".report.partial"));
}

TEST(DiffReport, BadPathsAreRefusedBeforeComparing) {
  const TestDir dir;
  folder_pair(dir);
  write_file(dir / "notes/todo.txt", "mine");
  const std::vector<std::vector<std::string>> cases = {
      {"--report", "notes"},           // a folder of other files: replacing it would delete them
      {"--report", "."},               // holds the inputs
      {"--junit", "golden"},           // a folder
      {"--junit", "actual/same.png"},  // an input
  };
  for (const auto& extra : cases) {
    std::vector<std::string> args = {"diff", "golden", "actual"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run_tumble(args, dir.path());
    EXPECT_EQ(r.exit_code, 2) << extra[0] << " " << extra[1] << ": " << describe(r);
    EXPECT_TRUE(r.out.empty()) << "compared before refusing: " << r.out;
    EXPECT_TRUE(contains(r.err, "tumble: error: " + extra[0])) << r.err;
  }
  EXPECT_EQ(read_file(dir / "notes/todo.txt"), "mine");
}

// Renders the default scene's clip at 160x120, 0.25 s (15 frames at 60 fps) unless `extra` gives
// a --duration, into `out`.
bool render_clip(const TestDir& dir, const std::string& out, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"render", "--size", "160x120", "--out", out, "--quiet"};
  if (std::find(extra.begin(), extra.end(), "--duration") == extra.end())
    extra.insert(extra.end(), {"--duration", "0.25"});
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult r = run_tumble(args, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  return r.exit_code == 0;
}

TEST(DiffReport, AVideoShowsTheFramesThatDifferMostWithIndexAndTime) {
  const TestDir dir;
  ASSERT_TRUE(render_clip(dir, "a"));
  ASSERT_TRUE(render_clip(dir, "b", {"--crf", "40"}));  // every frame a little off
  const RunResult r =
      run_tumble({"diff", "a/clip.mp4", "b/clip.mp4", "--report", "report", "--junit", "junit.xml"},
                 dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  const std::string page = read_file(dir / "report/index.html");
  // At most eight frames, each with its index and its time k/60 s.
  std::size_t diffs = 0;
  for (const std::string& name : names_in(dir / "report/images"))
    diffs += name.ends_with("-diff.png") ? 1 : 0;
  EXPECT_EQ(diffs, 8u);
  EXPECT_TRUE(contains(page, "frames: 15 expected, 15 actual.")) << page;
  EXPECT_TRUE(contains(page, "(at most 8)")) << page;
  for (long k = 0; k < 15; ++k) {
    char time[64];
    std::snprintf(time, sizeof time, "<td>%.3f s (frame %ld)</td>", double(k) / 60.0, k);
    const bool shown = contains(page, time);
    EXPECT_EQ(shown, fs::exists(dir / ("report/images/frame_000" + std::string(k < 10 ? "0" : "") +
                                       std::to_string(k) + "-diff.png")))
        << "frame " << k << ": its time and its pictures go together";
  }
  const std::string junit = read_file(dir / "junit.xml");
  EXPECT_TRUE(contains(junit, "tests=\"15\"")) << junit;
  EXPECT_TRUE(contains(junit, "name=\"frame_00014\"")) << junit;
}

TEST(DiffReport, AVideoOfAnotherLengthListsTheMissingFramesAsOneFailureFirst) {
  const TestDir dir;
  ASSERT_TRUE(render_clip(dir, "a"));
  ASSERT_TRUE(render_clip(dir, "b", {"--duration", "0.5"}));
  // The longer run is framed and encoded a little differently: only the length is to fail.
  const RunResult r = run_tumble({"diff", "a/clip.mp4", "b/clip.mp4", "--max-delta", "255",
                                  "--max-fraction", "1", "--report", "report"},
                                 dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  const std::string page = read_file(dir / "report/index.html");
  const std::size_t missing =
      page.find("<h2><span class=\"badge fail\">FAIL</span> frames 15 to 29</h2>");
  EXPECT_NE(missing, std::string::npos) << page;
  EXPECT_LT(missing, page.find("<h2><span class=\"badge pass\">PASS</span> frame ")) << page;
  EXPECT_TRUE(contains(page, "only in b/clip.mp4 (15 frames the other video does not have)"))
      << page;
  EXPECT_TRUE(contains(page,
                       "Failing frames: 15\xE2\x80\x93"
                       "29."))
      << page;
}

// The README's CI recipe, run as written: its first two sh blocks under "Image-diff tests in
// CI" (approve the goldens, then render and compare), in a fresh folder that sees assets/ and
// has the built tumble first in PATH.
TEST(DiffReport, ReadmeCiRecipeRunsAsWritten) {
  const TestDir dir;
  const std::string readme = read_file(source_dir() / "README.md");
  std::size_t at = readme.find("\n## Image-diff tests in CI\n");
  ASSERT_NE(at, std::string::npos) << "README: no section \"Image-diff tests in CI\"";
  std::string script;
  for (int block = 0; block < 2; ++block) {
    at = readme.find("```sh\n", at);
    ASSERT_NE(at, std::string::npos);
    const std::size_t end = readme.find("```\n", at + 6);
    script += readme.substr(at + 6, end - at - 6);
    at = end + 4;
  }
  ASSERT_TRUE(contains(script, "--report diff-report --junit diff.xml")) << script;
  fs::create_directory_symlink(source_dir() / "assets", dir / "assets");
  const std::string path = tumble_binary().parent_path().string() + ":" + getenv("PATH");
  RunOptions options;
  options.timeout = std::chrono::seconds(120);
  const RunResult r = run_program(
      "bash", {"-euo", "pipefail", "-c", "export PATH=\"$1\"; " + script, "recipe", path},
      dir.path(), options);
  EXPECT_EQ(r.exit_code, 0) << script << describe(r);
  EXPECT_TRUE(contains(r.out, "tumble diff: all 2 files within tolerance")) << r.out;
  EXPECT_TRUE(fs::exists(dir / "diff-report/index.html"));
  EXPECT_TRUE(contains(read_file(dir / "diff.xml"), "tests=\"2\" failures=\"0\""));

  // The GitLab CI job below them: its script lines, as a runner runs them, against the goldens
  // approved above.
  at = readme.find("```yaml\n", at);
  ASSERT_NE(at, std::string::npos) << "README: no GitLab CI job";
  const std::string yaml = readme.substr(at, readme.find("```\n", at + 8) - at);
  std::string job;
  bool in_script = false;
  for (const std::string& line : split(yaml, '\n')) {
    if (line.find_first_not_of(' ') == std::string::npos) continue;
    const std::size_t indent = line.find_first_not_of(' ');
    if (line.substr(indent) == "script:") {
      in_script = true;
    } else if (in_script && line.compare(indent, 2, "- ") == 0) {
      job += line.substr(indent + 2) + "\n";
    } else {
      in_script = false;
    }
  }
  ASSERT_TRUE(contains(job, "tumble diff golden actual")) << yaml;
  fs::remove_all(dir / "diff-report");
  fs::remove(dir / "diff.xml");
  const RunResult ci =
      run_program("bash", {"-euo", "pipefail", "-c", "export PATH=\"$1\"; " + job, "job", path},
                  dir.path(), options);
  EXPECT_EQ(ci.exit_code, 0) << job << describe(ci);
  EXPECT_TRUE(fs::exists(dir / "diff-report/index.html")) << "the job's artifact";
  EXPECT_TRUE(contains(read_file(dir / "diff.xml"), "tests=\"2\" failures=\"0\""))
      << "the job's JUnit report";
}

}  // namespace
}  // namespace tumble_e2e
