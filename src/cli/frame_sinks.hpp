#pragma once
// The outputs of `tumble render`, one sink each (frame_sink.hpp), each in its own file:
// mp4_sink.cpp, png_frames_sink.cpp, png_image_sink.cpp, gif_sink.cpp, webp_sink.cpp.

#include <filesystem>

#include "frame_sink.hpp"
#include "tumble/mp4_writer.hpp"
#include "tumble/output_folder.hpp"
#include "tumble/png.hpp"
#include "tumble/scene.hpp"

namespace tumble::cli {

// Each sink writes `out.staged` and reports `out.final` (OutputFolder::file, ::folder).

/// clip.mp4 (Mp4Writer). With a transparent backdrop, frames are composited over `background`
/// first: an MP4 has no alpha.
SinkPtr make_mp4_sink(const StagedOutput& out, const Mp4Settings& settings, Color background);
/// frames/frame_NNNNN.png, one per frame as it comes, into the staged folder that replaces
/// frames/ as a whole when the run commits; RGBA with straight alpha when the backdrop is
/// transparent.
SinkPtr make_png_frames_sink(const StagedOutput& folder);
/// Whether a file name is one of frames/'s (frame_NNNNN.png).
bool is_frame_file_name(const std::string& name);
/// One PNG (a still, strobe.png): kept in memory and written at finish(). RGBA with straight alpha
/// when the backdrop is transparent.
SinkPtr make_png_image_sink(const StagedOutput& out,
                            PngOptions::Packing packing = PngOptions::Packing::Fast);
/// clip.gif (GifWriter) for a clip of `clip_frames` frames at `fps`; `alpha`: 1-bit
/// transparency.
SinkPtr make_gif_sink(const StagedOutput& out, int width, int height, int fps, long clip_frames,
                      bool alpha);
/// clip.webp (WebpWriter) for a clip of `clip_frames` frames at `fps`; `alpha`: keep the alpha
/// channel.
SinkPtr make_webp_sink(const StagedOutput& out, int width, int height, int fps, long clip_frames,
                       bool alpha);

}  // namespace tumble::cli
