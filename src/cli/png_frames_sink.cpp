// frames/frame_NNNNN.png as a frame sink: one PNG per clip frame, each written atomically as it
// comes (nothing grows with the clip's length).
#include "frame_sinks.hpp"
#include "progress.hpp"
#include "tumble/premultiplied.hpp"

namespace tumble::cli {
namespace {

class PngFramesSink final : public FrameSink {
 public:
  explicit PngFramesSink(const std::filesystem::path& folder) : folder_(folder) {}

  void accept(const FrameView& f) override {
    const Image image = f.premultiplied ? straight_image_from_gl_rgba(f.rgba, f.width, f.height)
                                        : image_from_gl_rgba(f.rgba, f.width, f.height);
    write_png(folder_ / (frame_stem(f.index) + ".png"), image, {f.premultiplied});
    ++written_;
  }

  // Each frame is complete once written: there is nothing left to rename.
  void finish() override {}
  void abort() noexcept override {}

  void report(RunReport& r, double seconds) const override {
    for (long k = 0; k < written_; ++k) r.outputs.push_back(folder_ / (frame_stem(k) + ".png"));
    r.times.png_s = r.times.png_s.value_or(0.0) + seconds;
  }

 private:
  std::filesystem::path folder_;
  long written_ = 0;
};

}  // namespace

SinkPtr make_png_frames_sink(const std::filesystem::path& folder) {
  return std::make_unique<PngFramesSink>(folder);
}

}  // namespace tumble::cli
