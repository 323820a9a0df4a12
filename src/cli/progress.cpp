#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tumble::cli {
namespace {

Progress::Style style_for(bool enabled) {
  if (!enabled) return Progress::Style::Off;
  return isatty(STDERR_FILENO) ? Progress::Style::Terminal : Progress::Style::Log;
}

double steady_seconds() {
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

void write_stderr(const std::string& text) {
  std::fputs(text.c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace

Progress::Progress(bool enabled, long total, std::string label, std::string unit)
    : Progress(style_for(enabled), total, std::move(label), std::move(unit), steady_seconds,
               write_stderr) {}

Progress::Progress(Style style, long total, std::string label, std::string unit,
                   std::function<double()> now_s, std::function<void(const std::string&)> write)
    : style_(style),
      total_(total),
      label_(std::move(label)),
      unit_(std::move(unit)),
      now_s_(std::move(now_s)),
      write_(std::move(write)) {
  if (style_ == Style::Off) return;
  start_s_ = now_s_();
  if (style_ == Style::Log) last_s_ = start_s_;
}

void Progress::update(long done) {
  if (style_ == Style::Off) return;
  const double now = now_s_();
  const double elapsed = now - start_s_;
  const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
  const double eta = rate > 0.0 ? static_cast<double>(total_ - done) / rate : 0.0;
  char line[256];
  if (style_ == Style::Terminal) {
    if (done != total_ && now - last_s_ < kRedrawInterval_s) return;
    last_s_ = now;
    std::snprintf(line, sizeof line, "\r%s: %ld/%ld %s, %.1f/s, ETA %.1f s   ", label_.c_str(),
                  done, total_, unit_.c_str(), rate, eta);
    write_(done == total_ ? std::string(line) + "\n" : std::string(line));
    return;
  }
  // Log: a line only once kLogInterval_s has passed since the last (or the start), never for
  // the end (the command's own "wrote ..." line says that): a run shorter than the interval
  // leaves no progress in the log at all.
  if (done >= total_ || now - last_s_ < kLogInterval_s) return;
  last_s_ = now;
  const std::string eta_text = rate > 0.0 ? format_duration(eta) : std::string("unknown");
  std::snprintf(line, sizeof line, "%s: %ld/%ld %s, elapsed %s, ETA %s\n", label_.c_str(), done,
                total_, unit_.c_str(), format_duration(elapsed).c_str(), eta_text.c_str());
  write_(line);
}

std::string format_duration(double seconds) {
  char text[64];
  if (!(seconds < 60.0)) {
    const long whole = std::lround(std::min(seconds, 1e9));  // NaN never reaches here: rate > 0
    if (whole < 3600)
      std::snprintf(text, sizeof text, "%ld min %02ld s", whole / 60, whole % 60);
    else
      std::snprintf(text, sizeof text, "%ld h %02ld min", whole / 3600, whole % 3600 / 60);
  } else {
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  }
  return text;
}

std::string frame_stem(long k) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05ld", k);
  return name;
}

}  // namespace tumble::cli
