#include "run_comparison.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

namespace tumble::study {
namespace {

// What an impact was between: its two sides in ascending order (the floor, -1, first).
std::pair<int, int> impact_pair(const ImpactEvent& e) {
  return {std::min(e.body, e.other), std::max(e.body, e.other)};
}

std::vector<double> bounce_times(const RunRecord& r, std::pair<int, int> pair, double min_speed) {
  std::vector<double> times;
  for (const ImpactEvent& e : r.events)
    if (impact_pair(e) == pair && e.approach_speed_mps > min_speed) times.push_back(e.t_s);
  return times;
}

}  // namespace

double angle_between(const Quat& a, const Quat& b) {
  // 2 atan2(|v|, |w|) of the relative rotation: accurate for tiny and for near-π angles alike
  // (acos of a dot product loses half the digits near 0). q and -q are the same rotation.
  const Quat d = a.conjugate() * b;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

RunErrors compare_runs(const RunRecord& run, const RunRecord& reference, double gap_s) {
  assert(run.samples.size() == reference.samples.size());
  RunErrors out;
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    for (std::size_t i = 0; i < run.samples[k].size(); ++i) {
      const BodySample& a = run.samples[k][i];
      const BodySample& b = reference.samples[k][i];
      for (std::size_t p = 0; p < a.points.size(); ++p) {
        out.position_m = std::max(out.position_m, (a.points[p] - b.points[p]).norm());
        if (a.pixels[p] && b.pixels[p])
          out.pixel_px = std::max(out.pixel_px, (*a.pixels[p] - *b.pixels[p]).norm());
      }
      if (a.points.size() > 1)  // a particle has no orientation
        out.orientation_rad = std::max(out.orientation_rad, angle_between(a.q, b.q));
    }
  }
  // Impacts are matched pair by pair (a body and the floor, or two bodies): a run that has a
  // box hit its neighbour where the reference has it hit the floor misses one and adds one.
  // Pairs in ascending order, so the sums and the largest error do not depend on event order.
  std::vector<std::pair<int, int>> pairs;
  for (const RunRecord* r : {&run, &reference})
    for (const ImpactEvent& e : r->events) pairs.push_back(impact_pair(e));
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  auto rest_speed = [&](int body) {
    if (body < 0) return 0.0;
    const auto i = static_cast<std::size_t>(body);
    return std::max(run.rest_speed_mps[i], reference.rest_speed_mps[i]);
  };
  for (const std::pair<int, int>& pair : pairs) {
    const double threshold = std::max(rest_speed(pair.first), rest_speed(pair.second));
    const std::vector<double> theirs = bounce_times(reference, pair, threshold);
    const BounceMatch m = match_bounces(bounce_times(run, pair, threshold), theirs, gap_s);
    out.bounces += static_cast<int>(theirs.size());
    out.missed += m.missed;
    out.extra += m.extra;
    if (m.largest_dt_s)
      out.impact_time_s = std::max(out.impact_time_s.value_or(0.0), *m.largest_dt_s);
  }
  return out;
}

BounceMatch match_bounces(const std::vector<double>& run, const std::vector<double>& reference,
                          double gap_s) {
  const std::size_t n = run.size(), m = reference.size();
  BounceMatch out;
  auto pair = [&](std::size_t a, std::size_t b) {
    ++out.matched;
    out.largest_dt_s = std::max(out.largest_dt_s.value_or(0.0), std::abs(run[a] - reference[b]));
  };
  if (static_cast<double>(n + 1) * static_cast<double>(m + 1) > 1e7) {
    for (std::size_t k = 0; k < std::min(n, m); ++k) pair(k, k);
    out.extra = static_cast<int>(n - std::min(n, m));
    out.missed = static_cast<int>(m - std::min(n, m));
    return out;
  }
  // cost(a, b): the cheapest alignment of run[0, a) with reference[0, b). The choice per cell is
  // kept for the walk back; ties prefer a pair, then an extra bounce (deterministic).
  enum Step : unsigned char { Pair, Extra, Missed };
  const std::size_t w = m + 1;
  std::vector<double> cost((n + 1) * w);
  std::vector<Step> step((n + 1) * w, Pair);
  for (std::size_t a = 0; a <= n; ++a)
    for (std::size_t b = 0; b <= m; ++b) {
      if (a == 0 && b == 0) continue;
      double best = INFINITY;
      Step how = Pair;
      if (a > 0 && b > 0)
        best = cost[(a - 1) * w + b - 1] + std::abs(run[a - 1] - reference[b - 1]);
      if (a > 0 && cost[(a - 1) * w + b] + gap_s < best)
        best = cost[(a - 1) * w + b] + gap_s, how = Extra;
      if (b > 0 && cost[a * w + b - 1] + gap_s < best)
        best = cost[a * w + b - 1] + gap_s, how = Missed;
      cost[a * w + b] = best;
      step[a * w + b] = how;
    }
  for (std::size_t a = n, b = m; a > 0 || b > 0;) {
    switch (step[a * w + b]) {
      case Pair:
        pair(--a, --b);
        break;
      case Extra:
        ++out.extra, --a;
        break;
      case Missed:
        ++out.missed, --b;
        break;
    }
  }
  return out;
}

double energy_drift(const RunRecord& record, const std::vector<double>& scale_J) {
  double drift = 0.0;
  const std::size_t n = record.samples.size();
  for (std::size_t i = 0; i < scale_J.size(); ++i) {
    // Impacts of this body, in time order: one pointer walks them along the samples.
    std::vector<double> impacts;
    for (const ImpactEvent& e : record.events)
      if (e.body == static_cast<int>(i)) impacts.push_back(e.t_s);
    std::size_t next_impact = 0;
    std::size_t start = 0;  // first sample of the current stretch
    for (std::size_t k = 0; k + 1 < n; ++k) {
      const BodySample& a = record.samples[k][i];
      const BodySample& b = record.samples[k + 1][i];
      bool impact = false;
      while (next_impact < impacts.size() && impacts[next_impact] <= record.times[k + 1]) {
        impact = impact || impacts[next_impact] > record.times[k];
        ++next_impact;
      }
      if (impact || a.touching || b.touching) {
        start = k + 1;
        continue;
      }
      const BodySample& s = record.samples[start][i];
      const double scale = s.kinetic_J + scale_J[i];
      drift = std::max(drift, std::abs(b.energy_J - s.energy_J) / scale);
    }
  }
  return drift;
}

}  // namespace tumble::study
