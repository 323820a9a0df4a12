#include "frame_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>
#include <thread>

#include "commands.hpp"
#include "tumble/bounded_queue.hpp"

namespace tumble::cli {

FramePipeline::FramePipeline(const WorldDef& def, Renderer& renderer, int fps, long clip_frames,
                             KeptRun* kept)
    : renderer_(renderer),
      fps_(fps),
      clip_frames_(clip_frames),
      kept_(kept),
      world_(kept && kept->resume ? std::move(*kept->resume) : World(def)),
      sampler_(world_) {}

World FramePipeline::sample(double t) {
  if (kept_)
    if (std::optional<World> w = kept_->take(t)) return std::move(*w);
  return sampler_.at(t);
}

void FramePipeline::add_clip_sink(SinkPtr sink) {
  clip_sinks_.push_back(std::move(sink));
  clip_seconds_.push_back(0.0);
}

void FramePipeline::add_picture(Picture picture) {
  pictures_.push_back(PendingPicture{std::move(picture), {}, 0.0});
}

void FramePipeline::run(Progress& progress) {
  try {
    run_all(progress);
  } catch (...) {
    abort_all();
    throw;
  }
}

void FramePipeline::abort_all() noexcept {
  for (SinkPtr& s : clip_sinks_) s->abort();
  for (PendingPicture& p : pictures_) p.picture.sink->abort();
}

void FramePipeline::draw_picture(PendingPicture& p) {
  std::vector<Exposure> exposures;
  for (std::size_t i = 0; i < p.poses.size(); ++i)
    exposures.push_back({&p.poses[i], p.picture.opacities[i]});
  auto t0 = Clock::now();
  renderer_.draw(exposures);
  render_s_ += seconds_since(t0);
  t0 = Clock::now();
  renderer_.read_rgba(picture_pixels_);
  readback_s_ += seconds_since(t0);
  t0 = Clock::now();
  p.picture.sink->accept(FrameView{0, p.picture.times_s.back(), picture_pixels_.data(),
                                   renderer_.width(), renderer_.height(),
                                   renderer_.backdrop() == Backdrop::Transparent});
  p.seconds += seconds_since(t0);
  p.poses.clear();  // a strobe's worlds are not needed any more
  p.poses.shrink_to_fit();
}

void FramePipeline::run_all(Progress& progress) {
  const int width = renderer_.width(), height = renderer_.height();
  const bool premultiplied = renderer_.backdrop() == Backdrop::Transparent;

  // The encoder thread: every clip sink in turn, fed through a bounded queue of frame buffers
  // that are recycled.
  struct Job {
    long frame;
    std::vector<std::uint8_t> rgba;  // empty for a repeat
    bool repeat = false;             // the same picture as the frame before
  };
  BoundedQueue<Job> queue(3);
  BoundedQueue<std::vector<std::uint8_t>> spare(4);
  std::exception_ptr worker_error;
  std::thread worker([&] {
    try {
      std::vector<std::uint8_t> shown;  // the last drawn frame's pixels, kept for its repeats
      while (auto job = queue.pop()) {
        if (!job->repeat) {
          if (!shown.empty()) spare.push(std::move(shown));
          shown = std::move(job->rgba);
        }
        const FrameView view{
            job->frame, double(job->frame) / fps_, shown.data(), width, height, premultiplied,
            job->repeat};
        for (std::size_t i = 0; i < clip_sinks_.size(); ++i) {
          const auto t0 = Clock::now();
          clip_sinks_[i]->accept(view);
          clip_seconds_[i] += seconds_since(t0);
        }
      }
    } catch (...) {
      worker_error = std::current_exception();
      queue.close();  // the producer's next push fails and it stops
      spare.close();  // and it never waits for a buffer that will not come back
    }
  });
  // Whatever happens below, the worker is stopped and joined before anything unwinds past it.
  struct Join {
    BoundedQueue<Job>& q;
    std::thread& t;
    ~Join() {
      q.close();
      if (t.joinable()) t.join();
    }
  } join{queue, worker};

  // Every exposure of every picture, in time order (pictures keep the order they were added in
  // at equal times); nothing here grows with the clip's length.
  struct Due {
    double t;
    std::size_t picture, exposure;
  };
  std::vector<Due> due;
  for (std::size_t p = 0; p < pictures_.size(); ++p)
    for (std::size_t e = 0; e < pictures_[p].picture.times_s.size(); ++e)
      due.push_back({pictures_[p].picture.times_s[e], p, e});
  std::stable_sort(due.begin(), due.end(), [](const Due& a, const Due& b) { return a.t < b.t; });

  long next_frame = 0;
  std::size_t next_due = 0;
  int buffers_made = 0;
  std::optional<World> last_drawn;  // the poses of the last clip frame drawn
  // Frame k is read back while frame k+1 is drawn (asynchronous on GPUs): it is collected, in
  // order, after the next frame's readback has begun, or at the end.
  std::optional<long> pending;
  auto collect_pending = [&]() -> bool {
    const auto t0 = Clock::now();
    // A recycled buffer: after the first few, no allocation. Four are enough: three in the
    // queue and the one the encoder thread keeps for repeats.
    std::vector<std::uint8_t> buffer;
    if (buffers_made >= 4)
      buffer = spare.pop().value_or(std::vector<std::uint8_t>{});
    else
      ++buffers_made;
    renderer_.finish_readback(buffer);
    readback_s_ += seconds_since(t0);
    const bool pushed = queue.push(Job{*pending, std::move(buffer)});  // false: the worker failed
    pending.reset();
    progress.update(++frames_done_);
    return pushed;
  };
  for (;;) {
    const bool frame_left = next_frame < clip_frames_, due_left = next_due < due.size();
    if (!frame_left && !due_left) break;
    const double frame_t = frame_left ? double(next_frame) / fps_ : INFINITY;
    throw_if_interrupted();
    if (due_left && due[next_due].t <= frame_t) {
      const Due& d = due[next_due++];
      const auto t0 = Clock::now();
      PendingPicture& p = pictures_[d.picture];
      p.poses.push_back(sample(d.t));
      simulate_s_ += seconds_since(t0);
      if (p.poses.size() == p.picture.times_s.size()) draw_picture(p);
      continue;
    }
    auto t0 = Clock::now();
    World snapshot = sample(frame_t);
    simulate_s_ += seconds_since(t0);
    if (!draw_every_frame_ && last_drawn && same_poses(*last_drawn, snapshot)) {
      // Nothing moved since the last drawn frame, and the camera sees only the bodies' poses
      // (follow included): drawing again would give the same pixels (the renderer is a pure
      // function of the poses), so the encoder gets the previous ones again.
      if (pending && !collect_pending()) break;
      if (!queue.push(Job{next_frame++, {}, true})) break;
      progress.update(++frames_done_);
      ++frames_reused_;
      continue;
    }
    t0 = Clock::now();
    renderer_.draw(snapshot);
    render_s_ += seconds_since(t0);
    last_drawn = std::move(snapshot);
    t0 = Clock::now();
    renderer_.begin_readback();
    readback_s_ += seconds_since(t0);
    if (pending && !collect_pending()) break;
    pending = next_frame++;
  }
  if (pending) collect_pending();
  queue.close();
  worker.join();
  if (worker_error) std::rethrow_exception(worker_error);

  for (std::size_t i = 0; i < clip_sinks_.size(); ++i) {
    const auto t0 = Clock::now();
    clip_sinks_[i]->finish();
    clip_seconds_[i] += seconds_since(t0);
  }
  for (PendingPicture& p : pictures_) {
    const auto t0 = Clock::now();
    p.picture.sink->finish();
    p.seconds += seconds_since(t0);
  }
}

void FramePipeline::report(RunReport& report) const {
  report.times.simulate_s = simulate_s_;
  report.times.render_s = render_s_;
  report.times.readback_s = readback_s_;
  if (clip_frames_ > 0) report.frames_reused = frames_reused_;
  for (std::size_t i = 0; i < clip_sinks_.size(); ++i)
    clip_sinks_[i]->report(report, clip_seconds_[i]);
  for (const PendingPicture& p : pictures_) p.picture.sink->report(report, p.seconds);
}

}  // namespace tumble::cli
