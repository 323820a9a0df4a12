#pragma once
// The convergence order an integrator shows on this scene: the least-squares slope of log(error)
// against log(dt), and how well a straight line fits (R²).

#include <optional>
#include <vector>

namespace tumble::study {

struct LineFit {
  double slope = 0.0, intercept = 0.0;
  double r_squared = 0.0;  ///< 1 for a perfect line (and for two points)
};

/// Least-squares line y = slope·x + intercept; none with fewer than 2 points or all x equal.
std::optional<LineFit> fit_line(const std::vector<double>& x, const std::vector<double>& y);

/// The fitted order: slope of log(error) on log(dt) over the pairs with error > 0.
std::optional<LineFit> fit_order(const std::vector<double>& dts_s,
                                 const std::vector<double>& errors);

}  // namespace tumble::study
