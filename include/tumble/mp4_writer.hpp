#pragma once
/// clip.mp4 through libavcodec/libavformat/libswscale: H.264, yuv420p, BT.709 limited range,
/// +faststart, timestamps from the frame index (frame k at k/fps; duration exactly N/fps).
/// Bytes are identical run to run: the encoder's thread count is fixed, never the machine's.
/// Written under a temporary name and renamed into place by finish().

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tumble/image.hpp"

namespace tumble {

struct Mp4Settings {
  int width = 1280;  ///< even (yuv420p); odd sizes are a BadInput error
  int height = 720;  ///< even
  int fps = 60;
  int crf = 23;                  ///< libx264 constant rate factor, 0–51
  std::string encoder = "auto";  ///< "auto": a hardware H.264 encoder that opens, else libx264
};

class Mp4Writer {
 public:
  /// Opens the encoder and the temporary output. Throws tumble::Error: BadInput for settings
  /// (odd size, unknown encoder name), Environment when no encoder opens or the file cannot be
  /// written.
  Mp4Writer(const std::filesystem::path& path, const Mp4Settings& settings);
  ~Mp4Writer();  ///< without finish(): the temporary file is removed
  Mp4Writer(const Mp4Writer&) = delete;
  Mp4Writer& operator=(const Mp4Writer&) = delete;

  /// Encodes one frame: 8-bit RGBA (or RGB), `stride` bytes per row; `bottom_up` rows as
  /// glReadPixels returns them (flipped for free with a negative stride into swscale).
  void add_frame(const std::uint8_t* pixels, int channels, std::ptrdiff_t stride, bool bottom_up);
  void add_frame(const Image& image) {
    add_frame(image.pixels.data(), image.channels, static_cast<std::ptrdiff_t>(image.stride()),
              false);
  }
  /// Encodes the last added frame's picture once more, as the next frame (a clip whose image
  /// did not change): no conversion, the same bytes as adding the same pixels again.
  void repeat_frame();
  /// Flushes the encoder, writes the trailer (moov moved to the front) and renames into place.
  void finish();

  /// The libavcodec encoder in use, e.g. "libx264" or "h264_nvenc".
  const std::string& encoder_name() const;
  long frames() const;

  /// H.264 encoders this FFmpeg build offers (names), whether or not hardware for them exists.
  static std::vector<std::string> available_h264_encoders();
  /// Of those, the ones that open here (each is opened once at a small size and closed), and the
  /// one "auto" would use: what `tumble info` reports as usable.
  static std::vector<std::string> usable_h264_encoders();
  static std::string auto_h264_encoder();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tumble
