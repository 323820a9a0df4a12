// What `tumble study` prints on stdout: one line per run, the fitted orders, the recommendation.
#include <cstdio>
#include <string>

#include "text_format.hpp"
#include "tumble/study.hpp"

namespace tumble::study {
namespace {

std::string pad(const std::string& s, std::size_t width) {
  return s.size() < width ? s + std::string(width - s.size(), ' ') : s;
}

std::string pad_left(const std::string& s, std::size_t width) {
  return s.size() < width ? std::string(width - s.size(), ' ') + s : s;
}

}  // namespace

std::string study_summary(const StudyResult& result) {
  const Reference& ref = result.reference;
  std::string s =
      "tumble study: " + result.scene_stem + ", " + rounded(result.duration_s, 6) + " s at " +
      std::to_string(result.fps) + " fps, " + std::to_string(result.width) + "x" +
      std::to_string(result.height) +
      "; reference: " + (ref.analytic ? std::string("exact") : short_setting(ref.setting)) +
      " (uncertainty " + rounded(ref.uncertainty_m, 2) + " m, " + rounded(ref.uncertainty_px, 2) +
      " px); " + std::to_string(result.rows.size()) + " runs on " + std::to_string(result.jobs) +
      " thread" + (result.jobs == 1 ? "" : "s") + " in " + rounded(result.wall_s, 2) + " s\n";
  s += pad("integrator", 17) + pad_left("dt (s)", 9) + pad_left("tol", 8) + pad_left("evals", 10) +
       pad_left("wall ms", 9) + pad_left("error m", 10) + pad_left("px", 9) + pad_left("drift", 9) +
       "  notes\n";
  for (std::size_t r = 0; r < result.rows.size(); ++r) {
    const RunRow& row = result.rows[r];
    const RunSetting& set = row.setting;
    s += pad(std::string(to_string(set.integrator)), 17) + pad_left(rounded(set.dt_s, 4), 9) +
         pad_left(set.tolerance ? rounded(*set.tolerance, 2) : "-", 8);
    if (row.diverged) {
      s += pad_left("", 10 + 9 + 10 + 9 + 9) + "  diverged\n";
      continue;
    }
    std::string notes;
    if (result.recommended == r) notes += " recommended";
    if (result.target == r) notes += " target";
    if (row.indistinguishable) notes += " <0.5px";
    if (row.pareto) notes += " pareto";
    if (!row.trusted) notes += " untrusted";
    s += pad_left(std::to_string(row.evaluations), 10) + pad_left(milliseconds(row.wall_s), 9) +
         pad_left(rounded(row.error_m, 2), 10) + pad_left(rounded(row.pixel_error_px, 2), 9) +
         pad_left(rounded(row.energy_drift, 2), 9) + " " + notes + "\n";
  }
  std::string orders;
  for (const OrderFit& f : result.fits)
    orders += (orders.empty() ? "" : ", ") + std::string(to_string(f.integrator)) + " " +
              (f.order ? rounded(*f.order, 2) + " (R² " + rounded(f.r_squared, 2) + ")"
                       : std::string("-"));
  if (!orders.empty()) s += "fitted order: " + orders + "\n";
  if (result.recommended) {
    const RunRow& row = result.rows[*result.recommended];
    s += "recommended: " + short_setting(row.setting) + " (" + std::to_string(row.evaluations) +
         " evaluations, " + rounded(row.pixel_error_px, 2) +
         " px from the reference: indistinguishable)\n";
  } else {
    s += "recommended: none of these runs is within 0.5 px of the reference\n";
  }
  if (result.target_error_m) {
    s += "target " + rounded(*result.target_error_m) + " m: ";
    if (result.target) {
      const RunRow& row = result.rows[*result.target];
      s += short_setting(row.setting) + " (error " + rounded(row.error_m, 2) + " m, " +
           std::to_string(row.evaluations) + " evaluations)\n";
    } else {
      s += "no run reaches it\n";
    }
  }
  return s;
}

}  // namespace tumble::study
