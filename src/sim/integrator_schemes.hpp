#pragma once
// The integration schemes written once over a "system": a single body (integrators.cpp) and an
// island of bodies joined by contacts (island.cpp) are integrated by the same arithmetic, so a
// body alone is stepped exactly as it always was.
//
// A system provides:
//   using State, Rates;
//   Rates eval(const State&) const;                      dY/dt (counts an evaluation)
//   State add(const State&, const Rates&, double h) const;   s + h·d over the live components
//   State kick(const State&, const Rates&, double h) const;  momenta only: P += h F, L += h τ
//   State drift(const State&, const Rates&, double h) const; positions only: x, q or R
//   void accumulate_error(ErrorSum&, const Rates&, double w) const;  Σ w_j k_j for the estimate
//   double scaled_error(const State&, const ErrorSum&, const Stepping&) const;
//   void finish(State&, StepInfo&) const;                renormalise, record the drift

#include <algorithm>
#include <cmath>

#include "integrators.hpp"

namespace tumble::schemes {

// Dormand & Prince, "A family of embedded Runge-Kutta formulae" (1980): the 5th-order solution
// is propagated, the embedded 4th-order one only estimates the error; FSAL (the last stage is the
// next step's first).
inline constexpr double kA[7][6] = {
    {},
    {1.0 / 5.0},
    {3.0 / 40.0, 9.0 / 40.0},
    {44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0},
    {19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0},
    {9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0},
    {35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0}};
// b (5th order) − b* (4th order): the error estimate's weights.
inline constexpr double kE[7] = {71.0 / 57600.0,      0.0,          -71.0 / 16695.0, 71.0 / 1920.0,
                                 -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0};

// Symplectic Euler: momenta first, then positions with the new velocities.
template <class Sys>
typename Sys::State symplectic_euler(const Sys& f, const typename Sys::State& s, double h) {
  const auto kicked = f.kick(s, f.eval(s), h);
  return f.drift(kicked, f.eval(kicked), h);  // v and ω from the new momenta, old configuration
}

template <class Sys>
typename Sys::State rk4(const Sys& f, const typename Sys::State& s, double h) {
  const auto k1 = f.eval(s);
  const auto k2 = f.eval(f.add(s, k1, 0.5 * h));
  const auto k3 = f.eval(f.add(s, k2, 0.5 * h));
  const auto k4 = f.eval(f.add(s, k3, h));
  // Weighted sum written as successive adds, so the arithmetic is fixed and deterministic.
  auto out = f.add(s, k1, h / 6.0);
  out = f.add(out, k2, h / 3.0);
  out = f.add(out, k3, h / 3.0);
  return f.add(out, k4, h / 6.0);
}

// s + h Σ_j w_j k_j, as successive adds in a fixed order (deterministic arithmetic).
template <class Sys>
typename Sys::State combine(const Sys& f, const typename Sys::State& s,
                            const typename Sys::Rates* k, const double* w, int n, double h) {
  auto out = s;
  for (int j = 0; j < n; ++j)
    if (w[j] != 0.0) out = f.add(out, k[j], h * w[j]);
  return out;
}

// Covers h in substeps of Dormand–Prince 5(4) with Hairer's PI controller (DOPRI5: β = 0.04,
// exponent 1/5 − 0.75β, safety 0.9, step ratio in [0.2, 10]).
template <class Sys>
typename Sys::State dormand_prince(const Sys& f, const typename Sys::State& s0, double h,
                                   const Stepping& how, StepInfo& info) {
  constexpr double kBeta = 0.04, kExpo = 0.2 - 0.75 * kBeta, kSafe = 0.9;
  constexpr double kMinRatio = 0.2, kMaxRatio = 10.0;
  AdaptiveController c = how.controller;
  auto s = s0;
  double t = 0.0;
  // The controller's wish; a substep is the wish, or what is left of the stretch when that is
  // (a hair more than) less.
  double wish = c.h_next_s > 0.0 ? c.h_next_s : h;
  typename Sys::Rates k[7];
  k[0] = f.eval(s);
  while (t < h) {
    const bool last = h - t <= wish * (1.0 + 1e-9);
    const double hs = last ? h - t : wish;
    for (int i = 1; i < 7; ++i) k[i] = f.eval(combine(f, s, k, kA[i], i, hs));
    typename Sys::ErrorSum sum = f.error_sum();
    for (int j = 0; j < 7; ++j)
      if (kE[j] != 0.0) f.accumulate_error(sum, k[j], hs * kE[j]);
    const double err = f.scaled_error(s, sum, how);
    const bool finite = std::isfinite(err);
    const bool at_floor = hs <= how.min_step_s;
    if ((finite && err <= 1.0) || at_floor) {
      // Pinned: the controller was held at its floor with the error above tolerance (not a
      // stretch end shorter than the floor, which an impact can leave: femtoseconds).
      const bool whole = hs >= wish * (1.0 - 1e-9);
      if (at_floor && whole && !(err <= 1.0)) info.pinned = true;
      s = combine(f, s, k, kA[6], 6, hs);
      t = last ? h : t + hs;
      ++info.accepted;
      // Step statistics are the controller's choices, not substeps cut short by the stretch.
      if (whole) {
        info.smallest_step_s =
            info.smallest_step_s == 0.0 ? hs : std::min(info.smallest_step_s, hs);
        info.largest_step_s = std::max(info.largest_step_s, hs);
      }
      const double e = finite ? std::max(err, 1e-4) : 1.0;
      double ratio = std::pow(e, kExpo) / std::pow(c.err_prev, kBeta) / kSafe;
      ratio = std::clamp(ratio, 1.0 / kMaxRatio, 1.0 / kMinRatio);
      c.err_prev = e;
      const double proposal = std::max(hs / ratio, how.min_step_s);
      // A substep shortened to end the stretch says little about the next one's size.
      c.h_next_s = whole ? proposal : std::max(proposal, wish);
      wish = c.h_next_s;
      k[0] = k[6];  // FSAL: the last stage was evaluated at the new state
    } else {
      ++info.rejected;
      const double shrink =
          finite ? std::clamp(std::pow(err, kExpo) / kSafe, 1.0, 1.0 / kMinRatio) : 1.0 / kMinRatio;
      wish = std::max(hs / shrink, how.min_step_s);
    }
  }
  info.controller = c;
  return s;
}

/// One step of `how.method` over h from s; the state renormalised by the system.
template <class Sys>
typename Sys::State step(const Sys& f, const typename Sys::State& s, double h, const Stepping& how,
                         StepInfo* info) {
  StepInfo local;
  StepInfo& out_info = info ? *info : local;
  out_info = StepInfo{};
  out_info.controller = how.controller;
  typename Sys::State out;
  switch (how.method) {
    case Integrator::Euler:
      out = f.add(s, f.eval(s), h);
      break;
    case Integrator::SymplecticEuler:
      out = symplectic_euler(f, s, h);
      break;
    case Integrator::Midpoint:
      out = f.add(s, f.eval(f.add(s, f.eval(s), 0.5 * h)), h);
      break;
    case Integrator::Rk4:
      out = rk4(f, s, h);
      break;
    case Integrator::Adaptive:
      out = dormand_prince(f, s, h, how, out_info);
      break;
  }
  f.finish(out, out_info);
  return out;
}

}  // namespace tumble::schemes
