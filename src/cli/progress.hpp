#pragma once
// Progress on stderr while a long command runs, unless --quiet. On a terminal: one line redrawn
// in place ("render: 120/300 frames, 96.3/s, ETA 1.9 s"), at most 5 times a second. Off a
// terminal (a CI log, a file): a complete plain line at most every 10 s ("render: 120/300
// frames, elapsed 10.0 s, ETA 15.0 s"), so a log shows a long run is alive without filling up.
// Also the wall-clock helpers the commands use for run.json's stage times. Progress may read a
// clock; the physics never does.

#include <chrono>
#include <functional>
#include <string>

namespace tumble::cli {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

class Progress {
 public:
  enum class Style {
    Off,       ///< nothing (--quiet)
    Terminal,  ///< one line redrawn with \r, ended by a newline when done
    Log,       ///< a whole line at most every kLogInterval, none at the start or the end
  };
  /// Seconds between two lines of the Log style.
  static constexpr double kLogInterval_s = 10.0;
  /// Seconds between two redraws of the Terminal style.
  static constexpr double kRedrawInterval_s = 0.2;

  /// `label` names the command, `unit` what is counted ("frames", "samples"). Terminal when
  /// stderr is a terminal, else Log; Off unless `enabled`. Written to stderr, timed by the
  /// steady clock.
  Progress(bool enabled, long total, std::string label, std::string unit);
  /// The same with the style, the clock (seconds, monotonic) and the writer given: for tests.
  Progress(Style style, long total, std::string label, std::string unit,
           std::function<double()> now_s, std::function<void(const std::string&)> write);

  void update(long done);
  Style style() const { return style_; }

 private:
  Style style_;
  long total_;
  std::string label_, unit_;
  std::function<double()> now_s_;
  std::function<void(const std::string&)> write_;
  double start_s_ = 0.0;
  double last_s_ = -1.0;  // when the last line was written (Log: the start)
};

/// "12.0 s", "3 min 05 s", "2 h 07 min": a duration as a log line shows it.
std::string format_duration(double seconds);

/// "frame_00012": how frames are named by `render --png` and in `diff` of videos.
std::string frame_stem(long k);

}  // namespace tumble::cli
