// clip.gif as a frame sink (GifWriter): the clip's frames, every frame_step-th kept, straight
// alpha when the backdrop is transparent.
#include <vector>

#include "animation_sink.hpp"
#include "frame_sinks.hpp"
#include "tumble/gif_writer.hpp"

namespace tumble::cli {
namespace {

class GifSink final : public AnimationSink<GifWriter> {
 public:
  GifSink(const StagedOutput& out, const GifSettings& settings)
      : AnimationSink(out, settings),
        timing_(writer_->timing()),
        delays_cs_(writer_->delays_cs()) {}

  void report(RunReport& r, double seconds) const override {
    if (!written_) return;
    r.outputs.push_back(path_);
    r.times.gif_s = r.times.gif_s.value_or(0.0) + seconds;
    FigureFacts::Animation a;
    a.frames = timing_.frames();
    a.frame_step = timing_.frame_step;
    a.rate_hz = timing_.rate_hz();
    a.delays = delays_cs_;
    a.exact = timing_.exact();
    long end_cs = 0;
    for (long j = 0; j < timing_.frames(); ++j) end_cs += timing_.delay_cs(j);
    a.duration_s = double(end_cs) / 100.0;
    if (!r.figures) r.figures.emplace();
    r.figures->gif = a;
  }

 private:
  // Only the frames the GIF keeps are worth converting.
  bool converts_next(const GifWriter& w) const override { return w.keeps_next_frame(); }

  GifTiming timing_;
  std::vector<int> delays_cs_;
};

}  // namespace

SinkPtr make_gif_sink(const StagedOutput& out, int width, int height, int fps, long clip_frames,
                      bool alpha) {
  return std::make_unique<GifSink>(out, GifSettings{width, height, fps, clip_frames, alpha});
}

}  // namespace tumble::cli
