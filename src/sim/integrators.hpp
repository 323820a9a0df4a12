#pragma once
// One step of a fixed-step integrator over a body's whole state.

#include "dynamics.hpp"
#include "tumble/integrators.hpp"

namespace tumble {

/// The state after a step of size h from s, orientation renormalised (q to unit length, or R
/// re-orthonormalised) and the other orientation form derived from the live one.
BodyState integrate(const BodyDynamics& f, const BodyState& s, double h, Integrator method);

/// Renormalises the live orientation form and derives the other from it.
void normalize_orientation(BodyState& s, RotationRep rep);

}  // namespace tumble
