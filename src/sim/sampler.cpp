#include "tumble/sampler.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace tumble {

long Sampler::steps_before(double t, double dt) {
  const double r = t / dt;
  const double nearest = std::round(r);
  // t = k/fps rarely lands exactly on n·dt in binary; within 1e-9 of a step it is that boundary.
  if (std::abs(r - nearest) <= 1e-9 * std::max(1.0, nearest)) return static_cast<long>(nearest);
  return static_cast<long>(std::floor(r));
}

World Sampler::at(double t) {
  assert(t >= 0.0);
  const double dt = world_.def().dt_s;
  const long n = steps_before(t, dt);
  assert(n >= world_.step_count());
  while (world_.step_count() < n) world_.step();
  World copy = world_;
  const double h = t - static_cast<double>(n) * dt;
  if (h > 1e-9 * dt) copy.advance(h);
  return copy;
}

long sample_count(double duration_s, double rate_hz) {
  // Every k >= 0 with k / rate < duration (the division as the sample times compute it), then
  // the end itself.
  long n = std::max(0L, static_cast<long>(std::ceil(duration_s * rate_hz)));
  while (n > 0 && static_cast<double>(n - 1) / rate_hz >= duration_s) --n;
  while (static_cast<double>(n) / rate_hz < duration_s) ++n;
  return n + 1;
}

long step_count_for(double duration_s, double dt_s) {
  return static_cast<long>(std::ceil(duration_s / dt_s - 1e-9));
}

}  // namespace tumble
