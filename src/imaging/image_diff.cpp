#include "tumble/image_diff.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

namespace tumble {
namespace {

// The largest of the R, G, B differences of one pixel; alpha (a 4th channel) is never read.
int pixel_delta(const std::uint8_t* e, const std::uint8_t* a) {
  return std::max({std::abs(int{e[0]} - int{a[0]}), std::abs(int{e[1]} - int{a[1]}),
                   std::abs(int{e[2]} - int{a[2]})});
}

// BT.709 luma (the weights of tumble's video path), in 0–255, mixed halfway toward white: the
// picture stays readable as context but never reaches the magenta's saturation or darkness.
std::uint8_t faded_grey(const std::uint8_t* rgb) {
  const int luma = (2126 * rgb[0] + 7152 * rgb[1] + 722 * rgb[2] + 5000) / 10000;
  return static_cast<std::uint8_t>((luma + 255 + 1) / 2);
}

// Magenta level for a delta in 1–255: 128 + 127·sqrt(delta / 255). The square root spreads the
// small deltas that decide a golden comparison (1 → 136, 5 → 146, 20 → 164) while 255 is full
// magenta; the floor of 128 keeps the smallest change clearly visible on the pale grey.
std::uint8_t magenta_level(int delta) {
  const double level = 128.0 + 127.0 * std::sqrt(delta / 255.0);
  return static_cast<std::uint8_t>(std::lround(level));
}

void check_arguments(const Image& expected, const Image& actual, int max_delta) {
  assert(expected.channels >= 3 && actual.channels >= 3);
  assert(max_delta >= 0 && max_delta <= 255);
  assert(expected.pixels.size() == expected.stride() * std::size_t(expected.height));
  assert(actual.pixels.size() == actual.stride() * std::size_t(actual.height));
  (void)expected, (void)actual, (void)max_delta;
}

}  // namespace

bool DiffResult::within(const DiffTolerance& tolerance) const {
  if (size_mismatch) return false;
  // Both sides are the correctly rounded doubles of their fractions, so a share exactly at the
  // limit (1 of 1000 against 0.001) compares equal and passes.
  if (fraction > tolerance.max_fraction) return false;
  return !tolerance.min_psnr_db || psnr_db >= *tolerance.min_psnr_db;
}

DiffResult compare_images(const Image& expected, const Image& actual, int max_delta) {
  check_arguments(expected, actual, max_delta);
  const int overlap_w = std::min(expected.width, actual.width);
  const int overlap_h = std::min(expected.height, actual.height);
  const int ec = expected.channels, ac = actual.channels;

  DiffResult r;
  r.size_mismatch = expected.width != actual.width || expected.height != actual.height;
  r.total_pixels =
      long{std::max(expected.width, actual.width)} * std::max(expected.height, actual.height);
  // At most 3 · 255² · 16384² ≈ 5e13 for the largest image tumble renders: exact in 64 bits.
  std::uint64_t squared_error = 0;
  for (int y = 0; y < overlap_h; ++y) {
    const std::uint8_t* e = expected.row(y);
    const std::uint8_t* a = actual.row(y);
    for (int x = 0; x < overlap_w; ++x, e += ec, a += ac) {
      for (int c = 0; c < 3; ++c) {
        const int d = int{e[c]} - int{a[c]};
        squared_error += static_cast<std::uint64_t>(d * d);
      }
      const int delta = pixel_delta(e, a);
      if (delta > max_delta) ++r.differing_pixels;
      r.largest_delta = std::max(r.largest_delta, delta);
    }
  }
  const long overlap = long{overlap_w} * overlap_h;
  r.differing_pixels += r.total_pixels - overlap;  // outside the overlap nothing matches
  r.fraction = r.total_pixels > 0
                   ? static_cast<double>(r.differing_pixels) / static_cast<double>(r.total_pixels)
                   : 0.0;
  // PSNR = 10 log10(255² / MSE), MSE = mean of the squared differences over the R, G and B
  // samples of the overlap.
  if (squared_error == 0) {
    r.psnr_db = std::numeric_limits<double>::infinity();
  } else {
    const double mse = static_cast<double>(squared_error) / (3.0 * static_cast<double>(overlap));
    r.psnr_db = 10.0 * std::log10(255.0 * 255.0 / mse);
  }
  return r;
}

Image diff_image(const Image& expected, const Image& actual, int max_delta) {
  check_arguments(expected, actual, max_delta);
  const int overlap_w = std::min(expected.width, actual.width);
  const int overlap_h = std::min(expected.height, actual.height);
  const int ec = expected.channels, ac = actual.channels;
  Image out(std::max(expected.width, actual.width), std::max(expected.height, actual.height), 3);
  for (int y = 0; y < out.height; ++y) {
    std::uint8_t* o = out.row(y);
    for (int x = 0; x < out.width; ++x, o += 3) {
      if (x >= overlap_w || y >= overlap_h) {
        // Stripes 4 pixels wide: "no pixel here", unlike any change, at any size.
        const bool yellow = ((x + y) / 4) % 2 == 0;
        o[0] = yellow ? 255 : 64;
        o[1] = yellow ? 210 : 64;
        o[2] = yellow ? 0 : 64;
        continue;
      }
      const std::uint8_t* e = expected.row(y) + std::size_t(x) * ec;
      const std::uint8_t* a = actual.row(y) + std::size_t(x) * ac;
      const int delta = pixel_delta(e, a);
      if (delta > max_delta) {
        o[0] = o[2] = magenta_level(delta);
        o[1] = 0;
      } else {
        o[0] = o[1] = o[2] = faded_grey(e);
      }
    }
  }
  return out;
}

}  // namespace tumble
