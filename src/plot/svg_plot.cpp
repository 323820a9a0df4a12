#include "tumble/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string_view>

#include "axis_ticks.hpp"
#include "tumble/markup_text.hpp"

namespace tumble::plot {
namespace {

// Okabe & Ito's colour-blind-safe palette ("Color Universal Design", 2008) without its yellow,
// which is too pale on white, and with Paul Tol's "wine" as an eighth colour.
constexpr std::array<std::string_view, 8> kPalette = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                                      "#e69f00", "#56b4e9", "#000000", "#882255"};

// Font sizes (px).
constexpr double kTickFontPx = 11.0;
constexpr double kAxisLabelFontPx = 12.0;
constexpr double kPanelTitleFontPx = 13.0;
constexpr double kFigureTitleFontPx = 16.0;
constexpr double kMarkLabelFontPx = 10.0;
constexpr double kLegendFontPx = 11.0;

// Text is measured without the font: a glyph's advance is taken as 0.6 em, which covers the
// digits of DejaVu Sans (0.636 em, the widest usual sans-serif) within a few percent and
// overestimates Helvetica and Arial (0.556 em). Labels get room; they are never crowded.
constexpr double kGlyphEm = 0.6;
// A sans-serif's capitals rise about 0.72 em above the baseline; half of that centres a line.
constexpr double kCapEm = 0.72;

constexpr double kMajorTickPx = 5.0;
constexpr double kMinorTickPx = 3.0;
constexpr double kGapPx = 4.0;       // between a tick and its label, a label and the axis label
constexpr double kOuterPadPx = 8.0;  // between the panel's edge and anything drawn
constexpr double kMarkerRadiusPx = 3.5;

constexpr std::string_view kTextColor = "#222222";
constexpr std::string_view kTickTextColor = "#444444";
constexpr std::string_view kFrameColor = "#555555";
constexpr std::string_view kGridColor = "#e6e6e6";
constexpr std::string_view kFontFamily =
    "Helvetica, Arial, 'Liberation Sans', 'DejaVu Sans', sans-serif";

// Pixel coordinates are printed with two decimals (1/100 px is below anything a screen shows)
// and trailing zeros dropped; std::to_chars never consults the locale.
std::string num(double v) {
  // Points far outside the plot are clipped anyway; clamping keeps "1e300" data from printing
  // 300-digit coordinates. ±1e6 px leaves any visible segment's slope exact.
  v = std::isnan(v) ? 0.0 : std::clamp(v, -1e6, 1e6);
  std::array<char, 32> buf{};
  const auto end =
      std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::fixed, 2).ptr;
  std::string s(buf.data(), end);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

// Text for an element's content or a double-quoted attribute (one escape serves both: what
// an attribute needs escaped is also valid as a reference in content).
std::string escape(std::string_view text) { return escape_markup_attribute(text); }

// Appends the parts in order, numbers through num(): put(out, "<circle cx=\"", x, "\"/>").
void put_part(std::string& out, std::string_view text) {
  out += text;
}
void put_part(std::string& out, double v) {
  out += num(v);
}
template <typename... Parts>
void put(std::string& out, const Parts&... parts) {
  (put_part(out, parts), ...);
}

// Width in px of text in a font of font_px, counting UTF-8 code points, not bytes ("µs" is 2).
double text_width(std::string_view text, double font_px) {
  std::size_t glyphs = 0;
  for (const char c : text) glyphs += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1 : 0;
  return static_cast<double>(glyphs) * kGlyphEm * font_px;
}

bool usable(double v, Scale scale) {
  return std::isfinite(v) && (scale == Scale::Linear || v > 0.0);
}

struct Point {
  double x = 0.0, y = 0.0;
};

struct Rect {
  double left = 0.0, top = 0.0, right = 0.0, bottom = 0.0;
  double width() const { return right - left; }
  double height() const { return bottom - top; }
  bool contains(Point p, double slack = 0.0) const {
    return p.x >= left - slack && p.x <= right + slack && p.y >= top - slack &&
           p.y <= bottom + slack;
  }
};

// Data value → pixel along one axis; log axes map log10 of the value.
struct AxisMap {
  Scale scale = Scale::Linear;
  double t0 = 0.0, t1 = 1.0;  // the limits, in log10 on a log axis
  double p0 = 0.0, p1 = 1.0;  // their pixel positions

  AxisMap(Scale s, const AxisTicks& ticks, double from_px, double to_px)
      : scale(s), t0(transform(ticks.min)), t1(transform(ticks.max)), p0(from_px), p1(to_px) {}
  double transform(double v) const { return scale == Scale::Log10 ? std::log10(v) : v; }
  double operator()(double v) const { return p0 + (transform(v) - t0) / (t1 - t0) * (p1 - p0); }
};

// The extent of the usable points of all series along one axis (a point is usable when both of
// its coordinates are), and of the marks along x.
std::optional<DataExtent> extent(const Panel& panel, bool along_x) {
  std::optional<DataExtent> e;
  const auto add = [&e](double v) {
    if (!e) e = DataExtent{v, v};
    e->min = std::min(e->min, v);
    e->max = std::max(e->max, v);
  };
  for (const Series& s : panel.series) {
    assert(s.x.size() == s.y.size());
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i)
      if (usable(s.x[i], panel.x.scale) && usable(s.y[i], panel.y.scale))
        add(along_x ? s.x[i] : s.y[i]);
  }
  if (along_x)
    for (const VerticalMark& m : panel.marks)
      if (usable(m.x, panel.x.scale)) add(m.x);
  return e;
}

// A series in pixels: its unbroken runs of usable points, and its colour.
struct Trace {
  const Series* series = nullptr;
  std::string color;  // escaped, ready for an attribute
  std::vector<std::vector<Point>> runs;
};

std::vector<Trace> traces(const Panel& panel, const AxisMap& x, const AxisMap& y) {
  std::vector<Trace> out;
  std::size_t next_color = 0;  // per panel, so every panel's first series is blue
  for (const Series& s : panel.series) {
    Trace t;
    t.series = &s;
    t.color =
        !s.color.empty() ? escape(s.color) : std::string(kPalette[next_color++ % kPalette.size()]);
    std::vector<Point> run;
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (usable(s.x[i], panel.x.scale) && usable(s.y[i], panel.y.scale)) {
        run.push_back({x(s.x[i]), y(s.y[i])});
      } else if (!run.empty()) {
        t.runs.push_back(std::move(run));  // a skipped point breaks the line
        run.clear();
      }
    }
    if (!run.empty()) t.runs.push_back(std::move(run));
    out.push_back(std::move(t));
  }
  return out;
}

// One marker centred on p, in the fill and stroke of its enclosing group. Shapes are scaled to
// about the same ink: a square or diamond as wide as the circle looks larger than it.
void marker(std::string& out, Marker shape, Point p, double r) {
  switch (shape) {
    case Marker::None:
      return;
    case Marker::Circle:
      put(out, "<circle cx=\"", p.x, "\" cy=\"", p.y, "\" r=\"", r, "\"/>\n");
      return;
    case Marker::Square: {
      const double h = 0.88 * r;
      put(out, "<rect x=\"", p.x - h, "\" y=\"", p.y - h, "\" width=\"", 2 * h, "\" height=\"",
          2 * h, "\"/>\n");
      return;
    }
    case Marker::Triangle: {
      // Centred on its centroid: the apex 1.25 r above, the base 0.625 r below.
      const double a = 1.25 * r, half_base = a * std::sqrt(3.0) / 2.0;
      put(out, "<path d=\"M", p.x, " ", p.y - a, "L", p.x + half_base, " ", p.y + a / 2, "L",
          p.x - half_base, " ", p.y + a / 2, "Z\"/>\n");
      return;
    }
    case Marker::Diamond: {
      const double a = 1.2 * r;
      put(out, "<path d=\"M", p.x, " ", p.y - a, "L", p.x + a, " ", p.y, "L", p.x, " ", p.y + a,
          "L", p.x - a, " ", p.y, "Z\"/>\n");
      return;
    }
    case Marker::Cross: {
      const double a = r;
      put(out, "<path fill=\"none\" d=\"M", p.x - a, " ", p.y - a, "L", p.x + a, " ", p.y + a, "M",
          p.x - a, " ", p.y + a, "L", p.x + a, " ", p.y - a, "\"/>\n");
      return;
    }
  }
}

void polyline(std::string& out, const std::vector<Point>& run, const Trace& t) {
  // SVG rejects a negative width; a hairline still shows the series is there.
  const double given_width = t.series->line_width_px;
  const double width = std::isfinite(given_width) ? std::clamp(given_width, 0.25, 20.0) : 1.5;
  put(out, "<polyline stroke=\"", t.color, "\" stroke-width=\"", width, "\"");
  // Dashes and gaps grow with the line, so a thick dashed line still reads as dashed.
  if (t.series->dashed) put(out, " stroke-dasharray=\"", 4.0 * width, " ", 2.5 * width, "\"");
  out += " points=\"";
  for (std::size_t i = 0; i < run.size(); ++i) put(out, i > 0 ? " " : "", run[i].x, ",", run[i].y);
  out += "\"/>\n";
}

// The fill and stroke a series' markers share.
void open_marker_group(std::string& out, const Trace& t) {
  if (t.series->filled)
    put(out, "<g fill=\"", t.color, "\" stroke=\"", t.color, "\" stroke-width=\"1\">\n");
  else
    put(out, "<g fill=\"#ffffff\" stroke=\"", t.color, "\" stroke-width=\"1.25\">\n");
}

// A text element; `attributes` (already escaped) go after the position.
void text(std::string& out, Point at, std::string_view content, std::string_view anchor,
          std::string_view attributes = {}) {
  put(out, "<text x=\"", at.x, "\" y=\"", at.y, "\"");
  if (anchor != "start") put(out, " text-anchor=\"", anchor, "\"");
  if (!attributes.empty()) put(out, " ", attributes);
  put(out, ">", escape(content), "</text>\n");
}

// The labels of a horizontal axis that do not overlap the last label kept (ticks come in
// ascending x), with at least a wide space between two.
std::vector<std::size_t> x_labels_that_fit(const AxisTicks& ticks, const AxisMap& map) {
  std::vector<std::size_t> kept;
  double last_right = -1e9;
  for (std::size_t i = 0; i < ticks.ticks.size(); ++i) {
    const Tick& t = ticks.ticks[i];
    if (t.label.empty()) continue;
    const double half = text_width(t.label, kTickFontPx) / 2.0;
    const double px = map(t.value);
    if (px - half < last_right + 1.5 * kGapPx) continue;
    kept.push_back(i);
    last_right = px + half;
  }
  return kept;
}

// The same for a vertical axis, where labels need a line's height between them.
std::vector<std::size_t> y_labels_that_fit(const AxisTicks& ticks, const AxisMap& map) {
  std::vector<std::size_t> kept;
  double last_px = 1e9;
  for (std::size_t i = 0; i < ticks.ticks.size(); ++i) {
    const Tick& t = ticks.ticks[i];
    if (t.label.empty()) continue;
    const double px = map(t.value);  // decreasing: pixel y grows downwards
    if (last_px - px < kTickFontPx + 2.0) continue;
    kept.push_back(i);
    last_px = px;
  }
  return kept;
}

// What a legend box must not cover: every point of every series, and samples every 4 px (at
// most 256 a segment) along its lines.
std::vector<Point> ink(const std::vector<Trace>& ts) {
  std::vector<Point> out;
  for (const Trace& t : ts) {
    for (const std::vector<Point>& run : t.runs) {
      for (std::size_t i = 0; i < run.size(); ++i) {
        out.push_back(run[i]);
        if (i == 0 || !t.series->line) continue;
        const Point a = run[i - 1], b = run[i];
        const double length = std::hypot(b.x - a.x, b.y - a.y);
        const int samples = static_cast<int>(std::min(256.0, std::ceil(length / 4.0)));
        for (int k = 1; k < samples; ++k) {
          const double f = k / static_cast<double>(samples);
          out.push_back({a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)});
        }
      }
    }
  }
  return out;
}

// Where in the plot a legend of box_w × box_h hides no data (no point, no line, with a marker's
// radius of room): the inner corners first (top-right, top-left, bottom-right, bottom-left),
// then any place on an 8 px grid, nearest the top-right corner first. None: every place hides
// something, and the legend goes beside the plot (draw_panel).
std::optional<Rect> empty_legend_box(const std::vector<Point>& ink, const Rect& plot, double box_w,
                                     double box_h) {
  constexpr double kInset = 6.0, kStepPx = 8.0;
  const double left = plot.left + kInset, right = plot.right - kInset;
  const double top = plot.top + kInset, bottom = plot.bottom - kInset;
  if (right - left < box_w || bottom - top < box_h) return std::nullopt;
  const auto empty = [&](const Rect& box) {
    return std::none_of(ink.begin(), ink.end(),
                        [&](Point p) { return box.contains(p, kMarkerRadiusPx + 1.0); });
  };
  const std::array<Rect, 4> corners = {
      Rect{right - box_w, top, right, top + box_h},
      Rect{left, top, left + box_w, top + box_h},
      Rect{right - box_w, bottom - box_h, right, bottom},
      Rect{left, bottom - box_h, left + box_w, bottom},
  };
  for (const Rect& c : corners)
    if (empty(c)) return c;
  std::vector<Rect> places;
  for (double y = top; y + box_h <= bottom; y += kStepPx)
    for (double x = right - box_w; x >= left; x -= kStepPx)
      places.push_back({x, y, x + box_w, y + box_h});
  std::stable_sort(places.begin(), places.end(), [&](const Rect& a, const Rect& b) {
    return std::hypot(right - a.right, a.top - top) < std::hypot(right - b.right, b.top - top);
  });
  for (const Rect& place : places)
    if (empty(place)) return place;
  return std::nullopt;
}

// The legend's rows: the named series.
struct LegendSize {
  std::vector<const Trace*> entries;
  double w = 0.0, h = 0.0;
};
constexpr double kLegendPad = 6.0, kLegendSamplePx = 26.0, kLegendRowPx = 16.0;

LegendSize legend_size(const std::vector<Trace>& ts) {
  LegendSize size;
  double text_w = 0.0;
  for (const Trace& t : ts) {
    if (t.series->name.empty()) continue;
    size.entries.push_back(&t);
    text_w = std::max(text_w, text_width(t.series->name, kLegendFontPx));
  }
  if (size.entries.empty()) return size;
  size.w = kLegendPad + kLegendSamplePx + kGapPx + text_w + kLegendPad;
  size.h = 2.0 * kLegendPad + kLegendRowPx * static_cast<double>(size.entries.size()) - 4.0;
  return size;
}

void legend(std::string& out, const LegendSize& size, const Rect& box) {
  if (size.entries.empty()) return;
  put(out, "<g font-size=\"", kLegendFontPx, "\" fill=\"", kTextColor, "\">\n");
  put(out, "<rect x=\"", box.left, "\" y=\"", box.top, "\" width=\"", size.w, "\" height=\"",
      size.h, "\" rx=\"3\" fill=\"#ffffff\" fill-opacity=\"0.9\" stroke=\"#cccccc\"/>\n");
  for (std::size_t i = 0; i < size.entries.size(); ++i) {
    const Trace& t = *size.entries[i];
    const double cy = box.top + kLegendPad + kLegendRowPx * (static_cast<double>(i) + 0.5) - 2.0;
    const double x0 = box.left + kLegendPad, x1 = x0 + kLegendSamplePx;
    if (t.series->line) {
      out += "<g fill=\"none\">\n";
      polyline(out, {{x0, cy}, {x1, cy}}, t);
      out += "</g>\n";
    }
    if (t.series->marker != Marker::None) {
      open_marker_group(out, t);
      marker(out, t.series->marker, {(x0 + x1) / 2.0, cy}, kMarkerRadiusPx);
      out += "</g>\n";
    }
    text(out, {x1 + kGapPx, cy + kCapEm * kLegendFontPx / 2.0}, t.series->name, "start");
  }
  out += "</g>\n";
}

// More marks than this are labelled by their lines alone: twenty labels already fill a row.
constexpr std::size_t kMaxLabelledMarks = 20;

bool marks_labelled(const Panel& panel) {
  if (panel.marks.size() > kMaxLabelledMarks) return false;
  return std::any_of(panel.marks.begin(), panel.marks.end(),
                     [](const VerticalMark& m) { return !m.label.empty(); });
}

void marks(std::string& out, const Panel& panel, const Rect& plot, const AxisMap& x,
           double panel_w) {
  // Pixel x of each mark, or NaN for one outside the plot.
  std::vector<double> xs;
  for (const VerticalMark& m : panel.marks) {
    const double px = usable(m.x, panel.x.scale) ? x(m.x) : -1.0;
    xs.push_back(px >= plot.left - 0.5 && px <= plot.right + 0.5 ? px : std::nan(""));
  }
  std::vector<std::size_t> shown;  // indices of the marks inside, left to right
  for (std::size_t i = 0; i < xs.size(); ++i)
    if (!std::isnan(xs[i])) shown.push_back(i);
  if (shown.empty()) return;
  std::stable_sort(shown.begin(), shown.end(),
                   [&xs](std::size_t a, std::size_t b) { return xs[a] < xs[b]; });

  put(out, "<path fill=\"none\" stroke=\"", escape(panel.marks_color),
      "\" stroke-width=\"1\" d=\"");
  for (const std::size_t i : shown) put(out, "M", xs[i], " ", plot.top, "V", plot.bottom);
  out += "\"/>\n";
  if (!marks_labelled(panel)) return;

  // Labels sit above the frame, centred on their line (pushed inwards at the panel's edges), in
  // the tick labels' grey: the marks' own colour is meant for thin lines and too pale for text.
  // A label that would overlap the one to its left is left out.
  put(out, "<g font-size=\"", kMarkLabelFontPx, "\" fill=\"", kTickTextColor, "\">\n");
  double last_right = -1e9;
  for (const std::size_t i : shown) {
    const std::string& label = panel.marks[i].label;
    if (label.empty()) continue;
    const double w = text_width(label, kMarkLabelFontPx);
    const double left = std::clamp(xs[i] - w / 2.0, 2.0, std::max(2.0, panel_w - 2.0 - w));
    if (left < last_right + kGapPx) continue;
    text(out, {left + w / 2.0, plot.top - 4.0}, label, "middle");
    last_right = left + w;
  }
  out += "</g>\n";
}

// Where a panel's plot area goes, and the ticks and labels drawn around it.
struct PanelLayout {
  Rect plot;  // in the panel's own coordinates
  AxisTicks x_ticks, y_ticks;
  std::vector<std::size_t> x_labels, y_labels;  // indices of the ticks whose label is drawn
};

// Distances from a panel's edges to its plot area. Panels in one column share their left
// margin and panels in one row their top and bottom ones, so the plot areas line up.
struct Margins {
  double left = 0.0, top = 0.0, bottom = 0.0;
};

PanelLayout layout_panel(const Panel& panel, double w, double h, const Margins& at_least) {
  const bool has_x_label = !panel.x.label.empty(), has_y_label = !panel.y.label.empty();
  // The bands above and below the plot area, top to bottom.
  const double title_band = !panel.title.empty() ? kPanelTitleFontPx + 8.0 : 0.0;
  const double marks_band = marks_labelled(panel) ? kMarkLabelFontPx + 6.0 : 0.0;
  const double tick_label_band = kMajorTickPx + kGapPx + kTickFontPx + 2.0;
  const double x_label_band = has_x_label ? kGapPx + kAxisLabelFontPx + 2.0 : 0.0;

  PanelLayout layout;
  Rect& plot = layout.plot;
  plot.top = std::round(std::max(at_least.top, kOuterPadPx + title_band + marks_band));
  const double bottom_margin =
      std::max(at_least.bottom, kOuterPadPx + x_label_band + tick_label_band);
  plot.bottom = std::round(std::max(plot.top + 20.0, h - bottom_margin));

  // The y axis first: its labels' width decides where the plot starts.
  const std::optional<DataExtent> x_data = extent(panel, true), y_data = extent(panel, false);
  // Vertical labels need a line each; linear ones a little more, to read as a scale.
  const double y_spacing = panel.y.scale == Scale::Log10 ? kTickFontPx + 6.0 : 45.0;
  layout.y_ticks = axis_ticks(panel.y, y_data, {plot.height(), y_spacing});
  const AxisMap y_map(panel.y.scale, layout.y_ticks, plot.bottom, plot.top);
  layout.y_labels = y_labels_that_fit(layout.y_ticks, y_map);
  double y_label_w = 0.0;
  for (const std::size_t i : layout.y_labels)
    y_label_w = std::max(y_label_w, text_width(layout.y_ticks.ticks[i].label, kTickFontPx));
  const double y_axis_label_band = has_y_label ? kAxisLabelFontPx + kGapPx : 0.0;
  plot.left = std::round(
      std::max(at_least.left, kOuterPadPx + y_axis_label_band + y_label_w + kGapPx + kMajorTickPx));

  // The last x label is centred on the right edge: the margin grows to keep it in the panel.
  // An x label is about five glyphs wide, plus a space or two on either side.
  const double x_spacing = panel.x.scale == Scale::Log10 ? 44.0 : 70.0;
  double right_margin = 16.0;
  for (int attempt = 0; attempt < 2; ++attempt) {
    plot.right = std::round(std::max(plot.left + 20.0, w - right_margin));
    layout.x_ticks = axis_ticks(panel.x, x_data, {plot.width(), x_spacing});
    const AxisMap x_map(panel.x.scale, layout.x_ticks, plot.left, plot.right);
    layout.x_labels = x_labels_that_fit(layout.x_ticks, x_map);
    if (layout.x_labels.empty()) break;
    const Tick& last = layout.x_ticks.ticks[layout.x_labels.back()];
    const double label_right = x_map(last.value) + text_width(last.label, kTickFontPx) / 2.0;
    if (label_right + 2.0 <= w) break;
    right_margin += label_right + 2.0 - w;
  }
  return layout;
}

Margins margins(const PanelLayout& layout, double h) {
  return {layout.plot.left, layout.plot.top, h - layout.plot.bottom};
}

void draw_panel(std::string& out, const Panel& panel, const Margins& aligned, int index,
                Point origin, double w, double h) {
  PanelLayout layout = layout_panel(panel, w, h, aligned);
  // The legend goes where it hides no data; where no place inside the plot is empty, the plot
  // narrows and the legend stands beside it, to the right.
  std::optional<Rect> legend_at;
  LegendSize legend_rows;
  {
    const AxisMap x_map(panel.x.scale, layout.x_ticks, layout.plot.left, layout.plot.right);
    const AxisMap y_map(panel.y.scale, layout.y_ticks, layout.plot.bottom, layout.plot.top);
    const std::vector<Trace> ts = traces(panel, x_map, y_map);
    legend_rows = legend_size(ts);
    if (panel.legend && !legend_rows.entries.empty()) {
      legend_at = empty_legend_box(ink(ts), layout.plot, legend_rows.w, legend_rows.h);
      if (!legend_at) {
        const double beside = legend_rows.w + 2.0 * kGapPx;
        layout = layout_panel(panel, w - beside, h, aligned);
        legend_at =
            Rect{layout.plot.right + kGapPx, layout.plot.top,
                 layout.plot.right + kGapPx + legend_rows.w, layout.plot.top + legend_rows.h};
      }
    }
  }
  const Rect& plot = layout.plot;
  const AxisTicks &x_ticks = layout.x_ticks, &y_ticks = layout.y_ticks;
  const AxisMap x_map(panel.x.scale, x_ticks, plot.left, plot.right);
  const AxisMap y_map(panel.y.scale, y_ticks, plot.bottom, plot.top);

  put(out, "<g transform=\"translate(", origin.x, ",", origin.y, ")\">\n");
  const std::string clip_id = "tumble-plot-area-" + std::to_string(index);
  put(out, "<defs><clipPath id=\"", clip_id, "\"><rect x=\"", plot.left, "\" y=\"", plot.top,
      "\" width=\"", plot.width(), "\" height=\"", plot.height(), "\"/></clipPath></defs>\n");
  std::string style;
  if (!panel.title.empty()) {
    put(style, "font-size=\"", kPanelTitleFontPx, "\" font-weight=\"bold\" fill=\"", kTextColor,
        "\"");
    text(out, {(plot.left + plot.right) / 2.0, kOuterPadPx + kCapEm * kPanelTitleFontPx + 1.0},
         panel.title, "middle", style);
  }

  // Grid lines at the major ticks that are not on the frame.
  put(out, "<path fill=\"none\" stroke=\"", kGridColor,
      "\" stroke-width=\"1\" shape-rendering=\"crispEdges\" d=\"");
  for (const Tick& t : x_ticks.ticks) {
    const double px = x_map(t.value);
    if (t.major && px > plot.left + 0.5 && px < plot.right - 0.5)
      put(out, "M", px, " ", plot.top, "V", plot.bottom);
  }
  for (const Tick& t : y_ticks.ticks) {
    const double py = y_map(t.value);
    if (t.major && py > plot.top + 0.5 && py < plot.bottom - 0.5)
      put(out, "M", plot.left, " ", py, "H", plot.right);
  }
  out += "\"/>\n";

  if (!panel.marks.empty()) marks(out, panel, plot, x_map, w);

  const std::vector<Trace> ts = traces(panel, x_map, y_map);
  // Lines are clipped to the plot area; markers are drawn whole, but only for points inside it.
  put(out, "<g clip-path=\"url(#", clip_id,
      ")\" fill=\"none\" stroke-linejoin=\"round\" stroke-linecap=\"round\">\n");
  for (const Trace& t : ts)
    if (t.series->line)
      for (const std::vector<Point>& run : t.runs)
        if (run.size() >= 2) polyline(out, run, t);
  out += "</g>\n";
  for (const Trace& t : ts) {
    if (t.series->marker == Marker::None) continue;
    open_marker_group(out, t);
    for (const std::vector<Point>& run : t.runs)
      for (const Point& p : run)
        if (plot.contains(p, 0.5)) marker(out, t.series->marker, p, kMarkerRadiusPx);
    out += "</g>\n";
  }

  // Frame and ticks over the data, so a line along an edge does not hide them.
  put(out, "<rect x=\"", plot.left, "\" y=\"", plot.top, "\" width=\"", plot.width(),
      "\" height=\"", plot.height(), "\" fill=\"none\" stroke=\"", kFrameColor,
      "\" stroke-width=\"1\" shape-rendering=\"crispEdges\"/>\n");
  put(out, "<path fill=\"none\" stroke=\"", kFrameColor,
      "\" stroke-width=\"1\" shape-rendering=\"crispEdges\" d=\"");
  for (const Tick& t : x_ticks.ticks)
    put(out, "M", x_map(t.value), " ", plot.bottom, "v", t.major ? kMajorTickPx : kMinorTickPx);
  for (const Tick& t : y_ticks.ticks)
    put(out, "M", plot.left, " ", y_map(t.value), "h", t.major ? -kMajorTickPx : -kMinorTickPx);
  out += "\"/>\n";

  put(out, "<g font-size=\"", kTickFontPx, "\" fill=\"", kTickTextColor, "\">\n");
  const double x_label_y = plot.bottom + kMajorTickPx + kGapPx + kCapEm * kTickFontPx;
  for (const std::size_t i : layout.x_labels)
    text(out, {x_map(x_ticks.ticks[i].value), x_label_y}, x_ticks.ticks[i].label, "middle");
  const double y_label_x = plot.left - kMajorTickPx - kGapPx;
  for (const std::size_t i : layout.y_labels)
    text(out, {y_label_x, y_map(y_ticks.ticks[i].value) + kCapEm * kTickFontPx / 2.0},
         y_ticks.ticks[i].label, "end");
  out += "</g>\n";

  style.clear();
  put(style, "font-size=\"", kAxisLabelFontPx, "\" fill=\"", kTextColor, "\"");
  if (!panel.x.label.empty())
    text(out, {(plot.left + plot.right) / 2.0, h - kOuterPadPx - 2.0}, panel.x.label, "middle",
         style);
  if (!panel.y.label.empty()) {
    // A quarter turn anticlockwise: the baseline runs up the panel, the glyphs' tops face left.
    const Point at{kOuterPadPx + kCapEm * kAxisLabelFontPx + 1.0, (plot.top + plot.bottom) / 2.0};
    put(style, " transform=\"rotate(-90 ", at.x, " ", at.y, ")\"");
    text(out, at, panel.y.label, "middle", style);
  }

  if (legend_at) {
    // The rows point at this drawing's traces (the same series, in the same order).
    LegendSize rows = legend_rows;
    rows.entries.clear();
    for (const Trace& t : ts)
      if (!t.series->name.empty()) rows.entries.push_back(&t);
    legend(out, rows, *legend_at);
  }
  out += "</g>\n";
}

}  // namespace

std::string render_svg(const Figure& figure) {
  // Panels smaller than this have no room for a plot between their labels.
  constexpr int kMinPanelWidthPx = 160, kMinPanelHeightPx = 120;
  const int panel_count = static_cast<int>(figure.panels.size());
  const int columns = std::clamp(figure.columns, 1, std::max(1, panel_count));
  const int rows = std::max(1, (panel_count + columns - 1) / columns);
  const int panel_w = std::max(figure.panel_width_px, kMinPanelWidthPx);
  const int panel_h = std::max(figure.panel_height_px, kMinPanelHeightPx);
  const int title_h = figure.title.empty() ? 0 : 32;
  const std::string width = std::to_string(columns * panel_w);
  const std::string height = std::to_string(title_h + rows * panel_h);

  std::string out;
  put(out, "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"", width,
      "\" height=\"", height, "\" viewBox=\"0 0 ", width, " ", height, "\" font-family=\"",
      kFontFamily, "\">\n");
  if (!figure.title.empty()) put(out, "<title>", escape(figure.title), "</title>\n");
  put(out, "<rect width=\"", width, "\" height=\"", height, "\" fill=\"#ffffff\"/>\n");
  if (!figure.title.empty()) {
    std::string style;
    put(style, "font-size=\"", kFigureTitleFontPx, "\" font-weight=\"bold\" fill=\"", kTextColor,
        "\"");
    text(out, {columns * panel_w / 2.0, 8.0 + kCapEm * kFigureTitleFontPx + 2.0}, figure.title,
         "middle", style);
  }
  // Two passes: each panel's own margins, then every panel laid out again with the widest
  // left margin of its column and the tallest top and bottom ones of its row.
  const double w_px = panel_w, h_px = panel_h;
  std::vector<Margins> column(static_cast<std::size_t>(columns)),
      row(static_cast<std::size_t>(rows));
  for (std::size_t i = 0; i < figure.panels.size(); ++i) {
    const Margins own = margins(layout_panel(figure.panels[i], w_px, h_px, {}), h_px);
    Margins& c = column[i % column.size()];
    Margins& r = row[i / column.size()];
    c.left = std::max(c.left, own.left);
    r.top = std::max(r.top, own.top);
    r.bottom = std::max(r.bottom, own.bottom);
  }
  for (std::size_t i = 0; i < figure.panels.size(); ++i) {
    const std::size_t c = i % column.size(), r = i / column.size();
    const Margins aligned{column[c].left, row[r].top, row[r].bottom};
    const Point origin{static_cast<double>(c) * w_px, title_h + static_cast<double>(r) * h_px};
    draw_panel(out, figure.panels[i], aligned, static_cast<int>(i), origin, w_px, h_px);
  }
  out += "</svg>\n";
  return out;
}

}  // namespace tumble::plot
