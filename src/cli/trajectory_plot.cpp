#include "trajectory_plot.hpp"

#include <algorithm>
#include <cmath>

#include "tumble/svg_plot.hpp"

namespace tumble::cli {

TrajectoryPlot::TrajectoryPlot(std::string stem, double duration_s, long samples)
    : stem_(std::move(stem)),
      duration_s_(duration_s),
      samples_(samples),
      stride_(std::max(1L, (samples + kMaxPoints - 1) / kMaxPoints)) {}

void TrajectoryPlot::add(long k, double t, const World& world) {
  if (k % stride_ != 0 && k != samples_ - 1) return;
  if (bodies_.empty()) {
    for (std::size_t i = 0; i < world.bodies().size(); ++i) {
      bodies_.push_back(world.bodies()[i].name());
      rest_speed_mps_.push_back(world.tolerances(i).rest_speed_mps);
    }
    height_.resize(bodies_.size());
    energy_.resize(bodies_.size());
  }
  t_.push_back(t);
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    height_[i].push_back(world.bodies()[i].state.x.y());
    energy_[i].push_back(world.energy(i));
  }
}

std::string TrajectoryPlot::svg(const std::vector<ImpactEvent>& impacts) const {
  const bool several = bodies_.size() > 1;
  std::vector<plot::VerticalMark> marks;
  for (const ImpactMark& m : impact_marks(impacts))
    marks.push_back({m.t_s, several ? m.label : ""});

  const plot::Axis time{"time (s)", plot::Scale::Linear, 0.0, duration_s_};
  plot::Panel height;
  height.title = "height of the centre of mass (grey lines: impacts)";
  height.x = time;
  height.y = {"height (m)", plot::Scale::Linear, {}, {}};
  plot::Panel energy;
  energy.title = "energy, kinetic + potential (zero at y = 0)";
  energy.x = time;
  energy.y = {"energy (J)", plot::Scale::Linear, {}, {}};
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    plot::Series s;
    s.name = bodies_[i];
    s.x = t_;
    s.marker = plot::Marker::None;
    s.y = height_[i];
    height.series.push_back(s);
    s.y = energy_[i];
    energy.series.push_back(s);
  }
  if (several) {
    plot::Series total;
    total.name = "total";
    total.color = "#555555";
    total.dashed = true;
    total.marker = plot::Marker::None;
    total.x = t_;
    total.y.assign(t_.size(), 0.0);
    for (const auto& e : energy_)
      for (std::size_t k = 0; k < e.size(); ++k) total.y[k] += e[k];
    energy.series.push_back(total);
  }
  height.marks = marks;
  energy.marks = marks;
  // Labels (body names) once, above the upper panel.
  for (plot::VerticalMark& m : energy.marks) m.label.clear();

  plot::Figure f;
  f.title = "tumble simulate: " + stem_;
  f.columns = 1;
  f.panel_width_px = 720;
  f.panel_height_px = 300;
  f.panels = {height, energy};
  return plot::render_svg(f);
}

std::vector<TrajectoryPlot::ImpactMark> TrajectoryPlot::impact_marks(
    const std::vector<ImpactEvent>& impacts) const {
  std::vector<ImpactMark> marks;
  double last_t = -INFINITY;
  std::string last_label;
  for (const ImpactEvent& e : impacts) {
    const std::size_t body = static_cast<std::size_t>(e.body);
    if (body >= bodies_.size()) continue;
    // An impact is a bounce: a point arriving at the body's rest speed or faster. Slower
    // arrivals are contact coming to rest (a sliding box settling on its face, a resting body's
    // micro-impacts), which the height line already shows; they are not marked.
    if (!(e.approach_speed_mps >= rest_speed_mps_[body])) continue;
    // Impacts closer than a thousandth of the run (several points landing at once) are one
    // line: they would be drawn on the same pixel.
    if (e.t_s - last_t < duration_s_ / 1000.0) continue;
    last_t = e.t_s;
    // A label names the body that hit; a run of impacts of one body is named once, at its
    // first (the plot also leaves out a label that would overlap the one before).
    const std::string& name = bodies_[body];
    marks.push_back({e.t_s, name == last_label ? std::string() : name});
    last_label = name;
  }
  return marks;
}

}  // namespace tumble::cli
