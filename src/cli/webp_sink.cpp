// clip.webp as a frame sink (WebpWriter): the clip's frames (every frame_step-th above 90 fps),
// straight alpha when the backdrop is transparent.
#include <vector>

#include "animation_sink.hpp"
#include "frame_sinks.hpp"
#include "tumble/webp_writer.hpp"

namespace tumble::cli {
namespace {

class WebpSink final : public AnimationSink<WebpWriter> {
 public:
  WebpSink(const StagedOutput& out, const WebpSettings& settings)
      : AnimationSink(out, settings), timing_(writer_->timing()) {}

  void report(RunReport& r, double seconds) const override {
    if (!written_) return;
    r.outputs.push_back(path_);
    r.times.webp_s = r.times.webp_s.value_or(0.0) + seconds;
    FigureFacts::Animation a;
    a.frames = frames_;
    a.frame_step = timing_.frame_step;
    a.rate_hz = timing_.rate_hz();
    a.delays = durations_ms_;
    a.exact = timing_.exact();
    a.duration_s = double(timing_.end_ms()) / 1000.0;  // as the writer ends the last frame
    if (!r.figures) r.figures.emplace();
    r.figures->webp = a;
  }

 private:
  // Only the frames the WebP keeps are worth converting.
  bool converts_next(const WebpWriter& w) const override { return w.keeps_next_frame(); }
  void finished(const WebpWriter& w) override {
    frames_ = w.frames();
    durations_ms_ = w.durations_ms();
  }

  WebpTiming timing_;
  long frames_ = 0;
  std::vector<int> durations_ms_;
};

}  // namespace

SinkPtr make_webp_sink(const StagedOutput& out, int width, int height, int fps, long clip_frames,
                       bool alpha) {
  return std::make_unique<WebpSink>(out, WebpSettings{width, height, fps, clip_frames, alpha});
}

}  // namespace tumble::cli
