#pragma once
/// An 8-bit image with rows stored top-down and tightly packed: what PNG files hold, what the
/// renderer hands to sinks (after its one flip), what `diff` compares.

#include <cstdint>
#include <cstring>
#include <vector>

namespace tumble {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 3;  ///< 3 = RGB, 4 = RGBA
  std::vector<std::uint8_t> pixels;

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c) {}
  std::size_t stride() const { return std::size_t(width) * channels; }
  std::uint8_t* row(int y) { return pixels.data() + std::size_t(y) * stride(); }
  const std::uint8_t* row(int y) const { return pixels.data() + std::size_t(y) * stride(); }
};

/// A top-down RGB image from RGBA rows bottom-up, as glReadPixels returns them: the one flip and
/// the dropped alpha in a single pass.
inline Image image_from_gl_rgba(const std::uint8_t* rgba, int width, int height) {
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* in = rgba + std::size_t(height - 1 - y) * width * 4;
    std::uint8_t* out = image.row(y);
    for (int x = 0; x < width; ++x) std::memcpy(out + 3 * x, in + 4 * x, 3);
  }
  return image;
}

}  // namespace tumble
