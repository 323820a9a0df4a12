#pragma once
/// The World owns the bodies and the force and contact models the scene asks for, and advances
/// them in fixed steps dt from t = 0. Each step groups the moving bodies into islands: those
/// that touch, or whose swept bounds overlap during the step (with the fixed bodies and the
/// floor they may meet). Islands are stepped one after another in a fixed order; a body alone
/// with at most the floor is stepped exactly as a single body always was (below), so a scene
/// of far-apart bodies costs what it did before bodies met each other. Islands of several
/// bodies (island_step.cpp) locate their impacts in time the same way and resolve them over
/// all the bodies they join.
///
/// Floor contact (only with a floor): a contact vertex crossing the plane inside a step is an
/// impact; its time is located to within kToiGap of the plane, impulses are applied at every
/// approaching contact point together (a small LCP, so a symmetric landing gives no spin), and
/// the step is finished from there. Points touching the floor with a small normal speed are
/// resting contacts: they get contact forces (an acceleration-level LCP, as in Baraff's notes)
/// inside every derivative evaluation. Friction (Coulomb) only when friction > 0.

#include <algorithm>
#include <functional>
#include <optional>
#include <vector>

#include "tumble/body.hpp"
#include "tumble/diagnostics.hpp"
#include "tumble/integrators.hpp"
#include "tumble/math.hpp"

namespace tumble {

struct Stepping;
struct StepInfo;
class BodyDynamics;

struct FloorDef {
  double height = 0.0;
  double friction = 0.0;  ///< Coulomb mu; 0 = frictionless
};

/// The floor, where a body index names a side of a pair.
inline constexpr int kFloorBody = -1;

/// What two bodies (or a body and the floor) do when they meet, where a scene says so.
struct PairDef {
  int a = kFloorBody, b = kFloorBody;  ///< body indices, a < b (kFloorBody first)
  std::optional<double> restitution;   ///< default: the larger of the two bodies'
  std::optional<double> friction;      ///< default: sqrt(mu_a mu_b)
  bool collide = true;
};

struct WorldDef {
  double dt_s = 0.001;
  Integrator integrator = Integrator::Rk4;
  RotationRep rotation = RotationRep::Quaternion;
  Vec3 gravity{0.0, -9.81, 0.0};
  /// Local error tolerance of the adaptive integrator (dt is then its largest step).
  double tolerance = 1e-8;
  /// Adaptive only: the controller's first trial step, at most dt; 0 = dt itself.
  double first_step_s = 0.0;
  double linear_drag = 0.0;   ///< N·s/m, 0 = none
  double angular_drag = 0.0;  ///< N·m·s, 0 = none
  std::optional<FloorDef> floor;
  std::vector<BodyDef> bodies;
  /// Bodies meet each other (SPEC `collisions = "all"`); false: each meets only the floor.
  bool collisions = true;
  /// Sorted by (a, b). Against the floor a body's BodyDef restitution and friction already
  /// include its floor pair.
  std::vector<PairDef> pairs;
  /// Tests and benchmarks: solve every resting contact with the general LCP, the reference the
  /// resting-face fast path is checked against.
  bool general_contact_only = false;
  /// Called before every step and between the events of an island's step; it may throw to stop
  /// the run (the command line's interrupt check: a step of a chattering pile can take long).
  std::function<void()> poll;
};

/// Tolerances of the contact model, with their reasons. Physics has no preferred scale: every
/// tolerance is a fixed fraction of the body's own length ℓ (its largest extent), speed
/// u = sqrt(g ℓ) and time ℓ/u, normalised so that a 1 m body under standard gravity gets the
/// figures quoted below. A 1 mm box dropped from 3 mm is then a scaled copy of a 1 m box dropped
/// from 3 m (lengths × s, times × √s), down to its resting height. Without gravity, standard
/// gravity sets the speed scale.
struct ContactTolerances {
  double length_m = 1.0;  ///< ℓ: the body's largest extent (a particle: its drawn size)
  /// An impact's time is located to within this, from a bracket that always holds the
  /// crossing: 1e-12 s for a 1 m body, where a vertex is then within 1e-10 m of the plane at
  /// impact speeds below 100 m/s.
  double toi_time_s = 1e-12;
  /// Points this close to the plane touch it (1e-6 ℓ): they form one contact set (a nearly flat
  /// landing is resolved as one simultaneous impact) and may rest.
  double touch_m = 1e-6;
  /// Below the rest speed an impact is inelastic (e = 0), so bouncing ends instead of going Zeno.
  /// It is the larger of 1 cm/s at 1 m (a bounce that would rise v²/2g ≈ 5 µm, 5e-6 ℓ) and the
  /// speed gravity adds in two steps, g·2dt: a fixed-step scheme cannot tell slower bounces from
  /// resting (with the seed's dt = 1/30 s that is 0.65 m/s, a 2 cm hop). The adaptive
  /// integrator controls its error in every substep: it gets the small-dt limit (dt = 0).
  double rest_speed_mps = 1e-2;
  /// Resting points the floor holds (with contact forces) separate no faster than this (1 µm/s
  /// at 1 m): a force at a point that moves away would do work. After an inelastic impulse, held
  /// points have zero normal speed to round-off, far below it.
  double hold_speed_mps = 1e-6;
  /// In an island (bodies that touch), a touching point that leaves slower than this where a
  /// stretch starts is stopped with the held ones: sqrt(2 g · 1e-3 touch), so under gravity it
  /// would rise at most 1e-3 of the touch distance (1e-9 ℓ) and come back as an impact of its
  /// own. 1.4e-4 m/s at 1 m under standard gravity; none without gravity.
  double lift_speed_mps = 1.4e-4;
  /// A body supported by >= 3 resting points around its centre of mass, every point of it slower
  /// than this (1 mm/s at 1 m), is put at rest (P = L = 0): removes at most ½ m (1e-3 u)² of
  /// kinetic energy.
  double sleep_speed_mps = 1e-3;
  /// Events (impacts) handled inside one step of one body before the rest of the step treats
  /// every contact as inelastic; an island has this many per 16 members.
  static constexpr int kMaxEventsPerStep = 64;

  /// The tolerances of a body of largest extent `length_m` under `gravity`, stepped with dt.
  static ContactTolerances for_body(double length_m, const Vec3& gravity, double dt_s);
};

/// The largest extent of a body's contact vertices (box: its longest edge); `fallback` when they
/// span nothing (a particle, whose one vertex is its centre).
double body_length(const std::vector<Vec3>& vertices, double fallback);
/// The length ℓ that scales a body's contact tolerances: its BodyDef::length_m when set, else
/// the extent of its vertices (1 m when they span nothing).
double length_scale(const BodyDef& body);

/// One impact event against the floor: when, which body, and how fast its fastest approaching
/// point came in (m/s, > 0). Impacts slower than the body's rest speed are inelastic.
struct ImpactEvent {
  double t_s = 0.0;
  int body = 0;
  double approach_speed_mps = 0.0;
  int other = kFloorBody;  ///< what it hit: another body's index, or the floor
};

/// What one pair (two bodies, or a body and the floor) did over the run: the pairs that touched.
struct PairContactStats {
  int a = kFloorBody, b = 0;  ///< a < b; kFloorBody for the floor
  long impacts = 0;
  double first_impact_t_s = -1.0;  ///< -1 while none
  double deepest_penetration_m = 0.0;
};

/// What contact did over the run, for run.json and tests.
struct ContactStats {
  long impacts = 0;                ///< impact events (impulse resolutions)
  double max_energy_gain_J = 0.0;  ///< largest energy increase across any contact event
  double deepest_penetration_m = 0.0;
  /// Every impact in time order (the first kMaxRecordedImpacts of them).
  std::vector<ImpactEvent> events;
  static constexpr std::size_t kMaxRecordedImpacts = 100000;
  /// Every pair that touched, in (a, b) order.
  std::vector<PairContactStats> pairs;
};

/// What the adaptive integrator did (zero for the fixed-step ones): the substeps of the states
/// the world kept (not those of time-of-impact searches or of samples between steps).
struct StepStats {
  long accepted = 0;
  long rejected = 0;
  double smallest_step_s = 0.0;  ///< 0 until a step was taken
  double largest_step_s = 0.0;
};

/// Two bodies that overlap at the start by more than their touch tolerance.
struct StartOverlap {
  int a = 0, b = 0;      ///< body indices, a < b
  double depth_m = 0.0;  ///< how deep, m (> 0)
};
/// Every pair of bodies of `def` that can meet and overlaps at t = 0 beyond the touch tolerance
/// of the finer of the two (fixed bodies may overlap each other: they never meet).
std::vector<StartOverlap> overlaps_at_start(const WorldDef& def);

class World;
struct Island;
struct IslandContact;
/// True when every body of `a` and `b` (worlds of one WorldDef) is in the same pose (same_pose):
/// a picture of one is the picture of the other.
bool same_poses(const World& a, const World& b);

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
  /// Derivative evaluations dY/dt so far, counted per body (every stage of every step, impact
  /// searches included): the work measure of `tumble study`.
  long derivative_evaluations() const { return evaluations_; }
  const StepStats& step_stats() const { return step_stats_; }
  const Diagnostics& diagnostics() const { return diagnostics_; }
  /// The contact tolerances of body i (they scale with its size).
  const ContactTolerances& tolerances(std::size_t body) const { return tolerances_[body]; }
  double energy(std::size_t body) const { return bodies_[body].energy(def_.gravity); }
  double total_energy() const;

 private:
  // One step (or part of one) of every body: islands found, then stepped in order.
  void advance_all(double h);
  void advance_body(std::size_t body, double h);
  void advance_island(const Island& island, double h);
  std::vector<Island> find_islands(double h);
  // The pair statistics entry of (a, b), created when first touched.
  PairContactStats& pair_stats(int a, int b);
  // Restitution and friction of bodies a and b (a may be kFloorBody).
  std::pair<double, double> pair_material(int a, int b) const;
  bool pair_collides(int a, int b) const;
  std::string smaller_step_fix() const;
  // The body's integrator settings, with its controller state (adaptive).
  Stepping stepping(std::size_t body) const;
  // Integrates body i over h from s (trial states of impact searches included).
  BodyState integrate_body(std::size_t body, const BodyDynamics& f, const BodyState& s, double h,
                           StepInfo* info) const;
  // The world goes on from a step's state: its controller, statistics and diagnostics count.
  void keep_step(std::size_t body, const StepInfo& info);
  // After a body's step: a non-finite state ends the run (exit 2); spin against dt is checked.
  /// Throws where the body's state or what derives from it is not finite; returns its angular
  /// velocity, computed on the way (zero for a particle).
  Vec3 check_finite(std::size_t body) const;
  void check_state(std::size_t body);
  void check_free_flight(std::size_t body, bool contact);
  void record_impact(std::size_t body, double t_s, double approach_speed_mps);

  WorldDef def_;
  std::vector<RigidBody> bodies_;
  std::vector<ContactTolerances> tolerances_;
  std::vector<AdaptiveController> controllers_;
  std::vector<double> flight_start_energy_;    // energy when the current contact-free stretch began
  std::vector<BodyState> flight_start_state_;  // the last contact step's end, until evaluated
  std::vector<char> flight_start_known_;       // flight_start_energy_ is that state's energy
  std::vector<int> crossing_;                  // scratch: vertices found below the floor
  bool meets_bodies_ = false;  // some pair of bodies can touch: islands are looked for
  std::vector<double> own_restitution_;  // each body's own (for pairs of bodies)
  std::vector<double> own_friction_;     // each body's own, else the floor's, else 0
  std::vector<double> floor_friction_;   // against the floor: its [[pair]], else own_friction_
  std::vector<char> sliding_toward_rest_;  // scratch of island steps
  long steps_ = 0;
  double time_ = 0.0;
  long evaluations_ = 0;
  ContactStats stats_;
  StepStats step_stats_;
  Diagnostics diagnostics_;
};

}  // namespace tumble
