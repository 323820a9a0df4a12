// clip.mp4 as a frame sink: every clip frame into the H.264 encoder.
#include <optional>
#include <vector>

#include "frame_sinks.hpp"
#include "tumble/premultiplied.hpp"

namespace tumble::cli {
namespace {

class Mp4Sink final : public FrameSink {
 public:
  Mp4Sink(const StagedOutput& out, const Mp4Settings& settings, Color background)
      : path_(out.final), background_(background) {
    writer_.emplace(out.staged, settings);
  }

  void accept(const FrameView& f) override {
    if (f.repeat) {  // the same picture: skip compositing and conversion
      writer_->repeat_frame();
      return;
    }
    const std::uint8_t* pixels = f.rgba;
    if (f.premultiplied) {
      // A figure's transparent frames, shown on the sky for the clip (an MP4 has no alpha):
      // premultiplied "over" the scene's background colour is the picture a sky backdrop
      // draws, to within rounding and the silhouettes' smoothing (one render serves both).
      composited_.resize(std::size_t(f.width) * f.height * 4);
      composite_over(f.rgba, composited_.data(), std::size_t(f.width) * f.height, background_.r,
                     background_.g, background_.b);
      pixels = composited_.data();
    }
    writer_->add_frame(pixels, 4, std::ptrdiff_t(f.width) * 4, /*bottom_up=*/true);
  }

  void finish() override {
    writer_->finish();
    encoder_ = writer_->encoder_name();
    writer_.reset();
  }

  void abort() noexcept override { writer_.reset(); }  // removes its temporary file

  void report(RunReport& r, double seconds) const override {
    r.outputs.push_back(path_);
    r.encoder = encoder_;
    r.times.encode_s = r.times.encode_s.value_or(0.0) + seconds;
  }

 private:
  std::filesystem::path path_;
  Color background_;
  std::optional<Mp4Writer> writer_;
  std::string encoder_;
  std::vector<std::uint8_t> composited_;
};

}  // namespace

SinkPtr make_mp4_sink(const StagedOutput& out, const Mp4Settings& settings, Color background) {
  return std::make_unique<Mp4Sink>(out, settings, background);
}

}  // namespace tumble::cli
