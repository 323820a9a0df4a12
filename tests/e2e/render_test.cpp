// tumble render and tumble info end to end: clip.mp4 as ffprobe sees it, PNG frames and stills,
// run.json, determinism, agreement with simulate, the render options' checks, what a failed run
// leaves behind, and every example scene (SPEC.md: Commands, Exit codes, Time, Outputs).
// Every render is tiny (160x120, at most 2 s of scene time) so the file runs in a few seconds on
// llvmpipe.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <regex>
#include <tuple>
#include <utility>

#include "figures_formats.hpp"
#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

const std::regex kSha256Hex("[0-9a-f]{64}");

// The small render every test starts from.
const std::vector<std::string> kSmall = {"--size", "160x120"};

std::vector<std::string> args(std::vector<std::string> head, const std::vector<std::string>& tail) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

/// The types of the top-level boxes of an MP4, in file order ("ftyp", "moov", "mdat", …); empty
/// when the file is not a well-formed sequence of boxes.
std::vector<std::string> top_level_boxes(const fs::path& mp4) {
  const std::string bytes = read_file(mp4);
  std::vector<std::string> types;
  std::size_t at = 0;
  auto byte = [&](std::size_t i) {
    return static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[i]));
  };
  while (at + 8 <= bytes.size()) {
    std::uint64_t size = 0;
    for (std::size_t i = 0; i < 4; ++i) size = size << 8 | byte(at + i);
    std::size_t header = 8;
    if (size == 1) {  // 64-bit size after the type
      if (at + 16 > bytes.size()) return {};
      size = 0;
      for (std::size_t i = 8; i < 16; ++i) size = size << 8 | byte(at + i);
      header = 16;
    } else if (size == 0) {  // to the end of the file
      size = bytes.size() - at;
    }
    if (size < header || at + size > bytes.size()) return {};
    types.push_back(bytes.substr(at + 4, 4));
    at += static_cast<std::size_t>(size);
  }
  if (at != bytes.size()) return {};
  return types;
}

std::ptrdiff_t index_of(const std::vector<std::string>& v, const std::string& x) {
  const auto it = std::find(v.begin(), v.end(), x);
  return it == v.end() ? -1 : it - v.begin();
}

void expect_png(const fs::path& path, std::uint32_t width, std::uint32_t height) {
  SCOPED_TRACE(path.string());
  ASSERT_TRUE(fs::is_regular_file(path));
  const PngInfo h = png_info(path);
  ASSERT_TRUE(h.valid) << "not a PNG";
  EXPECT_EQ(h.width, width);
  EXPECT_EQ(h.height, height);
  EXPECT_EQ(h.bit_depth, 8);
  EXPECT_EQ(h.color_type, 2) << "SPEC: 8-bit RGB";
}

/// `tumble info`'s "Key: value" lines.
std::map<std::string, std::string> info_lines(const std::string& out) {
  std::map<std::string, std::string> values;
  for (const std::string& line : split(out, '\n')) {
    const std::size_t colon = line.find(": ");
    if (colon != std::string::npos && !line.starts_with(" "))
      values[line.substr(0, colon)] = line.substr(colon + 2);
  }
  return values;
}

// ---------------------------------------------------------------------------------------------
// clip.mp4 and run.json

TEST(Render, DefaultSceneWritesAPlayableMp4) {
  const TestDir dir;
  const RunResult r =
      run_tumble(args({"render"}, {"--size", "160x120", "--duration", "0.5"}), dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.err, "") << "stderr is not a terminal: no progress line, and nothing went wrong";
  EXPECT_NE(r.out.find("rendered 30 frames (160x120, 60 fps)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("out/default"), std::string::npos) << r.out;

  const fs::path clip = dir / "out/default/clip.mp4";
  ASSERT_TRUE(fs::is_regular_file(clip));
  EXPECT_EQ(names_in(dir / "out/default"), (std::vector<std::string>{"clip.mp4", "run.json"}));
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";

  auto p = probe(clip);
  EXPECT_EQ(p["codec_name"], "h264");
  EXPECT_EQ(p["pix_fmt"], "yuv420p");
  EXPECT_EQ(p["width"], "160");
  EXPECT_EQ(p["height"], "120");
  EXPECT_EQ(p["nb_read_frames"], "30");  // round(0.5 · 60)
  ASSERT_FALSE(p["duration"].empty());
  EXPECT_NEAR(std::strtod(p["duration"].c_str(), nullptr), 0.5, 1e-3);  // N / fps exactly

  // +faststart: the index (moov) comes before the media data (mdat).
  const std::vector<std::string> boxes = top_level_boxes(clip);
  ASSERT_FALSE(boxes.empty()) << "clip.mp4 is not a sequence of MP4 boxes";
  EXPECT_EQ(boxes.front(), "ftyp");
  const std::ptrdiff_t moov = index_of(boxes, "moov"), mdat = index_of(boxes, "mdat");
  ASSERT_GE(moov, 0);
  ASSERT_GE(mdat, 0);
  EXPECT_LT(moov, mdat) << "moov after mdat: not +faststart";

  nlohmann::json j = read_json(dir / "out/default/run.json");
  EXPECT_EQ(j["tool"]["name"], "tumble");
  EXPECT_EQ(j["command"], "render");
  EXPECT_EQ(j["scene"]["sha256"], system_sha256(source_dir() / "assets/scenes/default.toml"));
  EXPECT_EQ(j["settings"]["render"]["width"], 160);
  EXPECT_EQ(j["settings"]["render"]["height"], 120);
  EXPECT_EQ(j["settings"]["render"]["fps"], 60);
  EXPECT_EQ(j["settings"]["simulation"]["duration_s"], 0.5);
  EXPECT_EQ(j["counts"]["samples"], 30);
  EXPECT_EQ(j["counts"]["frames"], 30);  // SPEC: run.json has the frame count
  EXPECT_EQ(j["counts"]["steps"], 500);
  EXPECT_EQ(j["counts"]["sample_rate_hz"], 60.0);
  ASSERT_TRUE(j["gl"].is_object()) << j.dump(2);
  ASSERT_TRUE(j["gl"]["renderer"].is_string());
  const std::string renderer = j["gl"]["renderer"].get<std::string>();
  EXPECT_FALSE(renderer.empty());
  EXPECT_TRUE(j["gl"]["vendor"].is_string() && !j["gl"]["vendor"].get<std::string>().empty());
  // The renderer run.json names is the one tumble info reports (llvmpipe on a machine without a
  // GPU) and the one the summary line names.
  const RunResult info = run_tumble({"info"}, dir.path());
  ASSERT_EQ(info.exit_code, 0) << describe(info);
  const std::string info_renderer = info_lines(info.out)["GL renderer"];
  ASSERT_FALSE(info_renderer.empty()) << info.out;
  EXPECT_TRUE(renderer.starts_with(info_renderer)) << renderer << " vs " << info_renderer;
  EXPECT_NE(r.out.find(info_renderer), std::string::npos) << r.out;
  // --encoder auto: hardware H.264 where there is a GPU, else libx264. Rendering on llvmpipe
  // means no GPU, so no hardware encoder either.
  ASSERT_TRUE(j["encoder"].is_string()) << j.dump(2);
  const std::string encoder = j["encoder"].get<std::string>();
  EXPECT_NE(info.out.find(encoder), std::string::npos) << encoder << " is not listed by info";
  // info says which encoder auto uses here, and that one is usable.
  EXPECT_EQ(info_lines(info.out)["encoder auto"], encoder) << info.out;
  EXPECT_NE(info_lines(info.out)["H.264 encoders usable here"].find(encoder), std::string::npos)
      << info.out;
  if (info_renderer.find("llvmpipe") != std::string::npos) {
    EXPECT_NE(renderer.find("llvmpipe"), std::string::npos) << renderer;
    EXPECT_EQ(encoder, "libx264");
  }

  ASSERT_TRUE(j["wall_time"].is_object()) << j.dump(2);
  const double total = j["wall_time"]["total_s"].get<double>();
  EXPECT_GT(total, 0.0);
  for (const char* stage : {"simulate_s", "render_s", "readback_s", "encode_s"}) {
    SCOPED_TRACE(stage);
    ASSERT_TRUE(j["wall_time"][stage].is_number()) << j["wall_time"].dump();
    EXPECT_GE(j["wall_time"][stage].get<double>(), 0.0);
    EXPECT_LE(j["wall_time"][stage].get<double>(), total);
  }
  EXPECT_GT(j["wall_time"]["render_s"].get<double>(), 0.0);
  EXPECT_GT(j["wall_time"]["encode_s"].get<double>(), 0.0);
  EXPECT_FALSE(j["wall_time"].contains("png_s")) << "no PNG was written: the stage is absent";

  ASSERT_TRUE(j["outputs"].is_array());
  ASSERT_EQ(j["outputs"].size(), 1u) << j["outputs"].dump();
  EXPECT_EQ(j["outputs"][0]["path"], "out/default/clip.mp4");
  const std::string sha = j["outputs"][0]["sha256"].get<std::string>();
  EXPECT_TRUE(std::regex_match(sha, kSha256Hex)) << sha;
  EXPECT_EQ(sha, system_sha256(clip));
  ASSERT_EQ(j["bodies"].size(), 1u);
  EXPECT_EQ(j["bodies"][0]["name"], "box");
}

TEST(Render, EncoderLibx264ByName) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", "--encoder", "libx264", "--duration", "0.25", "--out", "o"}, kSmall),
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  auto p = probe(dir / "o/clip.mp4");
  EXPECT_EQ(p["codec_name"], "h264");
  EXPECT_EQ(p["pix_fmt"], "yuv420p");
  EXPECT_EQ(p["nb_read_frames"], "15");
  EXPECT_EQ(read_json(dir / "o/run.json")["encoder"], "libx264");
}

// SPEC: an MP4 of N frames lasts exactly N / fps, in the container too (mvhd, which players
// and ffprobe's format duration read): 7 frames at 60 fps are 0.1166… s, not the 0.117 that a
// millisecond movie clock would give, and 4 frames at 7 fps 0.571428… s.
TEST(Render, ClipDurationIsExactlyFramesOverFpsInTheContainer) {
  const TestDir dir;
  for (const auto& [fps, duration, frames] :
       {std::tuple{"60", "0.11667", 7}, std::tuple{"7", "0.5", 4}}) {
    const std::string out = std::string("o") + fps;
    const RunResult r = run_tumble(
        args({"render", "--fps", fps, "--duration", duration, "--out", out}, kSmall), dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    auto p = probe(dir / out / "clip.mp4");
    EXPECT_EQ(p["nb_read_frames"], std::to_string(frames));
    EXPECT_NEAR(std::strtod(p["duration"].c_str(), nullptr), frames / std::stod(fps), 1e-6)
        << fps << " fps: " << p["duration"];
  }
}

// ---------------------------------------------------------------------------------------------
// PNG frames and stills

TEST(Render, PngFramesOnePerFrame) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", "--png", "--no-mp4", "--fps", "10", "--duration", "0.5", "--out", "o"},
           kSmall),
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  // round(0.5 · 10) = 5 frames, numbered from 0, and nothing else in frames/.
  EXPECT_EQ(names_in(dir / "o/frames"),
            (std::vector<std::string>{"frame_00000.png", "frame_00001.png", "frame_00002.png",
                                      "frame_00003.png", "frame_00004.png"}));
  for (int k = 0; k < 5; ++k)
    expect_png(dir / "o/frames" / ("frame_0000" + std::to_string(k) + ".png"), 160, 120);
  EXPECT_FALSE(fs::exists(dir / "o/clip.mp4"));
  EXPECT_TRUE(find_files_named(dir.path(), "clip.mp4").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";

  nlohmann::json j = read_json(dir / "o/run.json");
  EXPECT_EQ(j["counts"]["samples"], 5);
  EXPECT_EQ(j["settings"]["render"]["fps"], 10);
  EXPECT_EQ(j["encoder"], nullptr) << "--no-mp4: no encoder was used";
  EXPECT_FALSE(j["wall_time"].contains("encode_s"));
  EXPECT_TRUE(j["wall_time"]["png_s"].is_number());
  ASSERT_EQ(j["outputs"].size(), 5u) << j["outputs"].dump();
  for (std::size_t k = 0; k < 5; ++k) {
    const std::string name = "o/frames/frame_0000" + std::to_string(k) + ".png";
    EXPECT_EQ(j["outputs"][k]["path"], name);
    EXPECT_EQ(j["outputs"][k]["sha256"], system_sha256(dir / name));
  }
}

TEST(Render, StillsAtTheGivenTimes) {
  const TestDir dir;
  const RunResult r = run_tumble(args({"render", "--still", "0.25", "--still", "0", "--no-mp4",
                                       "--duration", "0.5", "--out", "o"},
                                      kSmall),
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  expect_png(dir / "o/still_0.25.png", 160, 120);
  expect_png(dir / "o/still_0.png", 160, 120);
  EXPECT_EQ(names_in(dir / "o"),
            (std::vector<std::string>{"run.json", "still_0.25.png", "still_0.png"}));
  EXPECT_TRUE(read_file(dir / "o/still_0.png") != read_file(dir / "o/still_0.25.png"))
      << "the box falls between t = 0 and t = 0.25: the stills must differ";
  nlohmann::json j = read_json(dir / "o/run.json");
  std::vector<std::string> listed;
  for (const auto& out : j["outputs"]) {
    listed.push_back(out["path"].get<std::string>());
    EXPECT_EQ(out["sha256"], system_sha256(dir / out["path"].get<std::string>()));
  }
  std::sort(listed.begin(), listed.end());
  EXPECT_EQ(listed, (std::vector<std::string>{"o/still_0.25.png", "o/still_0.png"}));
}

TEST(Render, AStillTakesOneTimeSoTheScenePathMayFollow) {
  // `--still T` is one time per occurrence: a scene path after it is the scene, not a time.
  const TestDir dir;
  const RunResult r =
      run_tumble({"render", "--size", "64x48", "--duration", "0.5", "--no-mp4", "--out", "o",
                  "--still", "0.25", (source_dir() / "assets/scenes/particle.toml").string()},
                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(names_in(dir / "o"), (std::vector<std::string>{"run.json", "still_0.25.png"}));
  const std::string scene = read_json(dir / "o/run.json")["scene"]["path"].get<std::string>();
  EXPECT_NE(scene.find("particle.toml"), std::string::npos) << scene;
}

TEST(Render, StillAtAFrameTimeIsThatFrame) {
  // A still at t = k/fps draws the same state as frame k: the same pixels, the same PNG bytes.
  const TestDir dir;
  const RunResult r = run_tumble(args({"render", "--png", "--no-mp4", "--still", "0", "--still",
                                       "0.25", "--duration", "0.5", "--out", "o"},
                                      kSmall),
                                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(read_file(dir / "o/still_0.png") == read_file(dir / "o/frames/frame_00000.png"));
  EXPECT_TRUE(read_file(dir / "o/still_0.25.png") == read_file(dir / "o/frames/frame_00015.png"));
}

TEST(Render, FramesChangeOverTime) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", "--png", "--no-mp4", "--fps", "10", "--duration", "0.5", "--out", "o"},
           kSmall),
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const std::string first = read_file(dir / "o/frames/frame_00000.png");
  const std::string last = read_file(dir / "o/frames/frame_00004.png");
  ASSERT_FALSE(first.empty());
  ASSERT_FALSE(last.empty());
  EXPECT_TRUE(first != last) << "the box falls ~0.8 m by t = 0.4 s; the frames must differ";
  EXPECT_TRUE(read_file(dir / "o/frames/frame_00001.png") != first);
}

// ---------------------------------------------------------------------------------------------
// Determinism and agreement with simulate

TEST(Render, SameRunTwiceIsByteIdentical) {
  const TestDir dir;
  for (const char* out : {"a", "b"}) {
    const RunResult r =
        run_tumble(args({"render", "--png", "--duration", "0.5", "--out", out, "--quiet"}, kSmall),
                   dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
  }
  const std::string clip_a = read_file(dir / "a/clip.mp4");
  ASSERT_FALSE(clip_a.empty());
  EXPECT_TRUE(clip_a == read_file(dir / "b/clip.mp4")) << "clip.mp4 differs between two runs";
  const std::vector<std::string> frames = names_in(dir / "a/frames");
  ASSERT_EQ(frames.size(), 30u);
  EXPECT_EQ(frames, names_in(dir / "b/frames"));
  for (const std::string& f : frames)
    EXPECT_TRUE(read_file(dir / "a/frames" / f) == read_file(dir / "b/frames" / f))
        << f << " differs between two runs";
  nlohmann::json a = read_json(dir / "a/run.json"), b = read_json(dir / "b/run.json");
  EXPECT_EQ(a["outputs"][0]["sha256"], b["outputs"][0]["sha256"]);
  EXPECT_EQ(a["physics"], b["physics"]);
}

// The trajectory is not visible in the pixels exactly, but run.json's physics block is computed
// from it: energy at the start and end, contacts, the largest gain and the deepest penetration
// must be exactly those of simulate for the same scene and duration, whatever the fps and outputs.
TEST(Render, PhysicsMatchesSimulate) {
  const TestDir dir;
  const RunResult sim =
      run_tumble({"simulate", "--duration", "2", "--out", "s", "--quiet"}, dir.path());
  ASSERT_EQ(sim.exit_code, 0) << describe(sim);
  nlohmann::json s = read_json(dir / "s/run.json");
  ASSERT_TRUE(s["physics"].is_object());
  EXPECT_GT(s["physics"]["contacts"].get<long>(), 0) << "2 s covers the first impacts";
  // The render at the scene's fps with an MP4, and at another fps with a still only.
  const std::vector<std::vector<std::string>> variants = {
      {},
      {"--fps", "24", "--no-mp4", "--still", "1.3"},
  };
  for (std::size_t v = 0; v < variants.size(); ++v) {
    SCOPED_TRACE("render variant " + std::to_string(v));
    // Built by appending: GCC 12 misreports `"r" + std::to_string(v)` (-Wrestrict).
    std::string out = "r";
    out += std::to_string(v);
    const RunResult ren = run_tumble(
        args(args({"render", "--duration", "2", "--out", out, "--quiet"}, kSmall), variants[v]),
        dir.path());
    ASSERT_EQ(ren.exit_code, 0) << describe(ren);
    nlohmann::json r = read_json(dir / out / "run.json");
    EXPECT_EQ(r["physics"]["energy_start_J"], s["physics"]["energy_start_J"]);
    EXPECT_EQ(r["physics"]["energy_end_J"], s["physics"]["energy_end_J"]);
    EXPECT_EQ(r["physics"]["contacts"], s["physics"]["contacts"]);
    EXPECT_EQ(r["physics"], s["physics"]);  // and the largest gain, the deepest penetration
    EXPECT_EQ(r["counts"]["steps"], s["counts"]["steps"]);
    EXPECT_EQ(r["bodies"], s["bodies"]);
  }
}

// ---------------------------------------------------------------------------------------------
// Sizes

TEST(Render, OddSizeNeedsNoMp4) {
  const TestDir dir;
  const RunResult mp4 =
      run_tumble({"render", "--size", "161x121", "--duration", "0.1"}, dir.path());
  EXPECT_EQ(mp4.exit_code, 2) << describe(mp4);
  EXPECT_TRUE(mp4.err.starts_with("tumble: error: ")) << mp4.err;
  EXPECT_NE(mp4.err.find("even"), std::string::npos) << mp4.err;
  EXPECT_NE(mp4.err.find("161x121"), std::string::npos) << mp4.err;
  EXPECT_TRUE(find_files_named(dir.path(), "clip.mp4").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "run.json").empty());

  const RunResult png = run_tumble(
      {"render", "--size", "161x121", "--no-mp4", "--png", "--duration", "0.1", "--out", "o"},
      dir.path());
  ASSERT_EQ(png.exit_code, 0) << describe(png);
  const std::vector<std::string> frames = names_in(dir / "o/frames");
  ASSERT_EQ(frames.size(), 6u);  // round(0.1 · 60)
  for (const std::string& f : frames) expect_png(dir / "o/frames" / f, 161, 121);
  EXPECT_FALSE(fs::exists(dir / "o/clip.mp4"));
}

TEST(Render, AbsurdSizesAreBadInput) {
  for (const char* size : {"0x0", "100000x100000", "160x0", "0x120", "-160x120", "160x", "x120"}) {
    SCOPED_TRACE(size);
    const TestDir dir;
    const RunResult r = run_tumble({"render", "--size", size, "--duration", "0.1"}, dir.path());
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_EQ(r.signal, 0);
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
    EXPECT_NE(r.err.find("--size"), std::string::npos) << "the option is not named: " << r.err;
    EXPECT_NE(r.err.find(size), std::string::npos) << "the value is not quoted: " << r.err;
    EXPECT_TRUE(fs::is_empty(dir.path())) << "a rejected render wrote files";
  }
}

// ---------------------------------------------------------------------------------------------
// Output folders that cannot be written; nothing half-written

TEST(Render, OutUnderARegularFileIsExit3) {
  const TestDir dir;
  write_file(dir / "blocker", "not a folder\n");
  const RunResult r = run_tumble(
      args({"render", "--out", "blocker/sub", "--duration", "0.25", "--png"}, kSmall), dir.path());
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
  EXPECT_NE(r.err.find("blocker/sub"), std::string::npos) << "the path is not named: " << r.err;
  EXPECT_TRUE(find_files_named(dir.path(), "clip.mp4").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "run.json").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";
  EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{"blocker"});
  EXPECT_EQ(read_file(dir / "blocker"), "not a folder\n");
}

TEST(Render, UnwritableLocationIsExit3) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", "--out", "/proc/tumble-x", "--duration", "0.25"}, kSmall), dir.path());
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
  EXPECT_NE(r.err.find("/proc/tumble-x"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists("/proc/tumble-x"));
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(Render, FailedRenderKeepsThePreviousGoodClip) {
  const TestDir dir;
  const RunResult good = run_tumble(
      args({"render", "--png", "--duration", "0.25", "--out", "o", "--quiet"}, kSmall), dir.path());
  ASSERT_EQ(good.exit_code, 0) << describe(good);
  const std::string clip = read_file(dir / "o/clip.mp4");
  const std::string json = read_file(dir / "o/run.json");
  const std::string frame = read_file(dir / "o/frames/frame_00000.png");
  ASSERT_FALSE(clip.empty());
  ASSERT_FALSE(frame.empty());

  // Failures of every stage: option checks, the encoder, the EGL device. Into the same folder.
  const std::vector<std::pair<int, std::vector<std::string>>> failures = {
      {2, {"--still", "99"}},
      {2, {"--crf", "60"}},
      {2, {"--size", "161x121"}},
      {2, {"--encoder", "nonexistent"}},
      {3, {"--egl-device", "99"}},
      // An H.264 encoder of FFmpeg that this build lacks (VideoToolbox is macOS only): missing.
      {3, {"--encoder", "h264_videotoolbox"}},
  };
  for (const auto& [code, extra] : failures) {
    SCOPED_TRACE(extra[0] + " " + extra[1]);
    const RunResult bad = run_tumble(
        args(args({"render", "--png", "--duration", "0.25", "--out", "o"}, kSmall), extra),
        dir.path());
    EXPECT_EQ(bad.exit_code, code) << describe(bad);
    EXPECT_TRUE(read_file(dir / "o/clip.mp4") == clip) << "clip.mp4 was changed";
    EXPECT_TRUE(read_file(dir / "o/run.json") == json) << "run.json was changed";
    EXPECT_TRUE(read_file(dir / "o/frames/frame_00000.png") == frame) << "a frame was changed";
    EXPECT_FALSE(fs::exists(dir / "o/.clip.mp4.partial"));
    EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";
  }
}

// A failure on the encoder thread part-way through (here: a frame's PNG path is taken by a
// folder, so its rename fails) ends the run with exit 3 and the path named: promptly, not hung
// waiting for the failed thread, and with no clip, run.json or temporary file left behind.
TEST(Render, FrameWriteFailingPartWayIsExit3) {
  const TestDir dir;
  fs::create_directories(dir / "o/frames/frame_00010.png");
  RunOptions options;
  options.timeout = std::chrono::seconds(10);
  const RunResult r = run_tumble(
      args({"render", "--png", "--duration", "0.5", "--out", "o"}, kSmall), dir.path(), options);
  ASSERT_FALSE(r.timed_out) << "the render hung after its encoder thread failed";
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
  EXPECT_NE(r.err.find("frame_00010.png"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_directory(dir / "o/frames/frame_00010.png"));
  EXPECT_FALSE(fs::exists(dir / "o/clip.mp4"));
  EXPECT_FALSE(fs::exists(dir / "o/run.json"));
  EXPECT_TRUE(find_files_named(dir.path(), "").empty()) << "a temporary file was left behind";
}

// A render stopped part-way (Ctrl-C, a CI timeout) leaves the previous clip under its name.
TEST(Render, InterruptedRenderKeepsThePreviousGoodClip) {
  const TestDir dir;
  const RunResult good = run_tumble(
      args({"render", "--duration", "0.25", "--out", "o", "--quiet"}, kSmall), dir.path());
  ASSERT_EQ(good.exit_code, 0) << describe(good);
  const std::string clip = read_file(dir / "o/clip.mp4");
  const std::string json = read_file(dir / "o/run.json");
  for (const int signal : {SIGINT, SIGTERM}) {
    SCOPED_TRACE("signal " + std::to_string(signal));
    RunOptions options;
    options.signal = signal;
    options.signal_after = std::chrono::milliseconds(400);
    // 3 hours of clip at 160x120 takes far longer than 0.4 s.
    const RunResult stopped =
        run_tumble(args({"render", "--duration", "10000", "--out", "o", "--quiet"}, kSmall),
                   dir.path(), options);
    EXPECT_NE(stopped.exit_code, 0) << describe(stopped);
    EXPECT_FALSE(stopped.timed_out);
    EXPECT_TRUE(read_file(dir / "o/clip.mp4") == clip) << "clip.mp4 was changed";
    EXPECT_TRUE(read_file(dir / "o/run.json") == json) << "run.json was changed";
  }
}

// ---------------------------------------------------------------------------------------------
// Option checks

TEST(Render, StillBeyondTheRunIsBadInput) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", "--still", "99", "--no-mp4", "--duration", "0.5"}, kSmall), dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
  EXPECT_NE(r.err.find("--still 99"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("0.5"), std::string::npos) << "the run's length is not named: " << r.err;
  EXPECT_TRUE(find_files_named(dir.path(), "still_99.png").empty());
  for (const char* t : {"-1", "0.5000001", "nan", "inf"}) {
    SCOPED_TRACE(t);
    const RunResult r2 = run_tumble(
        args({"render", "--still", t, "--no-mp4", "--duration", "0.5"}, kSmall), dir.path());
    EXPECT_EQ(r2.exit_code, 2) << describe(r2);
  }
  // The end of the run itself is in the run.
  const RunResult end = run_tumble(
      args({"render", "--still", "0.5", "--no-mp4", "--duration", "0.5", "--out", "e"}, kSmall),
      dir.path());
  EXPECT_EQ(end.exit_code, 0) << describe(end);
  expect_png(dir / "e/still_0.5.png", 160, 120);
}

TEST(Render, NoMp4AloneHasNothingToWrite) {
  const TestDir dir;
  const RunResult r =
      run_tumble(args({"render", "--no-mp4", "--duration", "0.25"}, kSmall), dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_NE(r.err.find("nothing to write"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(Render, CrfOutOfRangeIsBadInput) {
  const TestDir dir;
  for (const char* crf : {"60", "-1", "52"}) {
    SCOPED_TRACE(crf);
    const RunResult r =
        run_tumble(args({"render", "--crf", crf, "--duration", "0.25"}, kSmall), dir.path());
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_NE(r.err.find("--crf"), std::string::npos) << r.err;
  }
  EXPECT_TRUE(find_files_named(dir.path(), "clip.mp4").empty());
  // The end of the range works (the other end, 0, is lossless and slower to encode).
  const RunResult r51 = run_tumble(
      args({"render", "--crf", "51", "--duration", "0.1", "--out", "c"}, kSmall), dir.path());
  EXPECT_EQ(r51.exit_code, 0) << describe(r51);
  EXPECT_TRUE(fs::is_regular_file(dir / "c/clip.mp4"));
}

TEST(Render, UnknownEncoderIsBadInput) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", "--encoder", "nonexistent", "--duration", "0.25"}, kSmall), dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
  EXPECT_NE(r.err.find("nonexistent"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("libx264"), std::string::npos)
      << "the encoders that exist are not listed: " << r.err;
  EXPECT_TRUE(find_files_named(dir.path(), "clip.mp4").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "run.json").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "").empty());
  // An encoder that exists but is not H.264 is refused the same way.
  const RunResult mpeg4 =
      run_tumble(args({"render", "--encoder", "mpeg4", "--duration", "0.25"}, kSmall), dir.path());
  EXPECT_EQ(mpeg4.exit_code, 2) << describe(mpeg4);
  EXPECT_TRUE(find_files_named(dir.path(), "clip.mp4").empty());
}

TEST(Render, MissingEglDeviceIsExit3AndNamesTheCount) {
  const TestDir dir;
  const RunResult info = run_tumble({"info"}, dir.path());
  ASSERT_EQ(info.exit_code, 0) << describe(info);
  const std::string count = info_lines(info.out)["EGL devices"];
  ASSERT_FALSE(count.empty()) << info.out;

  const RunResult r =
      run_tumble(args({"render", "--egl-device", "99", "--duration", "0.25"}, kSmall), dir.path());
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
  EXPECT_NE(r.err.find("99"), std::string::npos) << r.err;
  // In agreement with the number: "there is only 1 EGL device", "there are only 2 EGL devices".
  const std::string expected = count == "0"   ? "there is no EGL device"
                               : count == "1" ? "there is only 1 EGL device"
                                              : "there are only " + count + " EGL devices";
  EXPECT_NE(r.err.find(": " + expected + " (see 'tumble info')"), std::string::npos)
      << "the device count (" << count << ") is not named right: " << r.err;
  EXPECT_EQ(r.err.find("only 1 EGL devices"), std::string::npos) << r.err;
  EXPECT_TRUE(find_files_named(dir.path(), "clip.mp4").empty());
  EXPECT_TRUE(find_files_named(dir.path(), "").empty());
}

TEST(Render, ExistingEglDeviceByNumber) {
  const TestDir dir;
  const RunResult info = run_tumble({"info"}, dir.path());
  ASSERT_EQ(info.exit_code, 0) << describe(info);
  if (info_lines(info.out)["EGL devices"] == "0") GTEST_SKIP() << "no EGL device to name";
  const RunResult r = run_tumble(
      args({"render", "--egl-device", "0", "--duration", "0.1", "--out", "o"}, kSmall), dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(fs::is_regular_file(dir / "o/clip.mp4"));
  EXPECT_EQ(read_json(dir / "o/run.json")["counts"]["samples"], 6);
}

// The summary line says what was drawn: frames, stills and a strobe, never "0 frames".
TEST(Render, TheSummarySaysWhatWasWritten) {
  const TestDir dir;
  RunResult r = run_tumble(
      args({"render", "--no-mp4", "--strobe", "6", "--duration", "0.5", "--out", "s"}, kSmall),
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(r.out.starts_with("tumble: rendered strobe.png (6 poses) at 160x120 on ")) << r.out;
  EXPECT_EQ(r.out.find("0 frames"), std::string::npos) << r.out;
  r = run_tumble(args({"render", "--no-mp4", "--still", "0", "--still", "0.2", "--strobe", "3",
                       "--duration", "0.5", "--out", "t"},
                      kSmall),
                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(
      r.out.starts_with("tumble: rendered 2 stills and strobe.png (3 poses) at 160x120 on "))
      << r.out;
  r = run_tumble(args({"render", "--still", "0.1", "--duration", "0.25", "--out", "u"}, kSmall),
                 dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(r.out.starts_with("tumble: rendered 15 frames (160x120, 60 fps) and 1 still on "))
      << r.out;
}

// ---------------------------------------------------------------------------------------------
// Anti-aliasing

// --msaa overrides the scene: 4 samples and none must both render and look different (edges).
TEST(Render, MsaaOptionChangesThePixels) {
  const TestDir dir;
  for (const char* msaa : {"4", "0"}) {
    const RunResult r = run_tumble(args({"render", "--msaa", msaa, "--no-mp4", "--still", "0.25",
                                         "--duration", "0.5", "--out", std::string("m") + msaa},
                                        kSmall),
                                   dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
  }
  const std::string with = read_file(dir / "m4/still_0.25.png");
  const std::string without = read_file(dir / "m0/still_0.25.png");
  ASSERT_FALSE(with.empty());
  ASSERT_FALSE(without.empty());
  EXPECT_TRUE(with != without) << "--msaa 4 and --msaa 0 gave the same image";
  nlohmann::json j4 = read_json(dir / "m4/run.json"), j0 = read_json(dir / "m0/run.json");
  EXPECT_EQ(j4["settings"]["render"]["msaa"], 4);
  EXPECT_EQ(j0["settings"]["render"]["msaa"], 0);
  // What the renderer did: 4x MSAA (llvmpipe offers 4), and no anti-aliasing for 0 ("off").
  EXPECT_EQ(j4["gl"]["antialias"], "msaa 4x") << j4["gl"].dump();
  EXPECT_EQ(j0["gl"]["antialias"], "none") << j0["gl"].dump();
}

// The same through the scene file (the loader's path): antialias = "msaa" with msaa 4 or 0 (no
// samples: none).
TEST(Render, MsaaInTheSceneChangesThePixels) {
  const TestDir dir;
  const std::string base = read_file(source_dir() / "assets/scenes/default.toml");
  ASSERT_FALSE(base.empty());
  for (const char* msaa : {"4", "0"}) {
    write_scene(dir.path(), std::string("m") + msaa + ".toml",
                base + "\n[render]\nantialias = \"msaa\"\nmsaa = " + msaa + "\n");
  }
  for (const char* msaa : {"4", "0"}) {
    const RunResult r =
        run_tumble(args({"render", std::string("m") + msaa + ".toml", "--no-mp4", "--still", "0.25",
                         "--duration", "0.5", "--out", std::string("m") + msaa},
                        kSmall),
                   dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
  }
  EXPECT_TRUE(read_file(dir / "m4/still_0.25.png") != read_file(dir / "m0/still_0.25.png"));
  EXPECT_EQ(read_json(dir / "m4/run.json")["gl"]["antialias"], "msaa 4x");
  EXPECT_EQ(read_json(dir / "m0/run.json")["gl"]["antialias"], "none");
}

// ---------------------------------------------------------------------------------------------
// Example scenes, quiet, info

TEST(Render, EveryExampleSceneRenders) {
  const TestDir dir;
  const std::vector<fs::path> scenes = example_scenes();
  ASSERT_GE(scenes.size(), 5u);
  for (const fs::path& scene : scenes) {
    SCOPED_TRACE(scene.string());
    const RunResult r =
        run_tumble(args({"render", scene.string(), "--duration", "0.25"}, kSmall), dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(r.err, "");
    const fs::path out = dir / "out" / scene.stem();
    nlohmann::json j = read_json(out / "run.json");
    const long frames = std::lround(0.25 * j["settings"]["render"]["fps"].get<double>());
    EXPECT_EQ(j["counts"]["samples"], frames);
    EXPECT_EQ(j["scene"]["sha256"], system_sha256(scene));
    EXPECT_EQ(j["outputs"][0]["sha256"], system_sha256(out / "clip.mp4"));
    EXPECT_EQ(j["settings"]["render"]["width"], 160);
    EXPECT_EQ(j["settings"]["render"]["height"], 120);
  }
}

TEST(Render, QuietPrintsNothingOnSuccess) {
  const TestDir dir;
  const RunResult r = run_tumble(
      args({"render", "--quiet", "--png", "--still", "0.1", "--duration", "0.25"}, kSmall),
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(fs::is_regular_file(dir / "out/default/clip.mp4"));
  const RunResult q =
      run_tumble(args({"render", "-q", "--duration", "0.1", "--out", "q"}, kSmall), dir.path());
  ASSERT_EQ(q.exit_code, 0) << describe(q);
  EXPECT_EQ(q.out, "");
  EXPECT_EQ(q.err, "");
}

TEST(Info, PrintsRendererEncodersAndPlatform) {
  const TestDir dir;
  const RunResult r = run_tumble({"info"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("GL renderer:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("libx264"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("EGL platform:"), std::string::npos) << r.out;
  auto lines = info_lines(r.out);
  EXPECT_FALSE(lines["GL renderer"].empty());
  EXPECT_FALSE(lines["GL version"].empty());
  EXPECT_FALSE(lines["EGL platform"].empty());
  EXPECT_TRUE(r.out.starts_with("tumble ")) << r.out;
  // info writes nothing into the working folder.
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
}  // namespace tumble_e2e
