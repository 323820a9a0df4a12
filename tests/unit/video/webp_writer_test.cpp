#include "tumble/webp_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
  WebpWriter webp(file, {w, h, fps, frames, alpha});
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
  WebpWriter webp(file, {32, 32, 60, 6, false});
  for (int k = 0; k < 6; ++k) {
    const Image f = frame(32, 32, k);
    webp.add_frame(f.pixels.data(), static_cast<std::ptrdiff_t>(f.stride()), false);
  }
  webp.finish();
  EXPECT_EQ(webp.frames(), 6);
  EXPECT_EQ(webp.durations_ms(), (std::vector<int>{16, 17}));
}

// Browsers play a frame of 10 ms or less as 100 ms: at 120 fps every 3rd frame is kept (25 ms
// each, 40 frames/s), and the loop still lasts the clip's duration.
TEST(WebpWriter, FastClipsKeepFewerFramesOfAtLeast20Ms) {
  const fs::path file = fresh_dir("fast") / "clip.webp";
  const Chunks c = chunks(write_webp(file, 64, 48, 120, 24));
  EXPECT_EQ(c.durations, std::vector<int>(8, 25));
}

TEST(WebpWriter, AShortLastFrameIsLeftOutAndTheOneBeforeLastsToTheEnd) {
  // 25 frames at 120 fps: kept 0, 3, ..., 21 (8 frames); clip frame 24 would last 8 ms, so
  // frame 21 lasts from 175 ms to round(1000·25/120) = 208 ms.
  const fs::path file = fresh_dir("short_last") / "clip.webp";
  const Chunks c = chunks(write_webp(file, 64, 48, 120, 25));
  std::vector<int> expected(7, 25);
  expected.push_back(33);
  EXPECT_EQ(c.durations, expected);
}

TEST(WebpTiming, EveryFramePlaysAsWrittenAndTheLoopKeepsTheClipsClock) {
  for (const int fps : {1, 24, 30, 50, 60, 90, 91, 99, 100, 120, 144, 240, 1000}) {
    for (const long n : {1L, 2L, 7L, 100L, 241L, 1001L}) {
      SCOPED_TRACE(testing::Message() << fps << " fps, " << n << " frames");
      const WebpTiming t = WebpTiming::for_clip(fps, n);
      // The thinning only where a frame would otherwise last 10 ms or less.
      EXPECT_EQ(t.frame_step == 1, fps <= 90);
      long kept = 0, total_ms = 0;
      for (long k = 0; k < n; ++k) kept += t.keeps(k);
      EXPECT_EQ(kept, t.frames());
      for (long j = 0; j < t.frames(); ++j) {
        const int d = t.duration_ms(j);
        // (Unless the whole clip is shorter: 1 frame at 1000 fps lasts 1 ms.)
        const long shortest =
            std::min<long>(t.frame_step == 1 ? 11 : WebpTiming::kThinnedMinMs, t.end_ms());
        EXPECT_GE(d, shortest) << "frame " << j;
        total_ms += d;
      }
      // The loop lasts the clip, N / fps, to the millisecond.
      EXPECT_EQ(total_ms, t.end_ms());
      EXPECT_LE(std::abs(double(total_ms) - 1000.0 * double(n) / fps), 0.5);
      EXPECT_DOUBLE_EQ(t.rate_hz(), double(fps) / t.frame_step);
    }
  }
  EXPECT_EQ(WebpTiming::for_clip(120, 480).frame_step, 3);  // 40 frames/s, 25 ms each
  EXPECT_TRUE(WebpTiming::for_clip(120, 480).exact());
  EXPECT_EQ(WebpTiming::for_clip(100, 400).frame_step, 2);  // 50 frames/s, 20 ms each
  EXPECT_FALSE(WebpTiming::for_clip(60, 240).exact());      // 17, 17, 16 ms
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
    WebpWriter webp(dir / "clip.webp", {32, 32, 30, 1, false});
    const Image f = frame(32, 32, 0);
    webp.add_frame(f.pixels.data(), static_cast<std::ptrdiff_t>(f.stride()), false);
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(WebpWriter, SizeBeyondWhatWebpHoldsIsBadInput) {
  try {
    WebpWriter webp(fresh_dir("size") / "clip.webp", {16384, 16, 30, 1, false});
    FAIL() << "a 16384-pixel-wide WebP was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  }
}

}  // namespace
}  // namespace tumble
