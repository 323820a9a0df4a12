// One PNG picture (a still, strobe.png) as a sink: the image is kept until the run ends and
// written then (into the staging folder; committed with the run's other outputs).
#include <optional>

#include "frame_sinks.hpp"
#include "tumble/premultiplied.hpp"

namespace tumble::cli {
namespace {

class PngImageSink final : public FrameSink {
 public:
  PngImageSink(const StagedOutput& out, PngOptions::Packing packing)
      : out_(out), packing_(packing) {}

  void accept(const FrameView& f) override {
    image_ = f.premultiplied ? straight_image_from_gl_rgba(f.rgba, f.width, f.height)
                             : image_from_gl_rgba(f.rgba, f.width, f.height);
    alpha_ = f.premultiplied;
  }

  void finish() override {
    if (!image_) return;
    write_png(out_.staged, *image_, {alpha_, packing_});
    image_.reset();
    written_ = true;
  }

  void abort() noexcept override { image_.reset(); }

  void report(RunReport& r, double seconds) const override {
    if (written_) r.outputs.push_back(out_.final);
    r.times.png_s = r.times.png_s.value_or(0.0) + seconds;
  }

 private:
  StagedOutput out_;
  PngOptions::Packing packing_;
  std::optional<Image> image_;
  bool alpha_ = false;
  bool written_ = false;
};

}  // namespace

SinkPtr make_png_image_sink(const StagedOutput& out, PngOptions::Packing packing) {
  return std::make_unique<PngImageSink>(out, packing);
}

}  // namespace tumble::cli
