// tumble diff (SPEC.md: diff; exit codes): two PNGs, two folders of PNGs, two videos; every exit
// code (0 within tolerance, 1 beyond, 2 missing or undecodable input and bad options), folder
// pairing, video comparison and the diff image.
//
// The test PNGs are written here by a minimal encoder (stored deflate blocks: no zlib needed), so
// every pixel is known exactly. Diff images are read back with the ffmpeg tool where it exists.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>

#include "run_tumble.hpp"

namespace tumble_e2e {
namespace {

constexpr int kWidth = 8;
constexpr int kHeight = 6;  // 48 pixels

struct Rgb {
  int width = kWidth;
  int height = kHeight;
  std::vector<std::uint8_t> pixels;  // top-down RGB

  std::uint8_t* at(int x, int y) { return pixels.data() + 3 * (std::size_t(y) * width + x); }
};

// A small gradient, every channel in 20–230 so a change of ±10 never clips.
Rgb picture(int width = kWidth, int height = kHeight) {
  Rgb image{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 3)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = static_cast<std::uint8_t>(20 + 20 * x);
      p[1] = static_cast<std::uint8_t>(40 + 25 * y);
      p[2] = static_cast<std::uint8_t>(200 - 10 * x - 10 * y);
    }
  return image;
}

std::uint32_t crc32(std::string_view bytes) {
  std::uint32_t crc = 0xffffffffu;
  for (const char ch : bytes) {
    crc ^= static_cast<std::uint8_t>(ch);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put_u32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((v >> shift) & 0xff);
}

void put_chunk(std::string& out, const char* type, const std::string& data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::string body = type + data;
  out += body;
  put_u32(out, crc32(body));
}

// An 8-bit RGB PNG: filter 0 on every row, zlib stream of stored (uncompressed) blocks.
std::string png_bytes(const Rgb& image) {
  std::string raw;
  for (int y = 0; y < image.height; ++y) {
    raw += '\0';
    raw.append(
        reinterpret_cast<const char*>(image.pixels.data()) + 3 * std::size_t(y) * image.width,
        3 * std::size_t(image.width));
  }
  std::string zlib = "\x78\x01";
  for (std::size_t at = 0; at < raw.size() || at == 0; at += 65535) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    zlib += static_cast<char>(at + n == raw.size() ? 1 : 0);  // BFINAL, BTYPE 00
    zlib += static_cast<char>(n & 0xff);
    zlib += static_cast<char>(n >> 8);
    zlib += static_cast<char>(~n & 0xff);
    zlib += static_cast<char>((~n >> 8) & 0xff);
    zlib.append(raw, at, n);
  }
  std::uint32_t a = 1, b = 0;  // Adler-32 of the uncompressed data
  for (const char ch : raw) {
    a = (a + static_cast<std::uint8_t>(ch)) % 65521;
    b = (b + a) % 65521;
  }
  put_u32(zlib, b << 16 | a);

  std::string png = "\x89PNG\r\n\x1a\n";
  std::string header;
  put_u32(header, static_cast<std::uint32_t>(image.width));
  put_u32(header, static_cast<std::uint32_t>(image.height));
  header +=
      std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, no filter, no interlace
  put_chunk(png, "IHDR", header);
  put_chunk(png, "IDAT", zlib);
  put_chunk(png, "IEND", "");
  return png;
}

fs::path write_png(const fs::path& path, const Rgb& image) {
  return write_file(path, png_bytes(image));
}

// A copy of picture() with pixel (x, y)'s green channel raised by `delta`.
Rgb changed(int x, int y, int delta) {
  Rgb image = picture();
  image.at(x, y)[1] = static_cast<std::uint8_t>(image.at(x, y)[1] + delta);
  return image;
}

bool contains(const std::string& text, std::string_view part) {
  return text.find(part) != std::string::npos;
}

// --- two PNGs -----------------------------------------------------------------------------

TEST(DiffImages, IdenticalPngsAreExit0) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_png(dir / "b.png", picture());
  const RunResult r = run_tumble({"diff", "a.png", "b.png"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(contains(r.out, "b.png: 0 of 48 pixels differ (0%), largest delta 0, identical\n"))
      << r.out;
  EXPECT_TRUE(contains(r.out,
                       "tumble diff: the images are within tolerance (max delta 0, max "
                       "fraction 0)\n"))
      << r.out;
  EXPECT_EQ(r.err, "");
}

TEST(DiffImages, OnePixelChangedIsExit1WithItsMetrics) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_png(dir / "b.png", changed(3, 2, 10));
  const RunResult r = run_tumble({"diff", "a.png", "b.png"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  // PSNR = 10 log10(255² / MSE), MSE = 10² / (48 · 3) samples: 10 log10(93636) = 49.71 dB.
  EXPECT_TRUE(contains(r.out,
                       "b.png: 1 of 48 pixels differ (2.08%), largest delta 10, PSNR "
                       "49.71 dB -- beyond tolerance\n"))
      << r.out;
  EXPECT_TRUE(contains(r.out, "tumble diff: the images differ beyond tolerance")) << r.out;
  EXPECT_EQ(r.err, "");
}

TEST(DiffImages, MaxDeltaCoveringTheChangeIsExit0) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_png(dir / "b.png", changed(3, 2, 10));
  const RunResult covered = run_tumble({"diff", "a.png", "b.png", "--max-delta", "10"}, dir.path());
  EXPECT_EQ(covered.exit_code, 0) << describe(covered);
  EXPECT_TRUE(contains(covered.out, "0 of 48 pixels differ")) << covered.out;
  const RunResult short_by_one =
      run_tumble({"diff", "a.png", "b.png", "--max-delta", "9"}, dir.path());
  EXPECT_EQ(short_by_one.exit_code, 1) << describe(short_by_one);
}

TEST(DiffImages, MaxFractionCoveringTheChangeIsExit0) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_png(dir / "b.png", changed(3, 2, 10));
  // 1 of 48 pixels = 0.0208.
  const RunResult covered =
      run_tumble({"diff", "a.png", "b.png", "--max-fraction", "0.021"}, dir.path());
  EXPECT_EQ(covered.exit_code, 0) << describe(covered);
  EXPECT_TRUE(contains(covered.out, "max fraction 0.021")) << covered.out;
  const RunResult short_of_it =
      run_tumble({"diff", "a.png", "b.png", "--max-fraction", "0.02"}, dir.path());
  EXPECT_EQ(short_of_it.exit_code, 1) << describe(short_of_it);
}

TEST(DiffImages, MinPsnrBothWays) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_png(dir / "b.png", changed(3, 2, 10));  // PSNR 49.71 dB
  const RunResult above =
      run_tumble({"diff", "a.png", "b.png", "--max-delta", "10", "--min-psnr", "49.7"}, dir.path());
  EXPECT_EQ(above.exit_code, 0) << describe(above);
  EXPECT_TRUE(contains(above.out, "min PSNR 49.7 dB")) << above.out;
  const RunResult below = run_tumble(
      {"diff", "a.png", "b.png", "--max-delta", "10", "--min-psnr", "49.72"}, dir.path());
  EXPECT_EQ(below.exit_code, 1) << describe(below);
  // Identical images have an infinite PSNR, which passes any floor.
  write_png(dir / "c.png", picture());
  EXPECT_EQ(run_tumble({"diff", "a.png", "c.png", "--min-psnr", "1000"}, dir.path()).exit_code, 0);
}

TEST(DiffImages, DifferentSizesAreExit1WhateverTheTolerance) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_png(dir / "b.png", picture(10, 6));
  const RunResult r = run_tumble(
      {"diff", "a.png", "b.png", "--max-delta", "255", "--max-fraction", "1"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(contains(r.out, "b.png: sizes differ: 8x6 expected, 10x6 actual")) << r.out;
}

TEST(DiffImages, MissingInputIsExit2NamingIt) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  for (const auto& args : {std::vector<std::string>{"diff", "a.png", "nowhere/b.png"},
                           std::vector<std::string>{"diff", "nowhere/b.png", "a.png"}}) {
    const RunResult r = run_tumble(args, dir.path());
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
    EXPECT_TRUE(contains(r.err, "nowhere/b.png")) << r.err;
    EXPECT_EQ(r.out, "");
  }
}

TEST(DiffImages, CorruptPngIsExit2NamingIt) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_file(dir / "truncated.png", png_bytes(picture()).substr(0, 40));
  write_file(dir / "text.png", "not a PNG at all\n");
  for (const char* bad : {"truncated.png", "text.png"}) {
    const RunResult r = run_tumble({"diff", "a.png", bad}, dir.path());
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
    EXPECT_TRUE(contains(r.err, bad)) << r.err;
  }
}

TEST(DiffImages, BadOptionValuesAreExit2) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_png(dir / "b.png", picture());
  const std::vector<std::vector<std::string>> bad = {
      {"--max-delta", "256"},    {"--max-delta", "-1"},      {"--max-delta", "two"},
      {"--max-delta", "1.5"},    {"--max-fraction", "1.01"}, {"--max-fraction", "-0.1"},
      {"--max-fraction", "nan"}, {"--min-psnr", "-1"},       {"--min-psnr", "inf"},
      {"--min-psnr", "nan"},     {"--min-psnr", "loud"}};
  for (const auto& option : bad) {
    std::vector<std::string> args = {"diff", "a.png", "b.png"};
    args.insert(args.end(), option.begin(), option.end());
    const RunResult r = run_tumble(args, dir.path());
    EXPECT_EQ(r.exit_code, 2) << option[0] << " " << option[1] << ": " << describe(r);
    EXPECT_TRUE(r.err.starts_with("tumble: error: ")) << r.err;
    EXPECT_TRUE(contains(r.err, option[0])) << "the option is not named: " << r.err;
  }
  // EXPECTED and ACTUAL are both required.
  EXPECT_EQ(run_tumble({"diff", "a.png"}, dir.path()).exit_code, 2);
  EXPECT_EQ(run_tumble({"diff"}, dir.path()).exit_code, 2);
  // A PNG cannot be compared with a folder.
  fs::create_directories(dir / "folder");
  const RunResult mixed = run_tumble({"diff", "a.png", "folder"}, dir.path());
  EXPECT_EQ(mixed.exit_code, 2) << describe(mixed);
  EXPECT_TRUE(contains(mixed.err, "folder")) << mixed.err;
}

// --- the diff image -----------------------------------------------------------------------

// Width and height from a PNG's IHDR.
std::array<int, 2> png_size(const fs::path& file) {
  const std::string bytes = read_file(file);
  if (bytes.size() < 24 || bytes.compare(12, 4, "IHDR") != 0) return {0, 0};
  auto u32 = [&](std::size_t at) {
    int v = 0;
    for (int i = 0; i < 4; ++i) v = v << 8 | static_cast<std::uint8_t>(bytes[at + i]);
    return v;
  };
  return {u32(16), u32(20)};
}

// A PNG decoded to top-down RGB by the ffmpeg tool ("" when it is not installed).
std::string decoded_rgb(const fs::path& file) {
  const RunResult r = run_program(
      "ffmpeg", {"-v", "error", "-i", file.string(), "-f", "rawvideo", "-pix_fmt", "rgb24", "-"},
      file.parent_path());
  return r.exit_code == 0 ? r.out : "";
}

bool have_ffmpeg() {
  return run_program("ffmpeg", {"-version"}, fs::temp_directory_path()).exit_code == 0;
}

TEST(DiffImage, DiffOutIsMagentaWhereChangedAndGreyElsewhere) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_png(dir / "b.png", changed(3, 2, 10));
  fs::create_directory(dir / "out");  // an explicit file's folder must exist (docs/outputs.md)
  const RunResult r =
      run_tumble({"diff", "a.png", "b.png", "--diff-out", "out/diff.png"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(contains(r.out, "diff image out/diff.png")) << r.out;
  ASSERT_TRUE(fs::exists(dir / "out/diff.png"));
  EXPECT_EQ(png_size(dir / "out/diff.png"), (std::array<int, 2>{kWidth, kHeight}));
  if (!have_ffmpeg()) FAIL() << "the ffmpeg tool (installed by scripts/setup --tests) is missing";
  const std::string rgb = decoded_rgb(dir / "out/diff.png");
  ASSERT_EQ(rgb.size(), std::size_t{kWidth} * kHeight * 3);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const auto* p = reinterpret_cast<const std::uint8_t*>(rgb.data()) + 3 * (y * kWidth + x);
      if (x == 3 && y == 2) {
        // Magenta: red and blue strong, no green.
        EXPECT_GE(p[0], 128);
        EXPECT_EQ(p[1], 0);
        EXPECT_EQ(p[0], p[2]);
      } else {
        EXPECT_TRUE(p[0] == p[1] && p[1] == p[2]) << "not grey at " << x << "," << y;
      }
    }
}

TEST(DiffImage, DiffOutOfDifferentSizesHasTheLargerSize) {
  const TestDir dir;
  write_png(dir / "a.png", picture(8, 6));
  write_png(dir / "b.png", picture(6, 10));
  const RunResult r = run_tumble({"diff", "a.png", "b.png", "--diff-out", "d.png"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_EQ(png_size(dir / "d.png"), (std::array<int, 2>{8, 10}));
}

TEST(DiffImage, NothingIsWrittenWithinTolerance) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_png(dir / "b.png", changed(3, 2, 10));
  const RunResult r = run_tumble(
      {"diff", "a.png", "b.png", "--max-delta", "10", "--diff-out", "diff.png"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "diff.png"));
}

TEST(DiffImage, DiffOutOntoAnInputIsExit2AndLeavesItAlone) {
  const TestDir dir;
  write_png(dir / "a.png", picture());
  write_png(dir / "b.png", changed(3, 2, 10));
  const std::string before = read_file(dir / "b.png");
  const RunResult r = run_tumble({"diff", "a.png", "b.png", "--diff-out", "b.png"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_EQ(read_file(dir / "b.png"), before);
}

// --- folders ------------------------------------------------------------------------------

TEST(DiffFolders, PairsByFileNameAndIgnoresOtherFiles) {
  const TestDir dir;
  for (const char* side : {"golden", "actual"}) {
    write_png(dir / side / "still_0.5.png", picture());
    write_png(dir / side / "still_1.png", changed(1, 1, 40));
    write_png(dir / side / "still_2.png", picture(4, 4));
  }
  write_file(dir / "actual/run.json", "{}\n");  // not a PNG: not compared
  const RunResult r = run_tumble({"diff", "golden", "actual"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  // One line per pair, in file-name order, then the verdict.
  EXPECT_EQ(r.out,
            "still_0.5.png: 0 of 48 pixels differ (0%), largest delta 0, identical\n"
            "still_1.png: 0 of 48 pixels differ (0%), largest delta 0, identical\n"
            "still_2.png: 0 of 16 pixels differ (0%), largest delta 0, identical\n"
            "tumble diff: all 3 files within tolerance (max delta 0, max fraction 0)\n");
}

TEST(DiffFolders, DifferingPairIsExit1AndGetsTheOnlyDiffImage) {
  const TestDir dir;
  for (const char* side : {"golden", "actual"}) {
    write_png(dir / side / "a.png", picture());
    write_png(dir / side / "c.png", picture());
  }
  write_png(dir / "golden/b.png", picture());
  write_png(dir / "actual/b.png", changed(0, 0, 20));
  const RunResult r = run_tumble({"diff", "golden", "actual", "--diff-out", "diffs"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(contains(r.out, "b.png: 1 of 48 pixels differ")) << r.out;
  EXPECT_TRUE(contains(r.out, "tumble diff: 1 of 3 files differ beyond tolerance")) << r.out;
  EXPECT_TRUE(fs::exists(dir / "diffs/b.png"));
  EXPECT_FALSE(fs::exists(dir / "diffs/a.png")) << "a diff image for an equal pair";
  EXPECT_FALSE(fs::exists(dir / "diffs/c.png"));
}

TEST(DiffFolders, MissingAndExtraFilesAreExit1AndNamed) {
  const TestDir dir;
  write_png(dir / "golden/frame_00000.png", picture());
  write_png(dir / "actual/frame_00000.png", picture());
  write_png(dir / "golden/frame_00001.png", picture());  // missing from actual
  write_png(dir / "actual/frame_00002.png", picture());  // extra in actual
  const RunResult r = run_tumble({"diff", "golden", "actual"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(contains(r.out, "frame_00001.png: missing from \"actual/frame_00001.png\"")) << r.out;
  EXPECT_TRUE(contains(r.out, "frame_00002.png: missing from \"golden/frame_00002.png\"")) << r.out;
  EXPECT_TRUE(contains(r.out, "tumble diff: 2 of 3 files differ beyond tolerance")) << r.out;
}

TEST(DiffFolders, CorruptPngInAFolderIsExit2NamingIt) {
  const TestDir dir;
  write_png(dir / "golden/a.png", picture());
  write_file(dir / "actual/a.png", "garbage");
  const RunResult r = run_tumble({"diff", "golden", "actual"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(contains(r.err, "actual/a.png")) << r.err;
}

TEST(DiffFolders, TwoEmptyFoldersAreExit2NotAVacuousPass) {
  const TestDir dir;
  fs::create_directories(dir / "golden");
  fs::create_directories(dir / "actual");
  const RunResult r = run_tumble({"diff", "golden", "actual"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
}

// --- videos -------------------------------------------------------------------------------

// Renders the default scene's clip at 160x120 into `out` (`--duration 0.25` unless `extra` gives
// one); false when this machine cannot render (no EGL/GL: exit 3), so the test can be skipped
// rather than fail.
bool render_clip(const TestDir& dir, const std::string& out, std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"render", "--size", "160x120", "--out", out, "--quiet"};
  if (std::find(extra.begin(), extra.end(), "--duration") == extra.end())
    extra.insert(extra.end(), {"--duration", "0.25"});
  args.insert(args.end(), extra.begin(), extra.end());
  const RunResult r = run_tumble(args, dir.path());
  if (r.exit_code == 3) return false;
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  return r.exit_code == 0;
}

#define RENDER_OR_SKIP(...) \
  if (!render_clip(__VA_ARGS__)) FAIL() << "tumble render failed (exit 3: no EGL/GL?)"

TEST(DiffVideos, TwoRendersOfOneSceneAreExit0) {
  const TestDir dir;
  RENDER_OR_SKIP(dir, "a");
  RENDER_OR_SKIP(dir, "b");
  const RunResult r = run_tumble({"diff", "a/clip.mp4", "b/clip.mp4"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  // 0.25 s at the default 60 fps: 15 frames, each its own line.
  EXPECT_TRUE(contains(r.out, "frame_00014: 0 of 19200 pixels differ")) << r.out;
  EXPECT_TRUE(contains(r.out, "tumble diff: all 15 frames within tolerance")) << r.out;
}

TEST(DiffVideos, OtherQualityIsExit1WithDiffImagesPerFrame) {
  const TestDir dir;
  RENDER_OR_SKIP(dir, "a");
  RENDER_OR_SKIP(dir, "b", {"--crf", "40"});
  const RunResult r =
      run_tumble({"diff", "a/clip.mp4", "b/clip.mp4", "--diff-out", "diffs"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(contains(r.out, "frames differ beyond tolerance")) << r.out;
  EXPECT_EQ(png_size(dir / "diffs/frame_00000.png"), (std::array<int, 2>{160, 120}));
}

TEST(DiffVideos, DifferentFrameCountIsExit1) {
  const TestDir dir;
  RENDER_OR_SKIP(dir, "a");
  RENDER_OR_SKIP(dir, "b", {"--duration", "0.5"});
  const RunResult r =
      run_tumble({"diff", "a/clip.mp4", "b/clip.mp4", "--max-delta", "255", "--max-fraction", "1"},
                 dir.path());
  EXPECT_EQ(r.exit_code, 1) << describe(r);
  EXPECT_TRUE(contains(r.out, "frame_00015 to frame_00029: only in \"b/clip.mp4\"")) << r.out;
  EXPECT_TRUE(contains(r.out, "frame counts differ: 15 expected, 30 actual")) << r.out;
}

TEST(DiffVideos, UndecodableVideoIsExit2NamingIt) {
  const TestDir dir;
  write_file(dir / "a.mp4", "not a video");
  write_file(dir / "b.mp4", "not a video either");
  const RunResult r = run_tumble({"diff", "a.mp4", "b.mp4"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_TRUE(r.err.starts_with("tumble: error: cannot decode \"a.mp4\"")) << r.err;
}

}  // namespace
}  // namespace tumble_e2e
