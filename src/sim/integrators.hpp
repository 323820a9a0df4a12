#pragma once
// One step of an integrator over a body's whole state: the fixed-step ones (euler,
// symplectic-euler, midpoint, rk4) and the adaptive embedded pair (Dormand–Prince 5(4) with a PI
// step-size controller), which covers the stretch in substeps whose local error it controls.

#include "dynamics.hpp"
#include "tumble/integrators.hpp"

namespace tumble {

/// How to integrate: the method, and for `adaptive` its tolerance, the scales of its error norm
/// (a position error is measured against the body's length, a momentum error against m·u, an
/// angular one against I·u/ℓ; rotation as an angle) and the controller state at the start.
struct Stepping {
  Integrator method = Integrator::Rk4;
  double tolerance = 1e-8;
  double length_m = 1.0;
  double speed_mps = 1.0;
  double min_step_s = 0.0;  ///< the adaptive controller never goes below this
  AdaptiveController controller;
};

/// What a step did, for diagnostics and statistics.
struct StepInfo {
  double orientation_drift = 0.0;  ///< | |q| - 1 | or ||RᵀR - I|| before renormalisation
  long accepted = 0, rejected = 0;
  double smallest_step_s = 0.0, largest_step_s = 0.0;
  bool pinned = false;  ///< an adaptive substep was accepted at min_step_s with too large an error
  AdaptiveController controller;  ///< the controller after the step
};

/// The state after a step of size h from s, orientation renormalised (q to unit length, or R
/// re-orthonormalised) and the other orientation form derived from the live one. Deterministic:
/// a function of (f, s, h, how) alone.
BodyState integrate(const BodyDynamics& f, const BodyState& s, double h, const Stepping& how,
                    StepInfo* info = nullptr);

/// Renormalises the live orientation form and derives the other from it.
void normalize_orientation(BodyState& s, RotationRep rep);

/// Symmetric orthonormalisation R (RᵀR)^(-1/2) (Newton–Schulz).
Mat3 orthonormalize(const Mat3& R);
/// | |q| - 1 | or ||RᵀR - I||: how far the live orientation form drifted.
double orientation_drift(const BodyState& s, RotationRep rep);
/// The adaptive error of one body's step estimate (dx, dP, dL, dq or dR) against its scales in
/// `how`, divided by the tolerance: <= 1 accepts the step.
double body_scaled_error(const RigidBody& b, RotationRep rep, const BodyState& s, const Vec3& dx,
                         const Vec3& dP, const Vec3& dL, const Vec4& dq, const Mat3& dR,
                         const Stepping& how);

}  // namespace tumble
