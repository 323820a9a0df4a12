#pragma once
/// Comparing two images within tolerances, as `tumble diff` does: how many pixels differ, by how
/// much, the PSNR, and a diff picture a person reads at a glance.
///
/// Colour only: the R, G and B channels are compared and alpha is ignored, whether one image or
/// both carry it. tumble's pictures are opaque (its PNGs are RGB); alpha from elsewhere says
/// how to composite, not what was drawn, so an RGBA golden compares equal to its RGB render.

#include <optional>

#include "tumble/image.hpp"

namespace tumble {

/// When two images count as equal. The defaults are exact.
struct DiffTolerance {
  int max_delta = 0;  ///< largest per-channel difference (0–255) that still counts as equal
  double max_fraction = 0.0;  ///< share of pixels (0–1) allowed to differ by more than max_delta
  std::optional<double> min_psnr_db;  ///< when set, the PSNR must be at least this
};

/// What compare_images measured.
struct DiffResult {
  long differing_pixels = 0;  ///< pixels with some channel off by more than max_delta
  long total_pixels = 0;      ///< pixels of the canvas: the larger width × the larger height
  double fraction = 0.0;      ///< differing_pixels / total_pixels (0 for an empty canvas)
  int largest_delta = 0;      ///< largest per-channel difference over the compared pixels
  double psnr_db = 0.0;       ///< over R, G, B with peak 255; +infinity when identical
  bool size_mismatch = false;

  /// Within `tolerance`: same size, fraction ≤ max_fraction and, when set, PSNR ≥ min_psnr_db.
  /// The result must come from compare_images with `tolerance.max_delta`.
  bool within(const DiffTolerance& tolerance) const;
};

/// Compares pixel (x, y) of one image with pixel (x, y) of the other, RGB only. A pixel differs
/// when any channel differs by more than `max_delta` (0–255). Images of different sizes:
/// `size_mismatch`; their overlap (top-left aligned) is compared and gives largest_delta and the
/// PSNR, and every canvas pixel outside the overlap counts as differing.
DiffResult compare_images(const Image& expected, const Image& actual, int max_delta);

/// An RGB picture of the differences, the size of the canvas (the larger width × the larger
/// height). Pixels within `max_delta` are the expected image's luma faded halfway to white, so
/// the scene stays recognisable but recedes (grey 128–255); differing pixels are magenta (green
/// 0) whose level grows with the pixel's largest delta on a square-root scale, from (136, 0, 136)
/// for a delta of 1 to (255, 0, 255) for 255, so small and large changes are told apart. Canvas
/// pixels outside either image (different sizes) are yellow and dark-grey diagonal stripes.
Image diff_image(const Image& expected, const Image& actual, int max_delta);

}  // namespace tumble
