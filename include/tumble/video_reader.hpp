#pragma once
/// Decodes a video file (any container and codec this FFmpeg reads: tumble's MP4s, WebM, MOV,
/// ...) frame by frame, in presentation order, to 8-bit RGB images, through
/// libavformat/libavcodec/libswscale. Y'CbCr is converted with the matrix and range the stream is
/// tagged with (tumble's own clips: BT.709 limited range); an untagged stream as the ffmpeg tool
/// converts it (BT.601, limited range unless the pixel format says full: yuvj*). The conversion
/// is bit-exact (the same bytes on every CPU), so comparing two decodes compares the files.

#include <filesystem>
#include <memory>
#include <optional>

#include "tumble/image.hpp"

namespace tumble {

class VideoReader {
 public:
  /// Opens the file and its best video stream's decoder. Throws tumble::Error (BadInput) naming
  /// the file ("cannot decode ...") when it is missing, unreadable or holds no decodable video.
  explicit VideoReader(const std::filesystem::path& path);
  ~VideoReader();
  VideoReader(const VideoReader&) = delete;
  VideoReader& operator=(const VideoReader&) = delete;

  /// Decodes the next frame into `out` (RGB, top-down, the frame's own size); false after the
  /// last. Throws tumble::Error (BadInput) naming the file when the data cannot be decoded.
  bool next(Image& out);

  /// The presentation time, in seconds from the stream's start, of the frame next() returned
  /// last; empty before the first or when the file gives it no timestamp.
  std::optional<double> frame_time_s() const;

  /// The stream's frame size as the container declares it.
  int width() const;
  int height() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tumble
