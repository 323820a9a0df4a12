#pragma once
// trajectory.svg (`simulate --plot`): the height of each body's centre of mass and its energy
// (kinetic + potential, as trajectory.csv's energy column) over time, in two panels sharing the
// time axis, with every impact marked by a vertical line in both. Drawn by tumble::plot, the
// project's one SVG writer. Points are the trajectory's own samples (every stride-th when a run
// has more than kMaxPoints, so an --every-step plot stays a few hundred kB).

#include <string>
#include <vector>

#include "tumble/world.hpp"

namespace tumble::cli {

class TrajectoryPlot {
 public:
  /// Plotted points per series at most.
  static constexpr long kMaxPoints = 2000;

  /// A plot of `samples` samples of a run lasting `duration_s`, of the scene `stem`.
  TrajectoryPlot(std::string stem, double duration_s, long samples);

  /// Sample k (0, 1, ... in order) at time t: kept when it is one of the plotted points.
  void add(long k, double t, const World& world);

  /// The figure as SVG text; `impacts` are the run's impact events (ContactStats::events).
  std::string svg(const std::vector<ImpactEvent>& impacts) const;

  /// A marked impact: its time, and the body named above its line (empty: none).
  struct ImpactMark {
    double t_s = 0.0;
    std::string label;
  };
  /// The impacts marked: bounces only (a point arriving at the body's rest speed or faster;
  /// contact coming to rest is not an impact), those within a thousandth of the run of the
  /// last one merged, and a body named only where the body before was another. Needs add().
  std::vector<ImpactMark> impact_marks(const std::vector<ImpactEvent>& impacts) const;

  /// Every stride-th sample is plotted (and the last).
  long stride() const { return stride_; }

 private:
  std::string stem_;
  double duration_s_;
  long samples_, stride_;
  std::vector<std::string> bodies_;
  std::vector<double> rest_speed_mps_;  // per body: below it an arrival is coming to rest
  std::vector<double> t_;
  std::vector<std::vector<double>> height_, energy_;  // [body][point]
};

}  // namespace tumble::cli
