#pragma once
// Geometry and impulses of one body against the floor plane y = height (normal +y).

#include <cmath>
#include <vector>

#include "dynamics.hpp"
#include "tumble/body.hpp"

namespace tumble {

/// Height of vertex i above the floor in state s.
inline double vertex_gap(const RigidBody& b, const BodyState& s, int i, double floor_height) {
  if (b.is_sphere()) return s.x.y() - b.radius() - floor_height;  // its lowest point
  return s.x.y() + s.R.row(1).dot(b.vertices()[i]) - floor_height;
}

/// The lowest gap in s of the vertices in `set`.
double min_gap(const RigidBody& b, const BodyState& s, double floor_height, const ContactSet& set);

/// The lowest gap in s of the vertices in `set` (any number of them).
double min_gap(const RigidBody& b, const BodyState& s, double floor_height,
               const std::vector<int>& set);

/// Vertices below the plane in s, other than those in `skip`, into `below` (cleared first; a mesh
/// hull may have any number below at once).
void vertices_below(const RigidBody& b, const BodyState& s, double floor_height,
                    const ContactSet& skip, std::vector<int>& below);

/// The lowest gap of all the body's contact vertices in s.
double lowest_gap(const RigidBody& b, const BodyState& s, double floor_height);

/// Reduces contact candidates to at most ContactSet::kMaxPoints that keep their support polygon
/// seen along the floor normal: the corners of the candidates' 2-D convex hull, and when there
/// are more corners than that, the ones extreme in 8 evenly spaced directions. Deterministic.
/// A box never has more than 4 candidates; a mesh hull's flat face can put dozens on the floor.
void reduce_to_support(const RigidBody& b, const std::vector<int>& candidates, ContactSet& out);

/// The fastest approach speed (> 0) of the points of `c`, 0 when none approaches.
double approach_speed(const RigidBody& b, const ContactSet& c);

/// How far the vertices that do not touch are from the floor, and how many touch faster than
/// the rest speed, as touching_vertices finds them.
struct Clearance {
  double lowest_m = INFINITY;  ///< the lowest gap beyond the touch distance
  int fast = 0;                ///< touching vertices left out for their speed
};

/// Vertices of the body's current state that touch the floor (gap <= touch_m); with a finite
/// `rest_speed`, only those whose normal speed is at most that (resting candidates). More than
/// ContactSet::kMaxPoints are reduced to their support polygon (reduce_to_support).
ContactSet touching_vertices(const RigidBody& b, double floor_height, double touch_m,
                             double rest_speed, Clearance* clearance = nullptr);

/// The points of `c` that do not separate (normal speed <= hold_speed): those the floor holds.
ContactSet held_points(const RigidBody& b, const ContactSet& c, double hold_speed);

/// Resolves an impact at the touching vertices `c` in the current state: normal impulses from a
/// velocity-level LCP with Newton restitution (e = 0 below `rest_speed`, or everywhere when it is
/// infinite), then
/// Coulomb friction when mu > 0. Never adds kinetic energy (falls back to e = 0 if it would).
/// Writes each point's normal impulse to `normal_impulse`. Returns the energy change (J).
double resolve_impact(RigidBody& b, const ContactSet& c, double rest_speed, double mu,
                      double* normal_impulse);

/// Coulomb friction impulses at contact points given their normal impulses: all points stick
/// when the sticking impulse lies inside every friction cone, else each slides against its slip
/// scaled by the step that dissipates most. Never adds kinetic energy.
void apply_friction(RigidBody& b, const ContactSet& c, const double* normal_impulse, double mu);

/// Marks the points of `c` that slide: their slip is faster than friction could stop within the
/// stretch (2·mu·dv, with dv = |g|·stretch), so kinetic friction acts on them inside the step.
void classify_sliding(const RigidBody& b, ContactSet& c, double mu, double dv);

/// Lifts the body straight up so no resting point is below the plane; returns the depth removed.
double lift_out_of_floor(RigidBody& b, const ContactSet& c, double floor_height);

/// True when the resting points support the body in static equilibrium: at least 3 of them
/// around the centre of mass (strictly inside their hull, seen from above), gravity pressing
/// down, and no point of the body moving faster than sleep_speed.
bool can_rest(const RigidBody& b, const ContactSet& c, const Vec3& gravity, double sleep_speed);

}  // namespace tumble
