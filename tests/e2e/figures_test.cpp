// Documentation figures end to end (SPEC.md: --strobe, --strobe-span, --transparent, [camera]
// projection and ortho_height): strobe.png and its poses, transparent PNGs with straight alpha,
// the orthographic camera, the option and scene checks, and what a failed run leaves behind.
// Every render is tiny (160x120, at most 1.5 s of scene time).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <utility>

#include "figures_formats.hpp"
#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

const std::vector<std::string> kSmall = {"--size", "160x120"};

std::vector<std::string> args(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

std::string scene_path(const std::string& stem) {
  return (source_dir() / "assets/scenes" / (stem + ".toml")).string();
}

// ---------------------------------------------------------------------------------------------
// --strobe

TEST(Strobe, OnePictureWithEveryPoseListedInRunJson) {
  const TestDir dir;
  const RunResult r = run_tumble(args({"render", scene_path("side_view"), "--no-mp4", "--strobe",
                                       "5", "--duration", "1", "--out", "o"},
                                      kSmall),
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(names_in(dir / "o"), (std::vector<std::string>{"run.json", "strobe.png"}));
  const PngInfo png = png_info(dir / "o/strobe.png");
  ASSERT_TRUE(png.valid);
  EXPECT_EQ(png.width, 160u);
  EXPECT_EQ(png.height, 120u);
  EXPECT_EQ(png.color_type, 2) << "opaque: 8-bit RGB, like every still";

  nlohmann::json j = read_json(dir / "o/run.json");
  ASSERT_TRUE(j["figures"].is_object()) << j.dump(2);
  EXPECT_EQ(j["figures"]["transparent"], false);
  const nlohmann::json& strobe = j["figures"]["strobe"];
  EXPECT_EQ(strobe["poses"], 5);
  // Evenly spaced over the whole run, both ends included; opacity ramps up to 1.
  const std::vector<double> times = strobe["times_s"].get<std::vector<double>>();
  ASSERT_EQ(times.size(), 5u);
  for (int k = 0; k < 5; ++k) EXPECT_DOUBLE_EQ(times[k], 0.25 * k);
  const std::vector<double> opacity = strobe["opacities"].get<std::vector<double>>();
  ASSERT_EQ(opacity.size(), 5u);
  EXPECT_EQ(opacity.back(), 1.0);
  for (int k = 1; k < 5; ++k) EXPECT_LT(opacity[k - 1], opacity[k]) << "earlier poses fainter";
  EXPECT_GT(opacity.front(), 0.0);
  ASSERT_EQ(j["outputs"].size(), 1u);
  EXPECT_EQ(j["outputs"][0]["path"], "o/strobe.png");
  EXPECT_EQ(j["outputs"][0]["sha256"], system_sha256(dir / "o/strobe.png"));
  EXPECT_TRUE(j["wall_time"]["png_s"].is_number());
}

// The strobe's last pose is drawn opaque, exactly as a still at that time draws the body; the
// earlier poses add ghosts elsewhere. So the two pictures are equal where the ghosts are not and
// differ where they are (the ball travels across the picture).
TEST(Strobe, LastPoseIsTheStillAndEarlierPosesAddGhosts) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", scene_path("side_view"), "--no-mp4", "--strobe", "4", "--strobe-span",
            "0.3:0.9", "--still", "0.9", "--out", "o", "--duration", "1.5"},
           kSmall),
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  nlohmann::json j = read_json(dir / "o/run.json");
  const std::vector<double> times = j["figures"]["strobe"]["times_s"].get<std::vector<double>>();
  ASSERT_EQ(times.size(), 4u);
  EXPECT_DOUBLE_EQ(times.front(), 0.3);
  EXPECT_DOUBLE_EQ(times[1], 0.5);
  EXPECT_DOUBLE_EQ(times[2], 0.7);
  EXPECT_EQ(times.back(), 0.9);
  const Rgba strobe = decode_rgba(dir / "o/strobe.png", 160, 120);
  const Rgba still = decode_rgba(dir / "o/still_0.9.png", 160, 120);
  ASSERT_FALSE(strobe.bytes.empty());
  ASSERT_FALSE(still.bytes.empty());
  long differing = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) differing += std::memcmp(strobe.at(x, y), still.at(x, y), 3) != 0;
  // Three ghosts of a ball some 5 px across, and their shadows: tens to a few hundred pixels;
  // most of the picture is the same floor and sky.
  EXPECT_GT(differing, 30);
  EXPECT_LT(differing, 160 * 120 / 10);
}

TEST(Strobe, SameRunTwiceIsByteIdentical) {
  const TestDir dir;
  for (const char* out : {"a", "b"}) {
    const RunResult r = run_tumble(args({"render", "--no-mp4", "--strobe", "6", "--transparent",
                                         "--duration", "1", "--out", out, "--quiet"},
                                        kSmall),
                                   dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
  }
  const std::string a = read_file(dir / "a/strobe.png");
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == read_file(dir / "b/strobe.png"));
}

// ---------------------------------------------------------------------------------------------
// --transparent

// The default scene at t = 0: the box hangs in the sky above the horizon, the floor below.
TEST(Transparent, StillHasStraightAlphaBackgroundZeroBodyOpaqueEdgesSoft) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", "--transparent", "--still", "0", "--duration", "0.5", "--out", "t"}, kSmall),
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const RunResult opaque = run_tumble(
      args({"render", "--no-mp4", "--still", "0", "--duration", "0.5", "--out", "o"}, kSmall),
      dir.path());
  ASSERT_EQ(opaque.exit_code, 0) << describe(opaque);

  const PngInfo png = png_info(dir / "t/still_0.png");
  ASSERT_TRUE(png.valid);
  EXPECT_EQ(png.color_type, 6) << "--transparent: 8-bit RGBA";
  EXPECT_EQ(png.bit_depth, 8);
  const Rgba t = decode_rgba(dir / "t/still_0.png", 160, 120);
  const Rgba o = decode_rgba(dir / "o/still_0.png", 160, 120);
  ASSERT_FALSE(t.bytes.empty());
  ASSERT_FALSE(o.bytes.empty());

  EXPECT_EQ(t.alpha(0, 0), 0) << "the sky is fully transparent";
  EXPECT_EQ(t.alpha(159, 0), 0);
  EXPECT_EQ(t.alpha(80, 115), 255) << "the floor in front keeps its ground, opaque";
  long body = 0, soft_edge = 0, soft_edge_body_coloured = 0;
  auto orange = [](const unsigned char* p) { return p[0] > 150 && p[1] < 120 && p[2] < 100; };
  for (int y = 1; y < 119; ++y)
    for (int x = 1; x < 159; ++x) {
      const unsigned char* p = t.at(x, y);
      if (p[3] == 255 && orange(p)) ++body;
      if (p[3] == 0 || p[3] == 255) continue;
      // A partly covered pixel next to both the body and the empty sky: the silhouette.
      bool near_body = false, near_sky = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const unsigned char* q = t.at(x + dx, y + dy);
          near_body |= q[3] == 255 && orange(q);
          near_sky |= q[3] == 0;
        }
      if (!near_body || !near_sky) continue;
      ++soft_edge;
      // Straight alpha: the colour is the body's own, not darkened by the coverage (a
      // premultiplied pixel at half coverage would be half as bright).
      if (p[3] <= 200 && orange(p)) ++soft_edge_body_coloured;
    }
  EXPECT_GT(body, 30) << "the box is there, opaque";
  EXPECT_GT(soft_edge, 6) << "anti-aliased against transparency";
  EXPECT_GT(soft_edge_body_coloured, 3) << "edge colours are straight, not premultiplied";

  // Composited over the sky colour, the transparent still is the opaque one, up to rounding and
  // the anti-aliasing of the silhouette (smoothed against transparency, not the sky).
  const int sky[3] = {0xdf, 0xe6, 0xee};
  long off = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      const unsigned char* p = t.at(x, y);
      const unsigned char* q = o.at(x, y);
      for (int c = 0; c < 3; ++c) {
        const double over = (p[c] * p[3] + sky[c] * (255 - p[3])) / 255.0;
        if (std::abs(over - q[c]) > 3.0) {
          ++off;
          break;
        }
      }
    }
  EXPECT_LT(off, 160 * 120 / 100) << off << " pixels differ from the opaque still";

  // The MP4 is unaffected: opaque 4:2:0 as always.
  nlohmann::json j = read_json(dir / "t/run.json");
  EXPECT_EQ(j["figures"]["transparent"], true);
  EXPECT_TRUE(fs::is_regular_file(dir / "t/clip.mp4"));
  EXPECT_EQ(j["outputs"][0]["path"], "t/clip.mp4");
}

TEST(Transparent, FramesAreRgba) {
  const TestDir dir;
  const RunResult r = run_tumble(args({"render", "--transparent", "--png", "--no-mp4", "--fps",
                                       "10", "--duration", "0.3", "--out", "o"},
                                      kSmall),
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const std::vector<std::string> frames = names_in(dir / "o/frames");
  ASSERT_EQ(frames.size(), 3u);
  for (const std::string& f : frames) {
    const PngInfo png = png_info(dir / "o/frames" / f);
    EXPECT_EQ(png.color_type, 6) << f;
  }
}

// The approved golden (tests/golden/default_transparent) has the same properties, so what the
// golden test holds the renderer to is a correct transparent picture.
TEST(Transparent, GoldenStillHasAlphaWhereExpected) {
  const fs::path golden = source_dir() / "tests/golden/default_transparent/still_0.3.png";
  ASSERT_EQ(png_info(golden).color_type, 6);
  const Rgba g = decode_rgba(golden, 160, 120);
  ASSERT_FALSE(g.bytes.empty());
  EXPECT_EQ(g.alpha(0, 0), 0);
  EXPECT_EQ(g.alpha(80, 115), 255);
  long partial = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) partial += g.alpha(x, y) > 0 && g.alpha(x, y) < 255;
  EXPECT_GT(partial, 10) << "soft edges and the fading horizon";
}

// ---------------------------------------------------------------------------------------------
// Orthographic camera

TEST(Orthographic, RunJsonNamesTheProjection) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", scene_path("side_view"), "--no-mp4", "--still", "0.5", "--out", "o"}, kSmall),
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["settings"]["camera"]["projection"], "orthographic");
  EXPECT_EQ(j["settings"]["camera"]["ortho_height"], 2.7);
  const RunResult d = run_tumble(
      args({"render", "--no-mp4", "--still", "0", "--duration", "0.1", "--out", "d"}, kSmall),
      dir.path());
  ASSERT_EQ(d.exit_code, 0) << describe(d);
  nlohmann::json dj = read_json(dir / "d/run.json");
  EXPECT_EQ(dj["settings"]["camera"]["projection"], "perspective");
  EXPECT_EQ(dj["settings"]["camera"]["ortho_height"], 4.0);
}

// In an orthographic view a body's image does not shrink with distance: a box moved 10 m away
// from the camera covers the same number of pixels (a perspective camera shows it smaller).
TEST(Orthographic, SizeDoesNotChangeWithDistance) {
  const TestDir dir;
  auto coverage = [&](const std::string& projection, double z) {
    const std::string scene = std::string(R"([simulation]
duration = 0.1
gravity = [0.0, 0.0, 0.0]
[render]
background = "#ffffff"
[camera]
position = [0.0, 1.0, 12.0]
target = [0.0, 1.0, 0.0]
)") + (projection == "orthographic" ? "projection = \"orthographic\"\northo_height = 3.0\n" : "") +
                              R"([light]
shadows = false
[[body]]
shape = "box"
size = [0.8, 0.8, 0.8]
mass = 1.0
color = "#000000"
position = [0.0, 1.0, )" + std::to_string(z) +
                              "]\n";
    const std::string name = projection + std::to_string(static_cast<int>(-z));
    write_scene(dir.path(), name + ".toml", scene);
    const RunResult r = run_tumble(args({"render", name + ".toml", "--no-mp4", "--still", "0",
                                         "--antialias", "none", "--out", name},
                                        kSmall),
                                   dir.path());
    EXPECT_EQ(r.exit_code, 0) << describe(r);
    const Rgba image = decode_rgba(dir / name / "still_0.png", 160, 120);
    long dark = 0;
    for (std::size_t i = 0; i + 3 < image.bytes.size(); i += 4)
      dark += static_cast<unsigned char>(image.bytes[i]) < 128;
    return dark;
  };
  const long ortho_near = coverage("orthographic", 0.0),
             ortho_far = coverage("orthographic", -10.0);
  const long persp_near = coverage("perspective", 0.0), persp_far = coverage("perspective", -10.0);
  EXPECT_GT(ortho_near, 100);
  // The same pixels, to a pixel row or column of rasterisation.
  EXPECT_NEAR(static_cast<double>(ortho_far), static_cast<double>(ortho_near),
              0.1 * static_cast<double>(ortho_near));
  EXPECT_LT(persp_far, persp_near / 2) << "a perspective camera shows the far box smaller";
}

TEST(Orthographic, SceneKeysAreChecked) {
  const TestDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      // [camera] starts on line 10; the value at column 16 (ortho_height = ) or 14 (fov_deg = ).
      {"projection = \"orthographic\"\northo_height = 0.0\n",
       "bad.toml:12:16: ortho_height in [camera] must be > 0, got 0"},
      {"projection = \"orthographic\"\northo_height = -2\n",
       "bad.toml:12:16: ortho_height in [camera] must be > 0, got -2"},
      {"ortho_height = 0.0\n", "bad.toml:11:16: ortho_height in [camera] must be > 0, got 0"},
      {"projection = \"orthographic\"\nfov_deg = 190.0\n",
       "bad.toml:12:11: fov_deg in [camera] must be in (0, 180), got 190"},
      {"projection = \"fisheye\"\n",
       "bad.toml:11:14: unknown projection \"fisheye\" (expected one of: perspective, "
       "orthographic)"},
      {"projecton = \"orthographic\"\n",
       "bad.toml:11:1: unknown key \"projecton\" in [camera] (did you mean \"projection\"?)"},
  };
  // SPEC's [camera] table gives fov_deg and ortho_height together: either projection takes both.
  for (const char* projection : {"perspective", "orthographic"}) {
    write_scene(dir.path(), "both.toml",
                std::string(kDropScene) + "[camera]\nprojection = \"" + projection +
                    "\"\nfov_deg = 45.0\northo_height = 4.0\n");
    const RunResult ok = run_tumble(
        {"render", "both.toml", "--no-mp4", "--still", "0", "--size", "64x48", "--out", "both"},
        dir.path());
    EXPECT_EQ(ok.exit_code, 0) << describe(ok);
  }
  for (const auto& [camera, message] : cases) {
    SCOPED_TRACE(camera);
    write_scene(dir.path(), "bad.toml", std::string(kDropScene) + "[camera]\n" + camera);
    const RunResult r = run_tumble({"render", "bad.toml", "--no-mp4", "--still", "0"}, dir.path());
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_NE(r.err.find("tumble: error: " + message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
}

// ---------------------------------------------------------------------------------------------
// Bad figure options: exit 2, a message naming the option, nothing written

TEST(FigureOptions, BadValuesAreExit2AndWriteNothing) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--strobe", "1"}, "--strobe 1"},
      {{"--strobe", "0"}, "--strobe 0"},
      {{"--strobe", "-3"}, "--strobe -3"},
      {{"--strobe", "1001"}, "--strobe 1001"},
      {{"--strobe", "4", "--strobe-span", "0.4:0.2"}, "--strobe-span 0.4:0.2"},
      {{"--strobe", "4", "--strobe-span", "0.2:0.2"}, "--strobe-span 0.2:0.2"},
      {{"--strobe", "4", "--strobe-span", "0:9"}, "outside the run [0, 0.5]"},
      {{"--strobe", "4", "--strobe-span", "-0.1:0.3"}, "outside the run [0, 0.5]"},
      {{"--strobe", "4", "--strobe-span", "0.1"}, "--strobe-span must look like"},
      {{"--strobe", "4", "--strobe-span", "a:b"}, "--strobe-span must look like"},
      {{"--strobe", "4", "--strobe-span", "0:nan"}, "--strobe-span must look like"},
      {{"--strobe-span", "0:0.3"}, "--strobe-span needs --strobe"},
      {{"--transparent"}, "--transparent"},
      {{"--webp", "--size", "16384x64", "--no-mp4"}, "16383"},
  };
  for (const auto& [extra, message] : cases) {
    SCOPED_TRACE(extra[0] + " " + (extra.size() > 1 ? extra[1] : ""));
    const TestDir dir;
    // One --size only: a repeated option is itself an error.
    const bool sized = std::find(extra.begin(), extra.end(), "--size") != extra.end();
    const RunResult r = run_tumble(
        args(args({"render", "--duration", "0.5"}, sized ? std::vector<std::string>{} : kSmall),
             extra),
        dir.path());
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_empty(dir.path())) << "a rejected render wrote files";
  }
}

// --transparent with an output that has alpha is fine without any PNG; alone with the MP4 it
// is the error above.
TEST(FigureOptions, TransparentNeedsAnOutputWithAlpha) {
  const TestDir dir;
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--gif"}, {"--webp"}, {"--png", "--no-mp4"}, {"--strobe", "2"}}) {
    SCOPED_TRACE(extra[0]);
    const RunResult r = run_tumble(
        args(args({"render", "--transparent", "--duration", "0.1", "--out", "o"}, kSmall), extra),
        dir.path());
    EXPECT_EQ(r.exit_code, 0) << describe(r);
  }
}

// Odd sizes: H.264 needs even ones, GIF and WebP do not.
TEST(FigureOptions, OddSizeIsFineForGifAndWebp) {
  const TestDir dir;
  const RunResult r = run_tumble({"render", "--size", "161x121", "--no-mp4", "--gif", "--webp",
                                  "--duration", "0.1", "--out", "o"},
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const GifFile gif = parse_gif(read_file(dir / "o/clip.gif"));
  ASSERT_TRUE(gif.valid);
  EXPECT_EQ(gif.width, 161);
  EXPECT_EQ(gif.height, 121);
  EXPECT_TRUE(parse_webp(read_file(dir / "o/clip.webp")).valid);
}

// ---------------------------------------------------------------------------------------------
// Failed and interrupted runs keep the previous figures

TEST(FigureOutputs, FailedRunKeepsThePreviousFigures) {
  const TestDir dir;
  const std::vector<std::string> figures = {"--gif", "--webp", "--strobe", "3", "--still", "0.2"};
  const RunResult good = run_tumble(
      args(args({"render", "--duration", "0.5", "--out", "o", "--quiet"}, kSmall), figures),
      dir.path());
  ASSERT_EQ(good.exit_code, 0) << describe(good);
  std::map<std::string, std::string> before;
  for (const char* f : {"clip.gif", "clip.webp", "strobe.png", "still_0.2.png", "run.json"}) {
    before[f] = read_file(dir / "o" / f);
    ASSERT_FALSE(before[f].empty()) << f;
  }
  auto unchanged = [&] {
    for (const auto& [name, bytes] : before)
      EXPECT_TRUE(read_file(dir / "o" / name) == bytes) << name << " was changed";
    EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";
  };

  // A frame that cannot be written part-way (its name taken by a folder): exit 3.
  fs::create_directories(dir / "o/frames/frame_00010.png");
  const RunResult failed = run_tumble(
      args(args({"render", "--png", "--duration", "0.5", "--out", "o"}, kSmall), figures),
      dir.path());
  EXPECT_EQ(failed.exit_code, 3) << describe(failed);
  unchanged();

  // Interrupted part-way (Ctrl-C): a long run, stopped after 0.4 s.
  RunOptions options;
  options.signal = SIGINT;
  options.signal_after = std::chrono::milliseconds(400);
  const RunResult stopped =
      run_tumble(args(args({"render", "--duration", "10000", "--out", "o", "--quiet"}, kSmall),
                      {"--gif", "--webp", "--strobe", "3", "--still", "0.2"}),
                 dir.path(), options);
  EXPECT_EQ(stopped.exit_code, 128 + SIGINT) << describe(stopped);
  unchanged();
}

}  // namespace
}  // namespace tumble_e2e
