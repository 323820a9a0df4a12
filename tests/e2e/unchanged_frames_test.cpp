// Frames whose bodies did not move are not drawn again (the frame pipeline hands the encoders
// the previous pixels): the outputs must be the very bytes of drawing every frame
// (--draw-every-frame, the reference), for every clip output, with pictures drawn in between,
// and run.json counts the frames reused. No tolerance: the claim is bit-identity.
#include <gtest/gtest.h>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

std::vector<std::string> with(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

// Renders `args` twice, reusing unchanged frames and drawing every one; every file must match.
// Returns the two runs' counts.frames_reused.
std::pair<long, long> render_both_ways(const TestDir& dir, const std::vector<std::string>& args) {
  for (const char* out : {"reused", "drawn"}) {
    std::vector<std::string> a = with({"render", "--quiet", "--out", out}, args);
    if (std::string(out) == "drawn") a.push_back("--draw-every-frame");
    const RunResult r = run_tumble(a, dir.path());
    EXPECT_EQ(r.exit_code, 0) << describe(r);
  }
  for (const auto& entry : fs::recursive_directory_iterator(dir / "drawn")) {
    if (!entry.is_regular_file() || entry.path().filename() == "run.json") continue;
    const fs::path rel = fs::relative(entry.path(), dir / "drawn");
    EXPECT_TRUE(read_file(dir / "reused" / rel) == read_file(entry.path()))
        << rel.string() << " differs from drawing every frame";
  }
  const nlohmann::json reused = read_json(dir / "reused/run.json");
  const nlohmann::json drawn = read_json(dir / "drawn/run.json");
  for (std::size_t i = 0; i < drawn["outputs"].size(); ++i)
    EXPECT_EQ(reused["outputs"][i]["sha256"], drawn["outputs"][i]["sha256"]);
  return {reused["counts"]["frames_reused"].get<long>(),
          drawn["counts"]["frames_reused"].get<long>()};
}

TEST(UnchangedFrames, DefaultSceneAtRestIsTheSameBytesAsDrawingEveryFrame) {
  // The default box rests in static equilibrium from about t = 2.45 s: of 240 frames at 60 fps
  // over 4 s, the last ~90 show nothing new. Every clip output (MP4, PNG frames, GIF, WebP) and
  // the pictures drawn between them (a still and a strobe pose inside the rest) must match.
  const TestDir dir;
  const auto [reused, drawn] = render_both_ways(
      dir, {"--size", "160x120", "--png", "--gif", "--webp", "--still", "3.5", "--strobe", "3"});
  EXPECT_GT(reused, 60) << "the box rests for over a second: those frames need no drawing";
  EXPECT_LT(reused, 240);
  EXPECT_EQ(drawn, 0);
  // A reused frame is what drawing at that time gives: still_3.5 is drawn, frame 210 reused.
  EXPECT_TRUE(read_file(dir / "reused/still_3.5.png") ==
              read_file(dir / "reused/frames/frame_00210.png"));
}

TEST(UnchangedFrames, TransparentFramesToo) {
  const TestDir dir;
  const auto [reused, drawn] = render_both_ways(
      dir, {"--size", "96x64", "--png", "--transparent", "--gif", "--duration", "3.5"});
  EXPECT_GT(reused, 30);
  EXPECT_EQ(drawn, 0);
}

TEST(UnchangedFrames, NothingMovingIsDrawnOnce) {
  // No gravity, no floor, no velocity: every frame after the first is the first.
  const TestDir dir;
  write_scene(dir.path(), "still.toml", R"([simulation]
duration = 1.0
gravity = [0.0, 0.0, 0.0]
[render]
fps = 30
[[body]]
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 1.0, 0.0]
)");
  const auto [reused, drawn] = render_both_ways(dir, {"still.toml", "--size", "64x48", "--png"});
  EXPECT_EQ(reused, 29);
  EXPECT_EQ(drawn, 0);
}

TEST(UnchangedFrames, AFollowedBodyThatMovesIsDrawnEveryFrame) {
  // A slow spin in free space with the camera following: every frame differs, none is reused.
  const TestDir dir;
  write_scene(dir.path(), "spin.toml", R"([simulation]
duration = 0.5
gravity = [0.0, 0.0, 0.0]
[render]
fps = 30
[camera]
follow = "box"
[[body]]
name = "box"
shape = "box"
size = [1.0, 0.5, 0.25]
mass = 1.0
position = [0.0, 1.0, 0.0]
velocity = [0.01, 0.0, 0.0]
angular_velocity = [0.0, 0.1, 0.0]
)");
  const auto [reused, drawn] = render_both_ways(dir, {"spin.toml", "--size", "64x48", "--png"});
  EXPECT_EQ(reused, 0);
  EXPECT_EQ(drawn, 0);
}

}  // namespace
}  // namespace tumble_e2e
