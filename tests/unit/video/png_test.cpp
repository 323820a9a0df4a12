#include "tumble/png.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "../test_dir.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  return test::fresh_dir("png_test", name);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void spit(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

long entries(const fs::path& dir) {
  return std::distance(fs::directory_iterator(dir), fs::directory_iterator());
}

// Every channel value 0-255 occurs, in a pattern with no two neighbouring rows alike, at an odd
// size (no row padding or even-width assumption can hide).
Image pattern(int width, int height, int channels) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c)
        image.row(y)[x * channels + c] = static_cast<std::uint8_t>(x * 7 + y * 13 + c * 101);
  return image;
}

// The error `read_png(path)` throws; fails the test when it throws none.
Error read_error(const fs::path& path) {
  try {
    read_png(path);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "read_png(" << path << ") did not throw";
  return Error(ErrorKind::Environment, "");
}

bool have_ffmpeg() {
  return std::system("ffmpeg -version >/dev/null 2>&1") == 0;
}

// Tolerance: none anywhere below, except where stated. PNG is lossless and 8-bit RGB is stored as
// it is, so every byte must come back.

TEST(Png, RgbRoundTripIsExact) {
  const fs::path file = fresh_dir("roundtrip") / "a.png";
  const Image image = pattern(37, 23, 3);
  write_png(file, image);
  const Image back = read_png(file);
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 23);
  EXPECT_EQ(back.channels, 3);
  EXPECT_EQ(back.pixels, image.pixels);
}

TEST(Png, RgbaInputIsWrittenAsRgb) {
  const fs::path file = fresh_dir("rgba") / "a.png";
  const Image rgba = pattern(20, 11, 4);
  write_png(file, rgba);
  const Image back = read_png(file);
  ASSERT_EQ(back.channels, 3);
  ASSERT_EQ(back.width, 20);
  ASSERT_EQ(back.height, 11);
  for (int y = 0; y < rgba.height; ++y)
    for (int x = 0; x < rgba.width; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(back.row(y)[x * 3 + c], rgba.row(y)[x * 4 + c]) << x << "," << y << "," << c;
}

TEST(Png, WriteLeavesOnlyTheFinalFile) {
  const fs::path dir = fresh_dir("only_final");
  write_png(dir / "a.png", pattern(8, 8, 3));
  write_png(dir / "a.png", pattern(9, 9, 3));  // replaces the first
  EXPECT_EQ(entries(dir), 1);
  EXPECT_EQ(read_png(dir / "a.png").width, 9);
}

TEST(Png, UnwritablePathIsAnEnvironmentError) {
  const fs::path file = "/proc/tumble-cannot-write-here/a.png";
  try {
    write_png(file, pattern(4, 4, 3));
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Environment);
    EXPECT_EQ(e.exit_code(), 3);
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

TEST(Png, MissingFileIsBadInputNamingIt) {
  const fs::path file = fresh_dir("missing") / "nowhere.png";
  const Error e = read_error(file);
  EXPECT_EQ(e.exit_code(), 2);
  EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
}

TEST(Png, NotAPngIsBadInputNamingIt) {
  const fs::path file = fresh_dir("garbage") / "garbage.png";
  spit(file, "this is not a PNG file at all, just text");
  const Error e = read_error(file);
  EXPECT_EQ(e.exit_code(), 2);
  EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
}

TEST(Png, TruncatedFileIsBadInputNotACrash) {
  const fs::path dir = fresh_dir("truncated");
  write_png(dir / "good.png", pattern(64, 64, 3));
  const std::string good = slurp(dir / "good.png");
  // Cut inside the header, inside the image data and just before the end chunk: each is an
  // error raised inside libpng (a longjmp), turned into an exception.
  for (const std::size_t keep : {std::size_t{20}, good.size() / 2, good.size() - 12}) {
    const fs::path file = dir / ("cut_" + std::to_string(keep) + ".png");
    spit(file, good.substr(0, keep));
    const Error e = read_error(file);
    EXPECT_EQ(e.exit_code(), 2) << keep;
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

TEST(Png, CorruptImageDataIsBadInputNotACrash) {
  const fs::path dir = fresh_dir("corrupt");
  write_png(dir / "good.png", pattern(64, 64, 3));
  std::string bytes = slurp(dir / "good.png");
  const std::size_t idat = bytes.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  bytes[idat + 40] = static_cast<char>(bytes[idat + 40] ^ 0x5a);  // the chunk's CRC now fails
  const fs::path file = dir / "corrupt.png";
  spit(file, bytes);
  const Error e = read_error(file);
  EXPECT_EQ(e.exit_code(), 2);
  EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
}

// Files of other layouts, made by the ffmpeg tool from its test pattern, must read as the ffmpeg
// tool decodes them (to rgb24, or rgba where the file has alpha).
TEST(Png, ReadsPaletteGray16BitAndAlphaLikeFfmpegDoes) {
  if (!have_ffmpeg()) FAIL() << "the ffmpeg tool (installed by scripts/setup --tests) is missing";
  const fs::path dir = fresh_dir("layouts");
  struct Case {
    const char* pix_fmt;
    int channels;
    int tolerance;
  };
  // Tolerance: exact for 8-bit and palette files. 16-bit files: 1 level, because libpng rounds
  // v * 255 / 65535 to nearest while swscale, the reference here, may round a sample down.
  for (const Case c : {Case{"rgb24", 3, 0}, Case{"pal8", 3, 0}, Case{"rgb48be", 3, 1},
                       Case{"rgba", 4, 0}, Case{"rgba64be", 4, 1}, Case{"gray", 3, 0},
                       Case{"gray16be", 3, 1}, Case{"ya8", 4, 0}, Case{"monob", 3, 0}}) {
    const fs::path file = dir / (std::string(c.pix_fmt) + ".png");
    // The test pattern, with alpha rising across the picture.
    const std::string make =
        "ffmpeg -v error -y -f lavfi -i \"testsrc2=s=24x10,format=rgba,"
        "geq=r='r(X,Y)':g='g(X,Y)':b='b(X,Y)':a='10*X+Y'\" "
        "-frames:v 1 -pix_fmt " +
        std::string(c.pix_fmt) + " '" + file.string() + "'";
    ASSERT_EQ(std::system(make.c_str()), 0) << make;
    const fs::path raw = dir / (std::string(c.pix_fmt) + ".raw");
    const std::string decode = "ffmpeg -v error -y -i '" + file.string() +
                               "' -f rawvideo -pix_fmt " + (c.channels == 4 ? "rgba" : "rgb24") +
                               " '" + raw.string() + "'";
    ASSERT_EQ(std::system(decode.c_str()), 0) << decode;
    const std::string expected = slurp(raw);

    const Image image = read_png(file);
    ASSERT_EQ(image.width, 24) << c.pix_fmt;
    ASSERT_EQ(image.height, 10) << c.pix_fmt;
    ASSERT_EQ(image.channels, c.channels) << c.pix_fmt;
    ASSERT_EQ(expected.size(), image.pixels.size()) << c.pix_fmt;
    int worst = 0;
    for (std::size_t i = 0; i < expected.size(); ++i)
      worst = std::max(
          worst, std::abs(int(static_cast<unsigned char>(expected[i])) - int(image.pixels[i])));
    EXPECT_LE(worst, c.tolerance) << c.pix_fmt;
  }
}

}  // namespace
}  // namespace tumble
