// A scene without a camera position is framed on its whole run (issue 13, docs/scene.md
// "[camera]"): every body stays inside the picture at every frame. The bodies' pixels are found
// exactly by rendering the scene twice with the bodies in two colours: the floor, the sky and the
// shadows do not depend on a body's colour, so a pixel that differs is a body pixel (threshold 8
// levels: anti-aliased edges count too). No body pixel may touch the image border.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <regex>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

constexpr int kWidth = 160, kHeight = 90;  // the default 16:9, small

// The scene with every body's colour replaced by `color`.
std::string recoloured(const std::string& scene, const std::string& color) {
  const std::string without =
      std::regex_replace(scene, std::regex(R"((^|\n)\s*color\s*=[^\n]*)"), "");
  return std::regex_replace(without, std::regex(R"(\[\[body\]\])"),
                            "[[body]]\ncolor = \"" + color + "\"");
}

// Every frame of the clip as RGB, top-down, frame after frame.
std::string frames_rgb(const fs::path& folder) {
  const RunResult r = run_program("ffmpeg",
                                  {"-v", "error", "-i", (folder / "frame_%05d.png").string(), "-f",
                                   "rawvideo", "-pix_fmt", "rgb24", "-"},
                                  "/");
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  return r.out;
}

struct FramingCheck {
  long frames = 0;
  long frames_with_body_on_border = 0;
  long frames_without_body = 0;
  int smallest_body_rows = 0;  // of the frames with a body: the fewest rows its pixels span
  nlohmann::json camera;       // run.json settings.camera
};

// Renders `scene_text` (written into `dir`, which holds any meshes it names) in two colours and
// checks every frame, at kWidth x kHeight or `width` x `height`. `extra`: more options for both
// renders.
FramingCheck check_framing(const fs::path& dir, const std::string& scene_text,
                           const std::vector<std::string>& extra = {}, int width = kWidth,
                           int height = kHeight) {
  FramingCheck check;
  check.smallest_body_rows = height;
  std::string rgb[2];
  const char* colors[2] = {"#ff2020", "#2020ff"};
  for (int i = 0; i < 2; ++i) {
    const std::string name = "framed_" + std::to_string(i);
    write_file(dir / (name + ".toml"), recoloured(scene_text, colors[i]));
    std::vector<std::string> args = {
        "render", name + ".toml", "--no-mp4",
        "--png",  "--size",       std::to_string(width) + "x" + std::to_string(height),
        "--out",  name,           "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run_tumble(args, dir);
    EXPECT_EQ(r.exit_code, 0) << describe(r);
    rgb[i] = frames_rgb(dir / name / "frames");
    if (i == 0) check.camera = read_json(dir / name / "run.json")["settings"]["camera"];
  }
  const std::size_t frame_bytes = std::size_t(width) * height * 3;
  EXPECT_EQ(rgb[0].size(), rgb[1].size());
  EXPECT_GT(rgb[0].size(), 0u);
  check.frames = long(rgb[0].size() / frame_bytes);
  for (long f = 0; f < check.frames; ++f) {
    bool any = false, border = false;
    int top = height, bottom = -1;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t at = std::size_t(f) * frame_bytes + (std::size_t(y) * width + x) * 3;
        bool body = false;
        for (int c = 0; c < 3; ++c)
          body |= std::abs(int(static_cast<unsigned char>(rgb[0][at + c])) -
                           int(static_cast<unsigned char>(rgb[1][at + c]))) > 8;
        if (!body) continue;
        any = true;
        border |= x == 0 || y == 0 || x == width - 1 || y == height - 1;
        top = std::min(top, y);
        bottom = std::max(bottom, y);
      }
    check.frames_with_body_on_border += border;
    check.frames_without_body += !any;
    if (any) check.smallest_body_rows = std::min(check.smallest_body_rows, bottom - top + 1);
  }
  return check;
}

void expect_framed(const FramingCheck& c, long frames) {
  EXPECT_EQ(c.frames, frames);
  EXPECT_EQ(c.frames_with_body_on_border, 0) << "a body touches the edge of the picture";
  EXPECT_EQ(c.frames_without_body, 0) << "a frame shows no body";
  EXPECT_EQ(c.camera["framed"], true);
}

TEST(CameraFraming, DefaultSceneKeepsTheBoxInsideEveryFrame) {
  // assets/scenes/default.toml is the built-in default scene (embedded at build time).
  const TestDir dir;
  const FramingCheck c =
      check_framing(dir.path(), read_file(source_dir() / "assets/scenes/default.toml"));
  expect_framed(c, 240);
  // The built-in default is framed the same way.
  const RunResult r = run_tumble(
      {"render", "--no-mp4", "--still", "0", "--size", "160x90", "--out", "builtin", "--quiet"},
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(read_json(dir / "builtin/run.json")["settings"]["camera"], c.camera);
}

TEST(CameraFraming, EveryExampleSceneWithoutACameraKeepsItsBodiesInside) {
  int framed = 0;
  for (const fs::path& scene : example_scenes()) {
    const std::string text = read_file(scene);
    if (text.find("[camera]") != std::string::npos) continue;
    SCOPED_TRACE(scene.filename().string());
    const TestDir dir;
    // Beside a copy of the meshes, so relative mesh paths still resolve.
    fs::create_directories(dir / "scenes");
    fs::copy(source_dir() / "assets/meshes", dir / "meshes", fs::copy_options::recursive);
    const FramingCheck c = check_framing(dir / "scenes", text);
    EXPECT_GT(c.frames, 0);
    expect_framed(c, c.frames);
    ++framed;
  }
  EXPECT_GE(framed, 2) << "flat_drop and seed_drop have no camera";
}

TEST(CameraFraming, AFiftyMetreThrowIsFramed) {
  // Thrown at 12.5 m/s sideways and 9 m/s up onto a frictionless floor: about 50 m in 4 s.
  const TestDir dir;
  const FramingCheck c = check_framing(dir.path(), R"([simulation]
duration = 4.0
[render]
fps = 15
[floor]
restitution = 0.5
[[body]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 0.6, 0.0]
velocity = [12.5, 9.0, 0.0]
angular_velocity = [0.0, 0.0, -3.0]
)");
  expect_framed(c, 60);
  const RunResult sim =
      run_tumble({"simulate", "framed_0.toml", "--out", "sim", "--quiet"}, dir.path());
  ASSERT_EQ(sim.exit_code, 0) << describe(sim);
  const Csv t = read_csv(dir / "sim/trajectory.csv");  // columns t,body,x,...
  ASSERT_FALSE(t.rows.empty());
  EXPECT_GT(t.value(t.rows.size() - 1, 2), 45.0) << "the throw must really go about 50 m";
}

// camera.follow without a position (issue 20): framing the whole throw would show the 0.5 m box
// 6 px tall at 480x270; the camera moves with it instead, so it is at least a sixth of the
// picture's height (45 px) in every frame, and never touches the edge.
TEST(CameraFraming, AFollowedThrownBoxFillsASixthOfThePictureInEveryFrame) {
  const TestDir dir;
  const FramingCheck c = check_framing(dir.path(), R"([simulation]
duration = 4.0
[render]
fps = 10
[floor]
[camera]
follow = "box"
[[body]]
name = "box"
shape = "box"
size = [0.5, 0.5, 0.5]
mass = 1.0
position = [0.0, 1.0, 0.0]
velocity = [7.2, 9.6, 0.0]
angular_velocity = [1.0, 2.0, 3.0]
)",
                                       {}, 480, 270);
  expect_framed(c, 40);
  EXPECT_GE(c.smallest_body_rows, 270 / 6) << "the followed box is too small in some frame";
  std::printf("[ followed ] 0.5 m box thrown at 12 m/s: at least %d rows of 270\n",
              c.smallest_body_rows);
  EXPECT_EQ(c.camera["follow"], "box");
}

// The drop scene with `camera` (a [camera] table) appended, rendered to one small still: the
// camera run.json says was used.
nlohmann::json camera_used(const std::string& camera) {
  const TestDir dir;
  write_file(dir / "cam.toml", std::string(kDropScene) + camera);
  const RunResult r = run_tumble({"render", "cam.toml", "--no-mp4", "--still", "0", "--size",
                                  "64x48", "--out", "o", "--quiet"},
                                 dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  return read_json(dir / "o/run.json")["settings"]["camera"];
}

TEST(CameraFraming, AStatedCameraIsUsedAsGiven) {
  const nlohmann::json cam = camera_used(R"([camera]
position = [1.0, 2.0, 9.0]
target = [0.0, 1.0, 0.0]
)");
  EXPECT_EQ(cam["position"], nlohmann::json::parse("[1.0, 2.0, 9.0]"));
  EXPECT_EQ(cam["target"], nlohmann::json::parse("[0.0, 1.0, 0.0]"));
  EXPECT_EQ(cam["framed"], false);
}

TEST(CameraFraming, AStatedTargetIsKeptAndThePositionFramed) {
  const nlohmann::json cam = camera_used(R"([camera]
target = [0.0, 1.0, 0.0]
)");
  EXPECT_EQ(cam["target"], nlohmann::json::parse("[0.0, 1.0, 0.0]"));
  EXPECT_EQ(cam["framed"], true);
  // Along the framing direction (5, 3, 6) from the target.
  const double dx = cam["position"][0].get<double>(), dy = cam["position"][1].get<double>() - 1.0,
               dz = cam["position"][2].get<double>();
  EXPECT_NEAR(dx / dz, 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(dy / dz, 3.0 / 6.0, 1e-12);
}

TEST(CameraFraming, AFramedPositionPinnedInTheSceneGivesTheSamePicture) {
  // run.json records the camera used, so writing it into the scene reproduces the view.
  const TestDir dir;
  write_file(dir / "a.toml", std::string(kDropScene));
  RunResult r = run_tumble({"render", "a.toml", "--no-mp4", "--still", "0.3", "--size", "64x48",
                            "--out", "a", "--quiet"},
                           dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const nlohmann::json cam = read_json(dir / "a/run.json")["settings"]["camera"];
  write_file(dir / "b.toml", std::string(kDropScene) +
                                 "[camera]\nposition = " + cam["position"].dump() +
                                 "\ntarget = " + cam["target"].dump() + "\n");
  r = run_tumble({"render", "b.toml", "--no-mp4", "--still", "0.3", "--size", "64x48", "--out", "b",
                  "--quiet"},
                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(read_file(dir / "a/still_0.3.png") == read_file(dir / "b/still_0.3.png"));
}

}  // namespace
}  // namespace tumble_e2e
