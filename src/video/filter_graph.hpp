#pragma once
// A libavfilter graph fed through buffer sources and drained through one buffer sink, built from
// a description whose open ends are labelled [in0], [in1], ... and [out], e.g.
// "[in0][in1]paletteuse=dither=bayer[out]". It runs on the calling thread only: filters with
// slice threads would otherwise split their work by the machine's core count.

#include <string>
#include <vector>

#include "ffmpeg_handles.hpp"

namespace tumble {

class FilterGraph {
 public:
  /// What one source delivers.
  struct Input {
    AVPixelFormat format = AV_PIX_FMT_NONE;
    int width = 0, height = 0;
    AVRational time_base{1, 1};
  };

  /// Parses and configures the graph. Throws tumble::Error (Environment) when FFmpeg lacks a
  /// filter or refuses the description (a programming mistake, or an FFmpeg without
  /// libavfilter's palette filters).
  FilterGraph(const std::string& description, const std::vector<Input>& inputs);

  /// Hands `frame` to source `input`; the frame stays the caller's (a reference is taken).
  void push(std::size_t input, const AVFrame* frame);
  /// Tells source `input` that no more frames come.
  void close(std::size_t input);
  /// The next frame the graph has ready, into `out` (unreferenced first); false when it needs
  /// more input, or has delivered its last.
  bool pull(AVFrame* out);

 private:
  FilterGraphPtr graph_;
  std::vector<AVFilterContext*> sources_;  // owned by the graph
  AVFilterContext* sink_ = nullptr;
};

}  // namespace tumble
