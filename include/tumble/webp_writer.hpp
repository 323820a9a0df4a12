#pragma once
/// clip.webp: an animated WebP that loops forever (what GitHub READMEs show best in an <img>),
/// through FFmpeg's libwebp_anim encoder, lossy at quality 75 with the alpha channel lossless.
/// libwebp stores only what changed between frames and merges a frame identical to the one
/// before into it (one longer frame). Bytes are identical run to run. Written under a temporary
/// name and renamed into place by finish().
///
/// Timing: durations are whole milliseconds, and browsers (Chrome, Firefox, Safari) play a
/// frame of 10 ms or less as 100 ms, so a 120 fps clip would run 12 times slow. Up to 90 fps
/// every frame lasts at least 11 ms and the WebP keeps every clip frame; above, it keeps every
/// frame_step-th, the smallest step whose frame lasts at least 20 ms (at most 50 frames/s, the
/// GIF's rule). Frame j starts at round(1000·j·frame_step / fps) ms and the last ends at
/// round(1000·N / fps), so durations never drift from the clip's clock (exact where
/// 1000·frame_step/fps is whole; 60 fps alternates 17, 17 and 16 ms). A last frame that would be
/// shorter than the others (N not a whole number of steps) is left out and the one before lasts
/// to the end: every frame plays as written and the loop lasts the clip's duration to the ms.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

namespace tumble {

/// Which clip frames a WebP shows and for how long.
struct WebpTiming {
  /// The shortest duration browsers play as written is 11 ms; a clip too fast for that is
  /// thinned to frames of at least this long (the GIF's 2 cs).
  static constexpr int kThinnedMinMs = 20;

  int fps = 60;          ///< the clip's
  int frame_step = 1;    ///< every frame_step-th clip frame is a WebP frame
  long clip_frames = 0;  ///< frames of the clip (N); the WebP lasts round(1000·N / fps) ms

  /// The timing for a clip of `clip_frames` frames at `fps`.
  static WebpTiming for_clip(int fps, long clip_frames);
  long frames() const;            ///< WebP frames (a short last one left out)
  bool keeps(long k) const;       ///< whether clip frame k is a WebP frame
  long start_ms(long j) const;    ///< when WebP frame j starts
  long end_ms() const;            ///< when the last frame ends: round(1000·N / fps)
  int duration_ms(long j) const;  ///< how long WebP frame j shows
  double rate_hz() const { return double(fps) / frame_step; }    ///< on average
  bool exact() const { return (1000 * frame_step) % fps == 0; }  ///< all durations exact
};

struct WebpSettings {
  int width = 480;       ///< at most 16383 (WebP's limit); any parity
  int height = 270;      ///< at most 16383
  int fps = 60;          ///< of the clip
  long clip_frames = 0;  ///< of the clip: fixes the timing and the last frame's duration
  bool alpha = false;    ///< keep straight alpha (else every pixel is written opaque)
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

  /// Offers clip frame k = the number of frames offered so far: 8-bit straight-alpha RGBA,
  /// `stride` bytes per row, rows bottom-up (glReadPixels) or top-down. Only the frames the
  /// timing keeps are encoded.
  void add_frame(const std::uint8_t* rgba, std::ptrdiff_t stride, bool bottom_up);
  /// Whether the next frame offered is one the WebP keeps (the others need no pixels: a caller
  /// may skip converting them).
  bool keeps_next_frame() const;
  /// Assembles the animation, gives the last frame its exact duration and renames the file
  /// into place. Throws tumble::Error (Environment) when it cannot be written.
  void finish();

  const WebpTiming& timing() const;
  long frames() const;  ///< WebP frames encoded
  /// Durations used, in milliseconds: the distinct values, ascending.
  std::vector<int> durations_ms() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tumble
