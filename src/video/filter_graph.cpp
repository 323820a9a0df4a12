#include "filter_graph.hpp"

extern "C" {
#include <libavfilter/buffersink.h>
#include <libavfilter/buffersrc.h>
#include <libavutil/pixdesc.h>
}

#include "tumble/error.hpp"

namespace tumble {
namespace {

[[noreturn]] void fail(const std::string& what, int code) {
  throw Error(ErrorKind::Environment, "libavfilter: " + what + ": " + av_error_text(code));
}

}  // namespace

FilterGraph::FilterGraph(const std::string& description, const std::vector<Input>& inputs)
    : graph_(avfilter_graph_alloc()) {
  if (!graph_) fail("graph", AVERROR(ENOMEM));
  graph_->nb_threads = 1;
  // Format conversions the graph inserts by itself (RGBA to the palette filters' BGRA) are
  // byte shuffles; bit-exact flags keep them the same on every CPU anyway.
  graph_->scale_sws_opts = av_strdup("flags=bicubic+accurate_rnd+bitexact");

  // Open ends, from the parser's point of view: our sources feed its inputs [inN] ("outputs"
  // of the part of the graph we built), its [out] feeds our sink.
  FilterInOutPtr outputs;  // the chain of open ends, owned from its first link
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const Input& in = inputs[i];
    const std::string args = "video_size=" + std::to_string(in.width) + "x" +
                             std::to_string(in.height) +
                             ":pix_fmt=" + std::to_string(static_cast<int>(in.format)) +
                             ":time_base=" + std::to_string(in.time_base.num) + "/" +
                             std::to_string(in.time_base.den) + ":pixel_aspect=1/1";
    const std::string name = "in" + std::to_string(i);
    AVFilterContext* source = nullptr;
    int result = avfilter_graph_create_filter(&source, avfilter_get_by_name("buffer"), name.c_str(),
                                              args.c_str(), nullptr, graph_.get());
    if (result < 0) fail("buffer source", result);
    sources_.push_back(source);
    FilterInOutPtr open(avfilter_inout_alloc());
    if (!open) fail("graph", AVERROR(ENOMEM));
    open->name = av_strdup(name.c_str());
    open->filter_ctx = source;
    open->pad_idx = 0;
    open->next = outputs.release();
    outputs = std::move(open);
  }
  int result = avfilter_graph_create_filter(&sink_, avfilter_get_by_name("buffersink"), "out",
                                            nullptr, nullptr, graph_.get());
  if (result < 0) fail("buffer sink", result);
  FilterInOutPtr sink_end(avfilter_inout_alloc());
  if (!sink_end) fail("graph", AVERROR(ENOMEM));
  sink_end->name = av_strdup("out");
  sink_end->filter_ctx = sink_;
  sink_end->pad_idx = 0;
  sink_end->next = nullptr;

  AVFilterInOut* in_ends = sink_end.release();
  AVFilterInOut* out_ends = outputs.release();
  result =
      avfilter_graph_parse_ptr(graph_.get(), description.c_str(), &in_ends, &out_ends, nullptr);
  // Whatever the parser did not connect is handed back to be freed.
  FilterInOutPtr left_in(in_ends), left_out(out_ends);
  if (result < 0) fail("\"" + description + "\"", result);
  result = avfilter_graph_config(graph_.get(), nullptr);
  if (result < 0) fail("configuring \"" + description + "\"", result);
}

void FilterGraph::push(std::size_t input, const AVFrame* frame) {
  // KEEP_REF: the source takes a new reference, the caller's frame is left as it was.
  const int result = av_buffersrc_add_frame_flags(sources_.at(input), const_cast<AVFrame*>(frame),
                                                  AV_BUFFERSRC_FLAG_KEEP_REF);
  if (result < 0) fail("feeding a frame", result);
}

void FilterGraph::close(std::size_t input) {
  const int result = av_buffersrc_add_frame_flags(sources_.at(input), nullptr, 0);
  if (result < 0) fail("ending the input", result);
}

bool FilterGraph::pull(AVFrame* out) {
  av_frame_unref(out);
  const int result = av_buffersink_get_frame(sink_, out);
  if (result == AVERROR(EAGAIN) || result == AVERROR_EOF) return false;
  if (result < 0) fail("filtering", result);
  return true;
}

}  // namespace tumble
