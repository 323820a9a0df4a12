#include "tumble/video_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

#include "../test_dir.hpp"
#include "tumble/error.hpp"
#include "tumble/mp4_writer.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr int kFrames = 12;

fs::path fresh_dir(const std::string& name) {
  return test::fresh_dir("video_reader_test", name);
}

Mp4Settings small_settings() {
  Mp4Settings s;
  s.width = kWidth;
  s.height = kHeight;
  s.fps = 30;
  s.encoder = "libx264";
  return s;
}

// Frame k: a gradient with a bright block that moves 8 pixels per frame, so each frame is
// different and an upside-down or shifted decode is far off.
Image moving_frame(int k) {
  Image image(kWidth, kHeight, 3);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      std::uint8_t* p = image.row(y) + 3 * x;
      const bool in_block = x >= 8 * k && x < 8 * k + 32 && y >= 40 && y < 80;
      p[0] = in_block ? 240 : static_cast<std::uint8_t>(x + 40);
      p[1] = in_block ? 220 : static_cast<std::uint8_t>(2 * y);
      p[2] = in_block ? 30 : static_cast<std::uint8_t>(120);
    }
  return image;
}

fs::path moving_clip(const std::string& name) {
  const fs::path file = fresh_dir(name) / "clip.mp4";
  Mp4Writer writer(file, small_settings());
  for (int k = 0; k < kFrames; ++k) writer.add_frame(moving_frame(k));
  writer.finish();
  return file;
}

double psnr(const Image& a, const Image& b) {
  double squared = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = double(a.pixels[i]) - double(b.pixels[i]);
    squared += d * d;
  }
  return 10.0 * std::log10(255.0 * 255.0 * double(a.pixels.size()) / squared);
}

TEST(VideoReader, ReadsBackEveryFrameAtItsSize) {
  const fs::path file = moving_clip("count");
  VideoReader reader(file);
  EXPECT_EQ(reader.width(), kWidth);
  EXPECT_EQ(reader.height(), kHeight);
  Image frame;
  int frames = 0;
  while (reader.next(frame)) {
    EXPECT_EQ(frame.width, kWidth);
    EXPECT_EQ(frame.height, kHeight);
    EXPECT_EQ(frame.channels, 3);
    // Content and order: each decoded frame is closest to the input frame of its index.
    // Tolerance: at least 30 dB against its own input (CRF 23 on this simple picture measures
    // about 40 dB), and better than against the neighbouring frame, which is 8 pixels away.
    const double own = psnr(frame, moving_frame(frames));
    EXPECT_GT(own, 30.0) << "frame " << frames;
    if (frames + 1 < kFrames) {
      EXPECT_GT(own, psnr(frame, moving_frame(frames + 1)) + 3.0) << "frame " << frames;
    }
    ++frames;
  }
  EXPECT_EQ(frames, kFrames);
  EXPECT_FALSE(reader.next(frame)) << "past the end stays at the end";
}

TEST(VideoReader, SolidColourDecodesWithinThreeLevels) {
  // The default box colour #d9572b through BT.709 limited range and back. Tolerance 3 levels per
  // channel, the reasoning of Mp4Writer.SolidColourDecodesWithinThreeLevels: two roundings to
  // 8 bits on coarser scales (219 luma, 224 chroma steps), a chroma error magnified up to 1.86×
  // on the way back, about one more level from x264. Decoding with BT.601 instead is 12 off.
  constexpr std::uint8_t kRgb[3] = {217, 87, 43};
  const fs::path file = fresh_dir("solid") / "clip.mp4";
  Image solid(kWidth, kHeight, 3);
  for (std::size_t i = 0; i < solid.pixels.size(); ++i) solid.pixels[i] = kRgb[i % 3];
  {
    Mp4Writer writer(file, small_settings());
    for (int k = 0; k < 3; ++k) writer.add_frame(solid);
    writer.finish();
  }
  VideoReader reader(file);
  Image frame;
  int frames = 0;
  while (reader.next(frame)) {
    int worst = 0;
    for (std::size_t i = 0; i < frame.pixels.size(); ++i)
      worst = std::max(worst, std::abs(int(frame.pixels[i]) - int(kRgb[i % 3])));
    EXPECT_LE(worst, 3) << "frame " << frames;
    ++frames;
  }
  EXPECT_EQ(frames, 3);
}

TEST(VideoReader, TwoDecodesAreIdentical) {
  const fs::path file = moving_clip("twice");
  VideoReader first(file), second(file);
  Image a, b;
  while (first.next(a)) {
    ASSERT_TRUE(second.next(b));
    EXPECT_TRUE(a.pixels == b.pixels);
  }
  EXPECT_FALSE(second.next(b));
}

void expect_bad_input_naming(const fs::path& file) {
  try {
    VideoReader reader(file);
    Image frame;
    while (reader.next(frame)) {
    }
    FAIL() << "expected an error for " << file;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    const std::string message = e.what();
    EXPECT_NE(message.find("cannot decode"), std::string::npos) << message;
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  }
}

TEST(VideoReader, NonVideoFileIsBadInputNamingTheFile) {
  const fs::path file = fresh_dir("not_video") / "clip.mp4";
  std::ofstream(file) << "this is not a video, only some text that FFmpeg cannot probe\n";
  expect_bad_input_naming(file);
}

TEST(VideoReader, MissingFileIsBadInputNamingTheFile) {
  expect_bad_input_naming(fresh_dir("missing") / "no_such_clip.mp4");
}

}  // namespace
}  // namespace tumble
