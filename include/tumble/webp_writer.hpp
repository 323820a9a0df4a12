#pragma once
/// clip.webp: an animated WebP that loops forever (what GitHub READMEs show best in an <img>),
/// through FFmpeg's libwebp_anim encoder, lossy at quality 75 with the alpha channel lossless.
/// Every frame of the clip, timed in milliseconds: frame k starts at round(1000·k / fps) ms and
/// the last ends at round(1000·N / fps), so durations never drift (exact where 1000/fps is
/// whole; 60 fps alternates 17, 17 and 16 ms). libwebp stores only what changed between frames
/// and merges a frame identical to the one before into it (one longer frame). Bytes are
/// identical run to run. Written under a temporary name and renamed into place by finish().

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

namespace tumble {

struct WebpSettings {
  int width = 480;   ///< at most 16383 (WebP's limit); any parity
  int height = 270;  ///< at most 16383
  int fps = 60;
  bool alpha = false;  ///< keep straight alpha (else every pixel is written opaque)
};

class WebpWriter {
 public:
  /// The largest width or height a WebP holds.
  static constexpr int kMaxSide = 16383;

  /// Opens the encoder. Throws tumble::Error: BadInput for a size WebP cannot hold,
  /// Environment when this FFmpeg has no libwebp_anim encoder.
  WebpWriter(const std::filesystem::path& path, const WebpSettings& settings);
  ~WebpWriter();  ///< without finish(): nothing is written under the final name
  WebpWriter(const WebpWriter&) = delete;
  WebpWriter& operator=(const WebpWriter&) = delete;

  /// Encodes the next frame: 8-bit straight-alpha RGBA, `stride` bytes per row, rows bottom-up
  /// (glReadPixels) or top-down.
  void add_frame(const std::uint8_t* rgba, std::ptrdiff_t stride, bool bottom_up);
  /// Assembles the animation, gives the last frame its exact duration and renames the file
  /// into place. Throws tumble::Error (Environment) when it cannot be written.
  void finish();

  long frames() const;
  /// Durations used, in milliseconds: the distinct values, ascending.
  std::vector<int> durations_ms() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tumble
