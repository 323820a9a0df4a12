#include "tumble/svg_plot.hpp"

#include <gtest/gtest.h>

#include <clocale>
#include <cmath>
#include <limits>
#include <locale>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../../../src/plot/axis_ticks.hpp"

namespace tumble::plot {
namespace {

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos;
       at = text.find(needle, at + needle.size()))
    ++n;
  return n;
}

// The labels drawn, as the text between "<text …>" and "</text>".
std::vector<std::string> texts(const std::string& svg) {
  std::vector<std::string> out;
  for (std::size_t at = svg.find("<text"); at != std::string::npos;
       at = svg.find("<text", at + 1)) {
    const std::size_t open_end = svg.find('>', at);
    const std::size_t close = svg.find("</text>", open_end);
    out.push_back(svg.substr(open_end + 1, close - open_end - 1));
  }
  return out;
}

bool has_text(const std::string& svg, const std::string& label) {
  for (const std::string& t : texts(svg))
    if (t == label) return true;
  return false;
}

std::vector<std::string> labels(const AxisTicks& ticks) {
  std::vector<std::string> out;
  for (const Tick& t : ticks.ticks)
    if (!t.label.empty()) out.push_back(t.label);
  return out;
}

// A work-precision panel: error against derivative evaluations on log-log axes, one line per
// integrator falling with its order, and the Pareto front dashed.
Figure work_precision_figure() {
  Panel p;
  p.title = "Work–precision";
  p.x = {"derivative evaluations", Scale::Log10, {}, {}};
  p.y = {"max position error (m)", Scale::Log10, {}, {}};
  const std::vector<std::pair<std::string, int>> integrators = {
      {"euler", 1}, {"symplectic-euler", 1}, {"midpoint", 2}, {"rk4", 4}};
  for (const auto& [name, order] : integrators) {
    Series s;
    s.name = name;
    for (int k = 0; k < 6; ++k) {
      const double evals = 100.0 * std::pow(4.0, k);
      s.x.push_back(evals);
      s.y.push_back(std::pow(evals, -order));
    }
    p.series.push_back(s);
  }
  Series front;
  front.name = "Pareto front";
  front.x = {100.0, 1e5};
  front.y = {1e-2, 1e-20};
  front.dashed = true;
  front.marker = Marker::None;
  front.color = "#555555";
  p.series.push_back(front);
  Figure f;
  f.title = "tumble study";
  f.panels.push_back(p);
  return f;
}

// Tolerances: the output is text and compared exactly; tick values are i·step or 10^e and
// compared to 1e-12 relative, far below a pixel and above the rounding of one product.

TEST(SvgPlot, IsAStandaloneSvgDocument) {
  const std::string svg = render_svg(work_precision_figure());
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_EQ(svg.substr(svg.find_last_not_of('\n') - 5, 6), "</svg>");
  EXPECT_NE(svg.find("width=\"640\" height=\"432\" viewBox=\"0 0 640 432\""), std::string::npos);
  EXPECT_NE(svg.find("sans-serif"), std::string::npos);
  EXPECT_NE(svg.find("fill=\"#ffffff\""), std::string::npos);
  // No scripts, no links to anything outside the file (the clip path is a local url(#…)).
  EXPECT_EQ(svg.find("<script"), std::string::npos);
  EXPECT_EQ(svg.find("href"), std::string::npos);
  EXPECT_EQ(svg.find("<image"), std::string::npos);
  EXPECT_EQ(count(svg, "<g ") + count(svg, "<g>"), count(svg, "</g>"));
  EXPECT_EQ(count(svg, "<text"), count(svg, "</text>"));
  EXPECT_EQ(count(svg, "<svg"), count(svg, "</svg>"));
  EXPECT_EQ(count(svg, "<clipPath"), count(svg, "</clipPath>"));
}

TEST(SvgPlot, EscapesEveryPieceOfText) {
  Figure f;
  f.title = "a<b&c";
  Panel p;
  p.title = "\"quoted\" & 'single'";
  p.x.label = "x<y";
  p.y.label = "y>x";
  p.series.push_back({"a<b&c", {1, 2}, {3, 4}, "", true, false, 1.5, Marker::Circle, true});
  p.marks.push_back({1.5, "m&m"});
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  EXPECT_EQ(svg.find("a<b&c"), std::string::npos);
  EXPECT_GE(count(svg, "a&lt;b&amp;c"), 3u);  // document title, figure title, legend entry
  EXPECT_NE(svg.find("&quot;quoted&quot; &amp; &#39;single&#39;"), std::string::npos);
  EXPECT_NE(svg.find("x&lt;y"), std::string::npos);
  EXPECT_NE(svg.find("y&gt;x"), std::string::npos);
  EXPECT_NE(svg.find("m&amp;m"), std::string::npos);
}

TEST(SvgPlot, SameFigureGivesSameBytes) {
  EXPECT_EQ(render_svg(work_precision_figure()), render_svg(work_precision_figure()));
}

// A C++ locale writing "1,5" for 1.5 and grouping thousands: what an iostream would print there.
struct CommaDecimals : std::numpunct<char> {
  char do_decimal_point() const override { return ','; }
  char do_thousands_sep() const override { return '.'; }
  std::string do_grouping() const override { return "\3"; }
};

TEST(SvgPlot, NumbersDoNotDependOnTheLocale) {
  const std::string in_c_locale = render_svg(work_precision_figure());
  const std::locale previous =
      std::locale::global(std::locale(std::locale::classic(), new CommaDecimals));
  // The C library's too, when the machine has a locale with a decimal comma (printf would
  // write "1,5" there).
  for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8"})
    if (std::setlocale(LC_ALL, name) != nullptr) break;
  const std::string in_comma_locale = render_svg(work_precision_figure());
  std::locale::global(previous);
  std::setlocale(LC_ALL, "C");
  EXPECT_EQ(in_comma_locale, in_c_locale);
}

TEST(SvgPlot, LogAxisLabelsEveryDecade) {
  Figure f;
  Panel p;
  p.y.scale = Scale::Log10;
  Series s;
  for (int e = -9; e <= -3; ++e) {
    s.x.push_back(e);
    s.y.push_back(std::pow(10.0, e));
  }
  p.series.push_back(s);
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  for (const char* label : {"1e-9", "1e-8", "1e-7", "1e-6", "1e-5", "1e-4", "1e-3"})
    EXPECT_TRUE(has_text(svg, label)) << label;
  EXPECT_FALSE(has_text(svg, "1e-10"));  // the limits are the data's own decades
  EXPECT_FALSE(has_text(svg, "0.01"));
}

TEST(AxisTicks, LogLimitsExpandToWholeDecadesWithMinorTicks) {
  const Axis axis{"", Scale::Log10, {}, {}};
  const AxisTicks t = axis_ticks(axis, DataExtent{3e-7, 2e-2}, {400.0, 17.0});
  EXPECT_NEAR(t.min, 1e-7, 1e-19);
  EXPECT_NEAR(t.max, 1e-1, 1e-13);
  EXPECT_EQ(labels(t),
            (std::vector<std::string>{"1e-7", "1e-6", "1e-5", "1e-4", "1e-3", "0.01", "0.1"}));
  int minors = 0;
  for (const Tick& tick : t.ticks) minors += tick.major ? 0 : 1;
  EXPECT_EQ(minors, 6 * 8);  // 2..9 in each of the six decades
}

TEST(AxisTicks, LogAxisOverManyDecadesLabelsEveryThird) {
  // 18 decades: every decade labelled would be 19 labels; every 3rd keeps 7 round ones.
  const Axis axis{"", Scale::Log10, {}, {}};
  const AxisTicks t = axis_ticks(axis, DataExtent{1e-12, 1e6}, {300.0, 17.0});
  EXPECT_EQ(labels(t),
            (std::vector<std::string>{"1e-12", "1e-9", "1e-6", "1e-3", "1", "1000", "1e6"}));
  std::size_t majors = 0;
  for (const Tick& tick : t.ticks) majors += tick.major ? 1 : 0;
  EXPECT_EQ(majors, 19u);  // every decade still gets its tick
}

TEST(AxisTicks, LogAxisOverTenDecadesLabelsEveryOther) {
  const Axis axis{"", Scale::Log10, {}, {}};
  const AxisTicks t = axis_ticks(axis, DataExtent{1e-9, 1.0}, {560.0, 44.0});
  EXPECT_EQ(labels(t), (std::vector<std::string>{"1e-8", "1e-6", "1e-4", "0.01", "1"}));
}

TEST(AxisTicks, LogAxisWithinOneDecadeLabelsItsMinorTicks) {
  const Axis axis{"", Scale::Log10, 2.0, 8.0};
  const AxisTicks t = axis_ticks(axis, std::nullopt, {400.0, 17.0});
  EXPECT_EQ(t.min, 2.0);
  EXPECT_EQ(t.max, 8.0);
  EXPECT_EQ(labels(t), (std::vector<std::string>{"2", "3", "4", "5", "6", "7", "8"}));
}

TEST(AxisTicks, LogAxisOverOneDecadeLabelsTwoAndFive) {
  const Axis axis{"", Scale::Log10, {}, {}};
  const AxisTicks t = axis_ticks(axis, DataExtent{2.1, 7.9}, {300.0, 17.0});
  EXPECT_EQ(labels(t), (std::vector<std::string>{"1", "2", "5", "10"}));
}

TEST(AxisTicks, LogLabelsAreCompact) {
  EXPECT_EQ(log_label(1, -6), "1e-6");
  EXPECT_EQ(log_label(1, -3), "1e-3");
  EXPECT_EQ(log_label(1, -2), "0.01");
  EXPECT_EQ(log_label(5, -1), "0.5");
  EXPECT_EQ(log_label(1, 0), "1");
  EXPECT_EQ(log_label(1, 2), "100");
  EXPECT_EQ(log_label(2, 3), "2000");
  EXPECT_EQ(log_label(1, 4), "1e4");
}

TEST(AxisTicks, LinearStepsAreOneTwoOrFiveTimesAPowerOfTen) {
  const Axis axis;
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {0.013, 9.7}, {-3.2, 47.0}, {0.0, 0.0031}, {1234.0, 1299.0}, {-1e-7, 2e-7}}) {
    const AxisTicks t = axis_ticks(axis, DataExtent{lo, hi}, {560.0, 70.0});
    ASSERT_GE(t.ticks.size(), 4u) << lo << ".." << hi;
    EXPECT_LE(t.ticks.size(), 8u) << lo << ".." << hi;
    // Limits rounded outwards onto the first and last tick.
    EXPECT_LE(t.min, lo);
    EXPECT_GE(t.max, hi);
    EXPECT_EQ(t.ticks.front().value, t.min);
    EXPECT_EQ(t.ticks.back().value, t.max);
    const double step = t.ticks[1].value - t.ticks[0].value;
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 ||
                std::abs(mantissa - 5) < 1e-6)
        << "step " << step;
  }
}

TEST(AxisTicks, LinearLabelsHaveTheStepsDigits) {
  const Axis axis;
  EXPECT_EQ(labels(axis_ticks(axis, DataExtent{0.013, 9.7}, {560.0, 70.0})),
            (std::vector<std::string>{"0", "2", "4", "6", "8", "10"}));
  EXPECT_EQ(labels(axis_ticks(axis, DataExtent{0.0, 1.0}, {300.0, 45.0})),
            (std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
  EXPECT_EQ(labels(axis_ticks(axis, DataExtent{-2e-5, 3e-5}, {300.0, 45.0})),
            (std::vector<std::string>{"-2e-5", "-1e-5", "0", "1e-5", "2e-5", "3e-5"}));
}

TEST(AxisTicks, GivenLimitsAreKept) {
  const Axis axis{"", Scale::Linear, 0.3, 2.0};
  const AxisTicks t = axis_ticks(axis, DataExtent{-5.0, 5.0}, {560.0, 70.0});
  EXPECT_EQ(t.min, 0.3);
  EXPECT_EQ(t.max, 2.0);
  for (const Tick& tick : t.ticks) {
    EXPECT_GE(tick.value, 0.3);
    EXPECT_LE(tick.value, 2.0);
  }
}

TEST(AxisTicks, ZeroWidthRangeIsPadded) {
  const Axis linear, log{"", Scale::Log10, {}, {}};
  const AxisTicks around_five = axis_ticks(linear, DataExtent{5.0, 5.0}, {560.0, 70.0});
  EXPECT_LT(around_five.min, 5.0);
  EXPECT_GT(around_five.max, 5.0);
  const AxisTicks around_zero = axis_ticks(linear, DataExtent{0.0, 0.0}, {560.0, 70.0});
  EXPECT_EQ(around_zero.min, -1.0);
  EXPECT_EQ(around_zero.max, 1.0);
  const AxisTicks around_hundred = axis_ticks(log, DataExtent{100.0, 100.0}, {560.0, 44.0});
  EXPECT_NEAR(around_hundred.min, 10.0, 1e-12);
  EXPECT_NEAR(around_hundred.max, 1000.0, 1e-9);
}

TEST(AxisTicks, NoDataGivesTheDefaultRange) {
  const AxisTicks linear = axis_ticks(Axis{}, std::nullopt, {560.0, 70.0});
  EXPECT_EQ(linear.min, 0.0);
  EXPECT_EQ(linear.max, 1.0);
  const AxisTicks log = axis_ticks(Axis{"", Scale::Log10, {}, {}}, std::nullopt, {560.0, 44.0});
  EXPECT_EQ(log.min, 1.0);
  EXPECT_EQ(log.max, 10.0);
}

TEST(SvgPlot, NonFiniteAndNonPositiveOnLogPointsAreSkippedAndBreakTheLine) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  Panel p;
  p.y.scale = Scale::Log10;
  Series s;
  s.x = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  s.y = {1, 10, nan, 100, 1000, -1.0, 0.0, inf, 10};
  p.series.push_back(s);
  Figure f;
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
  // Runs {1, 10}, {100, 1000}, {10}: two lines (a single point is only a marker), five markers.
  EXPECT_EQ(count(svg, "<polyline"), 2u);
  EXPECT_EQ(count(svg, "<circle"), 5u);
}

TEST(SvgPlot, EmptyFigureIsABlankPage) {
  const std::string svg = render_svg(Figure{});
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("viewBox=\"0 0 640 400\""), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(SvgPlot, PanelWithoutUsableDataDrawsDefaultAxes) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Figure f;
  Panel linear;
  linear.series.push_back({"nothing", {nan}, {nan}, "", true, false, 1.5, Marker::Circle, true});
  Panel log;
  log.x.scale = log.y.scale = Scale::Log10;
  log.series.push_back(
      {"negative", {-1, -2}, {-3, -4}, "", true, false, 1.5, Marker::Square, false});
  f.panels = {linear, log, Panel{}};
  f.columns = 3;
  const std::string svg = render_svg(f);
  EXPECT_TRUE(has_text(svg, "0.0"));
  EXPECT_TRUE(has_text(svg, "1.0"));
  EXPECT_TRUE(has_text(svg, "1"));
  EXPECT_TRUE(has_text(svg, "10"));
  EXPECT_EQ(count(svg, "<polyline points"), 0u);
  EXPECT_NE(svg.find("viewBox=\"0 0 1920 400\""), std::string::npos);
}

TEST(SvgPlot, SeriesWithoutColourGetDistinctPaletteColours) {
  Panel p;
  for (int i = 0; i < 8; ++i)
    p.series.push_back({std::string("s").append(std::to_string(i)),
                        {0, 1},
                        {double(i), double(i + 1)},
                        "",
                        true,
                        false,
                        1.5,
                        Marker::None,
                        true});
  p.legend = false;
  Figure f;
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  std::set<std::string> colours;
  const std::string key = "<polyline stroke=\"";
  for (std::size_t at = svg.find(key); at != std::string::npos; at = svg.find(key, at + 1))
    colours.insert(svg.substr(at + key.size(), 7));
  EXPECT_EQ(colours.size(), 8u);
}

TEST(SvgPlot, DashedSeriesHasADashPatternAndSolidOnesNone) {
  const std::string svg = render_svg(work_precision_figure());
  // The front's line and its legend sample; the four integrators' are solid.
  EXPECT_EQ(count(svg, "stroke-dasharray"), 2u);
}

TEST(SvgPlot, LegendNamesEveryNamedSeries) {
  const std::string svg = render_svg(work_precision_figure());
  for (const char* name : {"euler", "symplectic-euler", "midpoint", "rk4", "Pareto front"})
    EXPECT_TRUE(has_text(svg, name)) << name;
}

TEST(SvgPlot, LegendMovesToTheEmptiestCorner) {
  // Points fill the top-right quarter: the legend goes to the top left.
  Panel p;
  Series s;
  s.name = "crowded";
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) {
      s.x.push_back(0.6 + 0.04 * i);
      s.y.push_back(0.6 + 0.04 * j);
    }
  s.line = false;
  s.x.push_back(0.0);  // fixes the limits at [0, 1]
  s.y.push_back(0.0);
  p.series.push_back(s);
  Figure f;
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  const std::size_t box = svg.find("rx=\"3\"");
  ASSERT_NE(box, std::string::npos);
  const std::size_t x_at = svg.rfind("<rect x=\"", box) + 9;
  EXPECT_LT(std::stod(svg.substr(x_at, svg.find('"', x_at) - x_at)), 320.0);
}

// The legend box of a one-panel figure (x, y, width, height), and every data point drawn before
// it: marker centres and polyline vertices, with the polylines sampled every pixel.
struct LegendCheck {
  double x = 0, y = 0, w = 0, h = 0;
  std::vector<std::pair<double, double>> ink;
  bool found = false;
};

double attribute(const std::string& svg, std::size_t from, const std::string& name) {
  const std::size_t at = svg.find(" " + name + "=\"", from) + name.size() + 3;
  return std::stod(svg.substr(at, svg.find('"', at) - at));
}

LegendCheck legend_check(const std::string& svg) {
  LegendCheck c;
  const std::size_t box_end = svg.find("rx=\"3\"");
  if (box_end == std::string::npos) return c;
  const std::size_t box = svg.rfind("<rect ", box_end);
  c.found = true;
  c.x = attribute(svg, box, "x");
  c.y = attribute(svg, box, "y");
  c.w = attribute(svg, box, "width");
  c.h = attribute(svg, box, "height");
  const std::string data = svg.substr(0, box);
  for (std::size_t at = data.find("<circle "); at != std::string::npos;
       at = data.find("<circle ", at + 1))
    c.ink.push_back({attribute(data, at, "cx"), attribute(data, at, "cy")});
  for (std::size_t at = data.find("points=\""); at != std::string::npos;
       at = data.find("points=\"", at + 1)) {
    std::string list = data.substr(at + 8, data.find('"', at + 8) - at - 8);
    for (char& ch : list)
      if (ch == ',') ch = ' ';
    std::istringstream in(list);
    std::vector<std::pair<double, double>> vertices;
    double px, py;
    while (in >> px >> py) vertices.push_back({px, py});
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      c.ink.push_back(vertices[i]);
      if (i == 0) continue;
      const auto [ax, ay] = vertices[i - 1];
      const auto [bx, by] = vertices[i];
      const int n = static_cast<int>(std::ceil(std::hypot(bx - ax, by - ay)));
      for (int k = 1; k < n; ++k) c.ink.push_back({ax + (bx - ax) * k / n, ay + (by - ay) * k / n});
    }
  }
  return c;
}

// No data point or line pixel inside the legend box (markers are drawn 3.5 px around their
// centre, so their centres keep that far away).
void expect_legend_covers_nothing(const std::string& svg) {
  const LegendCheck c = legend_check(svg);
  ASSERT_TRUE(c.found);
  ASSERT_FALSE(c.ink.empty());
  constexpr double kMarkerRadius = 3.5;
  for (const auto& [px, py] : c.ink)
    EXPECT_FALSE(px >= c.x - kMarkerRadius && px <= c.x + c.w + kMarkerRadius &&
                 py >= c.y - kMarkerRadius && py <= c.y + c.h + kMarkerRadius)
        << "(" << px << ", " << py << ") in the legend at (" << c.x << ", " << c.y << ") " << c.w
        << "x" << c.h;
}

TEST(SvgPlot, LegendCoversNoPointOfTheWorkPrecisionPlot) {
  expect_legend_covers_nothing(render_svg(work_precision_figure()));
}

TEST(SvgPlot, LegendFindsTheEmptyMiddleWhenEveryCornerIsTaken) {
  // A cluster of points in each corner: the legend goes between them, inside the plot.
  Panel p;
  Series s;
  s.name = "corners";
  s.line = false;
  for (const double cx : {0.0, 0.85})
    for (const double cy : {0.0, 0.85})
      for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 3; ++j) {
          s.x.push_back(cx + 0.05 * i);
          s.y.push_back(cy + 0.05 * j);
        }
  p.series.push_back(s);
  Figure f;
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  expect_legend_covers_nothing(svg);
  const LegendCheck c = legend_check(svg);
  double min_x = INFINITY, max_x = -INFINITY;
  for (const auto& [px, py] : c.ink) {
    min_x = std::min(min_x, px);
    max_x = std::max(max_x, px);
  }
  EXPECT_GT(c.x, min_x);
  EXPECT_LT(c.x + c.w, max_x);
}

TEST(SvgPlot, LegendStandsBesideAPlotWithNoEmptyPlace) {
  // Lines criss-crossing the whole plot every few pixels: no place inside is empty, so the plot
  // narrows and the legend stands to its right, still covering nothing.
  Panel p;
  for (int k = 0; k < 3; ++k) {
    Series s;
    s.name = "zigzag " + std::to_string(k);
    s.marker = Marker::None;
    for (int i = 0; i <= 200; ++i) {
      s.x.push_back(i / 200.0);
      s.y.push_back((i + k) % 2 == 0 ? 0.0 : 1.0);
    }
    p.series.push_back(s);
  }
  Figure f;
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  expect_legend_covers_nothing(svg);
  const LegendCheck c = legend_check(svg);
  for (const auto& [px, py] : c.ink) EXPECT_LT(px, c.x);
  EXPECT_LE(c.x + c.w, f.panel_width_px);
}

TEST(SvgPlot, VerticalMarksAreDrawnWithLabels) {
  Panel p;
  p.series.push_back(
      {"height", {0, 1, 2, 3}, {1, 0, 0.5, 0}, "", true, false, 1.5, Marker::None, true});
  p.marks = {{1.0, "contact"}, {3.0, "rest"}, {99.0, "out of range"}};
  p.x.max = 3.0;
  Figure f;
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  EXPECT_TRUE(has_text(svg, "contact"));
  EXPECT_TRUE(has_text(svg, "rest"));
  EXPECT_FALSE(has_text(svg, "out of range"));
  EXPECT_NE(svg.find("stroke=\"#999999\""), std::string::npos);
}

TEST(SvgPlot, MarkLabelsThatWouldOverlapAreLeftOut) {
  // Given out of order: the labels are still laid out left to right, and the one 0.01 s after
  // "first" (under a pixel away on a 3 s axis) is dropped, its line kept.
  Panel p;
  p.series.push_back({"", {0, 3}, {0, 1}, "", true, false, 1.5, Marker::None, true});
  p.marks = {{2.0, "third"}, {1.01, "second"}, {1.0, "first"}};
  Figure f;
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  EXPECT_TRUE(has_text(svg, "first"));
  EXPECT_FALSE(has_text(svg, "second"));
  EXPECT_TRUE(has_text(svg, "third"));
  const std::size_t path = svg.find("stroke=\"#999999\"");
  ASSERT_NE(path, std::string::npos);
  const std::size_t d = svg.find("d=\"", path);
  EXPECT_EQ(count(svg.substr(d, svg.find('"', d + 3) - d), "M"), 3u);
}

TEST(SvgPlot, ManyMarksAreDrawnWithoutLabels) {
  Panel p;
  p.series.push_back({"", {0, 10}, {0, 1}, "", true, false, 1.5, Marker::None, true});
  for (int i = 0; i < 40; ++i) p.marks.push_back({0.25 * i, "contact"});
  p.marks_color = "#aa0000";
  Figure f;
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  EXPECT_FALSE(has_text(svg, "contact"));
  const std::size_t path = svg.find("stroke=\"#aa0000\"");
  ASSERT_NE(path, std::string::npos);
  const std::size_t d = svg.find("d=\"", path);
  EXPECT_EQ(count(svg.substr(d, svg.find('"', d + 3) - d), "M"), 40u);
}

TEST(SvgPlot, AllXEqualIsPaddedNotDividedByZero) {
  Panel p;
  p.series.push_back({"flat", {2, 2, 2}, {1, 2, 3}, "", true, false, 1.5, Marker::Diamond, true});
  p.series.push_back({"point", {2}, {2}, "", true, false, 1.5, Marker::Cross, true});
  Figure f;
  f.panels.push_back(p);
  const std::string svg = render_svg(f);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
  EXPECT_TRUE(has_text(svg, "2.0"));
}

TEST(SvgPlot, OddSizesAndWidthsStillGiveAValidPicture) {
  Panel p;
  p.series.push_back({"s", {0, 1}, {0, 1}, "", true, true, std::nan(""), Marker::Triangle, true});
  p.series.push_back({"t", {0, 1}, {1, 0}, "", true, false, -3.0, Marker::Cross, false});
  Figure f;
  f.panels = {p, p};
  f.columns = 0;  // taken as 1
  f.panel_width_px = 10;
  f.panel_height_px = -5;
  const std::string svg = render_svg(f);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("stroke-width=\"-"), std::string::npos);
  EXPECT_EQ(svg.find("width=\"-"), std::string::npos);
  EXPECT_NE(svg.find("viewBox=\"0 0 160 240\""), std::string::npos);  // the smallest panels
}

}  // namespace
}  // namespace tumble::plot
