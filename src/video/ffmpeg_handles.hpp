#pragma once
// Owning handles for the FFmpeg objects the video layer uses: each frees its object the one way
// FFmpeg wants it freed, so every error path (an exception thrown half-way through setting up an
// encoder or a muxer) releases everything that was made before it.

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavfilter/avfilter.h>
#include <libavformat/avformat.h>
#include <libavutil/buffer.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/frame.h>
#include <libswscale/swscale.h>
}

#include <memory>
#include <string>

namespace tumble {

struct CodecContextFree {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FrameFree {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct PacketFree {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
struct SwsFree {
  void operator()(SwsContext* s) const { sws_freeContext(s); }
};
struct BufferUnref {
  void operator()(AVBufferRef* b) const { av_buffer_unref(&b); }
};
/// Closes the output file (if open) before freeing the muxer (output) context.
struct FormatContextFree {
  void operator()(AVFormatContext* f) const {
    if (f->pb && !(f->oformat->flags & AVFMT_NOFILE)) avio_closep(&f->pb);
    avformat_free_context(f);
  }
};

/// A filter graph frees every filter in it.
struct FilterGraphFree {
  void operator()(AVFilterGraph* g) const { avfilter_graph_free(&g); }
};
/// The open ends of a graph description being parsed.
struct FilterInOutFree {
  void operator()(AVFilterInOut* io) const { avfilter_inout_free(&io); }
};

/// An opened input (demuxer) is closed with avformat_close_input.
struct InputFormatClose {
  void operator()(AVFormatContext* f) const { avformat_close_input(&f); }
};

using CodecContextPtr = std::unique_ptr<AVCodecContext, CodecContextFree>;
using FramePtr = std::unique_ptr<AVFrame, FrameFree>;
using PacketPtr = std::unique_ptr<AVPacket, PacketFree>;
using SwsPtr = std::unique_ptr<SwsContext, SwsFree>;
using BufferPtr = std::unique_ptr<AVBufferRef, BufferUnref>;
using FormatContextPtr = std::unique_ptr<AVFormatContext, FormatContextFree>;
using InputFormatPtr = std::unique_ptr<AVFormatContext, InputFormatClose>;
using FilterGraphPtr = std::unique_ptr<AVFilterGraph, FilterGraphFree>;
using FilterInOutPtr = std::unique_ptr<AVFilterInOut, FilterInOutFree>;

/// Routes FFmpeg's log away from stderr (tumble's stderr carries only its own messages). Errors a
/// codec logs while it is being opened (its `opaque` pointing at a std::string) are kept there, as
/// the reason reported when it fails to open. Process-wide; idempotent.
void silence_ffmpeg_log();

/// An AVDictionary of options; avcodec_open2 and avformat_write_header take what they know out of
/// it and leave the rest, which is freed here.
class AvOptions {
 public:
  AvOptions() = default;
  ~AvOptions() { av_dict_free(&dict_); }
  AvOptions(const AvOptions&) = delete;
  AvOptions& operator=(const AvOptions&) = delete;

  void set(const char* key, const std::string& value) {
    av_dict_set(&dict_, key, value.c_str(), 0);
  }
  AVDictionary** get() { return &dict_; }

 private:
  AVDictionary* dict_ = nullptr;
};

/// FFmpeg's text for an AVERROR code, e.g. "No such file or directory".
inline std::string av_error_text(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

}  // namespace tumble
