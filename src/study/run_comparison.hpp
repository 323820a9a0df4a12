#pragma once
// How far one run is from another at the same sample times: body points in metres and in pixels,
// orientation as an angle, the bounces matched in order; and a run's own energy drift.

#include <optional>
#include <vector>

#include "run_record.hpp"

namespace tumble::study {

struct RunErrors {
  double position_m = 0.0;  ///< largest distance of a body point from the reference's
  double orientation_rad =
      0.0;                    ///< largest geodesic angle between the orientations (not particles)
  double pixel_px = 0.0;      ///< largest on-screen distance (points in front of both cameras)
  int bounces = 0;            ///< reference bounces compared
  int missed = 0, extra = 0;  ///< bounces of the reference without a partner here, and extra
  std::optional<double> impact_time_s;  ///< largest |Δt| of matched bounces
};

/// `run` against `reference` (same sample times, same bodies). A bounce is an impact faster than
/// both runs' rest speeds of that body (slower ones are inelastic by design at the coarser dt);
/// each body's bounces are matched in order (match_bounces) with `gap_s` as the price of an
/// unmatched one.
RunErrors compare_runs(const RunRecord& run, const RunRecord& reference, double gap_s);

struct BounceMatch {
  int matched = 0, missed = 0, extra = 0;
  std::optional<double> largest_dt_s;  ///< of the matched pairs
};

/// Matches the bounce times `run` to `reference` (both sorted) in order: the monotone pairing that
/// minimises the sum of |Δt| over the pairs plus `gap_s` per bounce left unpaired (an alignment,
/// as of two sequences). A late bounce is still that bounce; one missed near the rest speed does
/// not shift the pairing of every bounce after it. Beyond 1e7 pairs to weigh, pairs by index.
BounceMatch match_bounces(const std::vector<double>& run, const std::vector<double>& reference,
                          double gap_s);

/// Largest relative change of energy over the run's contact-free stretches: between consecutive
/// samples with no impact in between and no vertex touching the floor at either, a body's energy
/// is that of free flight, which gravity conserves. Each stretch is measured from its first sample
/// against |E - E_start| / (kinetic energy at the start + `scale_J` of the body (m·g·ℓ)).
double energy_drift(const RunRecord& record, const std::vector<double>& scale_J);

/// Geodesic angle between two orientations (radians, in [0, π]).
double angle_between(const Quat& a, const Quat& b);

}  // namespace tumble::study
