#pragma once
// Where an axis's limits and ticks go, and what the ticks say: "nice" 1, 2, 5 × 10^k steps on a
// linear axis; decades with minor ticks at 2..9 on a log10 axis, labelled every 1st, 2nd, 3rd…
// decade so labels never crowd. Private to the plot layer; svg_plot.cpp draws what this decides.

#include <optional>
#include <string>
#include <vector>

#include "tumble/svg_plot.hpp"

namespace tumble::plot {

/// One tick in data units. Majors get a grid line and a longer tick mark.
struct Tick {
  double value = 0.0;
  std::string label;  ///< empty: drawn without a label
  bool major = true;
};

/// The limits an axis is drawn with and its ticks, ascending and all within [min, max].
struct AxisTicks {
  double min = 0.0, max = 1.0;  ///< min < max; both > 0 on a log axis
  std::vector<Tick> ticks;
};

/// The extent of the data drawn on an axis: finite, and positive on a log axis.
struct DataExtent {
  double min = 0.0, max = 0.0;
};

/// How much room the ticks have: the axis length and the least distance between the centres of
/// two labels (a horizontal axis needs a label's width, a vertical one a line's height).
struct TickRoom {
  double length_px = 500.0;
  double min_label_spacing_px = 50.0;
};

/// Limits and ticks for `axis`. Limits the axis gives are kept (non-finite ones, and non-positive
/// ones on a log axis, are ignored); missing ones come from `data`, rounded outwards to a tick
/// (linear) or a decade (log). No data: [0, 1] (linear) or [1, 10] (log). A range of zero width
/// is padded (±10% of the value, ±1 around 0, a decade either side on a log axis).
AxisTicks axis_ticks(const Axis& axis, std::optional<DataExtent> data, TickRoom room);

/// The label of m × 10^e on a log axis (m in 1..9): plain from 0.01 to 9000 ("0.05", "1", "200"),
/// "me<e>" outside ("1e-6", "5e4").
std::string log_label(int mantissa, int exponent);

}  // namespace tumble::plot
