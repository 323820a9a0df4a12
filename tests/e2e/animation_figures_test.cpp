// clip.gif and clip.webp end to end (SPEC.md: --gif, --webp): looping forever, their frames and
// timing as the files store them, read back independently of tumble (the GIF's blocks and
// libavcodec through ffprobe/ffmpeg; the WebP's RIFF chunks, and libwebp's webpmux where the
// `webp` package is installed), transparency, determinism and size.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>

#include "figures_formats.hpp"
#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

std::vector<std::string> args(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

const std::vector<std::string> kSmall = {"--size", "160x120"};

std::string side_view() {
  return (source_dir() / "assets/scenes/side_view.toml").string();
}

// round(100·j·step / fps) in integers, as SPEC promises the GIF's frame starts.
long start_cs(long j, int step, int fps) {
  return (200L * j * step + fps) / (2L * fps);
}

/// ffprobe's packets of the first video stream: pts in the stream's time base.
std::vector<long> packet_pts(const fs::path& file) {
  const RunResult r = run_program("ffprobe",
                                  {"-v", "error", "-select_streams", "v:0", "-show_entries",
                                   "packet=pts", "-of", "csv=p=0", fs::absolute(file).string()},
                                  "/");
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  std::vector<long> pts;
  for (const std::string& line : split(r.out, '\n'))
    if (!line.empty()) pts.push_back(std::strtol(line.c_str(), nullptr, 10));
  return pts;
}

// ---------------------------------------------------------------------------------------------
// GIF

// 0.5 s at 60 fps: 30 clip frames. A GIF delay is whole centiseconds and browsers play one
// under 2 cs as 10 cs, so the GIF takes every 2nd frame (30 frames/s, 3.33 cs) and starts frame
// j at round(100·j·2/60) cs: delays 3, 4, 3, 3, 4, 3, ... that never drift, 0.5 s in all.
TEST(Gif, LoopsForeverWithTheClipsTimingInWholeCentiseconds) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", "--gif", "--no-mp4", "--duration", "0.5", "--out", "o"}, kSmall), dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const fs::path gif_path = dir / "o/clip.gif";
  const GifFile gif = parse_gif(read_file(gif_path));
  ASSERT_TRUE(gif.valid) << "clip.gif is not a well-formed GIF89a";
  EXPECT_EQ(gif.width, 160);
  EXPECT_EQ(gif.height, 120);
  ASSERT_TRUE(gif.loop_count.has_value()) << "no NETSCAPE2.0 loop extension";
  EXPECT_EQ(*gif.loop_count, 0) << "0 = loop forever";
  EXPECT_TRUE(gif.global_palette) << "one palette for the clip";
  EXPECT_EQ(gif.images, 15);
  ASSERT_EQ(gif.delays_cs.size(), 15u);
  long total = 0;
  for (long j = 0; j < 15; ++j) {
    const long end = j + 1 < 15 ? start_cs(j + 1, 2, 60) : 50;
    EXPECT_EQ(gif.delays_cs[j], end - start_cs(j, 2, 60)) << "frame " << j;
    EXPECT_GE(gif.delays_cs[j], 2);
    total += gif.delays_cs[j];
  }
  EXPECT_EQ(total, 50) << "the GIF lasts the clip's 0.5 s";

  // libavcodec agrees: 15 frames of GIF, 0.5 s, starting where the delays say.
  auto p = probe(gif_path);
  EXPECT_EQ(p["codec_name"], "gif");
  EXPECT_EQ(p["nb_read_frames"], "15");
  EXPECT_NEAR(std::strtod(p["duration"].c_str(), nullptr), 0.5, 1e-9);
  EXPECT_EQ(p["time_base"], "1/100");
  const std::vector<long> pts = packet_pts(gif_path);
  ASSERT_EQ(pts.size(), 15u);
  for (long j = 0; j < 15; ++j) EXPECT_EQ(pts[j], start_cs(j, 2, 60)) << "frame " << j;

  // The picture survives the palette: the sky corner stays within dithering of its colour.
  const Rgba first = decode_rgba(gif_path, 160, 120);
  ASSERT_FALSE(first.bytes.empty());
  const int sky[3] = {0xdf, 0xe6, 0xee};
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(first.at(2, 2)[c], sky[c], 12) << "channel " << c;

  nlohmann::json j = read_json(dir / "o/run.json");
  const nlohmann::json& g = j["figures"]["gif"];
  ASSERT_TRUE(g.is_object()) << j.dump(2);
  EXPECT_EQ(g["frames"], 15);
  EXPECT_EQ(g["frame_step"], 2);
  EXPECT_EQ(g["rate_hz"], 30.0);
  EXPECT_EQ(g["delays_cs"], nlohmann::json::array({3, 4}));
  EXPECT_EQ(g["exact"], false);
  EXPECT_EQ(g["duration_s"], 0.5);
  ASSERT_EQ(j["outputs"].size(), 1u);
  EXPECT_EQ(j["outputs"][0]["path"], "o/clip.gif");
  EXPECT_EQ(j["outputs"][0]["sha256"], system_sha256(gif_path));
  EXPECT_TRUE(j["wall_time"]["gif_s"].is_number());
}

// At 25 fps every frame lasts exactly 4 cs: all of them are kept, all delays equal.
TEST(Gif, ExactWhereCentisecondsCanCarryTheRate) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", "--gif", "--no-mp4", "--fps", "25", "--duration", "0.4", "--out", "o"},
           kSmall),
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const GifFile gif = parse_gif(read_file(dir / "o/clip.gif"));
  ASSERT_TRUE(gif.valid);
  EXPECT_EQ(gif.images, 10);
  EXPECT_EQ(gif.delays_cs, std::vector<int>(10, 4));
  nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["figures"]["gif"]["frame_step"], 1);
  EXPECT_EQ(j["figures"]["gif"]["exact"], true);
  EXPECT_EQ(j["figures"]["gif"]["delays_cs"], nlohmann::json::array({4}));
}

// ---------------------------------------------------------------------------------------------
// WebP

// The side view's ball moves in every frame (at the scene's aspect, 2.4:1, it is in view from
// the start), so every frame is its own ANMF; durations are
// whole milliseconds, frame k starting at round(1000·k/60) ms: 17, 16, 17, 17, 16, ... 500 ms.
TEST(Webp, LoopsForeverWithOneFramePerClipFrameInWholeMilliseconds) {
  const TestDir dir;
  const RunResult r = run_tumble({"render", side_view(), "--webp", "--no-mp4", "--duration", "0.5",
                                  "--size", "240x100", "--out", "o"},
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const fs::path path = dir / "o/clip.webp";
  const WebpFile webp = parse_webp(read_file(path));
  ASSERT_TRUE(webp.valid) << "clip.webp is not a well-formed RIFF WebP";
  EXPECT_TRUE(webp.animation_flag);
  ASSERT_TRUE(webp.loop_count.has_value()) << "no ANIM chunk";
  EXPECT_EQ(*webp.loop_count, 0) << "0 = loop forever";
  ASSERT_EQ(webp.durations_ms.size(), 30u) << "one ANMF per frame";
  long total = 0;
  for (long k = 0; k < 30; ++k) {
    const long start = (2000 * k + 60) / 120, end = (2000 * (k + 1) + 60) / 120;
    EXPECT_EQ(webp.durations_ms[k], end - start) << "frame " << k;
    total += webp.durations_ms[k];
  }
  EXPECT_EQ(total, 500) << "the WebP lasts the clip's 0.5 s";

  // libwebp's own reading, where its tools are installed (scripts/setup --tests installs `webp`).
  if (run_program("webpmux", {"-version"}, "/").exit_code == 0) {
    const RunResult info = run_program("webpmux", {"-info", fs::absolute(path).string()}, "/");
    EXPECT_EQ(info.exit_code, 0) << describe(info);
    EXPECT_NE(info.out.find("Number of frames: 30"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("Loop Count : 0"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("Canvas size: 240 x 100"), std::string::npos) << info.out;
  }

  nlohmann::json j = read_json(dir / "o/run.json");
  const nlohmann::json& w = j["figures"]["webp"];
  ASSERT_TRUE(w.is_object()) << j.dump(2);
  EXPECT_EQ(w["frames"], 30);
  EXPECT_EQ(w["frame_step"], 1);
  EXPECT_EQ(w["rate_hz"], 60.0);
  EXPECT_EQ(w["delays_ms"], nlohmann::json::array({16, 17}));
  EXPECT_EQ(w["duration_s"], 0.5);
  EXPECT_EQ(j["outputs"][0]["path"], "o/clip.webp");
  EXPECT_EQ(j["outputs"][0]["sha256"], system_sha256(path));
  EXPECT_TRUE(j["wall_time"]["webp_s"].is_number());
}

// Browsers play a WebP frame of 10 ms or less as 100 ms: a 120 fps clip keeps every 3rd frame
// (25 ms, 40 frames/s). 0.51 s at 120 fps is 61 clip frames, not a whole number of steps: the
// last kept frame (clip frame 60, 8 ms) is left out and frame 57 lasts to the end, so the loop
// lasts round(1000·61/120) = 508 ms, the clip's 508.3 ms to the millisecond.
TEST(Webp, At120FpsEveryFrameLastsAtLeast20MsAndTheLoopLastsTheClip) {
  const TestDir dir;
  const RunResult r = run_tumble({"render", side_view(), "--webp", "--no-mp4", "--fps", "120",
                                  "--duration", "0.51", "--size", "240x100", "--out", "o"},
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const fs::path path = dir / "o/clip.webp";
  const WebpFile webp = parse_webp(read_file(path));
  ASSERT_TRUE(webp.valid);
  ASSERT_TRUE(webp.loop_count.has_value());
  EXPECT_EQ(*webp.loop_count, 0);
  ASSERT_EQ(webp.durations_ms.size(), 20u) << "clip frames 0, 3, ..., 57";
  long total = 0;
  for (std::size_t j = 0; j < webp.durations_ms.size(); ++j) {
    EXPECT_GE(webp.durations_ms[j], 20) << "frame " << j << " would play as 100 ms";
    total += webp.durations_ms[j];
  }
  EXPECT_EQ(webp.durations_ms.back(), 33);
  const double clip_ms = 1000.0 * 61 / 120;
  EXPECT_LE(std::abs(double(total) - clip_ms), 0.5) << "the loop lasts the clip";
  if (run_program("webpmux", {"-version"}, "/").exit_code == 0) {
    const RunResult info = run_program("webpmux", {"-info", fs::absolute(path).string()}, "/");
    EXPECT_NE(info.out.find("Number of frames: 20"), std::string::npos) << info.out;
  }
  // run.json says what rate the WebP carries, as it does for the GIF.
  nlohmann::json j = read_json(dir / "o/run.json");
  const nlohmann::json& w = j["figures"]["webp"];
  ASSERT_TRUE(w.is_object()) << j.dump(2);
  EXPECT_EQ(w["frames"], 20);
  EXPECT_EQ(w["frame_step"], 3);
  EXPECT_EQ(w["rate_hz"], 40.0);
  EXPECT_EQ(w["delays_ms"], nlohmann::json::array({25, 33}));
  EXPECT_EQ(w["exact"], true);
  EXPECT_EQ(w["duration_s"], 0.508);
  EXPECT_EQ(j["counts"]["frames"], 61);
}

// ---------------------------------------------------------------------------------------------
// Transparency, determinism, size

// The default scene's first frames: the box in the sky. GIF transparency is one palette entry
// (alpha < 128 transparent); WebP keeps the alpha channel (ALPH chunks, the VP8X alpha flag).
TEST(AnimatedFigures, TransparentGifAndWebp) {
  const TestDir dir;
  const RunResult r = run_tumble(args({"render", "--transparent", "--gif", "--webp", "--no-mp4",
                                       "--duration", "0.2", "--out", "o"},
                                      kSmall),
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const GifFile gif = parse_gif(read_file(dir / "o/clip.gif"));
  ASSERT_TRUE(gif.valid);
  ASSERT_FALSE(gif.transparent.empty());
  EXPECT_TRUE(gif.transparent.front()) << "the first frame's control block sets transparency";
  const Rgba first = decode_rgba(dir / "o/clip.gif", 160, 120);
  ASSERT_FALSE(first.bytes.empty());
  EXPECT_EQ(first.alpha(0, 0), 0) << "the sky is transparent";
  EXPECT_EQ(first.alpha(80, 115), 255) << "the floor in front is opaque";

  const WebpFile webp = parse_webp(read_file(dir / "o/clip.webp"));
  ASSERT_TRUE(webp.valid);
  EXPECT_TRUE(webp.alpha_flag);
  EXPECT_GT(webp.alpha_chunks, 0);
  EXPECT_EQ(read_json(dir / "o/run.json")["figures"]["transparent"], true);
}

TEST(AnimatedFigures, SameRunTwiceIsByteIdentical) {
  const TestDir dir;
  for (const char* out : {"a", "b"}) {
    const RunResult r = run_tumble(
        args({"render", "--gif", "--webp", "--duration", "0.5", "--out", out, "--quiet"}, kSmall),
        dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
  }
  for (const char* f : {"clip.gif", "clip.webp", "clip.mp4"}) {
    const std::string a = read_file(dir / "a" / f);
    ASSERT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == read_file(dir / "b" / f)) << f << " differs between two runs";
  }
}

// SPEC's budget for a README figure: the default 4 s clip at 480x270 under 1 MB, each format.
TEST(AnimatedFigures, DefaultClipAt480x270IsUnderOneMegabyte) {
  const TestDir dir;
  const RunResult r = run_tumble(
      {"render", "--size", "480x270", "--gif", "--webp", "--out", "o", "--quiet"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  for (const char* f : {"clip.gif", "clip.webp"}) {
    const auto size = fs::file_size(dir / "o" / f);
    EXPECT_LT(size, 1'000'000u) << f;
    EXPECT_GT(size, 10'000u) << f << ": 4 s of animation cannot be this small";
  }
  nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["figures"]["gif"]["frames"], 120);
  EXPECT_EQ(j["figures"]["gif"]["duration_s"], 4.0);
  EXPECT_EQ(j["figures"]["webp"]["frames"], 240);
  EXPECT_EQ(j["figures"]["webp"]["duration_s"], 4.0);
}

}  // namespace
}  // namespace tumble_e2e
