#include "tumble/world.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "dynamics.hpp"
#include "floor_contact.hpp"
#include "integrators.hpp"

namespace tumble {

using Tol = ContactTolerances;

World::World(const WorldDef& def) : def_(def) {
  assert(def.dt_s > 0.0);
  bodies_.reserve(def.bodies.size());
  for (const BodyDef& b : def.bodies) bodies_.emplace_back(b);
}

double World::total_energy() const {
  double e = 0.0;
  for (const RigidBody& b : bodies_) e += b.energy(def_.gravity);
  return e;
}

void World::step() {
  for (RigidBody& b : bodies_) advance_body(b, def_.dt_s);
  ++steps_;
  // Time from the step count, never accumulated: t_n = n·dt exactly as the sampler computes it.
  time_ = static_cast<double>(steps_) * def_.dt_s;
}

void World::advance(double h) {
  assert(h > 0.0 && h <= def_.dt_s * (1.0 + 1e-12));
  for (RigidBody& b : bodies_) advance_body(b, h);
  time_ += h;
}

void World::advance_body(RigidBody& b, double h) {
  if (b.at_rest) return;  // static equilibrium: the exact motion over any step is none
  const ForceModel forces{def_.gravity, def_.linear_drag, def_.angular_drag};
  if (!def_.floor) {
    b.state =
        integrate(BodyDynamics(b, def_.rotation, forces, nullptr), b.state, h, def_.integrator);
    return;
  }
  const double floor_y = def_.floor->height;
  const double mu = def_.floor->friction;
  const double rest_speed = Tol::rest_speed(def_.gravity, def_.dt_s);
  if (can_rest(b, touching_vertices(b, floor_y, rest_speed), def_.gravity)) {
    b.state.P.setZero();
    b.state.L.setZero();
    b.at_rest = true;
    return;
  }
  double remaining = h;
  int events = 0;
  while (remaining > 0.0) {
    // Resting contacts for this stretch: touching points with a small normal speed. Any that
    // still approach are stopped first (an inelastic micro-impact), then held by contact forces.
    ContactSet resting = touching_vertices(b, floor_y, rest_speed);
    if (resting.count > 0) {
      const double e0 = b.energy(def_.gravity);
      double impulse[8];
      resolve_impact(b, resting, INFINITY, mu, impulse);
      stats_.max_energy_gain_J = std::max(stats_.max_energy_gain_J, b.energy(def_.gravity) - e0);
      // Only points that do not move away are held: a force at a separating point would work.
      resting = held_points(b, resting);
    }
    if (mu > 0.0) classify_sliding(b, resting, mu, def_.gravity.norm() * remaining);
    const BodyDynamics dynamics(b, def_.rotation, forces, resting.count > 0 ? &resting : nullptr);
    const BodyState start = b.state;
    auto advanced = [&](double tau) { return integrate(dynamics, start, tau, def_.integrator); };

    // Trial over the whole remaining stretch; an impact is a non-resting vertex crossing the plane.
    double tau = remaining;
    BodyState end = advanced(tau);
    const ContactSet crossing = vertices_below(b, end, floor_y, resting);
    const bool impact = crossing.count > 0;
    if (impact) {
      // Time of impact by the Illinois variant of regula falsi on the lowest crossing vertex's
      // gap, integrating from the stretch's start with the step's own integrator. Bracket
      // [lo, hi]: gap(lo) >= 0 > gap(hi), so a crossing lies inside. Stops when the bracket is
      // kToiTime wide: a vertex is then within speed·kToiTime (< 1e-10 m below 100 m/s) of it.
      double lo = 0.0, hi = remaining;
      // The gap is that of the vertices found below the plane at the end (a touching vertex that
      // moves away must not stop the search at once).
      double g_lo = std::max(min_gap(b, start, floor_y, crossing), 0.0);
      double g_hi = min_gap(b, end, floor_y, crossing);
      BodyState at_lo = start;
      int side = 0;
      for (int iter = 0; iter < 200 && hi - lo > Tol::kToiTime; ++iter) {
        double t = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
        // Bisect every few iterations so a stubborn (curved) gap still shrinks the bracket.
        if (iter % 4 == 3 || !(t > lo && t < hi)) t = 0.5 * (lo + hi);
        const BodyState s = advanced(t);
        const double g = min_gap(b, s, floor_y, crossing);
        if (g >= 0.0) {
          lo = t, g_lo = g, at_lo = s;
          if (side == -1) g_hi *= 0.5;
          side = -1;
        } else {
          hi = t, g_hi = g;
          if (side == +1) g_lo *= 0.5;
          side = +1;
        }
      }
      tau = lo;
      end = at_lo;
    }
    b.state = end;
    // Static friction of the resting points that do not slide, as an impulse bounded by mu times
    // their normal impulse over the stretch, f·τ (sliding points had theirs inside the step).
    if (mu > 0.0 && resting.count > 0 && tau > 0.0) {
      double force[8];
      dynamics.contact_forces(start, force);
      ContactSet sticking;
      double impulse[8];
      for (int i = 0; i < resting.count; ++i)
        if (!resting.sliding[i]) {
          impulse[sticking.count] = force[i] * tau;
          sticking.vertex[sticking.count++] = resting.vertex[i];
        }
      apply_friction(b, sticking, impulse, mu);
    }
    remaining = impact ? remaining - tau : 0.0;
    if (resting.count > 0) {
      // Integration drift of held points is removed by a lift; it counts as penetration.
      const double e0 = b.energy(def_.gravity);
      const double depth = lift_out_of_floor(b, resting, floor_y);
      stats_.deepest_penetration_m = std::max(stats_.deepest_penetration_m, depth);
      stats_.max_energy_gain_J = std::max(stats_.max_energy_gain_J, b.energy(def_.gravity) - e0);
    }
    if (impact) {
      ContactSet touching = touching_vertices(b, floor_y, INFINITY);
      const double e0 = b.energy(def_.gravity);
      double impulse[8];
      resolve_impact(b, touching, events >= Tol::kMaxEventsPerStep ? INFINITY : rest_speed, mu,
                     impulse);
      stats_.max_energy_gain_J = std::max(stats_.max_energy_gain_J, b.energy(def_.gravity) - e0);
      ++stats_.impacts;
      if (++events >= 2 * Tol::kMaxEventsPerStep) {
        // Pathological: finish the step in free flight and lift out, rather than loop on.
        b.state = integrate(BodyDynamics(b, def_.rotation, forces, nullptr), b.state, remaining,
                            def_.integrator);
        const double depth = std::max(0.0, -min_gap(b, b.state, floor_y, all_vertices(b, floor_y)));
        b.state.x.y() += depth;
        stats_.deepest_penetration_m = std::max(stats_.deepest_penetration_m, depth);
        remaining = 0.0;
      }
    }
  }
}

}  // namespace tumble
