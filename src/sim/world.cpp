#include "tumble/world.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "collide.hpp"
#include "dynamics.hpp"
#include "floor_contact.hpp"
#include "integrators.hpp"
#include "number_text.hpp"
#include "time_of_impact.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

using Tol = ContactTolerances;

// Standard gravity: the speed scale of tolerances when a scene has none, and the 1 m reference.
constexpr double kStandardGravity = 9.81;

// Largest dt·|ω| (radians turned per step) each fixed-step integrator follows faithfully: the
// orientation error per step grows as (dt·|ω|)^(order+1), so past these the motion in a clip is
// visibly wrong (first-order methods also gain energy fast). The adaptive integrator sizes its
// own substeps.
double max_turn_per_step(Integrator i) {
  switch (i) {
    case Integrator::Euler:
    case Integrator::SymplecticEuler:
      return 0.1;
    case Integrator::Midpoint:
      return 0.3;
    case Integrator::Rk4:
      return 1.0;
    case Integrator::Adaptive:
      return INFINITY;
  }
  return INFINITY;
}

bool finite(const BodyState& s) {
  return s.x.allFinite() && s.P.allFinite() && s.L.allFinite() && s.q.coeffs().allFinite() &&
         s.R.allFinite();
}

// Where a vertex dips in and out of the floor inside a stretch whose end shows none below:
// conservative advancement, as for islands. The body is evaluated at t + s until a vertex is
// found below (`crossing`, and the bracket [t_a, t_b] in `dip`) or the stretch's end is reached
// (`crossing` empty), s being the soonest a vertex not held could be a reach below the floor.
// Each vertex's height is watched two ways, and the later of the two is taken: its speed
// |v + ω × r| bounds how fast it comes down, or its vertical velocity now and its acceleration
// |a + α × r + ω × (ω × r)| bound a parabola below its path (each the larger of the stretch's
// two ends, +25 %). The second keeps a vertex sliding along just above the floor (a rocking
// L-shape's, at 1.5 m/s, microns up) from cutting the step into a hundred pieces. The reach is
// the touch distance, or 1e-4 of the size for a vertex touching at the start (one lifting off:
// all it could miss is a dip shallower than that, invisible). Held points cannot go in: their
// rows keep them. Out of line: the step of a body resting on a face never needs it.
struct Dip {
  double t_a = 0.0, t_b = 0.0;
  std::optional<BodyState> a, b;  ///< the states at t_a (none: the start) and t_b
  StepInfo info_a;
};
template <class Advance>
[[gnu::noinline]] void find_dip(const BodyDynamics& dynamics, const ContactSet& held,
                                bool face_held, const BodyState& start, const BodyState& end,
                                double remaining, double floor_y, const Tol& tol,
                                const Advance& advanced, std::vector<int>& crossing, Dip& dip) {
  const RigidBody& body = dynamics.body();
  const int nv = static_cast<int>(body.vertices().size());
  const bool turns = !body.is_particle() && !body.is_sphere();  // a ball's turning lowers nothing
  const auto held_points = held.indices();
  auto spin = [&](const BodyState& st) {
    return turns ? Vec3(st.R * body.inverse_inertia_body().asDiagonal() * st.R.transpose() * st.L)
                 : Vec3(Vec3::Zero());
  };
  std::vector<double> rate(static_cast<std::size_t>(nv), 0.0), accel(rate.size(), 0.0),
      reach(rate.size());
  for (const BodyState* st : {&start, &end}) {
    const Rate k = dynamics(*st);
    const Vec3 v = st->P * body.inverse_mass(), w = spin(*st);
    const Vec3 a = k.F * body.inverse_mass();
    const Vec3 alpha =
        turns ? Vec3(st->R * body.inverse_inertia_body().asDiagonal() * st->R.transpose() *
                     (k.tau - w.cross(st->L)))
              : Vec3(Vec3::Zero());
    for (int i = 0; i < nv; ++i) {
      const Vec3 r = body.vertex_offset(st->R, i);
      rate[i] = std::max(rate[i], (v + w.cross(r)).norm());
      accel[i] = std::max(accel[i], (a + alpha.cross(r) + w.cross(w.cross(r))).norm());
    }
  }
  for (int i = 0; i < nv; ++i) {
    rate[i] = 1.25 * rate[i] + 1e-300;
    accel[i] *= 1.25;
    const bool touching = vertex_gap(body, start, i, floor_y) <= tol.touch_m;
    reach[i] = touching ? std::max(tol.touch_m, 1e-4 * tol.length_m) : tol.touch_m;
    if ((touching && face_held) ||
        std::find(held_points.begin(), held_points.end(), i) != held_points.end())
      rate[i] = 0.0;
  }
  const BodyState* at = &start;
  for (int iter = 0; iter < 10000; ++iter) {
    const Vec3 v = at->P * body.inverse_mass(), w = spin(*at);
    double safe = INFINITY;
    for (int i = 0; i < nv; ++i) {
      if (!(rate[i] > 0.0)) continue;
      const double depth = std::max(vertex_gap(body, *at, i, floor_y), 0.0) + reach[i];
      // The parabola depth + u s - A s² / 2 reaches zero at s = (u + sqrt(u² + 2 A depth)) / A.
      const double u = (v + w.cross(body.vertex_offset(at->R, i))).y();
      const double A = accel[i];
      const double parabola = A > 0.0 ? (u + std::sqrt(u * u + 2.0 * A * depth)) / A
                              : u < 0.0 ? depth / -u
                                        : INFINITY;
      safe = std::min(safe, std::max(depth / rate[i], parabola));
    }
    const double next = dip.t_a + std::max(safe, 1e3 * tol.toi_time_s);
    if (next >= remaining) return;
    StepInfo info;
    dip.b = advanced(next, &info);
    vertices_below(body, *dip.b, floor_y, held, crossing);
    if (!crossing.empty()) {
      dip.t_b = next;
      return;
    }
    dip.t_a = next, dip.a = dip.b, dip.info_a = info, at = &*dip.a;
  }
}

}  // namespace

ContactTolerances ContactTolerances::for_body(double length_m, const Vec3& gravity, double dt_s) {
  const double g = gravity.norm() > 0.0 ? gravity.norm() : kStandardGravity;
  // u = sqrt(g ℓ) in units of its value for ℓ = 1 m under standard gravity.
  const double speed = std::sqrt(g * length_m / kStandardGravity);
  ContactTolerances t;
  t.length_m = length_m;
  t.toi_time_s = 1e-12 * length_m / speed;
  t.touch_m = 1e-6 * length_m;
  t.rest_speed_mps = std::max(1e-2 * speed, 2.0 * gravity.norm() * dt_s);
  t.hold_speed_mps = 1e-6 * speed;
  t.lift_speed_mps = std::sqrt(2e-3 * gravity.norm() * t.touch_m);
  t.sleep_speed_mps = 1e-3 * speed;
  return t;
}

double body_length(const std::vector<Vec3>& vertices, double fallback) {
  if (vertices.empty()) return fallback;
  Vec3 lo = vertices.front(), hi = vertices.front();
  for (const Vec3& v : vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double extent = (hi - lo).maxCoeff();
  return extent > 0.0 ? extent : fallback;
}

double length_scale(const BodyDef& body) {
  return body.length_m > 0.0 ? body.length_m : body_length(body.vertices, 1.0);
}

World::World(const WorldDef& def) : def_(def) {
  assert(def.dt_s > 0.0);
  assert(std::is_sorted(def.pairs.begin(), def.pairs.end(), [](const PairDef& x, const PairDef& y) {
    return std::pair(x.a, x.b) < std::pair(y.a, y.b);
  }));
  const double floor_mu = def.floor ? def.floor->friction : 0.0;
  bodies_.reserve(def.bodies.size());
  for (std::size_t i = 0; i < def.bodies.size(); ++i) {
    const BodyDef& b = def.bodies[i];
    own_restitution_.push_back(b.restitution);
    own_friction_.push_back(b.friction.value_or(floor_mu));
    floor_friction_.push_back(own_friction_.back());
    // Against the floor: the scene's [[pair]] with "floor" where it has one.
    BodyDef against_floor = b;
    for (const PairDef& p : def.pairs)
      if (p.a == kFloorBody && p.b == static_cast<int>(i)) {
        if (p.restitution) against_floor.restitution = *p.restitution;
        if (p.friction) floor_friction_.back() = *p.friction;
      }
    bodies_.emplace_back(against_floor);
    // The 2 g dt floor of the rest speed is for fixed steps, whose contact drift is O(g dt) a
    // step; the adaptive integrator controls its error in every substep, so it bounces down to
    // the small-dt limit whatever its largest step.
    const double step = def.integrator == Integrator::Adaptive ? 0.0 : def.dt_s;
    tolerances_.push_back(Tol::for_body(length_scale(b), def.gravity, step));
    flight_start_energy_.push_back(bodies_.back().energy(def.gravity));
    flight_start_state_.push_back(bodies_.back().state);
    flight_start_known_.push_back(true);
  }
  // The adaptive controller starts from its first trial step (the scene's dt) and grows to dt.
  AdaptiveController start;
  if (def.first_step_s > 0.0) start.h_next_s = std::min(def.first_step_s, def.dt_s);
  controllers_.assign(bodies_.size(), start);
  // Islands are looked for only when some pair of bodies can meet: a scene of one body, or of
  // bodies that pass through each other, is stepped body by body as it always was.
  if (def.collisions)
    for (std::size_t i = 0; i < bodies_.size() && !meets_bodies_; ++i)
      for (std::size_t j = i + 1; j < bodies_.size() && !meets_bodies_; ++j)
        meets_bodies_ = pair_collides(static_cast<int>(i), static_cast<int>(j));
  for (std::size_t i = 0; i < bodies_.size(); ++i) check_finite(i);  // the start is written too
}

namespace {

// Whether bodies a and b of def (a may be the floor) meet when they touch.
bool can_meet(const WorldDef& def, const std::vector<RigidBody>& bodies, int a, int b) {
  if (a > b) std::swap(a, b);
  if (a == kFloorBody) {
    if (!def.floor || bodies[b].is_fixed()) return false;
  } else {
    const RigidBody &x = bodies[a], &y = bodies[b];
    if (!def.collisions) return false;
    if (x.is_fixed() && y.is_fixed()) return false;
    if (x.is_particle() && y.is_particle()) return false;
  }
  for (const PairDef& p : def.pairs)
    if (p.a == a && p.b == b) return p.collide;
  return true;
}

}  // namespace

bool World::pair_collides(int a, int b) const {
  return can_meet(def_, bodies_, a, b);
}

std::vector<StartOverlap> overlaps_at_start(const WorldDef& def) {
  std::vector<RigidBody> bodies;
  for (const BodyDef& b : def.bodies) bodies.emplace_back(b);
  std::vector<StartOverlap> out;
  const int n = static_cast<int>(bodies.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if (!can_meet(def, bodies, i, j)) continue;
      const RigidBody &a = bodies[i], &b = bodies[j];
      // Far apart: their bounding spheres do not meet.
      if ((a.state.x - b.state.x).norm() > a.bounding_radius() + b.bounding_radius()) continue;
      const double touch =
          std::min(Tol::for_body(length_scale(def.bodies[i]), def.gravity, def.dt_s).touch_m,
                   Tol::for_body(length_scale(def.bodies[j]), def.gravity, def.dt_s).touch_m);
      const double sep = separation(a, pose_of(a.state), b, pose_of(b.state));
      if (sep < -touch) out.push_back({i, j, -sep});
    }
  return out;
}

std::pair<double, double> World::pair_material(int a, int b) const {
  if (a > b) std::swap(a, b);
  if (a == kFloorBody) return {bodies_[b].restitution(), floor_friction_[b]};
  double e = std::max(own_restitution_[a], own_restitution_[b]);
  double mu = std::sqrt(own_friction_[a] * own_friction_[b]);
  for (const PairDef& p : def_.pairs)
    if (p.a == a && p.b == b) {
      if (p.restitution) e = *p.restitution;
      if (p.friction) mu = *p.friction;
    }
  return {e, mu};
}

PairContactStats& World::pair_stats(int a, int b) {
  if (a > b) std::swap(a, b);
  auto& v = stats_.pairs;
  auto it = std::lower_bound(v.begin(), v.end(), std::pair(a, b),
                             [](const PairContactStats& p, const std::pair<int, int>& key) {
                               return std::pair(p.a, p.b) < key;
                             });
  if (it == v.end() || it->a != a || it->b != b) {
    PairContactStats fresh;
    fresh.a = a, fresh.b = b;
    it = v.insert(it, fresh);
  }
  return *it;
}

bool same_poses(const World& a, const World& b) {
  const auto& ba = a.bodies();
  const auto& bb = b.bodies();
  if (ba.size() != bb.size()) return false;
  for (std::size_t i = 0; i < ba.size(); ++i)
    if (!same_pose(ba[i].state, bb[i].state)) return false;
  return true;
}

double World::total_energy() const {
  double e = 0.0;
  for (const RigidBody& b : bodies_) e += b.energy(def_.gravity);
  return e;
}

void World::step() {
  if (def_.poll) def_.poll();
  advance_all(def_.dt_s);
  ++steps_;
  // Time from the step count, never accumulated: t_n = n·dt exactly as the sampler computes it.
  time_ = static_cast<double>(steps_) * def_.dt_s;
}

void World::advance(double h) {
  assert(h > 0.0 && h <= def_.dt_s * (1.0 + 1e-12));
  if (def_.poll) def_.poll();
  advance_all(h);
  time_ += h;
}

Stepping World::stepping(std::size_t i) const {
  const ContactTolerances& tol = tolerances_[i];
  Stepping how;
  how.method = def_.integrator;
  how.tolerance = def_.tolerance;
  how.length_m = tol.length_m;
  how.speed_mps = std::sqrt(kStandardGravity) * tol.hold_speed_mps / 1e-6;  // sqrt(g ℓ)
  // Substeps a millionth of the largest are a discontinuity the controller cannot resolve.
  how.min_step_s = 1e-6 * def_.dt_s;
  how.controller = controllers_[i];
  return how;
}

BodyState World::integrate_body(std::size_t i, const BodyDynamics& f, const BodyState& s, double h,
                                StepInfo* info) const {
  return integrate(f, s, h, stepping(i), info);
}

void World::keep_step(std::size_t i, const StepInfo& info) {
  // Statistics and diagnostics only for the states the world keeps, not for trial steps.
  controllers_[i] = info.controller;
  if (def_.integrator == Integrator::Adaptive) {
    step_stats_.accepted += info.accepted;
    step_stats_.rejected += info.rejected;
    if (info.smallest_step_s > 0.0)
      step_stats_.smallest_step_s =
          step_stats_.smallest_step_s == 0.0
              ? info.smallest_step_s
              : std::min(step_stats_.smallest_step_s, info.smallest_step_s);
    step_stats_.largest_step_s = std::max(step_stats_.largest_step_s, info.largest_step_s);
    if (info.pinned)
      if (!diagnostics_.recur("adaptive_step_pinned"))
        diagnostics_.warn(
            "adaptive_step_pinned", time_,
            "the adaptive step of body \"" + bodies_[i].name() + "\" was pinned at its minimum (" +
                fmt("%.3g", stepping(i).min_step_s) + " s) with its error above the tolerance",
            "loosen the tolerance (now " + fmt("%.3g", def_.tolerance) +
                ") or use rk4 with a small fixed dt");
  }
  // Renormalisation removes drift every step; a large one means the step misrepresents the turn:
  // 1 % in one step: the unrenormalised step was no longer near a rotation (a shear or scale of
  // 1 %), which happens only past the turn-per-step limits; the seed's coarse midpoint at
  // dt = 1/30 s peaks at 0.23 %.
  constexpr double kMaxDrift = 1e-2;
  if (info.orientation_drift > kMaxDrift)
    if (!diagnostics_.recur("rotation_drift"))
      diagnostics_.warn(
          "rotation_drift", time_,
          "the orientation of body \"" + bodies_[i].name() + "\" drifted " +
              fmt("%.2g", info.orientation_drift) + " from " +
              (def_.rotation == RotationRep::Quaternion ? "unit length" : "orthonormal") +
              " in one step",
          smaller_step_fix());
}

Vec3 World::check_finite(std::size_t i) const {
  const RigidBody& b = bodies_[i];
  // The state, and what outputs derive from it (velocities, energy): a finite state whose
  // energy overflows (a speed of 1e155 m/s) must not write inf either. The angular velocity
  // once (it was computed three times a step, with the turn's check).
  const Vec3 omega = b.is_particle() ? Vec3(Vec3::Zero()) : b.angular_velocity();
  if (finite(b.state) && b.velocity().allFinite() && omega.allFinite() &&
      std::isfinite(b.energy(def_.gravity, omega)))
    return omega;
  if (steps_ == 0 && time_ == 0.0)
    throw Error(ErrorKind::BadInput, "the starting state of body \"" + b.name() +
                                         "\" is beyond double precision (its energy overflows); "
                                         "check masses, sizes and velocities for extreme values");
  const bool high_order =
      def_.integrator == Integrator::Rk4 || def_.integrator == Integrator::Adaptive;
  throw Error(ErrorKind::BadInput,
              "the state of body \"" + b.name() +
                  "\" stopped being finite near t = " + fmt("%.6g", time_) + " s (integrator " +
                  std::string(to_string(def_.integrator)) + ", dt = " + fmt("%.3g", def_.dt_s) +
                  " s); " + (high_order ? "use" : "use rk4 or adaptive, or") +
                  " a smaller dt, and check masses, sizes and velocities for extreme values");
}

void World::check_state(std::size_t i) {
  const Vec3 omega = check_finite(i);
  RigidBody& b = bodies_[i];
  if (b.is_particle()) return;
  const double turn = def_.dt_s * omega.norm();
  const double limit = max_turn_per_step(def_.integrator);
  if (turn > limit)
    if (!diagnostics_.recur("step_too_large_for_spin"))
      diagnostics_.warn("step_too_large_for_spin", time_,
                        "body \"" + b.name() + "\" turns " + fmt("%.3g", turn) +
                            " rad per step (dt·|ω|), more than " +
                            std::string(to_string(def_.integrator)) + " follows faithfully (" +
                            fmt("%.3g", limit) + ")",
                        "use dt <= " + fmt("%.3g", 0.5 * limit / omega.norm()) +
                            " s, or adaptive");
}

void World::check_free_flight(std::size_t i, bool contact) {
  RigidBody& b = bodies_[i];
  if (contact) {
    // The energy a flight starts from is that of the last contact step's end: kept as a state
    // and only evaluated if a flight follows (a body in contact for many steps pays a copy).
    flight_start_state_[i] = b.state;
    flight_start_known_[i] = false;
    return;
  }
  if (!flight_start_known_[i]) {
    const BodyState now = b.state;
    b.state = flight_start_state_[i];
    flight_start_energy_[i] = b.energy(def_.gravity);
    b.state = now;
    flight_start_known_[i] = true;
  }
  const double e = b.energy(def_.gravity);
  // Gravity is conservative and drag only removes energy: in free flight any gain is the
  // integrator's. Scale: the body's kinetic energy plus m·g·ℓ (so a body at rest in zero
  // gravity does not make round-off look large). Threshold 0.1 %: rk4 and midpoint stay orders
  // below it in every example scene, explicit Euler at a coarse dt crosses it.
  constexpr double kMaxRelativeGain = 1e-3;
  const double g = def_.gravity.norm() > 0.0 ? def_.gravity.norm() : kStandardGravity;
  const double scale = b.energy(Vec3::Zero()) + b.mass() * g * tolerances_[i].length_m;
  const double gain = e - flight_start_energy_[i];
  if (gain > kMaxRelativeGain * scale)
    if (!diagnostics_.recur("free_flight_energy_gain"))
      diagnostics_.warn(
          "free_flight_energy_gain", time_,
          "body \"" + b.name() + "\" gained " + fmt("%.3g", gain) + " J (" +
              fmt("%.2g", 100.0 * gain / scale) + " %) in free flight",
          "use rk4 or adaptive, or a smaller dt (now " + fmt("%.3g", def_.dt_s) + " s)");
}

void World::record_impact(std::size_t i, double t, double speed) {
  ++stats_.impacts;
  if (stats_.events.size() < ContactStats::kMaxRecordedImpacts)
    stats_.events.push_back({t, static_cast<int>(i), speed, kFloorBody});
  PairContactStats& p = pair_stats(kFloorBody, static_cast<int>(i));
  if (p.impacts++ == 0) p.first_impact_t_s = t;
}

// The fix a diagnostic of integration error names: a higher-order integrator where there is
// one, and in any case a smaller step.
std::string World::smaller_step_fix() const {
  const bool high_order =
      def_.integrator == Integrator::Rk4 || def_.integrator == Integrator::Adaptive;
  return std::string(high_order ? "use" : "use rk4 or") + " a smaller dt (now " +
         fmt("%.3g", def_.dt_s) + " s)";
}

void World::advance_body(std::size_t index, double h) {
  RigidBody& b = bodies_[index];
  if (b.at_rest || b.is_fixed()) return;  // the exact motion over any step is none
  const ForceModel forces{def_.gravity, def_.linear_drag, def_.angular_drag,
                          def_.general_contact_only};
  if (!def_.floor) {
    StepInfo info;
    b.state = integrate_body(index, BodyDynamics(b, def_.rotation, forces, nullptr, &evaluations_),
                             b.state, h, &info);
    keep_step(index, info);
    check_state(index);
    check_free_flight(index, false);
    return;
  }
  const Tol& tol = tolerances_[index];
  const double floor_y = def_.floor->height;
  const double mu = floor_friction_[index];
  const double rest_speed = tol.rest_speed_mps;
  if (can_rest(b, touching_vertices(b, floor_y, tol.touch_m, rest_speed), def_.gravity,
               tol.sleep_speed_mps)) {
    b.state.P.setZero();
    b.state.L.setZero();
    b.at_rest = true;
    return;
  }
  double remaining = h;
  int events = 0;
  bool contact = false;
  while (remaining > 0.0) {
    // Resting contacts for this stretch: touching points with a small normal speed. Any that
    // still approach are stopped first (an inelastic micro-impact), then held by contact forces.
    Clearance clear;  // of the stretch's start (impulses change no positions)
    ContactSet resting = touching_vertices(b, floor_y, tol.touch_m, rest_speed, &clear);
    bool face_held = clear.fast == 0;
    if (resting.count > 0) {
      contact = true;
      // Impulses change the kinetic energy only: the energy they return is the gain. A point
      // approaching at round-off speed (1e-6 of the hold speed: 1e-12 m/s at 1 m, which moves
      // it 1e-17 m in a 1e-5 s step) is left to the contact forces, which hold it: an impulse
      // solve for it in every stretch of a sliding body cost more than the step's dynamics.
      if (approach_speed(b, resting) > 1e-6 * tol.hold_speed_mps) {
        double impulse[8];
        stats_.max_energy_gain_J =
            std::max(stats_.max_energy_gain_J, resolve_impact(b, resting, INFINITY, mu, impulse));
      }
      // Only points that do not move away are held: a force at a separating point would work.
      const int candidates = resting.count;
      resting = held_points(b, resting, tol.hold_speed_mps);
      // Every touching vertex is then held, or on a hull face with them (left out by
      // reduce_to_support): inside their support polygon, where it cannot go lower than they,
      // or beyond its eighth corner, a face tilting about its held corners; the end of the
      // stretch finds such a vertex below, and a dip of it in and out of the floor is left
      // unwatched (its face turning back within the step).
      face_held = clear.fast == 0 && resting.count == candidates;
    }
    if (mu > 0.0) classify_sliding(b, resting, mu, def_.gravity.norm() * remaining);
    const BodyDynamics dynamics(b, def_.rotation, forces, resting.count > 0 ? &resting : nullptr,
                                &evaluations_);
    const BodyState start = b.state;
    auto advanced = [&](double tau, StepInfo* info) {
      return integrate_body(index, dynamics, start, tau, info);
    };

    // Trial over the whole remaining stretch; an impact is a non-resting vertex crossing the plane.
    double tau = remaining;
    StepInfo end_info;
    BodyState end = advanced(tau, &end_info);
    std::vector<int>& crossing = crossing_;
    vertices_below(b, end, floor_y, resting, crossing);
    // A vertex can also dip in and out inside the stretch: a fast-turning body's corner
    // sweeping past the bottom, which the stretch's end does not see. Conservative advancement,
    // as for islands: each vertex not held comes down no faster than its own speed |v + ω × r|
    // (the larger end's, +25 %), so the body is evaluated at t + (height + reach) / speed until
    // a vertex is found below or the end is reached. The reach is the touch distance, or 1e-4
    // of the size for a vertex touching at the start (one that lifts off: what it could miss is
    // a dip shallower than that, invisible). Held points cannot go in (their rows keep them).
    // A body resting or sliding on a face has its other vertices far up: the end at once.
    double t_a = 0.0, t_b = remaining;
    const BodyState* s_a = &start;
    const BodyState* s_b = &end;
    // First at once for the whole body, which is how a body resting or sliding on a face, its
    // other vertices far up, pays nothing for it: its fastest point is slower than
    // |v| + |ω| r <= sqrt(2 (|P|² / m² + |L|² r² / I_min²)), squared here without a root.
    bool may_dip = false;
    if (crossing.empty() && !b.vertices().empty()) {
      const double spin = !b.is_particle() && !b.is_sphere() ? b.inverse_inertia_body().maxCoeff() * b.bounding_radius() : 0.0;
      const double im = b.inverse_mass();
      const double fastest2 =
          2.0 * (std::max(start.P.squaredNorm(), end.P.squaredNorm()) * im * im +
                 std::max(start.L.squaredNorm(), end.L.squaredNorm()) * spin * spin);
      // The lowest vertex beyond the touch distance, or zero where one touching is not held.
      const double lowest = face_held ? clear.lowest_m : 0.0;
      const double reach = lowest + tol.touch_m, travel = 1.25 * remaining;
      may_dip = reach * reach < travel * travel * fastest2;
    }
    std::optional<Dip> dip;
    if (may_dip) {
      dip.emplace();
      find_dip(dynamics, resting, face_held, start, end, remaining, floor_y, tol, advanced, crossing,
               *dip);
      if (!crossing.empty()) {
        t_a = dip->t_a, t_b = dip->t_b;
        if (dip->a) s_a = &*dip->a;
        s_b = &*dip->b;
      }
    }
    const bool impact = !crossing.empty();
    if (impact) {
      // Time of impact by the Illinois variant of regula falsi on the lowest crossing vertex's
      // gap, integrating from the stretch's start with the step's own integrator. Bracket
      // [lo, hi]: gap(lo) >= 0 > gap(hi), so a crossing lies inside. Stops when the bracket is
      // toi_time_s wide: a vertex is then within speed·toi_time_s (1e-10 ℓ below 100 u) of it.
      double lo = t_a, hi = t_b;
      // The gap is that of the vertices found below the plane at the bracket's end (a touching
      // vertex that moves away must not stop the search at once).
      double g_lo = std::max(min_gap(b, *s_a, floor_y, crossing), 0.0);
      double g_hi = min_gap(b, *s_b, floor_y, crossing);
      BodyState at_lo = *s_a;
      StepInfo lo_info;
      if (dip && dip->a)
        lo_info = dip->info_a;
      else
        lo_info.controller = controllers_[index];
      // A computed gap is exact only to round-off of the positions it comes from; a vertex that
      // just left the plane (a gap of ~1e-16 and a slow separating speed) can read as a hair
      // below it a moment later, which would put the impact at the stretch's start and find it
      // again and again. Within that noise a vertex counts as not yet below: the impact is then
      // located where it really returns, to within the same round-off of its position.
      const double noise = 32.0 * std::numeric_limits<double>::epsilon() *
                           (std::abs(floor_y) + std::abs(start.x.y()) + tol.length_m);
      const bool located = locate_impact(
          lo, hi, g_lo, g_hi, tol.toi_time_s, noise, at_lo, lo_info, advanced,
          [&](const BodyState& s) { return min_gap(b, s, floor_y, crossing); });
      if (!located)
        if (!diagnostics_.recur("contact_tolerance_missed"))
          diagnostics_.warn("contact_tolerance_missed", time_ + (h - remaining),
                            "the time of an impact of body \"" + b.name() +
                                "\" could not be located to " + fmt("%.3g", tol.toi_time_s) + " s",
                            "use a smaller dt (now " + fmt("%.3g", def_.dt_s) + " s)");
      tau = lo;
      end = at_lo;
      end_info = lo_info;
    }
    b.state = end;
    keep_step(index, end_info);
    // Static friction of the resting points that do not slide, as an impulse bounded by mu times
    // their normal impulse over the stretch, f·τ (sliding points had theirs inside the step).
    const bool any_sticking = [&] {
      for (int i = 0; i < resting.count; ++i)
        if (!resting.sliding[i]) return true;
      return false;
    }();
    if (mu > 0.0 && any_sticking && tau > 0.0) {
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
    const double t_event = time_ + (h - remaining) + tau;
    remaining = impact ? remaining - tau : 0.0;
    if (resting.count > 0) {
      // Integration drift of held points is removed by a lift; it counts as penetration.
      const double depth = lift_out_of_floor(b, resting, floor_y);
      stats_.deepest_penetration_m = std::max(stats_.deepest_penetration_m, depth);
      PairContactStats& touched = pair_stats(kFloorBody, static_cast<int>(index));
      touched.deepest_penetration_m = std::max(touched.deepest_penetration_m, depth);
      // A lift by `depth` along +y gains exactly the potential energy -m g_y depth.
      stats_.max_energy_gain_J =
          std::max(stats_.max_energy_gain_J, -b.mass() * def_.gravity.y() * depth);
      // A lift of more than 1e-4 ℓ in one stretch is drift the contact model should not see.
      if (depth > 1e-4 * tol.length_m)
        if (!diagnostics_.recur("contact_tolerance_missed"))
          diagnostics_.warn("contact_tolerance_missed", t_event,
                            "resting points of body \"" + b.name() + "\" sank " +
                                fmt("%.3g", depth) + " m into the floor in one step",
                            smaller_step_fix());
    }
    if (impact) {
      contact = true;
      ContactSet touching = touching_vertices(b, floor_y, tol.touch_m, INFINITY);
      const double speed = approach_speed(b, touching);
      double impulse[8];
      const bool capped = events >= Tol::kMaxEventsPerStep;
      stats_.max_energy_gain_J =
          std::max(stats_.max_energy_gain_J,
                   resolve_impact(b, touching, capped ? INFINITY : rest_speed, mu, impulse));
      record_impact(index, t_event, speed);
      if (events == Tol::kMaxEventsPerStep)
        if (!diagnostics_.recur("event_cap_hit"))
          diagnostics_.warn("event_cap_hit", t_event,
                            "body \"" + b.name() + "\" met " +
                                std::to_string(Tol::kMaxEventsPerStep) +
                                " impacts in one step; the rest of the step was made inelastic",
                            "use a smaller dt (now " + fmt("%.3g", def_.dt_s) + " s)");
      if (++events >= 2 * Tol::kMaxEventsPerStep) {
        // Pathological: finish the step in free flight and lift out, rather than loop on.
        StepInfo info;
        b.state =
            integrate_body(index, BodyDynamics(b, def_.rotation, forces, nullptr, &evaluations_),
                           b.state, remaining, &info);
        keep_step(index, info);
        const double depth = std::max(0.0, -lowest_gap(b, b.state, floor_y));
        b.state.x.y() += depth;
        stats_.deepest_penetration_m = std::max(stats_.deepest_penetration_m, depth);
        PairContactStats& touched = pair_stats(kFloorBody, static_cast<int>(index));
        touched.deepest_penetration_m = std::max(touched.deepest_penetration_m, depth);
        remaining = 0.0;
      }
    }
  }
  check_state(index);
  check_free_flight(index, contact);
}

}  // namespace tumble
