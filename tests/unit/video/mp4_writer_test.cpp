#include "tumble/mp4_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>

#include "../test_dir.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr int kFps = 30;
constexpr int kFrames = 30;

fs::path fresh_dir(const std::string& name) {
  return test::fresh_dir("mp4_test", name);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

long entries(const fs::path& dir) {
  return std::distance(fs::directory_iterator(dir), fs::directory_iterator());
}

// Standard output of a shell command (its exit status must be 0).
std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[65536];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  EXPECT_EQ(pclose(pipe), 0) << command;
  return out;
}

bool have_ffmpeg_tools() {
  return std::system("ffprobe -version >/dev/null 2>&1") == 0 &&
         std::system("ffmpeg -version >/dev/null 2>&1") == 0;
}

#define REQUIRE_FFMPEG_TOOLS() \
  if (!have_ffmpeg_tools())    \
  FAIL() << "ffprobe/ffmpeg (installed by scripts/setup --tests) are missing"

// Frame k of a moving scene: a diagonal gradient that slides by 3 pixels per frame and an orange
// box that crosses the picture, so consecutive frames differ and motion search has work to do.
Image moving_frame(int width, int height, int k, int channels = 3) {
  Image image(width, height, channels);
  const int box_x = (k * 5) % width;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = image.row(y) + x * channels;
      const bool in_box =
          x >= box_x && x < box_x + width / 5 && y >= height / 3 && y < height / 3 + height / 4;
      p[0] = in_box ? 217 : static_cast<std::uint8_t>((x + y + 3 * k) & 0xff);
      p[1] = in_box ? 87 : static_cast<std::uint8_t>((2 * x + k) & 0xff);
      p[2] = in_box ? 43 : static_cast<std::uint8_t>((255 - y) & 0xff);
      if (channels == 4) p[3] = 255;
    }
  return image;
}

Image bottom_up(const Image& image) {
  Image flipped(image.width, image.height, image.channels);
  for (int y = 0; y < image.height; ++y)
    std::copy_n(image.row(y), image.stride(), flipped.row(image.height - 1 - y));
  return flipped;
}

Mp4Settings small_settings() {
  Mp4Settings s;
  s.width = kWidth;
  s.height = kHeight;
  s.fps = kFps;
  s.encoder = "libx264";
  return s;
}

// Encodes kFrames moving frames (RGB, top-down) and returns the clip's bytes.
std::string encode_moving_clip(const fs::path& file, int channels = 3, bool flipped = false) {
  Mp4Writer writer(file, small_settings());
  for (int k = 0; k < kFrames; ++k) {
    const Image frame = moving_frame(kWidth, kHeight, k, channels);
    if (flipped) {
      const Image rows = bottom_up(frame);
      writer.add_frame(rows.pixels.data(), channels, static_cast<std::ptrdiff_t>(rows.stride()),
                       true);
    } else {
      writer.add_frame(frame);
    }
  }
  writer.finish();
  return slurp(file);
}

// Top-level MP4 box types in file order.
std::vector<std::string> top_level_boxes(const std::string& bytes) {
  std::vector<std::string> types;
  std::size_t at = 0;
  while (at + 8 <= bytes.size()) {
    std::uint64_t size = 0;
    for (int i = 0; i < 4; ++i) size = size << 8 | static_cast<unsigned char>(bytes[at + i]);
    types.push_back(bytes.substr(at + 4, 4));
    if (size == 1 && at + 16 <= bytes.size()) {  // 64-bit size follows the type
      size = 0;
      for (int i = 8; i < 16; ++i) size = size << 8 | static_cast<unsigned char>(bytes[at + i]);
    }
    if (size < 8) break;  // 0 = to the end of the file
    at += size;
  }
  return types;
}

std::map<std::string, std::string> ffprobe(const fs::path& file) {
  const std::string out =
      run("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
          "stream=codec_name,pix_fmt,nb_read_frames,color_space,color_primaries,color_transfer,"
          "color_range -show_entries format=duration -of default=nw=1 '" +
          file.string() + "'");
  std::map<std::string, std::string> fields;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos) fields[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return fields;
}

// All frames of a clip decoded by the ffmpeg tool to top-down RGB (converted back with the
// matrix and range the stream is tagged with).
std::string decode_rgb(const fs::path& file) {
  return run("ffmpeg -v error -i '" + file.string() + "' -f rawvideo -pix_fmt rgb24 -");
}

// Tolerances: none (files, bytes, counts and names are exact) except where a test states one.

TEST(Mp4Writer, ClipAppearsOnlyAfterFinish) {
  const fs::path dir = fresh_dir("appears");
  const fs::path file = dir / "clip.mp4";
  Mp4Writer writer(file, small_settings());
  for (int k = 0; k < kFrames; ++k) writer.add_frame(moving_frame(kWidth, kHeight, k));
  EXPECT_FALSE(fs::exists(file));
  // Its temporary beside it, named uniquely for this writer (.clip.mp4.XXXXXX.partial).
  const auto temporary = fs::directory_iterator(dir)->path().filename().string();
  EXPECT_TRUE(temporary.starts_with(".clip.mp4.") && temporary.ends_with(".partial")) << temporary;
  EXPECT_EQ(entries(dir), 1);
  writer.finish();
  EXPECT_TRUE(fs::exists(file));
  EXPECT_EQ(entries(dir), 1);  // the temporary is gone
  EXPECT_EQ(writer.frames(), kFrames);
  EXPECT_EQ(writer.encoder_name(), "libx264");
}

TEST(Mp4Writer, FfprobeSeesH264Yuv420pBt709WithExactFrameCountAndDuration) {
  REQUIRE_FFMPEG_TOOLS();
  const fs::path file = fresh_dir("probe") / "clip.mp4";
  encode_moving_clip(file);
  auto fields = ffprobe(file);
  EXPECT_EQ(fields["codec_name"], "h264");
  EXPECT_EQ(fields["pix_fmt"], "yuv420p");
  EXPECT_EQ(fields["nb_read_frames"], std::to_string(kFrames));
  EXPECT_EQ(fields["color_space"], "bt709");
  EXPECT_EQ(fields["color_primaries"], "bt709");
  EXPECT_EQ(fields["color_transfer"], "bt709");
  EXPECT_EQ(fields["color_range"], "tv");
  // 30 frames at 30 fps last 1 s. ffprobe prints microseconds; 1 ms of slack is far below one
  // frame (33 ms), so a missing or extra frame duration would still fail.
  ASSERT_FALSE(fields["duration"].empty());
  EXPECT_NEAR(std::stod(fields["duration"]), double(kFrames) / kFps, 1e-3);
}

TEST(Mp4Writer, DurationIsFramesOverFpsAtOtherRates) {
  REQUIRE_FFMPEG_TOOLS();
  const fs::path file = fresh_dir("rates") / "clip.mp4";
  for (const int fps : {24, 60, 7}) {
    Mp4Settings s = small_settings();
    s.fps = fps;
    Mp4Writer writer(file, s);
    for (int k = 0; k < 10; ++k) writer.add_frame(moving_frame(kWidth, kHeight, k));
    writer.finish();
    auto fields = ffprobe(file);
    EXPECT_EQ(fields["nb_read_frames"], "10") << fps;
    // Same 1 ms tolerance as above (ffprobe prints microseconds).
    EXPECT_NEAR(std::stod(fields["duration"]), 10.0 / fps, 1e-3) << fps;
  }
}

TEST(Mp4Writer, MoovBoxComesBeforeMdat) {
  const fs::path file = fresh_dir("faststart") / "clip.mp4";
  const std::vector<std::string> boxes = top_level_boxes(encode_moving_clip(file));
  const auto moov = std::find(boxes.begin(), boxes.end(), "moov");
  const auto mdat = std::find(boxes.begin(), boxes.end(), "mdat");
  ASSERT_NE(moov, boxes.end());
  ASSERT_NE(mdat, boxes.end());
  EXPECT_LT(moov - boxes.begin(), mdat - boxes.begin());
}

TEST(Mp4Writer, TwoEncodesAreByteIdentical) {
  const fs::path dir = fresh_dir("twice");
  const std::string first = encode_moving_clip(dir / "a.mp4");
  const std::string second = encode_moving_clip(dir / "b.mp4");
  ASSERT_GT(first.size(), 1000u);
  EXPECT_TRUE(first == second) << "sizes " << first.size() << " and " << second.size();
}

TEST(Mp4Writer, BottomUpRgbaAndRgbInputsGiveTheSameBytes) {
  // The same picture handed over three ways must be the same clip, byte for byte: the flip is a
  // negative stride and the alpha byte is ignored, so nothing may differ at all.
  const fs::path dir = fresh_dir("layouts");
  const std::string top_down = encode_moving_clip(dir / "rgb.mp4", 3, false);
  EXPECT_TRUE(top_down == encode_moving_clip(dir / "rgb_flipped.mp4", 3, true));
  EXPECT_TRUE(top_down == encode_moving_clip(dir / "rgba.mp4", 4, false));
  EXPECT_TRUE(top_down == encode_moving_clip(dir / "rgba_flipped.mp4", 4, true));
}

TEST(Mp4Writer, AbandonedWriterLeavesThePreviousClipAndNoTemporary) {
  const fs::path dir = fresh_dir("abandon");
  const fs::path file = dir / "clip.mp4";
  const std::string good = encode_moving_clip(file);
  {
    Mp4Writer writer(file, small_settings());
    for (int k = 0; k < 5; ++k) writer.add_frame(moving_frame(kWidth, kHeight, 100 + k));
    // destroyed without finish(), as when an exception unwinds
  }
  EXPECT_TRUE(slurp(file) == good);
  EXPECT_EQ(entries(dir), 1);

  const fs::path other = dir / "other.mp4";
  { Mp4Writer writer(other, small_settings()); }
  EXPECT_FALSE(fs::exists(other));
  EXPECT_EQ(entries(dir), 1);
}

TEST(Mp4Writer, OddSizeIsBadInput) {
  const fs::path dir = fresh_dir("odd");
  Mp4Settings s = small_settings();
  s.width = 161;
  try {
    Mp4Writer writer(dir / "clip.mp4", s);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    EXPECT_STREQ(e.what(), "H.264 (yuv420p) needs an even width and height; got 161x120");
  }
  EXPECT_EQ(entries(dir), 0);
}

TEST(Mp4Writer, UnwritableFolderIsAnEnvironmentError) {
  try {
    Mp4Writer writer("/proc/tumble-cannot-write-here/clip.mp4", small_settings());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 3);
    EXPECT_NE(std::string(e.what()).find("/proc/tumble-cannot-write-here/clip.mp4"),
              std::string::npos)
        << e.what();
  }
}

// Five frames of one colour, the default box colour #d9572b.
constexpr std::uint8_t kBoxRgb[3] = {217, 87, 43};

fs::path solid_colour_clip(const std::string& name) {
  const fs::path file = fresh_dir(name) / "clip.mp4";
  Image frame(kWidth, kHeight, 3);
  for (std::size_t i = 0; i < frame.pixels.size(); ++i) frame.pixels[i] = kBoxRgb[i % 3];
  Mp4Writer writer(file, small_settings());
  for (int k = 0; k < 5; ++k) writer.add_frame(frame);
  writer.finish();
  return file;
}

TEST(Mp4Writer, SolidColourIsStoredAsBt709LimitedRange) {
  REQUIRE_FFMPEG_TOOLS();
  // The stored samples themselves (decoded to yuv420p: no conversion on the way out), against
  // BT.709 (Kr = 0.2126, Kb = 0.0722) with limited range: Y' = 16 + 219 E'y, C = 128 + 224 E'c.
  const double r = kBoxRgb[0] / 255.0, g = kBoxRgb[1] / 255.0, b = kBoxRgb[2] / 255.0;
  const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  const double expected[3] = {16 + 219 * y, 128 + 224 * (b - y) / 1.8556,
                              128 + 224 * (r - y) / 1.5748};  // 111.7, 95.6, 186.9
  const std::string yuv = run("ffmpeg -v error -i '" + solid_colour_clip("colour_yuv").string() +
                              "' -frames:v 1 -f rawvideo -pix_fmt yuv420p -");
  const std::size_t luma = std::size_t{kWidth} * kHeight, chroma = luma / 4;
  ASSERT_EQ(yuv.size(), luma + 2 * chroma);
  // Tolerance 1 level: the rounding to 8 bits (0.5) plus what x264 may lose on a flat block's DC
  // at CRF 23 (here the samples are exactly the rounded values, 112, 96, 187). swscale's default
  // BT.601 coefficients would store (120, 89, 188).
  for (int plane = 0; plane < 3; ++plane) {
    const std::size_t first = plane == 0 ? 0 : luma + (plane - 1) * chroma;
    const std::size_t count = plane == 0 ? luma : chroma;
    for (std::size_t i = first; i < first + count; ++i)
      ASSERT_NEAR(static_cast<unsigned char>(yuv[i]), expected[plane], 1.0) << "plane " << plane;
  }
}

TEST(Mp4Writer, SolidColourDecodesWithinThreeLevels) {
  REQUIRE_FFMPEG_TOOLS();
  const std::string decoded = decode_rgb(solid_colour_clip("colour_rgb"));
  ASSERT_EQ(decoded.size(), std::size_t{5} * kWidth * kHeight * 3);
  // Tolerance 3 levels per channel (it measures 2). RGB -> limited-range Y'CbCr -> RGB rounds
  // twice to 8 bits on coarser scales (219 luma and 224 chroma steps for 256 RGB levels); a chroma
  // rounding error is magnified up to 1.86 times (the BT.709 Cb -> B coefficient) on the way back:
  // about 2 levels in all; x264 may move a flat block's DC by about one more. A wrong matrix is
  // far outside this: decoding this clip as BT.601 gives (205, 75, 46), 12 levels off.
  int worst = 0;
  for (std::size_t i = 0; i < decoded.size(); ++i)
    worst = std::max(worst,
                     std::abs(int(static_cast<unsigned char>(decoded[i])) - int(kBoxRgb[i % 3])));
  EXPECT_LE(worst, 3);
}

TEST(Mp4Writer, DecodedFramesFollowTheInput) {
  REQUIRE_FFMPEG_TOOLS();
  // A content check on the moving clip, handed over bottom-up: its PSNR against the input.
  // Tolerance: at least 25 dB. CRF 23 on this small, busy picture measures 29.8 dB (the gradient's
  // wrap from 255 to 0 is a sharp diagonal edge that 4:2:0 chroma smears); the same clip decoded
  // upside down scores 11 dB.
  const fs::path file = fresh_dir("content") / "clip.mp4";
  encode_moving_clip(file, 3, true);
  const std::string decoded = decode_rgb(file);
  ASSERT_EQ(decoded.size(), std::size_t{kFrames} * kWidth * kHeight * 3);
  double squared_error = 0;
  for (int k = 0; k < kFrames; ++k) {
    const Image input = moving_frame(kWidth, kHeight, k);
    for (std::size_t i = 0; i < input.pixels.size(); ++i) {
      const double d = double(static_cast<unsigned char>(decoded[k * input.pixels.size() + i])) -
                       input.pixels[i];
      squared_error += d * d;
    }
  }
  const double mse = squared_error / double(decoded.size());
  const double psnr = 10.0 * std::log10(255.0 * 255.0 / mse);
  EXPECT_GT(psnr, 25.0);
}

}  // namespace
}  // namespace tumble
