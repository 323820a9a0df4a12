#include "tumble/webp_writer.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <optional>

#include "../test_dir.hpp"
#include "tumble/error.hpp"
#include "tumble/image.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  return test::fresh_dir("webp_test", name);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Frame k of w x h: a gradient with a square moving 3 px per frame, so every frame differs
// (libwebp merges a frame identical to the one before into it); `alpha`: the left half is
// transparent.
Image frame(int w, int h, int k, bool alpha = false) {
  Image image(w, h, 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.row(y) + 4 * x;
      const bool square = x >= 3 * k % w && x < 3 * k % w + 8 && y >= h / 3 && y < h / 3 + 8;
      p[0] = square ? 30 : static_cast<std::uint8_t>(4 * x);
      p[1] = square ? 200 : static_cast<std::uint8_t>(4 * y);
      p[2] = square ? 90 : 128;
      p[3] = alpha && x < w / 2 && !square ? 0 : 255;
    }
  return image;
}

std::string write_webp(const fs::path& file, int w, int h, int fps, int frames,
                       bool alpha = false) {
  WebpWriter webp(file, {w, h, fps, alpha});
  for (int k = 0; k < frames; ++k) {
    const Image f = frame(w, h, k, alpha);
    webp.add_frame(f.pixels.data(), static_cast<std::ptrdiff_t>(f.stride()), false);
  }
  webp.finish();
  return slurp(file);
}

struct Chunks {
  bool riff = false, animated = false, alpha = false;
  std::optional<int> loop;
  std::vector<int> durations;
};

// The RIFF chunks (WebP Container Specification): VP8X flags, ANIM loop count, ANMF durations.
Chunks chunks(const std::string& d) {
  Chunks c;
  auto le = [&](std::size_t at, int n) {
    std::uint32_t v = 0;
    for (int i = n - 1; i >= 0; --i)
      v = v << 8 | static_cast<unsigned char>(d[at + static_cast<std::size_t>(i)]);
    return v;
  };
  if (d.size() < 12 || d.compare(0, 4, "RIFF") != 0 || d.compare(8, 4, "WEBP") != 0) return c;
  c.riff = le(4, 4) + 8 == d.size();
  for (std::size_t at = 12; at + 8 <= d.size();) {
    const std::string fourcc = d.substr(at, 4);
    const std::uint32_t size = le(at + 4, 4);
    if (fourcc == "VP8X") c.animated = d[at + 8] & 2, c.alpha = d[at + 8] & 0x10;
    if (fourcc == "ANIM") c.loop = static_cast<int>(le(at + 12, 2));
    if (fourcc == "ANMF") c.durations.push_back(static_cast<int>(le(at + 20, 3)));
    at += 8 + size + (size & 1);
  }
  return c;
}

TEST(WebpWriter, LoopsForeverOneFramePerFrameTimedInMilliseconds) {
  const fs::path file = fresh_dir("timing") / "clip.webp";
  const Chunks c = chunks(write_webp(file, 64, 48, 30, 10));
  EXPECT_TRUE(c.riff);
  EXPECT_TRUE(c.animated);
  ASSERT_TRUE(c.loop.has_value());
  EXPECT_EQ(*c.loop, 0);
  // Frame k starts at round(1000·k/30) ms; the last ends at round(1000·10/30) = 333 ms (libwebp
  // alone would give it the average of the others, truncated).
  const std::vector<int> expected = {33, 34, 33, 33, 34, 33, 33, 34, 33, 33};
  EXPECT_EQ(c.durations, expected);
}

TEST(WebpWriter, WholeMillisecondRatesAreExact) {
  const fs::path file = fresh_dir("exact") / "clip.webp";
  const Chunks c = chunks(write_webp(file, 64, 48, 50, 6));
  EXPECT_EQ(c.durations, std::vector<int>(6, 20));
}

TEST(WebpWriter, ReportsTheDurationsItUsed) {
  const fs::path file = fresh_dir("report") / "clip.webp";
  WebpWriter webp(file, {32, 32, 60, false});
  for (int k = 0; k < 6; ++k) {
    const Image f = frame(32, 32, k);
    webp.add_frame(f.pixels.data(), static_cast<std::ptrdiff_t>(f.stride()), false);
  }
  webp.finish();
  EXPECT_EQ(webp.frames(), 6);
  EXPECT_EQ(webp.durations_ms(), (std::vector<int>{16, 17}));
}

TEST(WebpWriter, OddSizesAndAlpha) {
  const fs::path file = fresh_dir("odd") / "clip.webp";
  const Chunks c = chunks(write_webp(file, 33, 17, 25, 4, /*alpha=*/true));
  EXPECT_TRUE(c.riff);
  EXPECT_TRUE(c.alpha) << "the alpha channel is kept";
  EXPECT_EQ(c.durations.size(), 4u);
}

TEST(WebpWriter, SameFramesSameBytes) {
  const fs::path dir = fresh_dir("determinism");
  const std::string a = write_webp(dir / "a.webp", 64, 48, 60, 12);
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == write_webp(dir / "b.webp", 64, 48, 60, 12));
}

TEST(WebpWriter, UnfinishedLeavesNothing) {
  const fs::path dir = fresh_dir("unfinished");
  {
    WebpWriter webp(dir / "clip.webp", {32, 32, 30, false});
    const Image f = frame(32, 32, 0);
    webp.add_frame(f.pixels.data(), static_cast<std::ptrdiff_t>(f.stride()), false);
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(WebpWriter, SizeBeyondWhatWebpHoldsIsBadInput) {
  try {
    WebpWriter webp(fresh_dir("size") / "clip.webp", {16384, 16, 30, false});
    FAIL() << "a 16384-pixel-wide WebP was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  }
}

}  // namespace
}  // namespace tumble
