#include "tumble/gif_writer.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <numeric>

#include "../test_dir.hpp"
#include "tumble/error.hpp"
#include "tumble/image.hpp"
#include "tumble/video_reader.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

constexpr int kW = 96, kH = 64;

fs::path fresh_dir(const std::string& name) {
  return test::fresh_dir("gif_test", name);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Frame k: a flat grey-blue field with an orange square moving 4 px per frame, RGBA; `alpha`:
// the field is fully transparent instead.
Image frame(int k, bool alpha = false) {
  Image image(kW, kH, 4);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      std::uint8_t* p = image.row(y) + 4 * x;
      const bool square = x >= 4 * k % kW && x < 4 * k % kW + 16 && y >= 20 && y < 36;
      const std::uint8_t rgba[4] = {static_cast<std::uint8_t>(square ? 217 : 200),
                                    static_cast<std::uint8_t>(square ? 87 : 210),
                                    static_cast<std::uint8_t>(square ? 43 : 225),
                                    static_cast<std::uint8_t>(square || !alpha ? 255 : 0)};
      std::copy(rgba, rgba + 4, p);
    }
  return image;
}

std::string write_gif(const fs::path& file, int fps, long frames, bool alpha = false) {
  GifWriter gif(file, {kW, kH, fps, frames, alpha});
  for (long k = 0; k < frames; ++k) {
    const Image f = frame(static_cast<int>(k), alpha);
    gif.add_frame(f.pixels.data(), static_cast<std::ptrdiff_t>(f.stride()), false);
  }
  gif.finish();
  return slurp(file);
}

// ---- timing: SPEC's rule, in numbers ----

TEST(GifTiming, SixtyFpsKeepsEveryOtherFrameAndNeverDrifts) {
  const GifTiming t = GifTiming::for_clip(60, 240);  // the default 4 s clip
  EXPECT_EQ(t.frame_step, 2);  // 1.67 cs is under the 2 cs browsers honour; 3.33 cs is not
  EXPECT_EQ(t.frames(), 120);
  EXPECT_DOUBLE_EQ(t.rate_hz(), 30.0);
  EXPECT_FALSE(t.exact());
  long total = 0;
  for (long j = 0; j < t.frames(); ++j) {
    // Frame j starts at round(100·j/30) cs: never more than half a centisecond off the clip.
    EXPECT_LE(std::abs(static_cast<double>(t.start_cs(j)) - 100.0 * static_cast<double>(j) / 30.0),
              0.5);
    const int d = t.delay_cs(j);
    EXPECT_TRUE(d == 3 || d == 4) << j;
    total += d;
  }
  EXPECT_EQ(total, 400);  // 4 s exactly
}

TEST(GifTiming, ExactWhereTheRateIsWholeCentiseconds) {
  for (const int fps : {1, 2, 4, 5, 10, 20, 25, 50}) {
    SCOPED_TRACE(fps);
    const GifTiming t = GifTiming::for_clip(fps, 3 * fps);
    EXPECT_EQ(t.frame_step, 1);
    EXPECT_TRUE(t.exact());
    for (long j = 0; j < t.frames(); ++j) EXPECT_EQ(t.delay_cs(j), 100 / fps);
  }
}

TEST(GifTiming, FastClipsAreThinnedToAtMostFiftyFramesPerSecond) {
  EXPECT_EQ(GifTiming::for_clip(51, 10).frame_step, 2);
  EXPECT_EQ(GifTiming::for_clip(100, 10).frame_step, 2);
  EXPECT_EQ(GifTiming::for_clip(1000, 10).frame_step, 20);
  EXPECT_EQ(GifTiming::for_clip(30, 10).frame_step, 1);
  // 7 frames at 100 fps, every 2nd: frames at 0, 2, 4, 6 cs; the clip ends at 7 cs, so the last
  // frame would last 1 cs, which browsers play as 10: it gets 2.
  const GifTiming t = GifTiming::for_clip(100, 7);
  EXPECT_EQ(t.frames(), 4);
  EXPECT_EQ(t.delay_cs(0), 2);
  EXPECT_EQ(t.delay_cs(3), 2);
}

// ---- the file ----

TEST(GifWriter, DecodesBackToTheFramesThroughLibavcodec) {
  const fs::path file = fresh_dir("decode") / "clip.gif";
  write_gif(file, 25, 10);
  VideoReader reader(file);
  EXPECT_EQ(reader.width(), kW);
  EXPECT_EQ(reader.height(), kH);
  Image decoded;
  int n = 0;
  while (reader.next(decoded)) {
    const Image expected = frame(n);
    // Flat colours come back within the palette's and the dither's reach: a few levels.
    long off = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        for (int c = 0; c < 3; ++c)
          off += std::abs(int{decoded.row(y)[3 * x + c]} - int{expected.row(y)[4 * x + c]}) > 12;
    EXPECT_LT(off, kW * kH / 50) << "frame " << n;
    ++n;
  }
  EXPECT_EQ(n, 10);
}

TEST(GifWriter, BottomUpRowsAreTheSamePicture) {
  const fs::path dir = fresh_dir("flip");
  const std::string top_down = write_gif(dir / "a.gif", 25, 4);
  GifWriter gif(dir / "b.gif", {kW, kH, 25, 4, false});
  for (int k = 0; k < 4; ++k) {
    const Image f = frame(k);
    // The last row first, stepping backwards: as glReadPixels returns it, read bottom-up.
    std::vector<std::uint8_t> flipped(f.pixels.size());
    for (int y = 0; y < kH; ++y)
      std::copy_n(f.row(y), f.stride(), flipped.data() + (kH - 1 - y) * f.stride());
    gif.add_frame(flipped.data(), static_cast<std::ptrdiff_t>(f.stride()), true);
  }
  gif.finish();
  EXPECT_TRUE(slurp(dir / "b.gif") == top_down);
}

TEST(GifWriter, SameFramesSameBytes) {
  const fs::path dir = fresh_dir("determinism");
  const std::string a = write_gif(dir / "a.gif", 60, 20);
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == write_gif(dir / "b.gif", 60, 20));
}

TEST(GifWriter, UnfinishedLeavesNothing) {
  const fs::path dir = fresh_dir("unfinished");
  {
    GifWriter gif(dir / "clip.gif", {kW, kH, 25, 10, false});
    const Image f = frame(0);
    gif.add_frame(f.pixels.data(), static_cast<std::ptrdiff_t>(f.stride()), false);
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "no clip, no temporary file";
}

TEST(GifWriter, AlphaBecomesTheTransparentEntry) {
  const fs::path file = fresh_dir("alpha") / "clip.gif";
  const std::string bytes = write_gif(file, 25, 3, /*alpha=*/true);
  // The first graphic control extension (0x21 0xf9, size 4) sets its transparency flag (bit 0).
  const std::size_t gce = bytes.find("\x21\xf9\x04");
  ASSERT_NE(gce, std::string::npos);
  EXPECT_EQ(bytes[gce + 3] & 1, 1);
  const std::string out = [&] {
    std::string o;
    FILE* pipe =
        popen(("ffmpeg -v error -i '" + file.string() + "' -frames:v 1 -f rawvideo -pix_fmt rgba -")
                  .c_str(),
              "r");
    if (!pipe) return o;
    char buffer[65536];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) o.append(buffer, n);
    pclose(pipe);
    return o;
  }();
  ASSERT_EQ(out.size(), std::size_t(kW) * kH * 4) << "ffmpeg (scripts/setup) decodes the GIF";
  EXPECT_EQ(static_cast<unsigned char>(out[3]), 0) << "the field is transparent";
  const std::size_t in_square = (std::size_t(28) * kW + 8) * 4;
  EXPECT_EQ(static_cast<unsigned char>(out[in_square + 3]), 255) << "the square is opaque";
}

TEST(GifWriter, SizeBeyondWhatGifHoldsIsBadInput) {
  const fs::path dir = fresh_dir("size");
  try {
    GifWriter gif(dir / "clip.gif", {70000, 10, 25, 1, false});
    FAIL() << "a 70000-pixel-wide GIF was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
  }
}

}  // namespace
}  // namespace tumble
