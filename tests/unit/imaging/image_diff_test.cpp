#include "tumble/image_diff.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace tumble {
namespace {

constexpr int kWidth = 16;
constexpr int kHeight = 8;  // 128 pixels, 384 RGB samples

// A picture with every channel well inside 1–254, so ±1 never clips.
Image gradient(int width = kWidth, int height = kHeight, int channels = 3) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = image.row(y) + x * channels;
      p[0] = static_cast<std::uint8_t>(20 + 10 * x);
      p[1] = static_cast<std::uint8_t>(30 + 20 * y);
      p[2] = static_cast<std::uint8_t>(200 - 5 * x - 3 * y);
      if (channels == 4) p[3] = 255;
    }
  return image;
}

std::uint8_t* pixel(Image& image, int x, int y) {
  return image.row(y) + x * image.channels;
}
const std::uint8_t* pixel(const Image& image, int x, int y) {
  return image.row(y) + x * image.channels;
}

// Tolerances: the counts and deltas are integers and exact; PSNR values are compared to 1e-9 dB,
// far below any meaning but above the rounding of one log10.

TEST(CompareImages, IdenticalImagesHaveNoDifferenceAndInfinitePsnr) {
  const Image a = gradient();
  const DiffResult r = compare_images(a, a, 0);
  EXPECT_EQ(r.differing_pixels, 0);
  EXPECT_EQ(r.total_pixels, kWidth * kHeight);
  EXPECT_EQ(r.fraction, 0.0);
  EXPECT_EQ(r.largest_delta, 0);
  EXPECT_EQ(r.psnr_db, std::numeric_limits<double>::infinity());
  EXPECT_FALSE(r.size_mismatch);
  EXPECT_TRUE(r.within(DiffTolerance{}));
  EXPECT_TRUE(r.within(DiffTolerance{0, 0.0, 1000.0}));  // +inf passes any PSNR floor
}

TEST(CompareImages, OnePixelOffByTen) {
  const Image expected = gradient();
  Image actual = expected;
  pixel(actual, 5, 3)[1] += 10;  // one channel of one pixel
  const DiffResult r = compare_images(expected, actual, 0);
  EXPECT_EQ(r.differing_pixels, 1);
  EXPECT_DOUBLE_EQ(r.fraction, 1.0 / 128.0);
  EXPECT_EQ(r.largest_delta, 10);
  // PSNR = 10 log10(255² / MSE), MSE over the 3 · 128 RGB samples = 10² / 384:
  // 10 log10(65025 · 384 / 100) = 10 log10(249696) = 53.9741 dB.
  EXPECT_NEAR(r.psnr_db, 53.974115852354416, 1e-9);
  EXPECT_FALSE(r.within(DiffTolerance{}));
  EXPECT_TRUE(r.within(DiffTolerance{0, 1.0 / 128.0, {}}));  // exactly at the limit passes
  EXPECT_FALSE(r.within(DiffTolerance{0, 0.0078, {}}));      // just below 1/128 = 0.0078125
  EXPECT_TRUE(compare_images(expected, actual, 10).within(DiffTolerance{10, 0.0, {}}));
  EXPECT_EQ(compare_images(expected, actual, 9).differing_pixels, 1);
}

TEST(CompareImages, AllPixelsOffByOneDifferOnlyBelowMaxDeltaOne) {
  const Image expected = gradient();
  Image actual = expected;
  for (std::size_t i = 0; i < actual.pixels.size(); ++i)
    actual.pixels[i] = static_cast<std::uint8_t>(actual.pixels[i] + (i % 2 == 0 ? 1 : -1));

  const DiffResult exact = compare_images(expected, actual, 0);
  EXPECT_EQ(exact.differing_pixels, 128);
  EXPECT_EQ(exact.fraction, 1.0);
  EXPECT_EQ(exact.largest_delta, 1);
  // Every sample off by 1: MSE = 1, PSNR = 10 log10(255²) = 48.1308 dB.
  EXPECT_NEAR(exact.psnr_db, 48.1308036086791, 1e-9);

  const DiffResult lenient = compare_images(expected, actual, 1);
  EXPECT_EQ(lenient.differing_pixels, 0);
  EXPECT_EQ(lenient.largest_delta, 1);
  EXPECT_NEAR(lenient.psnr_db, 48.1308036086791, 1e-9);
  EXPECT_TRUE(lenient.within(DiffTolerance{1, 0.0, {}}));
  EXPECT_TRUE(lenient.within(DiffTolerance{1, 0.0, 48.0}));
  EXPECT_FALSE(lenient.within(DiffTolerance{1, 0.0, 48.2}));  // the PSNR floor still applies
}

TEST(CompareImages, DifferentSizesAreAMismatchWhateverTheTolerance) {
  const Image small = gradient(16, 8);
  const Image large = gradient(20, 10);  // its top-left 16x8 equals `small`
  const DiffResult r = compare_images(small, large, 0);
  EXPECT_TRUE(r.size_mismatch);
  EXPECT_EQ(r.total_pixels, 200);
  EXPECT_EQ(r.differing_pixels, 200 - 128);  // the overlap matches; the rest counts as differing
  EXPECT_EQ(r.largest_delta, 0);
  EXPECT_FALSE(r.within(DiffTolerance{255, 1.0, {}}));

  // Crossed sizes: the canvas is the larger width by the larger height.
  const DiffResult crossed = compare_images(gradient(16, 4), gradient(8, 8), 0);
  EXPECT_TRUE(crossed.size_mismatch);
  EXPECT_EQ(crossed.total_pixels, 128);
  EXPECT_EQ(crossed.differing_pixels, 128 - 32);
}

TEST(CompareImages, AlphaIsIgnored) {
  const Image rgb = gradient(kWidth, kHeight, 3);
  Image rgba = gradient(kWidth, kHeight, 4);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) pixel(rgba, x, y)[3] = static_cast<std::uint8_t>(x * y);
  EXPECT_EQ(compare_images(rgb, rgba, 0).largest_delta, 0);
  EXPECT_EQ(compare_images(rgba, rgb, 0).differing_pixels, 0);
  EXPECT_EQ(compare_images(rgba, gradient(kWidth, kHeight, 4), 0).differing_pixels, 0);
  pixel(rgba, 2, 2)[2] += 7;  // a colour change in an RGBA image still counts
  EXPECT_EQ(compare_images(rgb, rgba, 0).largest_delta, 7);
}

bool is_grey(const std::uint8_t* p) {
  return p[0] == p[1] && p[1] == p[2];
}
// Magenta-dominant: no green, red and blue equal and clearly present.
bool is_magenta(const std::uint8_t* p) {
  return p[1] == 0 && p[0] == p[2] && p[0] >= 128;
}

TEST(DiffImage, UnchangedPixelsAreFadedGreyAndChangedOnesMagenta) {
  const Image expected = gradient();
  Image actual = expected;
  pixel(actual, 1, 1)[0] += 1;   // the smallest change
  pixel(actual, 9, 6)[2] += 50;  // a large one
  const Image d = diff_image(expected, actual, 0);
  ASSERT_EQ(d.width, kWidth);
  ASSERT_EQ(d.height, kHeight);
  ASSERT_EQ(d.channels, 3);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t* p = pixel(d, x, y);
      if ((x == 1 && y == 1) || (x == 9 && y == 6)) {
        EXPECT_TRUE(is_magenta(p)) << x << "," << y;
      } else {
        // Faded halfway to white: grey in [128, 255], and darker where the picture is darker.
        EXPECT_TRUE(is_grey(p)) << x << "," << y;
        EXPECT_GE(p[0], 128) << x << "," << y;
      }
    }
  EXPECT_LT(pixel(d, 1, 1)[0], pixel(d, 9, 6)[0]) << "a larger delta must look stronger";
  // Contrast of the context survives: the gradient's dark and light corners stay apart.
  EXPECT_NE(pixel(d, 0, 0)[0], pixel(d, kWidth - 1, kHeight - 1)[0]);
}

TEST(DiffImage, ChangesWithinMaxDeltaAreShownAsUnchanged) {
  const Image expected = gradient();
  Image actual = expected;
  pixel(actual, 3, 3)[0] += 4;
  EXPECT_TRUE(is_grey(pixel(diff_image(expected, actual, 4), 3, 3)));
  EXPECT_TRUE(is_magenta(pixel(diff_image(expected, actual, 3), 3, 3)));
}

TEST(DiffImage, DifferentSizesGiveTheLargerCanvasWithTheMissingAreaMarked) {
  const Image d = diff_image(gradient(16, 4), gradient(8, 8), 0);
  ASSERT_EQ(d.width, 16);
  ASSERT_EQ(d.height, 8);
  EXPECT_TRUE(is_grey(pixel(d, 2, 2)));  // in both, equal
  int marked = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) {
      const std::uint8_t* p = pixel(d, x, y);
      if (x < 8 && y < 4) continue;
      EXPECT_FALSE(is_magenta(p)) << x << "," << y;          // "missing" never reads as "changed"
      if (p[0] == 255 && p[1] > 150 && p[2] == 0) ++marked;  // yellow stripes
    }
  EXPECT_GT(marked, (128 - 32) / 3);
}

}  // namespace
}  // namespace tumble
