#pragma once
// Choosing and opening the H.264 encoder behind Mp4Writer: "auto" tries the hardware encoders
// this FFmpeg offers, keeping the first that actually opens, then libx264; a named encoder must
// open. Every encoder is set up the same way: 4:2:0 8-bit, tagged BT.709 limited range, time base
// 1/fps, no B-frames.

#include <string>
#include <vector>

#include "ffmpeg_handles.hpp"
#include "tumble/mp4_writer.hpp"

namespace tumble {

/// libx264's thread count, fixed: x264's output bytes depend on it (frame threads and lookahead
/// threads split the work differently), so it must never follow the machine's core count.
inline constexpr int kX264Threads = 4;

/// An opened encoder and what it wants to be fed.
struct H264Encoder {
  CodecContextPtr context;
  /// The software pixel format frames are converted to: YUV420P, or NV12 for encoders that only
  /// take that (h264_qsv, and the software side of a VAAPI upload).
  AVPixelFormat input_format = AV_PIX_FMT_NONE;
  /// Set when the encoder takes hardware frames (h264_vaapi): the pool frames are uploaded into.
  BufferPtr hardware_frames;
};

/// Opens the encoder `settings.encoder` names ("auto" or an FFmpeg encoder name) for
/// settings.width x height at settings.fps. `global_header`: the container keeps SPS/PPS in its
/// header (MP4). Throws tumble::Error: BadInput for a name that is no usable H.264 encoder,
/// Environment when the named encoder (or, for "auto", every candidate) cannot be opened.
H264Encoder open_h264_encoder(const Mp4Settings& settings, bool global_header);

/// Names of the H.264 encoders in this FFmpeg build that can produce 4:2:0 8-bit video.
std::vector<std::string> h264_encoder_names();

}  // namespace tumble
