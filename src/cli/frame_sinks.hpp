#pragma once
// The outputs of `tumble render`, one sink each (frame_sink.hpp), each in its own file:
// mp4_sink.cpp, png_frames_sink.cpp, png_image_sink.cpp, gif_sink.cpp, webp_sink.cpp.

#include <filesystem>

#include "frame_sink.hpp"
#include "tumble/mp4_writer.hpp"
#include "tumble/png.hpp"
#include "tumble/scene.hpp"

namespace tumble::cli {

/// clip.mp4 (Mp4Writer). With a transparent backdrop, frames are composited over `background`
/// first: an MP4 has no alpha.
SinkPtr make_mp4_sink(const std::filesystem::path& path, const Mp4Settings& settings,
                      Color background);
/// frames/frame_NNNNN.png, one per frame as it comes (each written atomically); RGBA with
/// straight alpha when the backdrop is transparent.
SinkPtr make_png_frames_sink(const std::filesystem::path& folder);
/// One PNG (a still, strobe.png): kept in memory and written at finish(), so a run that fails
/// leaves the previous one. RGBA with straight alpha when the backdrop is transparent.
SinkPtr make_png_image_sink(const std::filesystem::path& path,
                            PngOptions::Packing packing = PngOptions::Packing::Fast);
/// clip.gif (GifWriter) for a clip of `clip_frames` frames at `fps`; `alpha`: 1-bit
/// transparency.
SinkPtr make_gif_sink(const std::filesystem::path& path, int width, int height, int fps,
                      long clip_frames, bool alpha);
/// clip.webp (WebpWriter); `alpha`: keep the alpha channel.
SinkPtr make_webp_sink(const std::filesystem::path& path, int width, int height, int fps,
                       bool alpha);

}  // namespace tumble::cli
