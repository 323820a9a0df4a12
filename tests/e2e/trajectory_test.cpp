// The trajectory's promises (SPEC.md: Time, Outputs): the same scene gives the same bytes, the
// state at a time does not depend on which other times were sampled, and every float reads back
// bit-exact.
#include <gtest/gtest.h>

#include <cerrno>
#include <charconv>
#include <cstdlib>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

/// Runs `tumble simulate ARGS --out OUT` in `cwd` and returns the trajectory it wrote.
Csv simulate(const fs::path& cwd, std::vector<std::string> args, const std::string& out) {
  args.insert(args.begin(), "simulate");
  args.push_back("--out");
  args.push_back(out);
  const RunResult r = run_tumble(args, cwd);
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  return read_csv(cwd / out / "trajectory.csv");
}

TEST(Trajectory, SameSceneTwiceGivesIdenticalBytes) {
  const TestDir dir;
  for (const std::string scene :
       {"default.toml", "seed_drop.toml", "tumble_intermediate_axis.toml"}) {
    SCOPED_TRACE(scene);
    const std::string path = (source_dir() / "assets/scenes" / scene).string();
    const RunResult a = run_tumble({"simulate", path, "--out", "a", "--duration", "3"}, dir.path());
    const RunResult b = run_tumble({"simulate", path, "--out", "b", "--duration", "3"}, dir.path());
    ASSERT_EQ(a.exit_code, 0) << describe(a);
    ASSERT_EQ(b.exit_code, 0) << describe(b);
    const std::string first = read_file(dir / "a/trajectory.csv");
    ASSERT_FALSE(first.empty());
    EXPECT_TRUE(first == read_file(dir / "b/trajectory.csv")) << "the two runs differ";
    EXPECT_EQ(read_json(dir / "a/run.json")["outputs"][0]["sha256"],
              read_json(dir / "b/run.json")["outputs"][0]["sha256"]);
  }
}

TEST(Trajectory, DefaultSceneRunFromTwoFoldersIsIdentical) {
  const TestDir dir;
  fs::create_directories(dir / "one");
  fs::create_directories(dir / "two/deeper");
  ASSERT_EQ(run_tumble({"simulate"}, dir / "one").exit_code, 0);
  ASSERT_EQ(run_tumble({"simulate"}, dir / "two/deeper").exit_code, 0);
  EXPECT_TRUE(read_file(dir / "one/out/default/trajectory.csv") ==
              read_file(dir / "two/deeper/out/default/trajectory.csv"));
}

// t = k/12 is both 2k/24 and 5k/60; IEEE division rounds each to the same double, so those rows
// carry the same t text, and the states there must agree bit for bit.
TEST(Trajectory, SampleRateDoesNotChangeTheStateAtCommonTimes) {
  const TestDir dir;
  const Csv at24 = simulate(dir.path(), {"--rate", "24"}, "r24");
  const Csv at60 = simulate(dir.path(), {"--rate", "60"}, "r60");
  ASSERT_EQ(at24.rows.size(), 97u);
  ASSERT_EQ(at60.rows.size(), 241u);
  const auto by_time = rows_by_time(at60);
  int common = 0;
  for (const auto& row : at24.rows) {
    const auto match = by_time.find(row[T] + "," + row[BODY]);
    if (match == by_time.end()) continue;
    ++common;
    EXPECT_EQ(row, match->second) << "at t = " << row[T];
  }
  EXPECT_EQ(common, 49);  // k/12 for k = 0 … 48
}

// With dt = 0.001, --rate 1000 samples k/1000 and --every-step samples k·0.001; where those are
// the same double (the same text), the rows must be identical.
TEST(Trajectory, RateAtStepBoundariesEqualsEveryStep) {
  const TestDir dir;
  const Csv steps = simulate(dir.path(), {"--every-step", "--dt", "0.001"}, "steps");
  const Csv rate = simulate(dir.path(), {"--rate", "1000", "--dt", "0.001"}, "rate");
  ASSERT_EQ(steps.rows.size(), 4001u);
  ASSERT_EQ(rate.rows.size(), 4001u);
  const auto by_time = rows_by_time(steps);
  int common = 0;
  for (const auto& row : rate.rows) {
    const auto match = by_time.find(row[T] + "," + row[BODY]);
    if (match == by_time.end()) continue;
    ++common;
    EXPECT_EQ(row, match->second) << "at t = " << row[T];
  }
  // k/1000 and k·0.001 agree for most k (t = 0 and the end at least).
  EXPECT_GE(common, 2000) << "too few common times to compare";
}

// A frame time k/60 with k a multiple of 3 is the step boundary n = 50k/3 for dt = 0.001; its state
// is the state after n steps, the same as --every-step's row n (the t text may differ in the last
// digit, the state may not).
TEST(Trajectory, FrameTimesOnStepBoundariesMatchEveryStepStates) {
  const TestDir dir;
  const Csv steps = simulate(dir.path(), {"--every-step"}, "steps");
  const Csv frames = simulate(dir.path(), {}, "frames");
  ASSERT_EQ(steps.rows.size(), 4001u);
  ASSERT_EQ(frames.rows.size(), 241u);
  for (std::size_t k = 0; k < frames.rows.size(); k += 3) {
    const std::size_t n = k * 50 / 3;
    const auto& f = frames.rows[k];
    const auto& s = steps.rows[n];
    ASSERT_EQ(f.size(), s.size());
    for (int c = X; c < kColumns; ++c)
      EXPECT_EQ(f[static_cast<std::size_t>(c)], s[static_cast<std::size_t>(c)])
          << "frame " << k << " (t = " << f[T] << ") vs step " << n << " (t = " << s[T]
          << "), column " << c;
  }
}

TEST(Trajectory, FloatsReadBackBitExact) {
  const TestDir dir;
  const Csv csv = simulate(dir.path(), {}, "o");
  ASSERT_EQ(csv.rows.size(), 241u);
  int long_fields = 0;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    for (int c = 0; c < kColumns; ++c) {
      if (c == BODY) continue;
      const std::string& text = csv.text(i, c);
      errno = 0;
      char* end = nullptr;
      const double x = std::strtod(text.c_str(), &end);
      ASSERT_EQ(errno, 0) << text;
      ASSERT_EQ(end, text.c_str() + text.size()) << "not a whole number: \"" << text << "\"";
      // The shortest round-trip text of the value read is the text written: nothing was lost
      // and nothing is padded.
      EXPECT_EQ(shortest(x), text) << "row " << i << ", column " << c;
      double y = 0;
      const auto parsed = std::from_chars(text.data(), text.data() + text.size(), y);
      EXPECT_TRUE(parsed.ec == std::errc() && y == x) << text;
      if (text.size() >= 17) ++long_fields;
    }
  }
  // Full precision, not a %g-style 6 digits.
  EXPECT_GT(long_fields, 100);
  // A few values whose text is known from the scene.
  EXPECT_EQ(csv.text(0, Y), "3");
  EXPECT_EQ(csv.text(1, T), "0.016666666666666666");
  EXPECT_EQ(std::strtod(csv.text(1, T).c_str(), nullptr), 1.0 / 60.0);
}

}  // namespace
}  // namespace tumble_e2e
