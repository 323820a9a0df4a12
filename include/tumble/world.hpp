#pragma once
/// The World owns the bodies and the force and contact models the scene asks for, and advances
/// them in fixed steps dt from t = 0. Bodies do not collide with each other; each meets only the
/// floor, so a step advances every body independently, in scene order (deterministic).
///
/// Floor contact (only with a floor): a contact vertex crossing the plane inside a step is an
/// impact; its time is located to within kToiGap of the plane, impulses are applied at every
/// approaching contact point together (a small LCP, so a symmetric landing gives no spin), and
/// the step is finished from there. Points touching the floor with a small normal speed are
/// resting contacts: they get contact forces (an acceleration-level LCP, as in Baraff's notes)
/// inside every derivative evaluation. Friction (Coulomb) only when friction > 0.

#include <algorithm>
#include <optional>
#include <vector>

#include "tumble/body.hpp"
#include "tumble/integrators.hpp"
#include "tumble/math.hpp"

namespace tumble {

struct FloorDef {
  double height = 0.0;
  double friction = 0.0;  ///< Coulomb mu; 0 = frictionless
};

struct WorldDef {
  double dt_s = 0.001;
  Integrator integrator = Integrator::Rk4;
  RotationRep rotation = RotationRep::Quaternion;
  Vec3 gravity{0.0, -9.81, 0.0};
  double linear_drag = 0.0;   ///< N·s/m, 0 = none
  double angular_drag = 0.0;  ///< N·m·s, 0 = none
  std::optional<FloorDef> floor;
  std::vector<BodyDef> bodies;
};

/// Tolerances of the contact model, with their reasons.
struct ContactTolerances {
  /// An impact's time is located to within this (s), from a bracket that always holds the
  /// crossing: at impact speeds below 100 m/s the vertex is then within 1e-10 m of the plane.
  static constexpr double kToiTime = 1e-12;
  /// Points this close to the plane touch it: they form one contact set (a nearly flat landing is
  /// resolved as one simultaneous impact) and may rest.
  static constexpr double kTouch = 1e-6;
  /// Below the rest speed an impact is inelastic (e = 0), so bouncing ends instead of going Zeno.
  /// It is the larger of 1 cm/s (a bounce that would rise v²/2g ≈ 5 µm) and the speed gravity
  /// adds in two steps, g·2dt: a fixed-step scheme cannot tell slower bounces from resting
  /// (with the seed's dt = 1/30 s that is 0.65 m/s, a 2 cm hop).
  static constexpr double kRestSpeed = 1e-2;
  static double rest_speed(const Vec3& gravity, double dt_s) {
    return std::max(kRestSpeed, 2.0 * gravity.norm() * dt_s);
  }
  /// Resting points the floor holds (with contact forces) separate no faster than this: a force
  /// at a point that moves away would do work. After an inelastic impulse, held points have
  /// zero normal speed to round-off, far below it.
  static constexpr double kHoldSpeed = 1e-6;
  /// A body supported by >= 3 resting points around its centre of mass, every point of it slower
  /// than this, is put at rest (P = L = 0): removes at most ½ m (1e-3)² of kinetic energy.
  static constexpr double kSleepSpeed = 1e-3;
  /// Events (impacts) handled inside one step of one body before the rest of the step treats
  /// every contact as inelastic.
  static constexpr int kMaxEventsPerStep = 64;
};

/// What contact did over the run, for run.json and tests.
struct ContactStats {
  long impacts = 0;                ///< impact events (impulse resolutions)
  double max_energy_gain_J = 0.0;  ///< largest energy increase across any contact event
  double deepest_penetration_m = 0.0;
};

class World {
 public:
  explicit World(const WorldDef& def);

  /// Advances every body by one fixed step dt.
  void step();
  /// Advances every body by h in (0, dt] from the current state: used to sample between step
  /// boundaries on a copy, so the fixed-step trajectory is never disturbed.
  void advance(double h);

  long step_count() const { return steps_; }
  /// Time of the current state: step_count·dt (after step()), or as set by advance().
  double time() const { return time_; }
  const WorldDef& def() const { return def_; }
  const std::vector<RigidBody>& bodies() const { return bodies_; }
  const ContactStats& contact_stats() const { return stats_; }
  double energy(std::size_t body) const { return bodies_[body].energy(def_.gravity); }
  double total_energy() const;

 private:
  void advance_body(RigidBody& body, double h);

  WorldDef def_;
  std::vector<RigidBody> bodies_;
  long steps_ = 0;
  double time_ = 0.0;
  ContactStats stats_;
};

}  // namespace tumble
