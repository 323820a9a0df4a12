#pragma once
// A picture is one image made of exposures of the bodies at given times: a still (one opaque
// exposure at T) or a stroboscopic figure (N poses evenly spaced over a span, earlier poses
// fainter, the last opaque). The frame pipeline samples the world at each exposure's time and
// draws the picture when its last exposure is reached.

#include <vector>

#include "frame_sink.hpp"

namespace tumble::cli {

struct Picture {
  std::vector<double> times_s;    ///< ascending
  std::vector<double> opacities;  ///< one per time, in (0, 1]
  SinkPtr sink;
};

/// A still at `t_s`.
Picture still_picture(double t_s, SinkPtr sink);

/// The strobe's faintest pose: earlier poses ramp linearly from this to 1, so the order reads
/// at a glance and the first pose is still clearly there over the floor.
inline constexpr double kStrobeFirstOpacity = 0.25;

/// `poses` (>= 2) exposures at from_s + (to_s − from_s)·k/(poses − 1), k = 0 … poses − 1: both
/// ends included, so the last pose is the state at to_s. Opacity ramps from
/// kStrobeFirstOpacity to 1.
Picture strobe_picture(int poses, double from_s, double to_s, SinkPtr sink);

}  // namespace tumble::cli
