#pragma once
// An island: the moving bodies that touch each other, or may within a step (their swept
// bounds overlap), with the fixed bodies and the floor they may meet. It is one unit of the
// step: one stacked state, one derivative whose contact forces couple its bodies, one time
// line of impacts. Islands that do not touch are stepped independently.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "collide.hpp"
#include "dynamics.hpp"
#include "integrators.hpp"
#include "tumble/body.hpp"

namespace tumble {

/// A side of a pair: a member of the island (its local index), a fixed body, or the floor.
struct Side {
  enum Kind { Member, Fixed, Floor } kind = Member;
  int index = 0;  ///< local member index (Member) or world body index (Fixed)
};

/// Two things of an island that can meet, with their material.
struct IslandPair {
  Side a, b;          ///< the normal of their manifold points from a to b; b is a member
  int body_a = -1;    ///< world index of a (-1: the floor), for statistics and messages
  int body_b = -1;
  double restitution = 0.5;
  double friction = 0.0;
};

/// One contact point of a pair, anchored on its bodies so that it moves with them inside a
/// stretch: for a polyhedron the material point (body frame offset from the centre of mass),
/// for a round side its centre (the point is then `radius` along the normal from it).
struct IslandContact {
  int pair = 0;             ///< index into Island::pairs
  Vec3 anchor_a, anchor_b;  ///< body frame (members), world (fixed bodies, the floor)
  double radius_a = 0.0, radius_b = 0.0;
  Vec3 normal_local;        ///< in the frame of `normal_on` (a member), else world
  int normal_on = -1;       ///< local member index the normal turns with, -1: fixed in the world
  /// An edge against an edge: the normal is ±(edge_a × edge_b) of the edges as they turn now
  /// (body frames of a and b; a fixed side's own frame), the sign `edge_sign`. Taken as a's
  /// face normal instead, a held edge sliding along a turning edge sinks in (a die resting on
  /// another's edge: an impact every 16 µs).
  bool edge_edge = false;
  Vec3 edge_a_local = Vec3::Zero(), edge_b_local = Vec3::Zero();
  double edge_sign = 1.0;
  bool sliding = false;     ///< kinetic friction inside the derivative
  /// Where a contact starts sliding from rest (its slip is still zero), the way it will slide.
  Vec3 slip_direction = Vec3::Zero();
  /// Kinetic friction along slip_direction for the whole stretch (zero: none), not along the
  /// slip: for a contact set sliding at a slip it may reverse inside the stretch, whose
  /// direction there would be round-off.
  bool fixed_slip = false;
  std::uint32_t feature = 0;
};

struct Island {
  std::vector<int> members;  ///< world body indices, ascending
  std::vector<IslandPair> pairs;
};

/// The contact geometry of a contact at a stacked state: the world normal, the lever arms from
/// each side's centre of mass (zero for static sides) and the world points.
struct ContactFrame {
  Vec3 n, ra, rb, pa, pb;
  Vec3 ea = Vec3::Zero(), eb = Vec3::Zero();  ///< an edge–edge contact's edges (world)
};

/// The stacked state of an island's members.
using IslandState = std::vector<BodyState>;

/// What an island's derivative needs of the world.
struct IslandView {
  const std::vector<RigidBody>* bodies = nullptr;
  const Island* island = nullptr;
  RotationRep rotation = RotationRep::Quaternion;
  const ForceModel* forces = nullptr;

  const RigidBody& member(int local) const { return (*bodies)[island->members[local]]; }
  const RigidBody* side_body(const Side& s) const {
    return s.kind == Side::Member  ? &member(s.index)
           : s.kind == Side::Fixed ? &(*bodies)[s.index]
                                   : nullptr;
  }
};

/// The frame of contact c at state s.
ContactFrame contact_frame(const IslandView& v, const IslandContact& c, const IslandState& s);

struct Frames;
struct MassInfo;
class HeldRowsCache;

/// dY/dt of every member: gravity, drag and the contact forces at the held contacts, found by
/// one LCP over all of them (Baraff's resting contact, coupled across the island).
class IslandDynamics {
 public:
  IslandDynamics(const IslandView& view, const std::vector<IslandContact>* held,
                 std::vector<char>* active, long* evaluations, bool* solve_failed,
                 HeldRowsCache* cache = nullptr)
      : v_(view),
        held_(held),
        active_(active),
        evaluations_(evaluations),
        failed_(solve_failed),
        cache_(cache) {}
  ~IslandDynamics();
  IslandDynamics(const IslandDynamics&) = delete;
  IslandDynamics& operator=(const IslandDynamics&) = delete;

  std::vector<Rate> operator()(const IslandState& s) const;
  /// What the held contacts exert at a state: per contact, its normal force (N), its static
  /// friction (the world force on b of a sticking contact's tangential rows, zero for others)
  /// and the whole force on b (normal, kinetic friction and static friction).
  struct HeldForces {
    Eigen::VectorXd normal;
    std::vector<Vec3> friction, on_b;
  };
  /// The normal force at every held contact for state s (N).
  Eigen::VectorXd contact_forces(const IslandState& s) const;
  HeldForces held_forces(const IslandState& s) const;
  /// The tangential relative acceleration (b minus a) of every held contact's points at s.
  std::vector<Vec3> slip_accelerations(const IslandState& s) const;
  const IslandView& view() const { return v_; }

 private:
  struct Free {
    Mat3 R, Iinv;
    Vec3 v, omega, F, tau, alpha, a;
  };
  std::vector<Free> free_motion(const IslandState& s) const;
  HeldForces solve(const IslandState& s, const std::vector<Free>& k, const Frames& f) const;
  /// One group of held contacts that share no body with the others.
  HeldForces solve_group(const IslandState& s, const std::vector<Free>& k, const Frames& f,
                         const std::vector<MassInfo>& m, const std::vector<IslandContact>& held,
                         std::vector<char>& active, HeldRowsCache* cache) const;

  IslandView v_;
  const std::vector<IslandContact>* held_;
  std::vector<char>* active_;
  long* evaluations_;
  bool* failed_;
  HeldRowsCache* cache_;  ///< a large island's last sparse factorisation (held_rows.hpp)
};

/// Integrates an island over h from s with `how.method` (the same schemes as a single body).
IslandState integrate_island(const IslandDynamics& f, const IslandState& s, double h,
                             const Stepping& how, const std::vector<Stepping>& per_body,
                             StepInfo* info);

/// The normal speed (b relative to a, along n; negative = approaching) of contact c now.
double normal_speed(const IslandView& v, const IslandContact& c, const IslandState& s);

/// Resolves impacts at `contacts` (all touching now): repeatedly, the contacts that approach
/// get impulses from one velocity-level LCP with Newton restitution (e = 0 below rest_speed,
/// or everywhere when `inelastic`), so an impact passes along a chain of touching bodies as
/// in Newton's cradle; then Coulomb friction impulses. Never adds kinetic energy. Returns the
/// kinetic energy change (J) and adds each contact's normal impulse to `impulses`.
double resolve_island_impacts(const IslandView& v, const std::vector<IslandContact>& contacts,
                              IslandState& s, double rest_speed, bool inelastic,
                              std::vector<double>& impulses);

/// Zeroes the normal speed of every contact in `contacts` (least squares, minimum norm over
/// dependent points): a projection in the kinetic metric, so it never gains energy.
void stop_island_points(const IslandView& v, const std::vector<IslandContact>& contacts,
                        IslandState& s);

/// Static friction for the sticking contacts of a stretch: impulses bounded by mu times their
/// normal impulse over it (`normal_impulse`), all sticking when they fit, else sliding (a
/// contact slipping no faster than `still` then gets none: its slip's direction is round-off).
/// Returns whether every contact could stick.
bool apply_island_friction(const IslandView& v, const std::vector<IslandContact>& contacts,
                           const std::vector<double>& normal_impulse, IslandState& s,
                           double still = 0.0);

/// After a static friction impulse at held contacts whose normal impulse over the stretch was
/// `normal_impulse`: the normal impulses are redistributed (each staying >= 0) so that every
/// held contact's normal speed is zero again, as the contact forces would have done while
/// friction acted (the friction torque loads the leading points, unloads the trailing ones);
/// where no such redistribution exists, approaching contacts are stopped (inelastic). Without
/// it, a box stopped by friction would rock up onto its leading edge.
void restore_normal_speeds(const IslandView& v, const std::vector<IslandContact>& held,
                           const std::vector<double>& normal_impulse, IslandState& s);

/// True when contact forces at `contacts` (normal, and tangential inside each friction cone)
/// can hold every member still against gravity: the island's exact motion from rest is none.
bool island_in_equilibrium(const IslandView& v, const std::vector<IslandContact>& contacts,
                           const IslandState& s);

/// Kinetic energy of the members.
double island_kinetic_energy(const IslandView& v, const IslandState& s);

}  // namespace tumble
