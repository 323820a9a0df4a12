#pragma once
/// The project's one plotting module: line/marker charts written as standalone SVG 1.1 text
/// (no scripts, no external fonts or files), readable in a browser and on a printed page.
/// Used by `tumble study` (log-log work-precision plots) and `simulate --plot` (height and
/// energy over time). Plain data in, SVG text out; the caller writes the file.

#include <optional>
#include <string>
#include <vector>

namespace tumble::plot {

enum class Scale { Linear, Log10 };

/// One axis. Limits omitted: chosen from the data (log axes: whole decades around it; linear:
/// "nice" round numbers). Ticks are placed at round values (1, 2, 5 × 10^k on linear axes,
/// decades on log axes, with minor ticks) and labelled compactly (1e-6, 0.5, 120).
struct Axis {
  std::string label;  ///< with units, e.g. "time (s)"
  Scale scale = Scale::Linear;
  std::optional<double> min, max;
};

enum class Marker { None, Circle, Square, Triangle, Diamond, Cross };

/// A named polyline and/or markers. Points with non-finite coordinates, or non-positive ones on a
/// log axis, are skipped (a line is broken there, never drawn through).
struct Series {
  std::string name;          ///< legend entry; empty: not in the legend
  std::vector<double> x, y;  ///< same length
  std::string color;         ///< "#rrggbb"; empty: the next colour of the built-in palette
  bool line = true;
  bool dashed = false;
  double line_width_px = 1.5;
  Marker marker = Marker::Circle;
  bool filled = true;  ///< markers filled or hollow
};

/// A labelled vertical line across a panel (e.g. a contact at time t). Labels sit above the plot
/// area; with more than 20 marks, or where a label would overlap the one before, only the line
/// is drawn.
struct VerticalMark {
  double x = 0.0;
  std::string label;  ///< may be empty
};

/// One chart: axes, series, vertical marks, an optional legend. Series without a colour take the
/// palette (Okabe–Ito, colour-blind safe) in order, starting afresh in each panel. The legend
/// lists the named series where it covers no data (no point and no line): an inner corner
/// (top-right first), else any empty place in the plot nearest the top-right; where the plot has
/// none, the plot narrows and the legend stands to its right.
struct Panel {
  std::string title;
  Axis x, y;
  std::vector<Series> series;
  std::vector<VerticalMark> marks;
  std::string marks_color = "#999999";
  bool legend = true;
};

/// Panels laid out in a grid of `columns`, each `panel_width_px` × `panel_height_px` (at least
/// 160 × 120); the plot areas of a column share their left edge, those of a row their top and
/// bottom.
struct Figure {
  std::string title;  ///< above all panels; may be empty
  std::vector<Panel> panels;
  int columns = 1;
  int panel_width_px = 640;
  int panel_height_px = 400;
};

/// The figure as SVG text. Deterministic: the same figure gives the same bytes (numbers printed
/// with fixed precision, no locale). Text is XML-escaped.
std::string render_svg(const Figure& figure);

}  // namespace tumble::plot
