#include "order_fit.hpp"

#include <cassert>
#include <cmath>

namespace tumble::study {

std::optional<LineFit> fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  assert(x.size() == y.size());
  const std::size_t n = x.size();
  if (n < 2) return std::nullopt;
  // Centred sums: the textbook Σx², (Σx)² form cancels badly when the x are far from 0.
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (sxx <= 0.0) return std::nullopt;
  LineFit fit;
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  // R² = 1 - SS_res/SS_tot = sxy² / (sxx syy); a flat line through flat data fits perfectly.
  fit.r_squared = syy > 0.0 ? (sxy * sxy) / (sxx * syy) : 1.0;
  return fit;
}

std::optional<LineFit> fit_order(const std::vector<double>& dts_s,
                                 const std::vector<double>& errors) {
  assert(dts_s.size() == errors.size());
  std::vector<double> x, y;
  for (std::size_t i = 0; i < dts_s.size(); ++i)
    if (errors[i] > 0.0 && dts_s[i] > 0.0) {
      x.push_back(std::log(dts_s[i]));
      y.push_back(std::log(errors[i]));
    }
  return fit_line(x, y);
}

}  // namespace tumble::study
