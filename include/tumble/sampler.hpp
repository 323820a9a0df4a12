#pragma once
/// Samples a World at exact times t (frame times k/fps, trajectory times k/rate) without
/// disturbing its fixed-step trajectory: the world itself only ever takes whole steps; a time
/// between two step boundaries is reached by advancing a copy by the remainder, with the same
/// integrator and contact handling. So the state at a given t depends on t alone, never on which
/// other times were sampled.

#include "tumble/world.hpp"

namespace tumble {

class Sampler {
 public:
  explicit Sampler(World& world) : world_(world) {}

  /// The world as it is at time t >= 0. Calls must come in non-decreasing t.
  World at(double t);

  /// Number of whole steps n with n·dt <= t, treating t within 1e-9 steps of a boundary as on it.
  static long steps_before(double t, double dt);

 private:
  World& world_;
};

/// Number of samples of a run of `duration` at `rate` Hz: every t = k / rate < duration (k >= 0),
/// then t = duration itself (SPEC "Time").
long sample_count(double duration_s, double rate_hz);
/// Number of fixed steps that cover `duration` (the last may be sampled part-way).
long step_count_for(double duration_s, double dt_s);

}  // namespace tumble
