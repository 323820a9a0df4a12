#pragma once
// Locating an impact in time: the Illinois variant of regula falsi on a gap function, from a
// bracket [lo, hi] with gap(lo) >= 0 > gap(hi), integrating from the stretch's start with the
// step's own integrator at every trial time. Used by the single-body step (a vertex against
// the floor) and the island step (a pair of bodies), which differ only in what they integrate
// and which gap they watch.

#include <cmath>

namespace tumble {

/// One trial of a search at t: integrates there and moves the bracket's end on its side (the
/// state and step information with `lo`). Returns the gap there; `touched` where the search is
/// `open` and the gap is within the noise of zero, which ends it.
template <class State, class Info, class Advance, class Gap>
double try_impact_time(double t, double& lo, double& hi, double& g_lo, double& g_hi, double noise,
                       bool open, State& at_lo, Info& lo_info, const Advance& advance,
                       const Gap& gap, bool& touched) {
  Info info;
  const State s = advance(t, &info);
  const double g = gap(s);
  if (g >= -noise) {
    lo = t, g_lo = g, at_lo = s, lo_info = info;
    touched = open && g <= noise;
  } else {
    hi = t, g_hi = g;
  }
  return g;
}

/// Where the search ended: `lo` (the latest time found not yet across, with its state and step
/// information in `at_lo` and `lo_info`), and whether the bracket shrank to `width` within 200
/// iterations (false: the caller reports a contact tolerance missed).
/// `advance(t, info)` integrates from the start to t; `gap(state)` is the watched gap there. A
/// gap within `noise` below zero counts as not yet across (round-off of the positions).
/// With `at_touch`, and a gap that starts clearly open (above `noise`), a trial time where the
/// gap is within `noise` of zero also ends the search: the watched points touch there to
/// round-off of their positions, and a narrower bracket would read only that round-off (a
/// corner rocking down at 1e-5 m/s: a bracket of 1e-13 s took twenty trials, each integrating
/// a whole island). A gap that starts at zero may be flat there (a vertex that rests while
/// another goes in): it keeps to the bracket's width.
template <class State, class Info, class Advance, class Gap>
bool locate_impact(double& lo, double hi, double g_lo, double g_hi, double width, double noise,
                   State& at_lo, Info& lo_info, const Advance& advance, const Gap& gap,
                   bool at_touch = false) {
  int side = 0;
  int iter = 0;
  const bool open = at_touch && g_lo > noise;
  for (; iter < 200 && hi - lo > width; ++iter) {
    double t = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
    // Bisect every few iterations so a stubborn (curved) gap still shrinks the bracket.
    if (iter % 4 == 3 || !(t > lo && t < hi)) t = 0.5 * (lo + hi);
    bool touched = false;
    const double g = try_impact_time(t, lo, hi, g_lo, g_hi, noise, open, at_lo, lo_info, advance,
                                     gap, touched);
    if (touched) return true;
    if (g >= -noise) {
      if (side == -1) g_hi *= 0.5;
      side = -1;
    } else {
      if (side == +1) g_lo *= 0.5;
      side = +1;
    }
  }
  return iter < 200;
}

/// The same search, first tried where a cheaper model of the path puts the crossing (the island
/// step's Hermite curve through the stretch's ends): `guess` inside [lo, hi), and `slope` the
/// gap's rate there (negative). Up to six trials from there, each a Newton step of the gap on
/// the integrator's own states aimed half the noise above zero (inside the touching window),
/// the rate after the first the secant through the last two trials (the curve is off the
/// integrator's states by its error, which a slow corner turns into a time: a rocking die's
/// corner at 1e-6 m/s). A search that must close the bracket to its width (a gap starting at
/// zero) tries half the width across from a trial that touches to round-off, and a guess at
/// the bracket's start (a gap that falls at once) just past it: regula falsi from a gap of zero
/// is bisection, twenty trials. What the trials leave is a narrower bracket for locate_impact.
/// 27 dice landing in a pile: 8.9 trials a crossing from the advancement's bracket, 2.0 so.
template <class State, class Info, class Advance, class Gap>
bool locate_impact_from_guess(double& lo, double hi, double g_lo, double g_hi, double width,
                              double noise, State& at_lo, Info& lo_info, const Advance& advance,
                              const Gap& gap, double guess, double slope, bool at_touch = false) {
  const bool open = at_touch && g_lo > noise;
  double t = guess > lo ? guess : lo + 0.5 * width;
  double t_last = NAN, g_last = NAN;
  for (int trial = 0; trial < 6 && hi - lo > width && t > lo && t < hi; ++trial) {
    bool touched = false;
    const double g = try_impact_time(t, lo, hi, g_lo, g_hi, noise, open, at_lo, lo_info, advance,
                                     gap, touched);
    if (touched) return true;
    const double secant = (g - g_last) / (t - t_last);  // NaN at the first trial
    const double rate = secant < 0.0 ? secant : slope;
    t_last = t, g_last = g;
    if (!open && std::abs(g) <= 4.0 * noise)
      t += g >= -noise ? 0.5 * width : -0.5 * width;
    else
      t -= (g - 0.5 * noise) / rate;
  }
  if (hi - lo <= width) return true;
  return locate_impact(lo, hi, g_lo, g_hi, width, noise, at_lo, lo_info, advance, gap, at_touch);
}

}  // namespace tumble
