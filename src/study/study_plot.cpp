// study.svg: the work-precision diagram. Left, error against derivative evaluations (the cost
// that does not depend on the machine); right, against wall time. One line per integrator, the
// Pareto front dashed, the reference's uncertainty as a grey line (errors under it say nothing).
#include <algorithm>
#include <numeric>

#include "pareto.hpp"
#include "tumble/study.hpp"
#include "tumble/svg_plot.hpp"

namespace tumble::study {
namespace {

plot::Marker marker_of(Integrator i) {
  switch (i) {
    case Integrator::Euler:
      return plot::Marker::Circle;
    case Integrator::SymplecticEuler:
      return plot::Marker::Square;
    case Integrator::Midpoint:
      return plot::Marker::Triangle;
    case Integrator::Rk4:
      return plot::Marker::Diamond;
    case Integrator::Adaptive:
      return plot::Marker::Cross;
  }
  return plot::Marker::Circle;
}

plot::Panel panel(const StudyResult& result, bool by_wall_time) {
  auto cost = [&](const RunRow& row) {
    return by_wall_time ? row.wall_s : static_cast<double>(row.evaluations);
  };
  plot::Panel p;
  p.title = by_wall_time ? "error against wall time" : "error against derivative evaluations";
  p.x = {by_wall_time ? "wall time (s, best of 3)" : "derivative evaluations",
         plot::Scale::Log10,
         {},
         {}};
  p.y = {"largest position error (m)", plot::Scale::Log10, {}, {}};

  // One series per integrator, in the order the rows list them, points by increasing cost.
  std::vector<Integrator> integrators;
  for (const RunRow& row : result.rows)
    if (std::find(integrators.begin(), integrators.end(), row.setting.integrator) ==
        integrators.end())
      integrators.push_back(row.setting.integrator);
  double lo = INFINITY, hi = -INFINITY;
  for (const Integrator i : integrators) {
    std::vector<const RunRow*> rows;
    for (const RunRow& row : result.rows)
      if (row.setting.integrator == i && !row.diverged && row.error_m > 0.0) rows.push_back(&row);
    std::stable_sort(rows.begin(), rows.end(),
                     [&](const RunRow* a, const RunRow* b) { return cost(*a) < cost(*b); });
    plot::Series s;
    s.name = std::string(to_string(i));
    s.marker = marker_of(i);
    for (const RunRow* row : rows) {
      s.x.push_back(cost(*row));
      s.y.push_back(row->error_m);
      lo = std::min(lo, cost(*row));
      hi = std::max(hi, cost(*row));
    }
    p.series.push_back(s);
  }

  // The Pareto front for this panel's cost.
  std::vector<double> c, e;
  std::vector<bool> valid;
  for (const RunRow& row : result.rows) {
    c.push_back(cost(row));
    e.push_back(row.error_m);
    valid.push_back(!row.diverged && row.error_m > 0.0);
  }
  const std::vector<bool> front = pareto_front(c, e, valid);
  std::vector<std::size_t> on;
  for (std::size_t r = 0; r < front.size(); ++r)
    if (front[r]) on.push_back(r);
  std::stable_sort(on.begin(), on.end(), [&](std::size_t a, std::size_t b) { return c[a] < c[b]; });
  plot::Series pareto;
  pareto.name = "Pareto front";
  pareto.color = "#555555";
  pareto.dashed = true;
  pareto.marker = plot::Marker::None;
  for (const std::size_t r : on) {
    pareto.x.push_back(c[r]);
    pareto.y.push_back(e[r]);
  }
  if (pareto.x.size() >= 2) p.series.push_back(pareto);

  const double u = result.reference.uncertainty_m;
  if (u > 0.0 && lo < hi) {
    plot::Series band;
    band.name = "reference uncertainty";
    band.color = "#aaaaaa";
    band.marker = plot::Marker::None;
    band.line_width_px = 1.0;
    band.x = {lo, hi};
    band.y = {u, u};
    p.series.push_back(band);
  }
  return p;
}

}  // namespace

std::string study_svg(const StudyResult& result) {
  plot::Figure f;
  f.title = "tumble study: " + result.scene_stem + " (" + std::to_string(result.width) + "x" +
            std::to_string(result.height) + ", " + std::to_string(result.fps) + " fps)";
  f.columns = 2;
  f.panel_width_px = 560;
  f.panel_height_px = 400;
  f.panels.push_back(panel(result, false));
  f.panels.push_back(panel(result, true));
  // One legend is enough: the right panel has the same series and colours, and a second legend
  // would only cover its points.
  f.panels.back().legend = false;
  return plot::render_svg(f);
}

}  // namespace tumble::study
