// `tumble simulate --plot` end to end (SPEC.md: trajectory.svg): the SVG is parsed and every
// plotted point checked against trajectory.csv through the axis mapping, which is itself checked
// against the tick labels; impacts are marked where the trajectory bounces.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <set>

#include "figures_formats.hpp"
#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {
namespace {

std::string scene_path(const std::string& stem) {
  return (source_dir() / "assets/scenes" / (stem + ".toml")).string();
}

/// One panel of the figure: its data polylines (in series order) and tick labels.
struct SvgPanel {
  std::vector<std::vector<std::pair<double, double>>> lines;  ///< panel coordinates
  std::vector<std::pair<double, double>> x_labels;            ///< value, text x
  std::vector<std::pair<double, double>> y_labels;            ///< value, text y
  std::vector<double> mark_xs;                                ///< vertical marks
  std::string text;
};

/// The panels of a tumble::plot figure: each a `<g transform="translate(...)">`, its series the
/// polylines with more than two points (legend samples have two), its tick labels the numbers
/// in the tick font group, its marks the "M x y V y" runs of the marks' path.
std::vector<SvgPanel> parse_panels(const std::string& svg) {
  std::vector<std::size_t> starts;
  const std::string open = "<g transform=\"translate(";
  for (std::size_t at = svg.find(open); at != std::string::npos; at = svg.find(open, at + 1))
    starts.push_back(at);
  std::vector<SvgPanel> panels;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    SvgPanel p;
    p.text =
        svg.substr(starts[i], (i + 1 < starts.size() ? starts[i + 1] : svg.size()) - starts[i]);
    for (const std::string& line : elements(p.text, "polyline")) {
      auto points = polyline_points(line);
      if (points.size() > 2) p.lines.push_back(points);
    }
    const std::size_t ticks = p.text.find("<g font-size=\"11\" fill=\"#444444\">");
    if (ticks != std::string::npos) {
      const std::string group = p.text.substr(ticks, p.text.find("</g>", ticks) - ticks);
      for (std::size_t at = group.find("<text "); at != std::string::npos;
           at = group.find("<text ", at + 1)) {
        const std::size_t close = group.find('>', at), end = group.find("</text>", at);
        const std::string element = group.substr(at, close - at + 1);
        const std::string label = group.substr(close + 1, end - close - 1);
        char* parsed_end = nullptr;
        const double value = std::strtod(label.c_str(), &parsed_end);
        if (parsed_end == label.c_str() || *parsed_end != '\0') continue;
        const std::string anchor = attribute(element, "text-anchor");
        if (anchor == "middle")
          p.x_labels.emplace_back(value, std::strtod(attribute(element, "x").c_str(), nullptr));
        if (anchor == "end")
          p.y_labels.emplace_back(value, std::strtod(attribute(element, "y").c_str(), nullptr));
      }
    }
    const std::size_t marks = p.text.find("<path fill=\"none\" stroke=\"#999999\"");
    if (marks != std::string::npos) {
      const std::string d = attribute(p.text.substr(marks, p.text.find('>', marks) - marks), "d");
      for (std::size_t at = d.find('M'); at != std::string::npos; at = d.find('M', at + 1))
        p.mark_xs.push_back(std::strtod(d.c_str() + at + 1, nullptr));
    }
    panels.push_back(std::move(p));
  }
  return panels;
}

/// Column `column` of `csv` for body `body`, and the times of those rows.
void series(const Csv& csv, const std::string& body, int column, std::vector<double>& t,
            std::vector<double>& v) {
  t.clear();
  v.clear();
  for (std::size_t r = 0; r < csv.rows.size(); ++r)
    if (csv.text(r, BODY) == body) {
      t.push_back(csv.value(r, T));
      v.push_back(csv.value(r, column));
    }
}

// Coordinates are printed to 1/100 px; a straight-line fit through them is off by less than
// a hundredth of a pixel wherever the plot is the data under one affine map.
constexpr double kPx = 0.011;

TEST(Plot, EveryPointIsTheTrajectoryThroughTheAxes) {
  const TestDir dir;
  const RunResult r = run_tumble(
      {"simulate", scene_path("side_view"), "--plot", "--duration", "2", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const std::string svg = read_file(dir / "o/trajectory.svg");
  ASSERT_TRUE(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\"")) << svg.substr(0, 80);
  EXPECT_TRUE(svg.ends_with("</svg>\n"));
  for (const char* text : {"side_view", "time (s)", "height (m)", "energy (J)", ">ball<"})
    EXPECT_NE(svg.find(text), std::string::npos) << text;

  const Csv csv = read_csv(dir / "o/trajectory.csv");
  std::vector<double> t, height, energy;
  series(csv, "ball", Y, t, height);
  series(csv, "ball", ENERGY, t, energy);
  ASSERT_EQ(t.size(), 121u);  // 2 s at 60 Hz, both ends

  const std::vector<SvgPanel> panels = parse_panels(svg);
  ASSERT_EQ(panels.size(), 2u) << "height and energy";
  LineFit time_maps[2];
  for (int p = 0; p < 2; ++p) {
    SCOPED_TRACE(p == 0 ? "height panel" : "energy panel");
    const SvgPanel& panel = panels[p];
    ASSERT_EQ(panel.lines.size(), 1u) << "one body, one line";
    const auto& points = panel.lines[0];
    ASSERT_EQ(points.size(), t.size()) << "one point per trajectory sample";
    std::vector<double> px, py;
    for (const auto& [x, y] : points) px.push_back(x), py.push_back(y);
    const LineFit x = fit_line(t, px), y = fit_line(p == 0 ? height : energy, py);
    EXPECT_LT(x.worst, kPx) << "x is not time under one map";
    EXPECT_LT(y.worst, kPx) << "y is not the data under one map";
    EXPECT_GT(x.a, 0.0) << "time runs right";
    EXPECT_LT(y.a, 0.0) << "up is up";
    time_maps[p] = x;
    // The map is the axes': each x tick label is centred on its value...
    ASSERT_GE(panel.x_labels.size(), 3u);
    for (const auto& [value, label_x] : panel.x_labels)
      EXPECT_NEAR(x.a * value + x.b, label_x, kPx) << "x label " << value;
    // ... and each y label sits on its value's line (its baseline half a cap height below).
    ASSERT_GE(panel.y_labels.size(), 3u);
    for (const auto& [value, label_y] : panel.y_labels)
      EXPECT_NEAR(y.a * value + y.b, label_y, 6.0) << "y label " << value;
  }
  EXPECT_NEAR(time_maps[0].a, time_maps[1].a, 1e-9 * time_maps[0].a) << "one time axis";
  EXPECT_NEAR(time_maps[0].b, time_maps[1].b, kPx);

  // Impacts: a mark in each panel at each bounce, where the height has its minimum.
  nlohmann::json j = read_json(dir / "o/run.json");
  const long contacts = j["physics"]["contacts"].get<long>();
  ASSERT_GE(contacts, 2) << "2 s of the side view bounce twice";
  for (const SvgPanel& panel : panels) {
    ASSERT_GE(panel.mark_xs.size(), 2u);
    EXPECT_LE(static_cast<long>(panel.mark_xs.size()), contacts);
    for (const double mark : panel.mark_xs) {
      const double tm = (mark - time_maps[0].b) / time_maps[0].a;
      // The lowest sample within a frame of the mark is a local minimum of the height: the
      // ball's centre one radius (0.12 m) above the floor, give or take a frame's fall.
      std::size_t k = 0;
      for (std::size_t i = 0; i < t.size(); ++i)
        if (std::abs(t[i] - tm) < std::abs(t[k] - tm)) k = i;
      ASSERT_GT(k, 0u);
      ASSERT_LT(k + 1, t.size());
      const double low = std::min({height[k - 1], height[k], height[k + 1]});
      EXPECT_LT(low, 0.12 + 0.05) << "mark at t = " << tm << " s is not at a bounce";
    }
  }
  bool listed = false;
  for (const auto& out : j["outputs"])
    if (out["path"] == "o/trajectory.svg") {
      listed = true;
      EXPECT_EQ(out["sha256"], system_sha256(dir / "o/trajectory.svg"));
    }
  EXPECT_TRUE(listed) << j["outputs"].dump();
}

TEST(Plot, SeveralBodiesAndTheirTotalEnergy) {
  const TestDir dir;
  const RunResult r = run_tumble(
      {"simulate", scene_path("meshes"), "--plot", "--duration", "0.5", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Csv csv = read_csv(dir / "o/trajectory.csv");
  std::vector<std::string> bodies;
  for (std::size_t row = 0; row < csv.rows.size(); ++row)
    if (std::find(bodies.begin(), bodies.end(), csv.text(row, BODY)) == bodies.end())
      bodies.push_back(csv.text(row, BODY));
  ASSERT_GE(bodies.size(), 2u);
  const std::string svg = read_file(dir / "o/trajectory.svg");
  for (const std::string& b : bodies) EXPECT_NE(svg.find(">" + b + "<"), std::string::npos) << b;
  EXPECT_NE(svg.find(">total<"), std::string::npos);
  const std::vector<SvgPanel> panels = parse_panels(svg);
  ASSERT_EQ(panels.size(), 2u);
  EXPECT_EQ(panels[0].lines.size(), bodies.size());
  ASSERT_EQ(panels[1].lines.size(), bodies.size() + 1) << "each body's energy and the total";
  // Every energy line, the total too, is the data under the panel's one map.
  std::vector<double> t, e, sum;
  std::vector<double> all_v, all_py;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    series(csv, bodies[b], ENERGY, t, e);
    if (sum.empty()) sum.assign(e.size(), 0.0);
    for (std::size_t k = 0; k < e.size(); ++k) sum[k] += e[k];
    ASSERT_EQ(panels[1].lines[b].size(), e.size());
    for (std::size_t k = 0; k < e.size(); ++k) {
      all_v.push_back(e[k]);
      all_py.push_back(panels[1].lines[b][k].second);
    }
  }
  for (std::size_t k = 0; k < sum.size(); ++k) {
    all_v.push_back(sum[k]);
    all_py.push_back(panels[1].lines.back()[k].second);
  }
  EXPECT_LT(fit_line(all_v, all_py).worst, 0.02);
}

TEST(Plot, MarksImpactsNotABoxThatStopsSliding) {
  // "box" slides on the floor (mu = 0.5) from 3 m/s and stops at t = v / (mu g) = 0.61 s: its
  // only contact events are that stop (arrivals far below the rest speed). "top" falls tilted
  // and bounces. Only top's bounces are marked, and its name is written once above a run of
  // them, with no two labels overlapping.
  const TestDir dir;
  write_scene(dir.path(), "slide.toml", R"([simulation]
duration = 2.0
[floor]
friction = 0.5
[[body]]
name = "box"
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
position = [0.0, 0.5, 0.0]
velocity = [3.0, 0.0, 0.0]
[[body]]
name = "top"
shape = "box"
size = [0.5, 0.5, 0.5]
mass = 1.0
position = [4.0, 2.0, 0.0]
orientation = { axis = [1.0, 0.0, 1.0], degrees = 20.0 }
)");
  const RunResult r = run_tumble({"simulate", "slide.toml", "--plot", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const nlohmann::json run = read_json(dir / "o/run.json");
  ASSERT_GT(run["counts"]["impacts"].get<long>(), 10);  // the stop's events are contact events
  const std::string svg = read_file(dir / "o/trajectory.svg");
  const std::vector<SvgPanel> panels = parse_panels(svg);
  ASSERT_EQ(panels.size(), 2u);
  ASSERT_FALSE(panels[0].mark_xs.empty());
  // The time axis: the first plotted point is t = 0 at the left edge; the marks are top's
  // bounces, from its first landing (t ≈ 0.58 s) on, none at box's stop (0.612 s).
  const auto count = [&](const std::string& needle) {
    std::size_t n = 0;
    for (std::size_t at = svg.find(needle); at != std::string::npos; at = svg.find(needle, at + 1))
      ++n;
    return n;
  };
  EXPECT_EQ(count(">box</text>"), 2u) << "box is only in the two legends: it never bounced";
  const std::size_t tops = count(">top</text>");
  EXPECT_GE(tops, 3u);  // the legends and at least one mark
  EXPECT_LT(tops, 2u + panels[0].mark_xs.size()) << "a run of top's impacts is named once";
  // Mark labels (font size 10) do not overlap: each starts right of the one before ends, by
  // the plot's own glyph estimate (0.6 em; a label is centred on its x).
  const std::size_t group = svg.find("<g font-size=\"10\"");
  ASSERT_NE(group, std::string::npos);
  const std::string labels = svg.substr(group, svg.find("</g>", group) - group);
  double last_right = -1e9;
  for (std::size_t at = labels.find("<text x=\""); at != std::string::npos;
       at = labels.find("<text x=\"", at + 1)) {
    const double x = std::stod(labels.substr(at + 9));
    const std::size_t open_end = labels.find('>', at);
    const std::string text = labels.substr(open_end + 1, labels.find('<', open_end) - open_end - 1);
    const double half = 0.3 * 10.0 * static_cast<double>(text.size());
    EXPECT_GT(x - half, last_right) << text << " at " << x;
    last_right = x + half;
  }
}

TEST(Plot, SameRunTwiceIsByteIdentical) {
  const TestDir dir;
  for (const char* out : {"a", "b"}) {
    const RunResult r = run_tumble(
        {"simulate", "--plot", "--duration", "1.5", "--out", out, "--quiet"}, dir.path());
    ASSERT_EQ(r.exit_code, 0) << describe(r);
  }
  const std::string a = read_file(dir / "a/trajectory.svg");
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == read_file(dir / "b/trajectory.svg"));
}

TEST(Plot, WithoutTheOptionThereIsNoPlot) {
  const TestDir dir;
  const RunResult r = run_tumble({"simulate", "--duration", "0.2", "--out", "o"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_FALSE(fs::exists(dir / "o/trajectory.svg"));
}

}  // namespace
}  // namespace tumble_e2e
