#include "tumble/diff_report.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "../test_dir.hpp"
#include "tumble/error.hpp"
#include "tumble/png.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

// What the page says is checked in the browser (tests/e2e/diff_report_check.py); here: the
// folder, its pictures, the order of the sections, the choice of video frames, and that a
// report is never half there.

Image flat(int level, int width = 8, int height = 6) {
  Image image(width, height, 3);
  for (auto& v : image.pixels) v = static_cast<std::uint8_t>(level);
  return image;
}

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

DiffPair compared(const std::string& name, const Image& e, const Image& a, int max_delta = 0) {
  DiffPair p;
  p.name = name;
  p.result = compare_images(e, a, max_delta);
  p.beyond = !p.result.within(DiffTolerance{max_delta, 0.0, {}});
  p.summary = "metrics of " + name;
  p.expected_width = e.width;
  p.expected_height = e.height;
  p.actual_width = a.width;
  p.actual_height = a.height;
  return p;
}

DiffInputs folders(const fs::path& dir) {
  return DiffInputs{
      DiffInputs::Kind::Folders, (dir / "golden").string(), (dir / "actual").string(), {}};
}

// The folder pair of the acceptance test: identical, differing, missing and extra files.
void add_folder_pairs(DiffReport& report) {
  const Image grey = flat(100), lighter = flat(140);
  report.add(compared("a_same.png", grey, grey), &grey, &grey);
  report.add(compared("b_changed.png", grey, lighter), &grey, &lighter);
  DiffPair missing;
  missing.name = "c_missing.png";
  missing.side = DiffPair::Side::ExpectedOnly;
  missing.beyond = true;
  missing.summary = "missing from actual";
  report.add(missing, &grey, nullptr);
  DiffPair extra = missing;
  extra.name = "d_extra.png";
  extra.side = DiffPair::Side::ActualOnly;
  report.add(extra, nullptr, nullptr);  // one that did not decode: named, not shown
}

TEST(DiffReport, WritesThePageAndOnlyThePicturesItShows) {
  const fs::path dir = test::fresh_dir("DiffReport", "Folder");
  DiffReport report(dir / "report", folders(dir));
  add_folder_pairs(report);
  report.commit();
  const std::string html = read(dir / "report/index.html");
  ASSERT_FALSE(html.empty());
  EXPECT_FALSE(fs::exists(dir / ".report.partial"));
  // Identical: one picture; changed: expected, actual, diff; missing: the one it has.
  for (const char* file :
       {"001-a_same.png", "002-b_changed-expected.png", "002-b_changed-actual.png",
        "002-b_changed-diff.png", "003-c_missing-expected.png"}) {
    EXPECT_NE(html.find(std::string("src=\"images/") + file + "\""), std::string::npos) << file;
    EXPECT_EQ(read_png(dir / "report/images" / file).width, 8) << file;
  }
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir / "report/images")) ++files;
  EXPECT_EQ(files, 5u);
  // The three failures first, in name order; then the pass.
  const std::size_t b = html.find("<h2><span class=\"badge fail\">FAIL</span> b_changed.png");
  const std::size_t c = html.find("<h2><span class=\"badge fail\">FAIL</span> c_missing.png");
  const std::size_t d = html.find("<h2><span class=\"badge fail\">FAIL</span> d_extra.png");
  const std::size_t a = html.find("<h2><span class=\"badge pass\">PASS</span> a_same.png");
  ASSERT_NE(a, std::string::npos) << html;
  EXPECT_LT(b, c);
  EXPECT_LT(c, d);
  EXPECT_LT(d, a);
  EXPECT_NE(html.find("4 pairs, 3 failed, worst delta 40"), std::string::npos);
}

TEST(DiffReport, SameInputsGiveTheSameBytes) {
  const fs::path dir = test::fresh_dir("DiffReport", "Deterministic");
  std::string first;
  for (int run = 0; run < 2; ++run) {
    DiffReport report(dir / "report", folders(dir));
    add_folder_pairs(report);
    report.commit();
    if (run == 0) first = read(dir / "report/index.html");
  }
  EXPECT_EQ(read(dir / "report/index.html"), first);
}

TEST(DiffReport, ReplacesAnEarlierReportAndNothingElse) {
  const fs::path dir = test::fresh_dir("DiffReport", "Replace");
  {
    DiffReport report(dir / "report", folders(dir));
    add_folder_pairs(report);
    report.commit();
  }
  {
    DiffReport report(dir / "report", folders(dir));
    const Image grey = flat(100);
    report.add(compared("only.png", grey, grey), &grey, &grey);
    report.commit();
  }
  EXPECT_FALSE(fs::exists(dir / "report/images/002-b_changed-diff.png")) << "the old pictures go";
  EXPECT_TRUE(fs::exists(dir / "report/images/001-only.png"));
  EXPECT_FALSE(fs::exists(dir / ".report.old"));
  EXPECT_FALSE(fs::exists(dir / ".report.partial"));

  fs::create_directories(dir / "mine");
  std::ofstream(dir / "mine/notes.txt") << "keep me";
  try {
    DiffReport report(dir / "mine", folders(dir));
    FAIL() << "a folder of other files was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    EXPECT_NE(std::string(e.what()).find("not a tumble diff report"), std::string::npos);
  }
  EXPECT_EQ(read(dir / "mine/notes.txt"), "keep me");
}

TEST(DiffReport, RefusesAFolderThatHoldsAnInputOrIsAFile) {
  const fs::path dir = test::fresh_dir("DiffReport", "Refuse");
  fs::create_directories(dir / "golden");
  EXPECT_THROW(DiffReport(dir, folders(dir)), Error);  // it holds golden/
  std::ofstream(dir / "file") << "x";
  EXPECT_THROW(DiffReport(dir / "file", folders(dir)), Error);
}

TEST(DiffReport, WithoutCommitLeavesNoFolder) {
  const fs::path dir = test::fresh_dir("DiffReport", "NoCommit");
  {
    DiffReport report(dir / "report", folders(dir));
    add_folder_pairs(report);
  }
  EXPECT_FALSE(fs::exists(dir / "report"));
  EXPECT_FALSE(fs::exists(dir / ".report.partial"));
}

TEST(DiffReport, AVideoShowsTheFramesThatDifferMostAndGroupsMissingFrames) {
  const fs::path dir = test::fresh_dir("DiffReport", "Video");
  DiffReport report(dir / "report",
                    DiffInputs{DiffInputs::Kind::Videos, "a.mp4", "b.mp4", {1, 0.0, {}}});
  const Image base = flat(100);
  constexpr int kFrames = 20;
  for (int k = 0; k < kFrames; ++k) {
    // Frame k is off by k levels: frames 2..19 fail (more than 1), 19 most, 0 is identical.
    const Image other = flat(100 + k);
    DiffPair p =
        compared("frame_000" + std::string(k < 10 ? "0" : "") + std::to_string(k), base, other, 1);
    p.frame = k;
    p.time_s = k / 60.0;
    report.add(p, &base, &other);
  }
  for (int k = kFrames; k < kFrames + 3; ++k) {
    DiffPair p;
    p.name = "frame_000" + std::to_string(k);
    p.side = DiffPair::Side::ActualOnly;
    p.beyond = true;
    p.frame = k;
    p.summary = "only in b.mp4";
    report.add(p, nullptr, nullptr);
  }
  report.commit();
  const std::string html = read(dir / "report/index.html");
  std::size_t frames = 0;
  for (const auto& e : fs::directory_iterator(dir / "report/images"))
    frames += e.path().string().ends_with("-diff.png") ? 1 : 0;
  EXPECT_EQ(frames, std::size_t(DiffReport::kMaxFramesShown));
  // Ranked: all fail with 48 differing pixels, so by largest delta: 19, 18, ... 12.
  const std::size_t f19 = html.find("</span> frame 19</h2>");
  const std::size_t f12 = html.find("</span> frame 12</h2>");
  EXPECT_NE(f19, std::string::npos) << html;
  EXPECT_LT(f19, f12);
  EXPECT_EQ(html.find("</span> frame 11</h2>"), std::string::npos) << "only eight are shown";
  EXPECT_NE(html.find("</span> frames 20 to 22</h2>"), std::string::npos) << "one section";
  EXPECT_NE(html.find("0.317 s (frame 19)"), std::string::npos);
  EXPECT_NE(html.find("Failing frames: 2\xE2\x80\x93"
                      "22."),
            std::string::npos)
      << html;
}

}  // namespace
}  // namespace tumble
