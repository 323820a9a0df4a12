#include "tumble/sampler.hpp"

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
  return std::lround(duration_s * rate_hz) + 1;
}

long step_count_for(double duration_s, double dt_s) {
  return static_cast<long>(std::ceil(duration_s / dt_s - 1e-9));
}

}  // namespace tumble
