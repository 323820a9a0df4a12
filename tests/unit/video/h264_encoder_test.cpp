// Which encoder Mp4Writer opens (src/video/h264_encoder.cpp), seen through the public API.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <string>
#include <vector>

#include "../test_dir.hpp"
#include "tumble/error.hpp"
#include "tumble/mp4_writer.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 64;
constexpr int kHeight = 48;

fs::path fresh_dir(const std::string& name) {
  return test::fresh_dir("h264_test", name);
}

long entries(const fs::path& dir) {
  return std::distance(fs::directory_iterator(dir), fs::directory_iterator());
}

Mp4Settings small_settings() {
  Mp4Settings s;
  s.width = kWidth;
  s.height = kHeight;
  s.fps = 30;
  s.encoder = "libx264";
  return s;
}

// Tolerances: none; names, error kinds and stderr output are exact.

TEST(H264Encoder, EncoderNames) {
  const std::vector<std::string> names = Mp4Writer::available_h264_encoders();
  EXPECT_NE(std::find(names.begin(), names.end(), "libx264"), names.end());
  // libx264rgb encodes RGB 4:4:4, not the yuv420p clip.mp4 promises.
  EXPECT_EQ(std::find(names.begin(), names.end(), "libx264rgb"), names.end());
}

TEST(H264Encoder, AutoPicksAnEncoderThatOpensAndStaysQuiet) {
  const fs::path dir = fresh_dir("auto");
  Mp4Settings s = small_settings();
  s.encoder = "auto";
  // Hardware encoders that fail to open (no GPU here) must not print anything.
  testing::internal::CaptureStderr();
  std::string name;
  {
    Mp4Writer writer(dir / "clip.mp4", s);
    name = writer.encoder_name();
    for (int k = 0; k < 3; ++k) writer.add_frame(Image(kWidth, kHeight, 3));
    writer.finish();
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  const std::vector<std::string> names = Mp4Writer::available_h264_encoders();
  EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  EXPECT_TRUE(fs::exists(dir / "clip.mp4"));
}

TEST(H264Encoder, NamedEncoderThatIsNotH264IsBadInput) {
  const fs::path dir = fresh_dir("not_h264");
  for (const char* encoder : {"mpeg4", "libx264rgb", "no-such-encoder", ""}) {
    Mp4Settings s = small_settings();
    s.encoder = encoder;
    try {
      Mp4Writer writer(dir / "clip.mp4", s);
      ADD_FAILURE() << encoder << ": expected an error";
    } catch (const Error& e) {
      EXPECT_EQ(e.exit_code(), 2) << encoder;
      EXPECT_NE(std::string(e.what()).find("libx264"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(entries(dir), 0);
}

TEST(H264Encoder, NamedHardwareEncoderMustOpen) {
  // Where the hardware exists the writer opens it; where it does not (this CPU-only machine),
  // asking for it by name is an environment error that names it, still without FFmpeg noise.
  const std::vector<std::string> names = Mp4Writer::available_h264_encoders();
  const fs::path dir = fresh_dir("hardware");
  for (const std::string encoder : {"h264_nvenc", "h264_vaapi", "h264_qsv"}) {
    if (std::find(names.begin(), names.end(), encoder) == names.end()) continue;
    Mp4Settings s = small_settings();
    s.encoder = encoder;
    testing::internal::CaptureStderr();
    try {
      Mp4Writer writer(dir / "clip.mp4", s);
      EXPECT_EQ(writer.encoder_name(), encoder);
    } catch (const Error& e) {
      EXPECT_EQ(e.exit_code(), 3) << encoder;
      EXPECT_EQ(std::string(e.what()).rfind("encoder " + encoder + " could not be opened: ", 0), 0u)
          << e.what();
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << encoder;
  }
  EXPECT_EQ(entries(dir), 0);
}

}  // namespace
}  // namespace tumble
