#pragma once
// The exact reference where a scene has one: no drag, and every body a particle or a box that does
// not turn (zero angular velocity) and, with a floor, lands on a flat face (its lowest vertices,
// at least 3, level within the touch tolerance, the centre of mass above them). Each body then
// follows parabolas between impacts at exact times; an impact slower than the rest speed stops it
// (tumble's contact model, docs/physics.md), a faster one sends it back up at e times its speed.

#include <optional>
#include <string>

#include "run_record.hpp"

namespace tumble::study {

/// What rules the exact solution out ("body \"box\" spins"), or nullopt when the scene has one.
std::optional<std::string> analytic_obstacle(const StudySetup& setup);

struct AnalyticReference {
  RunRecord record;
  /// How exact it is: round-off and the 1e-12 s impact times (1e-9 of the largest body), or, once
  /// a body comes to rest on the floor, its touch tolerance: the contact model stops a slow body
  /// anywhere within it above the plane, depending on where the step boundaries fall.
  double uncertainty_m = 0.0;
};

/// The exact run of the scene, sampled at the study's times, with the rest speed of the small-dt
/// limit (1 cm/s at 1 m; a fixed step dt raises it to 2 g dt). A slow body stops on the plane.
/// Only when analytic_obstacle() is nullopt. Costs nothing: steps and evaluations are 0.
AnalyticReference analytic_reference(const StudySetup& setup);

}  // namespace tumble::study
