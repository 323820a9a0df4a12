#pragma once
/// PNG files through libpng: 8-bit RGB (RGBA input is written as RGB), written atomically.

#include <filesystem>

#include "tumble/image.hpp"

namespace tumble {

/// zlib level 1 with filter NONE by default: 3–4 ms per 720p frame here against 16–18 ms for the
/// default adaptive filter (PLATFORM.md), at larger files. Throws tumble::Error (Environment).
void write_png(const std::filesystem::path& path, const Image& image);

/// Reads an 8-bit (or 16-bit, reduced) gray/RGB/RGBA PNG as RGB or RGBA. Throws tumble::Error
/// (BadInput) naming the file when it is missing or cannot be decoded.
Image read_png(const std::filesystem::path& path);

}  // namespace tumble
