#pragma once
// Where rendered frames go. The frame pipeline hands each sink the pixels it asked for, in
// order; a sink turns them into one kind of output (clip.mp4, frames/, a still, strobe.png,
// clip.gif, clip.webp). Every sink writes into the run's staging folder (OutputFolder,
// tumble/output_folder.hpp) under its output's final name there, and reports the final name;
// the run commits every output together, run.json last, so a failed or interrupted run leaves
// no half-written file and the previous good one stays. A new kind of output is a new sink (one
// file), not a new branch in the pipeline.

#include <cstdint>
#include <filesystem>
#include <memory>

#include "tumble/run_report.hpp"

namespace tumble::cli {

/// One rendered image, as the renderer reads it back.
struct FrameView {
  long index = 0;                      ///< clip frame k (k / fps); a picture's: 0
  double t_s = 0.0;                    ///< its time (a strobe's: the last pose's)
  const std::uint8_t* rgba = nullptr;  ///< width·height RGBA pixels, rows bottom-up
  int width = 0, height = 0;
  bool premultiplied = false;  ///< transparent backdrop: premultiplied alpha; else alpha 255
  /// Clip frames: the same pixels as the previous frame (nothing moved, so it was not drawn
  /// again); a sink may reuse what it made of them. `rgba` is valid either way.
  bool repeat = false;
};

class FrameSink {
 public:
  /// An unfinished sink aborts: its temporary output is removed.
  virtual ~FrameSink() = default;
  /// Takes the next frame (clip sinks: every frame of the clip, in order, on the encoder
  /// thread; picture sinks: their one image). Throws tumble::Error when writing fails.
  virtual void accept(const FrameView& frame) = 0;
  /// Completes the output in the staging folder. Throws tumble::Error when it cannot.
  virtual void finish() = 0;
  /// Drops whatever was written so far (the staging folder goes too); the previous good output
  /// under the final name stays.
  virtual void abort() noexcept = 0;
  /// Adds the sink's outputs, its stage time (`seconds` spent in accept and finish) and any
  /// facts of its own to run.json.
  virtual void report(RunReport& report, double seconds) const = 0;
};

using SinkPtr = std::unique_ptr<FrameSink>;

}  // namespace tumble::cli
