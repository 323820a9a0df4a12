// clip.webp as a frame sink (WebpWriter): every clip frame, straight alpha when the backdrop is
// transparent.
#include <vector>

#include "animation_sink.hpp"
#include "frame_sinks.hpp"
#include "tumble/webp_writer.hpp"

namespace tumble::cli {
namespace {

class WebpSink final : public AnimationSink<WebpWriter> {
 public:
  WebpSink(const StagedOutput& out, const WebpSettings& settings)
      : AnimationSink(out, settings), fps_(settings.fps) {}

  void report(RunReport& r, double seconds) const override {
    if (!written_) return;
    r.outputs.push_back(path_);
    r.times.webp_s = r.times.webp_s.value_or(0.0) + seconds;
    FigureFacts::Animation a;
    a.frames = frames_;
    a.rate_hz = fps_;
    a.delays = durations_ms_;
    a.exact = 1000 % fps_ == 0;
    // round(1000·N / fps) ms, as the writer ends the last frame.
    a.duration_s = double((2000LL * frames_ + fps_) / (2LL * fps_)) / 1000.0;
    if (!r.figures) r.figures.emplace();
    r.figures->webp = a;
  }

 private:
  void finished(const WebpWriter& w) override {
    frames_ = w.frames();
    durations_ms_ = w.durations_ms();
  }

  int fps_;
  long frames_ = 0;
  std::vector<int> durations_ms_;
};

}  // namespace

SinkPtr make_webp_sink(const StagedOutput& out, int width, int height, int fps, bool alpha) {
  return std::make_unique<WebpSink>(out, WebpSettings{width, height, fps, alpha});
}

}  // namespace tumble::cli
