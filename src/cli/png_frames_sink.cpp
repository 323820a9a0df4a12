// frames/frame_NNNNN.png as a frame sink: one PNG per clip frame, written as it comes (nothing
// grows with the clip's length) into the run's staged frames/ folder, which replaces the previous
// frames/ as a whole when the run commits: frames/ is always exactly one run's frames.
#include "frame_sinks.hpp"
#include "progress.hpp"
#include "tumble/premultiplied.hpp"

namespace tumble::cli {
namespace {

class PngFramesSink final : public FrameSink {
 public:
  explicit PngFramesSink(const StagedOutput& folder) : folder_(folder) {}

  void accept(const FrameView& f) override {
    const Image image = f.premultiplied ? straight_image_from_gl_rgba(f.rgba, f.width, f.height)
                                        : image_from_gl_rgba(f.rgba, f.width, f.height);
    write_png(folder_.staged / (frame_stem(f.index) + ".png"), image, {f.premultiplied});
    ++written_;
  }

  // Each frame is complete once written; the folder is committed with the run's outputs.
  void finish() override {}
  void abort() noexcept override {}

  void report(RunReport& r, double seconds) const override {
    for (long k = 0; k < written_; ++k)
      r.outputs.push_back(folder_.final / (frame_stem(k) + ".png"));
    r.times.png_s = r.times.png_s.value_or(0.0) + seconds;
  }

 private:
  StagedOutput folder_;
  long written_ = 0;
};

}  // namespace

SinkPtr make_png_frames_sink(const StagedOutput& folder) {
  return std::make_unique<PngFramesSink>(folder);
}

bool is_frame_file_name(const std::string& name) {
  // frame_stem(k) + ".png": "frame_" and at least five digits.
  constexpr std::string_view kPrefix = "frame_", kSuffix = ".png";
  if (!name.starts_with(kPrefix) || !name.ends_with(kSuffix)) return false;
  const std::size_t digits = name.size() - kPrefix.size() - kSuffix.size();
  if (digits < 5) return false;
  for (std::size_t i = kPrefix.size(); i < kPrefix.size() + digits; ++i)
    if (name[i] < '0' || name[i] > '9') return false;
  return true;
}

}  // namespace tumble::cli
