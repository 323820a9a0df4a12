#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace tumble::cli {

Progress::Progress(bool enabled, long total, std::string label, std::string unit)
    : enabled_(enabled && isatty(STDERR_FILENO)),
      total_(total),
      label_(std::move(label)),
      unit_(std::move(unit)) {}

void Progress::update(long done) {
  if (!enabled_) return;
  const double elapsed = seconds_since(start_);
  if (done != total_ && elapsed - last_ < 0.2) return;
  last_ = elapsed;
  const double rate = elapsed > 0.0 ? double(done) / elapsed : 0.0;
  std::fprintf(stderr, "\r%s: %ld/%ld %s, %.1f/s, ETA %.1f s   ", label_.c_str(), done, total_,
               unit_.c_str(), rate, rate > 0.0 ? double(total_ - done) / rate : 0.0);
  if (done == total_) std::fputc('\n', stderr);
}

std::string frame_stem(long k) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05ld", k);
  return name;
}

}  // namespace tumble::cli
