#pragma once
/// Pixels a renderer with a transparent backdrop reads back: RGBA rows bottom-up with
/// premultiplied alpha (colour already scaled by coverage, as GL blending produces it). PNG, GIF
/// and WebP store straight alpha, and an MP4 has none: these turn one into the other.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tumble/image.hpp"

namespace tumble {

/// Straight alpha from premultiplied: c·255/a rounded to nearest (255 at most); a fully
/// transparent pixel becomes (0, 0, 0, 0), so its bytes do not depend on what was under it.
inline void unpremultiply_pixel(const std::uint8_t* in, std::uint8_t* out) {
  const unsigned a = in[3];
  for (int c = 0; c < 3; ++c) {
    const unsigned v = a == 0 ? 0u : (in[c] * 255u + a / 2u) / a;
    out[c] = static_cast<std::uint8_t>(v > 255u ? 255u : v);
  }
  out[3] = static_cast<std::uint8_t>(a);
}

/// A top-down straight-alpha RGBA image from premultiplied RGBA rows bottom-up: the flip and
/// the division by alpha in a single pass.
inline Image straight_image_from_gl_rgba(const std::uint8_t* premultiplied, int width, int height) {
  Image image(width, height, 4);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* in = premultiplied + std::size_t(height - 1 - y) * width * 4;
    std::uint8_t* out = image.row(y);
    for (int x = 0; x < width; ++x) unpremultiply_pixel(in + 4 * x, out + 4 * x);
  }
  return image;
}

/// Straight-alpha RGBA in place (rows keep their order).
inline void unpremultiply(std::uint8_t* rgba, std::size_t pixels) {
  for (std::size_t i = 0; i < pixels; ++i) unpremultiply_pixel(rgba + 4 * i, rgba + 4 * i);
}

/// A frame's pixels with straight alpha: premultiplied ones converted into a buffer reused from
/// frame to frame, straight ones passed through untouched (what the GIF and WebP sinks feed).
class StraightAlpha {
 public:
  const std::uint8_t* of(const std::uint8_t* rgba, std::size_t pixels, bool premultiplied) {
    if (!premultiplied) return rgba;
    buffer_.assign(rgba, rgba + pixels * 4);
    unpremultiply(buffer_.data(), pixels);
    return buffer_.data();
  }

 private:
  std::vector<std::uint8_t> buffer_;
};

/// `out` = premultiplied `in` composited over the opaque sRGB colour (r, g, b): c + bg·(1 − a),
/// alpha 255. The "over" operator on premultiplied values needs no division.
inline void composite_over(const std::uint8_t* in, std::uint8_t* out, std::size_t pixels,
                           std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  const unsigned bg[3] = {r, g, b};
  for (std::size_t i = 0; i < pixels; ++i, in += 4, out += 4) {
    const unsigned rest = 255u - in[3];
    for (int c = 0; c < 3; ++c) {
      const unsigned v = in[c] + (bg[c] * rest + 127u) / 255u;
      out[c] = static_cast<std::uint8_t>(v > 255u ? 255u : v);
    }
    out[3] = 255;
  }
}

}  // namespace tumble
