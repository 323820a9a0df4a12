#pragma once
// What the GIF and WebP sinks share: a writer opened at the start, fed every frame with straight
// alpha, finished (or dropped, leaving no file) at the end. Each sink adds only what its format
// reports.

#include <filesystem>
#include <optional>

#include "frame_sink.hpp"
#include "tumble/output_folder.hpp"
#include "tumble/premultiplied.hpp"

namespace tumble::cli {

template <class Writer>
class AnimationSink : public FrameSink {
 public:
  void accept(const FrameView& f) final {
    const std::uint8_t* pixels = straight_.of(f.rgba, std::size_t(f.width) * f.height,
                                              f.premultiplied && converts_next(*writer_));
    writer_->add_frame(pixels, std::ptrdiff_t(f.width) * 4, /*bottom_up=*/true);
  }
  void finish() final {
    writer_->finish();
    finished(*writer_);
    writer_.reset();
    written_ = true;
  }
  void abort() noexcept final { writer_.reset(); }

 protected:
  template <class Settings>
  AnimationSink(const StagedOutput& out, const Settings& settings) : path_(out.final) {
    writer_.emplace(out.staged, settings);
  }
  /// Whether the next frame is worth converting to straight alpha (a GIF skips some frames).
  virtual bool converts_next(const Writer&) const { return true; }
  /// The finished writer, for the facts report() gives.
  virtual void finished(const Writer&) {}

  std::filesystem::path path_;  // the final name, for run.json
  std::optional<Writer> writer_;
  bool written_ = false;

 private:
  StraightAlpha straight_;
};

}  // namespace tumble::cli
