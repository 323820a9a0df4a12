#pragma once
// A one-line progress display on stderr ("render: 120/300 frames, 96.3/s, ETA 1.9 s"), shown only
// when stderr is a terminal (never in logs or CI) and not --quiet; redrawn at most 5 times a
// second. Also the wall-clock helpers the commands use for run.json's stage times.

#include <chrono>
#include <string>

namespace tumble::cli {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

class Progress {
 public:
  /// `label` names the command, `unit` what is counted ("frames", "samples").
  Progress(bool enabled, long total, std::string label, std::string unit);
  void update(long done);

 private:
  bool enabled_;
  long total_;
  std::string label_, unit_;
  Clock::time_point start_ = Clock::now();
  double last_ = -1.0;
};

/// "frame_00012": how frames are named by `render --png` and in `diff` of videos.
std::string frame_stem(long k);

}  // namespace tumble::cli
