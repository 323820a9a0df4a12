#pragma once
/// clip.gif: an animated GIF that loops forever, with one 256-colour palette chosen for the
/// whole clip (libavfilter's palettegen over every frame, then paletteuse with ordered Bayer
/// dithering: deterministic, and steady from frame to frame where a random dither would crawl).
/// Bytes are identical run to run. Written under a temporary name and renamed into place by
/// finish(); frames are kept in memory, deflated, until then (the palette needs them all).
///
/// Timing: GIF delays are whole centiseconds, and browsers play delays under 2 cs as 10 cs. The
/// GIF shows every frame_step-th frame of the clip, the smallest step whose frame lasts at
/// least 2 cs (at most 50 frames/s), and frame j starts at round(100·j·frame_step / fps) cs: the
/// delays never drift from the clip's clock, and are all equal (exact) when 100·frame_step/fps
/// is whole (25, 50, 20, 10 fps ...); else they alternate (60 fps: 30 frames/s, 3 and 4 cs).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

namespace tumble {

/// Which clip frames a GIF shows and when.
struct GifTiming {
  int fps = 60;          ///< the clip's
  int frame_step = 1;    ///< every frame_step-th clip frame is a GIF frame
  long clip_frames = 0;  ///< frames of the clip (N); the GIF lasts N / fps

  /// The timing for a clip of `clip_frames` frames at `fps`.
  static GifTiming for_clip(int fps, long clip_frames);
  long frames() const;          ///< GIF frames: ceil(N / frame_step)
  long start_cs(long j) const;  ///< when GIF frame j starts, centiseconds
  int delay_cs(long j) const;   ///< how long GIF frame j shows (at least 2 cs)
  double rate_hz() const { return double(fps) / frame_step; }   ///< on average
  bool exact() const { return (100 * frame_step) % fps == 0; }  ///< all delays equal and exact
};

struct GifSettings {
  int width = 480;
  int height = 270;
  int fps = 60;          ///< of the clip
  long clip_frames = 0;  ///< of the clip: fixes the timing and the last frame's delay
  /// Keep transparency: GIF has one transparent palette entry, so a pixel is transparent when
  /// its alpha is below 128 and opaque otherwise (soft edges become hard).
  bool alpha = false;
};

class GifWriter {
 public:
  /// Sets up the palette pass. Throws tumble::Error: BadInput for a size GIF cannot hold
  /// (over 65535), Environment when FFmpeg lacks the gif encoder or the palette filters.
  GifWriter(const std::filesystem::path& path, const GifSettings& settings);
  ~GifWriter();  ///< without finish(): nothing is written under the final name
  GifWriter(const GifWriter&) = delete;
  GifWriter& operator=(const GifWriter&) = delete;

  /// Offers clip frame k = the number of frames offered so far: 8-bit straight-alpha RGBA,
  /// `stride` bytes per row, rows bottom-up (glReadPixels) or top-down. Only every
  /// frame_step-th is kept.
  void add_frame(const std::uint8_t* rgba, std::ptrdiff_t stride, bool bottom_up);
  /// Whether the next frame offered is one the GIF keeps (the others need no pixels: a caller
  /// may skip converting them).
  bool keeps_next_frame() const;
  /// Chooses the palette, encodes every kept frame and renames the file into place. Throws
  /// tumble::Error (Environment) when it cannot be written.
  void finish();

  const GifTiming& timing() const;
  /// Delays used, in centiseconds: the distinct values, ascending (one value when exact).
  std::vector<int> delays_cs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tumble
