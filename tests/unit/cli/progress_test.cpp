// Progress lines with an injected clock: on a terminal a line redrawn in place; in a log (stderr
// not a terminal) a complete line at most every 10 s, with done/total, elapsed time and ETA.
#include "progress.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tumble::cli {
namespace {

struct Recorder {
  double now_s = 100.0;  // an arbitrary origin: only differences matter
  std::vector<std::string> lines;
  Progress make(Progress::Style style, long total) {
    return Progress(
        style, total, "render", "frames", [this] { return now_s; },
        [this](const std::string& text) { lines.push_back(text); });
  }
};

TEST(ProgressLog, AtMostOneCompleteLineEveryTenSeconds) {
  // 1000 frames at one frame every 1/16 s (62.5 s in all; exact in binary): lines at 10, 20, 30,
  // 40, 50 and 60 s only.
  Recorder r;
  Progress p = r.make(Progress::Style::Log, 1000);
  for (long k = 1; k <= 1000; ++k) {
    r.now_s += 0.0625;
    p.update(k);
  }
  ASSERT_EQ(r.lines.size(), 6u);
  for (const std::string& line : r.lines) {
    EXPECT_EQ(line.find('\r'), std::string::npos) << line;
    EXPECT_EQ(line.back(), '\n') << line;
    EXPECT_EQ(line.find('\n'), line.size() - 1) << "one line per write: " << line;
  }
  // At the 160th frame 10 s have passed, 840 frames remain at 16 frames/s: 52.5 s to go.
  EXPECT_EQ(r.lines[0], "render: 160/1000 frames, elapsed 10.0 s, ETA 52.5 s\n");
  EXPECT_EQ(r.lines[5], "render: 960/1000 frames, elapsed 1 min 00 s, ETA 2.5 s\n");
}

TEST(ProgressLog, IntervalCountsFromTheLastLineNotTheLastUpdate) {
  // A slow stretch: one update after 25 s prints once (not twice), and the next line needs
  // another 10 s from then.
  Recorder r;
  Progress p = r.make(Progress::Style::Log, 10);
  r.now_s += 25.0;
  p.update(1);
  r.now_s += 9.0;
  p.update(2);
  r.now_s += 1.0;
  p.update(3);
  ASSERT_EQ(r.lines.size(), 2u);
  EXPECT_EQ(r.lines[0], "render: 1/10 frames, elapsed 25.0 s, ETA 3 min 45 s\n");
  EXPECT_EQ(r.lines[1].rfind("render: 3/10 frames, elapsed 35.0 s", 0), 0u) << r.lines[1];
}

TEST(ProgressLog, ShortRunWritesNothing) {
  Recorder r;
  Progress p = r.make(Progress::Style::Log, 300);
  for (long k = 1; k <= 300; ++k) {
    r.now_s += 0.03;  // 9 s in all
    p.update(k);
  }
  EXPECT_TRUE(r.lines.empty());
}

TEST(ProgressLog, TheEndIsNotALine) {
  // The command's own "wrote ..." line ends the run; a progress line for 100 % would only repeat
  // it, and could come sooner than 10 s after the last.
  Recorder r;
  Progress p = r.make(Progress::Style::Log, 2);
  r.now_s += 30.0;
  p.update(2);
  EXPECT_TRUE(r.lines.empty());
}

TEST(ProgressOff, QuietWritesNothingAndNeverReadsTheClock) {
  int reads = 0;
  std::vector<std::string> lines;
  Progress p(
      Progress::Style::Off, 5, "render", "frames",
      [&] {
        ++reads;
        return 1000.0 * reads;
      },
      [&](const std::string& text) { lines.push_back(text); });
  for (long k = 1; k <= 5; ++k) p.update(k);
  EXPECT_TRUE(lines.empty());
  EXPECT_EQ(reads, 0);
}

TEST(ProgressTerminal, RedrawsInPlaceAndEndsWithANewline) {
  Recorder r;
  Progress p = r.make(Progress::Style::Terminal, 3);
  r.now_s += 1.0;
  p.update(1);
  r.now_s += 0.1;  // within 0.2 s of the last redraw: skipped
  p.update(2);
  r.now_s += 0.1;
  p.update(3);  // the end is always drawn
  ASSERT_EQ(r.lines.size(), 2u);
  EXPECT_EQ(r.lines[0].front(), '\r');
  EXPECT_EQ(r.lines[0].find('\n'), std::string::npos);
  EXPECT_NE(r.lines[1].find("3/3 frames"), std::string::npos) << r.lines[1];
  EXPECT_EQ(r.lines[1].back(), '\n');
}

TEST(ProgressFormat, DurationsReadAsALogReaderExpects) {
  EXPECT_EQ(format_duration(0.0), "0.0 s");
  EXPECT_EQ(format_duration(59.94), "59.9 s");
  EXPECT_EQ(format_duration(65.0), "1 min 05 s");
  EXPECT_EQ(format_duration(3 * 3600 + 7 * 60 + 20), "3 h 07 min");
}

}  // namespace
}  // namespace tumble::cli
