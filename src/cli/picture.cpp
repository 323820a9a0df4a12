#include "picture.hpp"

#include <cassert>

namespace tumble::cli {

Picture still_picture(double t_s, SinkPtr sink) {
  return Picture{{t_s}, {1.0}, std::move(sink)};
}

Picture strobe_picture(int poses, double from_s, double to_s, SinkPtr sink) {
  assert(poses >= 2 && from_s < to_s);
  Picture p;
  p.sink = std::move(sink);
  for (int k = 0; k < poses; ++k) {
    const double f = double(k) / (poses - 1);
    // The last time is to_s exactly (f = 1), not a rounded sum.
    p.times_s.push_back(k == poses - 1 ? to_s : from_s + (to_s - from_s) * f);
    p.opacities.push_back(k == poses - 1 ? 1.0
                                         : kStrobeFirstOpacity + (1.0 - kStrobeFirstOpacity) * f);
  }
  return p;
}

}  // namespace tumble::cli
