#pragma once
// Numbers rounded for people (study.md, stdout): a few significant digits, "C"-locale snprintf
// (tumble never sets a locale). study.csv keeps the exact ones.

#include <cstdio>
#include <string>

#include "tumble/study.hpp"

namespace tumble::study {

/// x with `digits` significant digits, e.g. "0.00123", "4.5e-09".
inline std::string rounded(double x, int digits = 3) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*g", digits, x);
  return text;
}

/// Seconds as milliseconds with 3 significant digits ("0.352", "41.9"), whole ones from 1000 on.
inline std::string milliseconds(double s) {
  if (1e3 * s < 1e3) return rounded(1e3 * s);
  char text[48];
  std::snprintf(text, sizeof text, "%.0f", 1e3 * s);
  return text;
}

/// "rk4 dt=0.001 s" with the step rounded, or "adaptive tol=1e-08".
inline std::string short_setting(const RunSetting& s) {
  if (s.tolerance) return std::string(to_string(s.integrator)) + " tol=" + rounded(*s.tolerance);
  return std::string(to_string(s.integrator)) + " dt=" + rounded(s.dt_s, 4) + " s";
}

}  // namespace tumble::study
