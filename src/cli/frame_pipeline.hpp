#pragma once
// The frame pipeline of `tumble render`: samples the world at every time something is drawn
// (clip frames at k/fps, the exposures of each picture), draws, reads back and hands the pixels
// to the sinks (frame_sink.hpp).
//
// This thread samples, draws and reads back; clip sinks (MP4, PNG frames, GIF, WebP) run on one
// encoder thread behind a bounded queue of recycled frame buffers, so memory is a few frames
// whatever the clip's length. On a GPU the encoders are the slow stage and the overlap pays; on
// llvmpipe rendering already uses every core and the queue costs nothing. Pictures (stills, the
// strobe) are drawn here when their last exposure is reached; the sampler only goes forward, so
// frames and exposures are merged in time order on the fly (an exposure at a frame's time first).
// A clip frame whose bodies are all in the same pose (bit for bit) as in the last drawn frame is
// not drawn or read back: the encoder thread hands its sinks the previous pixels again, marked as
// a repeat (the MP4 then skips conversion too). The renderer is a pure function of the poses, so
// the output is the same bytes as drawing every frame (tested with --draw-every-frame, which
// also makes the renderer draw each frame in full rather than only where bodies moved).

#include <vector>

#include "frame_sink.hpp"
#include "framing_pass.hpp"
#include "picture.hpp"
#include "progress.hpp"
#include "tumble/renderer.hpp"
#include "tumble/run_report.hpp"
#include "tumble/sampler.hpp"
#include "tumble/world.hpp"

namespace tumble::cli {

class FramePipeline {
 public:
  /// A run of `def` drawn by `renderer`; `clip_frames` frames at `fps` go to the clip sinks
  /// (0: no clip, pictures only).
  /// `kept`: the worlds the framing pass kept (the pipeline takes them and goes on from its
  /// resume world), or null: everything is simulated here.
  FramePipeline(const WorldDef& def, Renderer& renderer, int fps, long clip_frames,
                KeptRun* kept = nullptr);
  FramePipeline(const FramePipeline&) = delete;
  FramePipeline& operator=(const FramePipeline&) = delete;

  /// A sink for every clip frame, in order (called on the encoder thread).
  void add_clip_sink(SinkPtr sink);
  /// A picture, drawn once all its exposures are sampled.
  void add_picture(Picture picture);
  /// Draws every clip frame, even one whose bodies did not move since the frame before (by
  /// default that frame is the previous image again, not drawn: the same bytes, less work).
  void draw_every_frame(bool on) { draw_every_frame_ = on; }

  /// Draws everything in time order, then finishes every sink (clip sinks first). On any
  /// failure or interruption the encoder thread is stopped, every sink aborted (nothing
  /// half-written is left, previous outputs stay) and the exception goes on.
  void run(Progress& progress);

  /// Stage times (simulate, render, readback) and each sink's outputs and facts: clip sinks in
  /// the order added, then pictures in the order added.
  void report(RunReport& report) const;

  /// The world as the run stepped it (contact statistics) and its sampler (later times).
  World& world() { return world_; }
  Sampler& sampler() { return sampler_; }
  long frames_done() const { return frames_done_; }
  /// Clip frames handed on as the previous image because nothing moved.
  long frames_reused() const { return frames_reused_; }

 private:
  struct PendingPicture {
    Picture picture;
    std::vector<World> poses;  // sampled so far
    double seconds = 0.0;      // its sink's time
  };
  void run_all(Progress& progress);
  // The world at t: the framing pass's where it kept it, else sampled here.
  World sample(double t);
  void draw_picture(PendingPicture& p);
  void abort_all() noexcept;

  Renderer& renderer_;
  int fps_;
  long clip_frames_;
  KeptRun* kept_;
  World world_;
  Sampler sampler_;
  std::vector<SinkPtr> clip_sinks_;
  std::vector<double> clip_seconds_;
  std::vector<PendingPicture> pictures_;
  double simulate_s_ = 0.0, render_s_ = 0.0, readback_s_ = 0.0;
  long frames_done_ = 0;
  long frames_reused_ = 0;
  bool draw_every_frame_ = false;
  std::vector<std::uint8_t> picture_pixels_;
};

}  // namespace tumble::cli
