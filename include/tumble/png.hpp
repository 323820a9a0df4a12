#pragma once
/// PNG files through libpng: 8-bit RGB, or RGBA with straight alpha when asked (RGBA input is
/// otherwise written as RGB), written atomically.

#include <filesystem>

#include "tumble/image.hpp"

namespace tumble {

/// How a PNG is written.
struct PngOptions {
  /// Write a 4-channel image as RGBA (straight alpha, as PNG defines it); else its alpha is
  /// dropped.
  bool alpha = false;
  /// Fast: zlib level 1 with filter NONE, 3–4 ms per 720p frame here against 16–18 ms for the
  /// adaptive filters (PLATFORM.md), at larger files: for frames and stills. Small: level 9
  /// with the adaptive filters, for a figure written once (a strobe), several times smaller.
  enum class Packing { Fast, Small } packing = Packing::Fast;
};

/// Throws tumble::Error (Environment).
void write_png(const std::filesystem::path& path, const Image& image,
               const PngOptions& options = {});

/// Reads an 8-bit (or 16-bit, reduced) gray/RGB/RGBA PNG as RGB or RGBA. Throws tumble::Error
/// (BadInput) naming the file when it is missing or cannot be decoded.
Image read_png(const std::filesystem::path& path);

}  // namespace tumble
